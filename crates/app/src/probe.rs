//! `atmos probe`: the radiance and transmittance of view rays read from a CSV file, for
//! one model, written as CSV (numbers instead of pictures).
//!
//! Input: a header naming the columns `altitude_m`, `view_zenith_deg`, `sun_zenith_deg`,
//! `view_sun_azimuth_deg` and optionally `distance_m` (any order; an empty distance: the
//! ray runs to the ground or to space), then one ray per line. Lines starting with `#`
//! are comments. Altitudes are at most 1e10 m, zeniths in [0, 180] and azimuths in
//! [-360, 360] degrees; the file at most 64 MiB of UTF-8 in lines of at most 4 KiB.
//! Output: the input columns as given, then per wavelength `L_<nm>`, then `T_<nm>`, then
//! `E_sun_<nm>`, then `luminance_cd_m2,r,g,b`, then `L_stderr_<nm>` (`probe_table.rs`;
//! with `--clouds` also `T_cloud`, and `paths` for the path tracer: `probe_clouds.rs`).

use std::io::Write;

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::limits::MAX_ALTITUDE_M;
use atmosphere_core::atmosphere::text_file::{TextLimits, read_text};
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::error::ModelError;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use thiserror::Error;

use crate::csv_lines::{record_fields, record_lines};
use crate::files::{check_writable, write_atomically};
use crate::probe_args::ProbeArgs;
use crate::probe_clouds;
use crate::probe_table::{ExtraColumns, Table};
use crate::probe_terrain::{self, TerrainPlace};
use crate::progress::map_with_progress;

/// The columns every input needs, in the order of [`ViewRay::from_angles`].
pub const REQUIRED_COLUMNS: [&str; 4] = [
    "altitude_m",
    "view_zenith_deg",
    "sun_zenith_deg",
    "view_sun_azimuth_deg",
];

/// The optional column: the distance to an object ending the ray.
pub const DISTANCE_COLUMN: &str = "distance_m";

/// Input files: 64 MiB (about two million rays), lines of 4 KiB.
pub const CSV_LIMITS: TextLimits = TextLimits {
    max_bytes: 64 << 20,
    max_line_bytes: 4 << 10,
};

/// The range of each required column, in their order: zeniths are not wrapped, azimuths
/// may turn once either way (an altitude below the ground is the model's to refuse).
const RANGES: [([f64; 2], &str); 4] = [
    ([f64::MIN, MAX_ALTITUDE_M], "at most 1e10 m"),
    ([0.0, 180.0], "in [0, 180] degrees"),
    ([0.0, 180.0], "in [0, 180] degrees"),
    ([-360.0, 360.0], "in [-360, 360] degrees"),
];

/// What is wrong with an input file. Lines count from 1.
#[derive(Debug, Error)]
pub enum InputError {
    #[error("{file} has no header line (expected {})", REQUIRED_COLUMNS.join(","))]
    NoHeader { file: String },
    #[error("{file} line {line}: {reason}")]
    Csv {
        file: String,
        line: u64,
        reason: csv::Error,
    },
    #[error(
        "{file} line {line}: unknown column(s) {} (expected {}, and optionally {DISTANCE_COLUMN})",
        quoted(.columns), REQUIRED_COLUMNS.join(", ")
    )]
    UnknownColumns {
        file: String,
        line: u64,
        columns: Vec<String>,
    },
    #[error("{file} line {line}: column(s) given more than once: {}", quoted(.columns))]
    RepeatedColumns {
        file: String,
        line: u64,
        columns: Vec<String>,
    },
    #[error("{file} line {line}: missing column(s) {}", quoted(.columns))]
    MissingColumns {
        file: String,
        line: u64,
        columns: Vec<String>,
    },
    #[error("{file} line {line}: {found} fields, but the header has {expected}")]
    FieldCount {
        file: String,
        line: u64,
        expected: usize,
        found: usize,
    },
    #[error("{file} line {line}, column {column}: '{value}' is not a number")]
    NotANumber {
        file: String,
        line: u64,
        column: &'static str,
        value: String,
    },
    #[error("{file} line {line}, column {column}: {value} must be {range}")]
    OutOfRange {
        file: String,
        line: u64,
        column: &'static str,
        value: String,
        range: &'static str,
    },
    #[error("{file} line {line}: {reason}")]
    Ray {
        file: String,
        line: u64,
        reason: ModelError,
    },
}

fn quoted(columns: &[String]) -> String {
    let quoted: Vec<String> = columns.iter().map(|c| format!("'{c}'")).collect();
    quoted.join(", ")
}

/// The rays of an input file, with its columns as given.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeInput {
    pub header: Vec<String>,
    pub rows: Vec<ProbeRow>,
}

