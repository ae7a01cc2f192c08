//! The CSV `atmos probe` writes: the input's columns as given, then per wavelength
//! `L_<nm>`, `T_<nm>`, `E_sun_<nm>`, then `luminance_cd_m2,r,g,b`, then `L_stderr_<nm>`,
//! then the columns of an option that adds its own (`--clouds`: `T_cloud`, and `paths`
//! for the path tracer).

use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::RayRadiance;

/// Columns beyond the probe's own: their names and one value per name for each row.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExtraColumns {
    pub names: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

/// The output table's columns beyond the input's.
pub(crate) struct Table<'a> {
    pub labels: &'a [&'a str],
    pub solar_irradiance: &'a [f64],
    pub color: &'a SpectrumToColor,
}

impl Table<'_> {
    /// The CSV text of the input `header`, each row's input `fields`, its result and its
    /// `extra` columns.
    pub fn write(
        &self,
        header: &[String],
        fields: &[&[String]],
        results: &[RayRadiance],
        extra: &ExtraColumns,
    ) -> anyhow::Result<Vec<u8>> {
        let mut out = csv::Writer::from_writer(Vec::new());
        let mut header = header.to_vec();
        for prefix in ["L_", "T_", "E_sun_"] {
            header.extend(self.labels.iter().map(|l| format!("{prefix}{l}")));
        }
        header.extend(["luminance_cd_m2", "r", "g", "b"].map(String::from));
        header.extend(self.labels.iter().map(|l| format!("L_stderr_{l}")));
        header.extend(extra.names.iter().cloned());
        out.write_record(&header)?;
        for (i, (given, result)) in fields.iter().zip(results).enumerate() {
            let luminance = self.color.luminance_cd_m2(&result.radiance);
            let rgb = self.color.linear_srgb_cd_m2(&result.radiance);
            let more = extra.rows.get(i).map_or(&[][..], Vec::as_slice);
            let numbers = [
                &result.radiance[..],
                &result.transmittance,
                self.solar_irradiance,
                &[luminance],
                &rgb,
                &result.radiance_std_error,
                more,
            ];
            let mut record = given.to_vec();
            record.extend(numbers.iter().flat_map(|n| n.iter()).map(|&x| number(x)));
            out.write_record(&record)?;
        }
        Ok(out.into_inner()?)
    }
}

/// The shortest text that reads back as `x`, in exponent form when very small or large.
pub fn number(x: f64) -> String {
    if x == 0.0 || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for x in [0.0, 1.0, 0.25, 1.5e-12, 3.1e20, -2.0e-7, 123456.789] {
            assert_eq!(number(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(number(0.5), "0.5");
        assert_eq!(number(1.5e-12), "1.5e-12");
    }
}
