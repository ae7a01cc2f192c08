//! Quantities that vary with wavelength, as they are written in presets and TOML files.
//!
//! A [`Spectral`] is a recipe, not a sampled spectrum: it is evaluated at whatever
//! wavelengths a model carries (three for the real-time models, dozens for the reference).

use serde::{Deserialize, Serialize};

use crate::atmosphere::{ozone, solar};

/// A quantity as a function of wavelength. Units are those of the field that holds it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Spectral {
    /// The same value at every wavelength (e.g. Mie scattering of large aerosols).
    Constant { value: f64 },
    /// `value_at_1um * (lambda / 1 um)^-exponent`: Rayleigh (exponent 4) and the
    /// Angstrom law of aerosols.
    PowerLaw { value_at_1um: f64, exponent: f64 },
    /// Linear interpolation of a table, clamped to its end values outside it.
    Table {
        wavelengths_nm: Vec<f64>,
        values: Vec<f64>,
    },
    /// `scale` times the ASTM G-173 extraterrestrial solar irradiance (W m^-2 nm^-1);
    /// `scale` is (1 au / distance)^2 for other planets.
    SolarAstmG173 { scale: f64 },
    /// Ozone absorption: `number_density_per_m3` times the Serdyuchenko et al. (2014)
    /// cross-section (233 K, as binned to 10 nm in Bruneton 2017's demo).
    OzoneSerdyuchenko { number_density_per_m3: f64 },
}

impl Spectral {
    /// The value at `lambda_nm`.
    pub fn at(&self, lambda_nm: f64) -> f64 {
        match self {
            Spectral::Constant { value } => *value,
            Spectral::PowerLaw {
                value_at_1um,
                exponent,
            } => value_at_1um * (lambda_nm / 1000.0).powf(-exponent),
            Spectral::Table {
                wavelengths_nm,
                values,
            } => interpolate_clamped(wavelengths_nm, values, lambda_nm),
            Spectral::SolarAstmG173 { scale } => {
                scale * solar::astm_g173_irradiance_w_m2_nm(lambda_nm)
            }
            Spectral::OzoneSerdyuchenko {
                number_density_per_m3,
            } => number_density_per_m3 * ozone::serdyuchenko_cross_section_m2(lambda_nm),
        }
    }

    /// This recipe with every value multiplied by `factor`.
    pub fn scaled(&self, factor: f64) -> Spectral {
        match self {
            Spectral::Constant { value } => Spectral::Constant {
                value: value * factor,
            },
            Spectral::PowerLaw {
                value_at_1um,
                exponent,
            } => Spectral::PowerLaw {
                value_at_1um: value_at_1um * factor,
                exponent: *exponent,
            },
            Spectral::Table {
                wavelengths_nm,
                values,
            } => Spectral::Table {
                wavelengths_nm: wavelengths_nm.clone(),
                values: values.iter().map(|v| v * factor).collect(),
            },
            Spectral::SolarAstmG173 { scale } => Spectral::SolarAstmG173 {
                scale: scale * factor,
            },
            Spectral::OzoneSerdyuchenko {
                number_density_per_m3,
            } => Spectral::OzoneSerdyuchenko {
                number_density_per_m3: number_density_per_m3 * factor,
            },
        }
    }

    /// Why this recipe cannot describe a physical non-negative quantity, if it cannot.
    pub fn problem(&self) -> Option<String> {
        let finite_non_negative = |v: f64| v.is_finite() && v >= 0.0;
        match self {
            Spectral::Constant { value } if !finite_non_negative(*value) => {
                Some(format!("value {value} must be finite and >= 0"))
            }
            Spectral::PowerLaw {
                value_at_1um,
                exponent,
            } => {
                if !finite_non_negative(*value_at_1um) {
                    Some(format!(
                        "value_at_1um {value_at_1um} must be finite and >= 0"
                    ))
                } else if !exponent.is_finite() {
                    Some(format!("exponent {exponent} must be finite"))
                } else {
                    None
                }
            }
            Spectral::Table {
                wavelengths_nm,
                values,
            } => {
                if wavelengths_nm.is_empty() || wavelengths_nm.len() != values.len() {
                    Some(format!(
                        "table needs as many values as wavelengths, at least one (got {} wavelengths, {} values)",
                        wavelengths_nm.len(),
                        values.len()
                    ))
                } else if wavelengths_nm.iter().any(|w| !w.is_finite() || *w <= 0.0)
                    || wavelengths_nm.windows(2).any(|w| w[1] <= w[0])
                {
                    Some("wavelengths_nm must be positive and strictly increasing".into())
                } else {
                    values
                        .iter()
                        .find(|v| !finite_non_negative(**v))
                        .map(|v| format!("table value {v} must be finite and >= 0"))
                }
            }
            Spectral::SolarAstmG173 { scale } if !finite_non_negative(*scale) => {
                Some(format!("scale {scale} must be finite and >= 0"))
            }
            Spectral::OzoneSerdyuchenko {
                number_density_per_m3,
            } if !finite_non_negative(*number_density_per_m3) => Some(format!(
                "number_density_per_m3 {number_density_per_m3} must be finite and >= 0"
            )),
            _ => None,
        }
    }
}

/// Linear interpolation in a strictly increasing table, clamped to the end values.
pub fn interpolate_clamped(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    debug_assert_eq!(xs.len(), ys.len());
    if x <= xs[0] {
        return ys[0];
    }
    if x >= xs[xs.len() - 1] {
        return ys[ys.len() - 1];
    }
    let i = xs.partition_point(|&v| v <= x) - 1;
    let f = (x - xs[i]) / (xs[i + 1] - xs[i]);
    ys[i] + f * (ys[i + 1] - ys[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rayleigh_power_law_matches_the_earth_preset_values() {
        let rayleigh = Spectral::PowerLaw {
            value_at_1um: 1.24062e-6,
            exponent: 4.0,
        };
        for (lambda, expected) in [(680.0, 5.8023e-6), (550.0, 1.35578e-5), (440.0, 3.3100e-5)] {
            let got = rayleigh.at(lambda);
            assert!((got / expected - 1.0).abs() < 1e-4, "{lambda} nm: {got}");
        }
    }

    #[test]
    fn table_interpolates_and_clamps() {
        let t = Spectral::Table {
            wavelengths_nm: vec![400.0, 500.0, 700.0],
            values: vec![1.0, 3.0, 5.0],
        };
        assert_eq!(t.at(300.0), 1.0);
        assert_eq!(t.at(450.0), 2.0);
        assert_eq!(t.at(600.0), 4.0);
        assert_eq!(t.at(900.0), 5.0);
        assert!(t.problem().is_none());
    }

    #[test]
    fn problems_are_named() {
        let bad = Spectral::Table {
            wavelengths_nm: vec![500.0, 400.0],
            values: vec![1.0, 1.0],
        };
        assert!(bad.problem().unwrap().contains("increasing"));
        let neg = Spectral::Constant { value: -1.0 };
        assert!(neg.problem().unwrap().contains(">= 0"));
        let nan = Spectral::PowerLaw {
            value_at_1um: f64::NAN,
            exponent: 4.0,
        };
        assert!(nan.problem().is_some());
    }
}