/// One ray of an input file.
#[derive(Clone, Debug, PartialEq)]
pub struct ProbeRow {
    /// Line of the file, from 1.
    pub line: u64,
    /// The fields as given (trimmed).
    pub fields: Vec<String>,
    pub ray: ViewRay,
}

/// Reads the rays of CSV text named `file` (for messages), on a planet of this radius.
/// Each record is one line (so that errors name the line); blank lines and lines
/// starting with `#` are skipped.
pub fn read_rays(text: &str, file: &str, bottom_radius_m: f64) -> Result<ProbeInput, InputError> {
    let mut records = record_lines(text);
    let fields = |line: u64, text: &str| -> Result<Vec<String>, InputError> {
        record_fields(text).map_err(|reason| InputError::Csv {
            file: file.to_string(),
            line,
            reason,
        })
    };
    let Some((header_line, header_text)) = records.next() else {
        return Err(InputError::NoHeader {
            file: file.to_string(),
        });
    };
    let header = fields(header_line, header_text)?;
    let known = |h: &str| REQUIRED_COLUMNS.contains(&h) || h == DISTANCE_COLUMN;
    let (mut unknown, mut repeated) = (Vec::new(), Vec::new());
    for (i, h) in header.iter().enumerate() {
        let list = if !known(h) {
            &mut unknown
        } else if header[..i].contains(h) {
            &mut repeated
        } else {
            continue;
        };
        if !list.contains(h) {
            list.push(h.clone());
        }
    }
    let index = |name: &str| header.iter().position(|h| h == name);
    let missing: Vec<String> = REQUIRED_COLUMNS
        .iter()
        .filter(|c| index(c).is_none())
        .map(|c| c.to_string())
        .collect();
    let (file_name, line) = (file.to_string(), header_line);
    if !unknown.is_empty() {
        return Err(InputError::UnknownColumns {
            file: file_name,
            line,
            columns: unknown,
        });
    }
    if !repeated.is_empty() {
        return Err(InputError::RepeatedColumns {
            file: file_name,
            line,
            columns: repeated,
        });
    }
    if !missing.is_empty() {
        return Err(InputError::MissingColumns {
            file: file_name,
            line,
            columns: missing,
        });
    }
    let required = REQUIRED_COLUMNS.map(|c| index(c).unwrap_or_default());
    let distance = index(DISTANCE_COLUMN);

    let mut rows = Vec::new();
    for (line, text) in records {
        let record = fields(line, text)?;
        if record.len() != header.len() {
            return Err(InputError::FieldCount {
                file: file.to_string(),
                line,
                expected: header.len(),
                found: record.len(),
            });
        }
        let number = |column: &'static str, value: &str| {
            value.parse::<f64>().map_err(|_| InputError::NotANumber {
                file: file.to_string(),
                line,
                column,
                value: value.to_string(),
            })
        };
        let mut values = [0.0; 4];
        for ((value, column), i) in values.iter_mut().zip(REQUIRED_COLUMNS).zip(required) {
            *value = number(column, &record[i])?;
        }
        let distance_m = match distance.map(|i| record[i].as_str()) {
            None | Some("") => None,
            Some(text) => Some(number(DISTANCE_COLUMN, text)?),
        };
        let [altitude, view_zenith, sun_zenith, azimuth] = values;
        let columns = REQUIRED_COLUMNS
            .iter()
            .zip(RANGES)
            .zip(values)
            .zip(required);
        for (((column, ([low, high], range)), value), i) in columns {
            if value.is_finite() && !(low..=high).contains(&value) {
                return Err(InputError::OutOfRange {
                    file: file.to_string(),
                    line,
                    column,
                    value: record[i].clone(),
                    range,
                });
            }
        }
        let ray = ViewRay::from_angles(
            bottom_radius_m,
            altitude,
            view_zenith,
            sun_zenith,
            azimuth,
            distance_m,
        )
        .map_err(|reason| InputError::Ray {
            file: file.to_string(),
            line,
            reason,
        })?;
        rows.push(ProbeRow {
            line,
            fields: record,
            ray,
        });
    }
    Ok(ProbeInput { header, rows })
}

