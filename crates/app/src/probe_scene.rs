//! `atmos probe --scene FILE.toml`: the radiance of view rays in a beams scene for one
//! beam method, CSV in and out (docs/beams.md).
//!
//! Input: a header naming the columns `origin_x_m`, `origin_y_m`, `origin_z_m`, `dir_x`,
//! `dir_y`, `dir_z` and optionally `distance_m` (any order; an empty distance: the ray
//! runs to the first occluder or until the medium has extinguished it), in the scene's
//! frame, then one ray per line; lines starting with `#` are comments. Output: the input
//! columns as given, then `L_<nm>` per wavelength (W m^-2 sr^-1 nm^-1), then
//! `luminance_cd_m2`.

use std::io::Write;
use std::path::Path;

use anyhow::Context;
use atmosphere_core::atmosphere::text_file::read_text;
use atmosphere_core::beams::error::BeamError;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::options::ModelOptions;
use glam::DVec3;
use thiserror::Error;

use crate::csv_lines::{record_fields, record_lines};
use crate::files::{check_writable, write_atomically};
use crate::probe::CSV_LIMITS;
use crate::probe_args::ProbeArgs;
use crate::probe_table::number;
use crate::progress::map_with_progress;

/// The columns every scene input needs.
pub const SCENE_COLUMNS: [&str; 6] = [
    "origin_x_m",
    "origin_y_m",
    "origin_z_m",
    "dir_x",
    "dir_y",
    "dir_z",
];

/// The optional column: the distance to an object ending the ray.
pub const DISTANCE_COLUMN: &str = "distance_m";

/// What is wrong with a scene probe's input file. Lines count from 1.
#[derive(Debug, Error)]
pub enum SceneInputError {
    #[error("{file} has no header line (expected {})", SCENE_COLUMNS.join(","))]
    NoHeader { file: String },
    #[error("{file} line {line}: {reason}")]
    Csv {
        file: String,
        line: u64,
        reason: csv::Error,
    },
    #[error(
        "{file} line {line}: the header must name each of {} once, and optionally {DISTANCE_COLUMN}, and nothing else (found {found})",
        SCENE_COLUMNS.join(", ")
    )]
    Header {
        file: String,
        line: u64,
        found: String,
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
        column: String,
        value: String,
    },
    #[error("{file} line {line}: {reason}")]
    Ray {
        file: String,
        line: u64,
        reason: Box<BeamError>,
    },
}

/// One ray of an input file with its fields as given.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneRow {
    pub line: u64,
    pub fields: Vec<String>,
    pub ray: SceneRay,
}

/// Reads the rays of CSV `text` named `file` in messages.
pub fn read_scene_rays(
    text: &str,
    file: &str,
) -> Result<(Vec<String>, Vec<SceneRow>), SceneInputError> {
    let mut records = record_lines(text);
    let fields = |line: u64, text: &str| -> Result<Vec<String>, SceneInputError> {
        record_fields(text).map_err(|reason| SceneInputError::Csv {
            file: file.to_string(),
            line,
            reason,
        })
    };
    let Some((header_line, header_text)) = records.next() else {
        return Err(SceneInputError::NoHeader {
            file: file.to_string(),
        });
    };
    let header = fields(header_line, header_text)?;
    let index = |name: &str| header.iter().position(|h| h == name);
    let mut expected: Vec<&str> = SCENE_COLUMNS.to_vec();
    if index(DISTANCE_COLUMN).is_some() {
        expected.push(DISTANCE_COLUMN);
    }
    let mut sorted_header: Vec<&str> = header.iter().map(String::as_str).collect();
    sorted_header.sort_unstable();
    expected.sort_unstable();
    if sorted_header != expected {
        return Err(SceneInputError::Header {
            file: file.to_string(),
            line: header_line,
            found: header.join(","),
        });
    }
    let columns = SCENE_COLUMNS.map(|c| index(c).unwrap_or_default());
    let distance = index(DISTANCE_COLUMN);
    let mut rows = Vec::new();
    for (line, text) in records {
        let record = fields(line, text)?;
        if record.len() != header.len() {
            return Err(SceneInputError::FieldCount {
                file: file.to_string(),
                line,
                expected: header.len(),
                found: record.len(),
            });
        }
        let number = |i: usize| {
            record[i]
                .parse::<f64>()
                .map_err(|_| SceneInputError::NotANumber {
                    file: file.to_string(),
                    line,
                    column: header[i].clone(),
                    value: record[i].clone(),
                })
        };
        let mut v = [0.0; 6];
        for (value, &i) in v.iter_mut().zip(&columns) {
            *value = number(i)?;
        }
        let distance_m = match distance {
            Some(i) if !record[i].is_empty() => Some(number(i)?),
            _ => None,
        };
        let ray = SceneRay::new(
            DVec3::new(v[0], v[1], v[2]),
            DVec3::new(v[3], v[4], v[5]),
            distance_m,
        )
        .map_err(|reason| SceneInputError::Ray {
            file: file.to_string(),
            line,
            reason: Box::new(reason),
        })?;
        rows.push(SceneRow {
            line,
            fields: record,
            ray,
        });
    }
    Ok((header, rows))
}