/// Runs `atmos probe`.
pub fn run(args: &ProbeArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.output {
        check_writable(path)?;
    }
    let model: ModelId = args
        .model
        .parse()
        .with_context(|| format!("--model {} is a beam method: it needs --scene", args.model))?;
    let settings = ModelSettings {
        wavelengths_nm: args.wavelengths.iter().map(|w| w.nm).collect(),
        max_orders: args.orders,
        target_relative_error: args.target_error,
        seed: args.seed,
        options: ModelOptions::parse(&args.set)?,
        prune: true,
    };
    settings.validate()?;
    // The model answers at the settings' wavelengths, in their order.
    let color = SpectrumToColor::new(&settings.wavelengths_nm)?;
    let atmosphere = Atmosphere::from_preset_or_file(&args.atmosphere)
        .and_then(|a| match model {
            ModelId::Reference => Ok(a),
            _ => a.check_real_time_range().map(|()| a),
        })
        .with_context(|| format!("--atmosphere {}", args.atmosphere))?;
    let file = args.input.display().to_string();
    let text = read_text(&args.input, CSV_LIMITS)?;
    let input = read_rays(&text, &file, atmosphere.bottom_radius_m)?;
    let rays: Vec<ViewRay> = input.rows.iter().map(|row| row.ray).collect();
    let mut extra = ExtraColumns::default();
    let clouds = args.clouds.on == Some(true);
    let (solar_irradiance, results) = match (place(args)?, clouds) {
        (Some(_), true) if args.terrain => anyhow::bail!(
            "--clouds and --terrain together are not supported: the cloud layer's rays have no relief"
        ),
        (Some(place), false) => {
            probe_terrain::evaluate(model, &atmosphere, &settings, &rays, &place)?
        }
        (Some(place), true) => {
            let (solar, results, columns) =
                probe_clouds::evaluate(model, &atmosphere, &settings, &rays, &place, args)?;
            extra = columns;
            (solar, results)
        }
        (None, _) => {
            let model = prepare(model, &atmosphere, &settings)?;
            let solar = model.solar_irradiance_w_m2_nm().to_vec();
            (solar, evaluate(model.as_ref(), &input.rows))
        }
    };
    let results = results
        .into_iter()
        .zip(&input.rows)
        .map(|(result, row)| {
            result.map_err(|reason| InputError::Ray {
                file: file.clone(),
                line: row.line,
                reason,
            })
        })
        .collect::<Result<Vec<_>, _>>()?;

    let labels: Vec<&str> = args.wavelengths.iter().map(|w| w.label.as_str()).collect();
    let table = Table {
        labels: &labels,
        solar_irradiance: &solar_irradiance,
        color: &color,
    };
    let fields: Vec<&[String]> = input.rows.iter().map(|row| &row.fields[..]).collect();
    let text = table.write(&input.header, &fields, &results, &extra)?;
    match &args.output {
        Some(path) => write_atomically(path, &text),
        None => Ok(std::io::stdout().lock().write_all(&text)?),
    }
}

/// The place of `--terrain` or `--clouds`, checked, or `None` without either.
fn place(args: &ProbeArgs) -> anyhow::Result<Option<TerrainPlace>> {
    let option = if args.terrain {
        "--terrain"
    } else {
        "--clouds"
    };
    let needed = args.terrain || args.clouds.on == Some(true);
    match (
        needed,
        args.latitude_deg,
        args.longitude_deg,
        args.sun_azimuth_deg,
    ) {
        (true, Some(lat), Some(lon), Some(azimuth)) => {
            Ok(Some(TerrainPlace::new(lat, lon, azimuth)?))
        }
        (true, ..) => {
            anyhow::bail!("{option} needs --latitude-deg, --longitude-deg and --sun-azimuth-deg")
        }
        (false, None, None, None) => Ok(None),
        (false, ..) => anyhow::bail!(
            "--latitude-deg, --longitude-deg and --sun-azimuth-deg place the rays of --terrain \
             or --clouds, and neither is given"
        ),
    }
}