/// Runs `atmos probe --scene`.
pub fn run(args: &ProbeArgs, scene_path: &Path) -> anyhow::Result<()> {
    if let Some(path) = &args.output {
        check_writable(path)?;
    }
    let method: BeamMethodId = args.model.parse().with_context(|| {
        format!(
            "--model {} is a sky model; with --scene the beam methods are {}",
            args.model,
            BeamMethodId::list(&BeamMethodId::ALL)
        )
    })?;
    let settings = BeamSettings {
        wavelengths_nm: args.wavelengths.iter().map(|w| w.nm).collect(),
        options: ModelOptions::parse(&args.set)?,
    };
    let color = SpectrumToColor::new(&settings.wavelengths_nm)?;
    let scene = BeamScene::load(scene_path)?;
    let file = args.input.display().to_string();
    let text = read_text(&args.input, CSV_LIMITS)?;
    let (header, rows) = read_scene_rays(&text, &file)?;
    let prepared = prepare(method, &scene, &settings)?;
    let radiance = evaluate(prepared.as_ref(), &rows)
        .into_iter()
        .zip(&rows)
        .map(|(r, row)| {
            r.map_err(|reason| SceneInputError::Ray {
                file: file.clone(),
                line: row.line,
                reason: Box::new(reason),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;

    let mut out = csv::Writer::from_writer(Vec::new());
    let mut columns = header;
    columns.extend(args.wavelengths.iter().map(|w| format!("L_{}", w.label)));
    columns.push("luminance_cd_m2".into());
    out.write_record(&columns)?;
    for (row, l) in rows.iter().zip(&radiance) {
        let mut record = row.fields.clone();
        record.extend(l.iter().map(|&x| number(x)));
        record.push(number(color.luminance_cd_m2(l)));
        out.write_record(&record)?;
    }
    let text = out.into_inner()?;
    match &args.output {
        Some(path) => write_atomically(path, &text),
        None => Ok(std::io::stdout().lock().write_all(&text)?),
    }
}

/// The radiance of every row, in parallel, in the order of the rows.
fn evaluate(method: &dyn BeamMethod, rows: &[SceneRow]) -> Vec<Result<Vec<f64>, BeamError>> {
    map_with_progress("probe", "rays", rows, |row| method.radiance(&row.ray))
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "origin_x_m,origin_y_m,origin_z_m,dir_x,dir_y,dir_z";

    #[test]
    fn reads_columns_in_any_order_with_an_optional_distance() {
        let text = "# rays\ndir_z,dir_y,dir_x,origin_z_m,origin_y_m,origin_x_m,distance_m\n\
                    -1,0,0,10,2,0,\n0,0,2,0,0,0,5\n";
        let (header, rows) = read_scene_rays(text, "r.csv").unwrap();
        assert_eq!(header[0], "dir_z");
        assert_eq!(rows[0].ray.origin_m, DVec3::new(0.0, 2.0, 10.0));
        assert_eq!(rows[0].ray.direction, DVec3::NEG_Z);
        assert_eq!(rows[0].ray.max_distance_m, None);
        assert_eq!(rows[1].ray.direction, DVec3::X);
        assert_eq!(rows[1].ray.max_distance_m, Some(5.0));
        assert_eq!(rows[1].line, 4);
    }

    #[test]
    fn bad_input_names_the_line_and_the_column() {
        let err = |text: &str| read_scene_rays(text, "r.csv").unwrap_err().to_string();
        assert!(err("origin_x_m,dir_x\n0,1\n").contains("line 1: the header must name"));
        assert!(err(&format!("{HEADER},label\n0,0,0,1,0,0,a\n")).contains("found origin_x_m"));
        assert_eq!(
            err(&format!("{HEADER}\n0,0,0,1,0,zero\n")),
            "r.csv line 2, column dir_z: 'zero' is not a number"
        );
        assert!(
            err(&format!("{HEADER}\n0,0,0,0,0,0\n"))
                .starts_with("r.csv line 2: invalid ray: direction")
        );
        assert!(err(&format!("{HEADER},distance_m\n0,0,0,1,0,0,-3\n")).contains("distance_m -3"));
        assert!(err(&format!("{HEADER}\n0,0,0\n")).contains("3 fields, but the header has 6"));
        assert!(err("").contains("no header"));
    }
}