/// The radiance of every row, in parallel, in the order of the rows.
fn evaluate(model: &dyn SkyModel, rows: &[ProbeRow]) -> Vec<Result<RayRadiance, ModelError>> {
    map_with_progress("probe", "rays", rows, |row| model.radiance(&row.ray))
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6_360_000.0;

    fn read(text: &str) -> Result<ProbeInput, InputError> {
        read_rays(text, "rays.csv", R)
    }

    #[test]
    fn reads_columns_in_any_order_with_comments() {
        let input = read(
            "# a comment\n\
             sun_zenith_deg, altitude_m ,view_sun_azimuth_deg,view_zenith_deg\n\
             30,0,0,0\n\
             # another\n\
             \n\
             95.5,1000,180,90\n",
        )
        .unwrap();
        assert_eq!(
            input.header,
            [
                "sun_zenith_deg",
                "altitude_m",
                "view_sun_azimuth_deg",
                "view_zenith_deg"
            ]
        );
        assert_eq!(input.rows.len(), 2);
        assert_eq!(input.rows[1].fields, ["95.5", "1000", "180", "90"]);
        assert_eq!(input.rows[1].line, 6);
        let ray = input.rows[1].ray;
        let expected = ViewRay::from_angles(R, 1000.0, 90.0, 95.5, 180.0, None).unwrap();
        assert_eq!(ray, expected);
    }

    #[test]
    fn shipped_example_reads() {
        let text = include_str!("../../../assets/probe/example_rays.csv");
        let input = read_rays(text, "example_rays.csv", R).unwrap();
        assert_eq!(input.rows.len(), 8);
        assert_eq!(input.rows[7].ray.max_distance_m, Some(5000.0));
    }

    #[test]
    fn empty_or_absent_distance_means_no_object() {
        let input = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg,distance_m\n\
             0,90,60,0,\n\
             0,90,60,0,5000\n",
        )
        .unwrap();
        assert_eq!(input.rows[0].ray.max_distance_m, None);
        assert_eq!(input.rows[1].ray.max_distance_m, Some(5000.0));
        assert_eq!(input.rows[0].fields[4], "");
    }

    #[test]
    fn missing_column_is_named() {
        let err = read("altitude_m,view_zenith_deg,view_sun_azimuth_deg\n0,0,0\n").unwrap_err();
        assert!(matches!(&err, InputError::MissingColumns { columns, .. }
            if columns == &["sun_zenith_deg"]));
        assert!(
            err.to_string()
                .contains("missing column(s) 'sun_zenith_deg'")
        );
    }

    #[test]
    fn unknown_column_is_named() {
        let err = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg,label,x\n\
             0,0,0,0,noon,1\n",
        )
        .unwrap_err();
        assert!(matches!(&err, InputError::UnknownColumns { columns, .. }
            if columns == &["label", "x"]));
        assert!(err.to_string().contains("unknown column(s) 'label', 'x'"));
    }

    #[test]
    fn repeated_column_is_an_error() {
        let err = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg,altitude_m\n\
             0,0,0,0,0\n",
        )
        .unwrap_err();
        assert!(matches!(&err, InputError::RepeatedColumns { columns, .. }
            if columns == &["altitude_m"]));
    }

    #[test]
    fn wrong_field_count_names_the_line() {
        let err = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n\
             0,0,0,0\n\
             0,0,0\n",
        )
        .unwrap_err();
        assert!(matches!(
            err,
            InputError::FieldCount {
                line: 3,
                expected: 4,
                found: 3,
                ..
            }
        ));
        assert_eq!(
            err.to_string(),
            "rays.csv line 3: 3 fields, but the header has 4"
        );
    }

    #[test]
    fn bad_number_names_line_and_column() {
        let err = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n\
             0,0,0,0\n\
             0,0,0,0\n\
             0,0,abc,0\n",
        )
        .unwrap_err();
        assert_eq!(
            err.to_string(),
            "rays.csv line 4, column sun_zenith_deg: 'abc' is not a number"
        );
        let err = read("altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n,0,0,0\n")
            .unwrap_err();
        assert!(matches!(
            err,
            InputError::NotANumber {
                line: 2,
                column: "altitude_m",
                ..
            }
        ));
    }

    #[test]
    fn angles_outside_their_ranges_name_line_and_column() {
        let header = "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg\n";
        let err = |row: &str| read(&format!("{header}{row}\n")).unwrap_err().to_string();
        assert_eq!(
            err("0,-5,0,0"),
            "rays.csv line 2, column view_zenith_deg: -5 must be in [0, 180] degrees"
        );
        assert_eq!(
            err("0,1000,0,0"),
            "rays.csv line 2, column view_zenith_deg: 1000 must be in [0, 180] degrees"
        );
        assert_eq!(
            err("0,0,180.5,0"),
            "rays.csv line 2, column sun_zenith_deg: 180.5 must be in [0, 180] degrees"
        );
        assert_eq!(
            err("0,0,0,-400"),
            "rays.csv line 2, column view_sun_azimuth_deg: -400 must be in [-360, 360] degrees"
        );
        assert_eq!(
            err("1e11,0,0,0"),
            "rays.csv line 2, column altitude_m: 1e11 must be at most 1e10 m"
        );
        assert!(read(&format!("{header}0,180,0,-360\n")).is_ok());
    }

    #[test]
    fn ray_the_model_rejects_names_the_line() {
        let err = read(
            "altitude_m,view_zenith_deg,sun_zenith_deg,view_sun_azimuth_deg,distance_m\n\
             -5,0,0,0,\n",
        )
        .unwrap_err();
        assert!(matches!(err, InputError::Ray { line: 2, .. }));
        let message = err.to_string();
        assert!(message.starts_with("rays.csv line 2: ") && message.contains("altitude_m"));
    }
}
