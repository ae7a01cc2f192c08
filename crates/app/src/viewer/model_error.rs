//! The model panel's error line: the selected model's measured error on the report view
//! nearest to the current camera, beside its GPU frame time, from the report's
//! `errors.csv` embedded at compile time (docs/report/).
//!
//! Nearest view: among the report views of the current atmosphere preset (the Earth's
//! views for a preset the report has none of), the one with the smallest
//! |log10((h + 1 km) / (h_view + 1 km))| + |sun zenith - sun zenith_view| / 10°, where h is
//! the camera's altitude: a decade of altitude counts as much as 10 degrees of sun.

use std::sync::LazyLock;

use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;

use crate::report::error_table::{self, ErrorRow};
use crate::report::views::{ReportView, report_views};

/// The report's table, as committed.
const ERRORS_CSV: &str = include_str!("../../../../docs/report/errors.csv");

/// The embedded table, parsed once.
static TABLE: LazyLock<Result<Vec<ErrorRow>, String>> =
    LazyLock::new(|| error_table::parse(ERRORS_CSV).map_err(|e| format!("{e:#}")));

/// The report's views (their ids and geometry do not depend on the ray grid).
static VIEWS: LazyLock<Vec<ReportView>> = LazyLock::new(|| report_views(1, 1));

/// Altitude below which heights count alike in the distance, m.
const ALTITUDE_SCALE_M: f64 = 1_000.0;
/// Sun zenith angle that counts as much as a decade of altitude, degrees.
const SUN_ZENITH_SCALE_DEG: f64 = 10.0;

/// Where the camera is, as the nearest view is chosen by it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Situation<'a> {
    pub preset: &'a str,
    pub altitude_m: f64,
    pub sun_zenith_deg: f64,
}

/// The view of `views` nearest to `at` (see the module's documentation); `None` when
/// there is no view of the preset nor of the Earth.
pub fn nearest_view<'v>(views: &'v [ReportView], at: &Situation) -> Option<&'v ReportView> {
    let preset = if views.iter().any(|v| v.atmosphere == at.preset) {
        at.preset
    } else {
        "earth"
    };
    let distance = |v: &ReportView| {
        let altitude = ((at.altitude_m.max(0.0) + ALTITUDE_SCALE_M)
            / (v.altitude_m + ALTITUDE_SCALE_M))
            .log10()
            .abs();
        altitude + (at.sun_zenith_deg - v.sun_zenith_deg).abs() / SUN_ZENITH_SCALE_DEG
    };
    views
        .iter()
        .filter(|v| v.atmosphere == preset)
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
}

/// The setting of a row as options (`orders=N` among them, as no model reads it).
fn setting_options(row: &ErrorRow) -> Option<ModelOptions> {
    let items: Vec<&str> = row.setting.split_whitespace().collect();
    ModelOptions::parse(&items).ok()
}

/// "1.6 % (largest 4.2 %) on ground, noon · 12 ms GPU" for `model` with `options` on `view`: the row of
/// the report setting equal to `options`, else the paper's values (and it says so).
pub fn line_for(
    rows: &[ErrorRow],
    model: ModelId,
    options: &ModelOptions,
    view: &ReportView,
) -> Option<String> {
    let on_view = |r: &&ErrorRow| r.model == model && r.view == view.id;
    let (row, note) = match rows
        .iter()
        .filter(on_view)
        .find(|r| setting_options(r).as_ref() == Some(options))
    {
        Some(row) => (row, ""),
        None => (
            rows.iter().filter(on_view).find(|r| r.setting.is_empty())?,
            " (paper's values)",
        ),
    };
    let gpu = row.gpu_ms.map_or_else(
        || "GPU not measured".to_string(),
        |ms| format!("{ms:.0} ms GPU"),
    );
    let error = match (row.rms_percent, row.max_percent) {
        (Some(rms), Some(max)) => format!("{rms:.1} % (largest {max:.1} %)"),
        (Some(rms), None) => format!("{rms:.1} %"),
        (None, _) => "error unknown (reference not converged)".to_string(),
    };
    Some(format!("{error} on {} · {gpu}{note}", view.title))
}

/// The panel's line for the current model, options and camera.
pub fn line(model: ModelId, options: &ModelOptions, at: &Situation) -> String {
    let rows = match &*TABLE {
        Ok(rows) => rows,
        Err(e) => return format!("no error table: {e}"),
    };
    nearest_view(&VIEWS, at)
        .and_then(|view| line_for(rows, model, options, view))
        .unwrap_or_else(|| format!("{model} is not in the report"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use render_wgpu::sky::registry::GPU_MODELS;

    fn nearest(preset: &str, altitude_m: f64, sun_zenith_deg: f64) -> &'static str {
        let at = Situation {
            preset,
            altitude_m,
            sun_zenith_deg,
        };
        nearest_view(&VIEWS, &at).unwrap().id
    }

    #[test]
    fn the_nearest_view_weighs_a_decade_of_altitude_like_ten_degrees_of_sun() {
        assert_eq!(nearest("earth", 2.0, 30.0), "noon");
        assert_eq!(nearest("earth", 50.0, 40.0), "noon");
        assert_eq!(nearest("earth", 2.0, 88.0), "sunset");
        assert_eq!(nearest("earth", 2.0, 97.0), "twilight");
        assert_eq!(nearest("earth", 2.0, 101.0), "nautical");
        assert_eq!(nearest("earth", 8_000.0, 50.0), "10km");
        assert_eq!(nearest("earth", 150_000.0, 45.0), "100km");
        assert_eq!(nearest("earth", 400_000.0, 60.0), "limb");
        assert_eq!(nearest("earth", 1e7, 70.0), "limb");
        assert_eq!(nearest("earth", 400_000.0, 95.0), "orbit-twilight");
        // The hazy preset has one view; presets without views use the Earth's.
        assert_eq!(nearest("hazy", 400_000.0, 100.0), "hazy");
        assert_eq!(nearest("mars", 2.0, 30.0), "noon");
        assert_eq!(nearest("clear", 2.0, 100.0), "nautical");
    }

    #[test]
    fn the_embedded_table_parses_and_names_every_model_on_every_view() {
        let rows = TABLE.as_ref().unwrap();
        for model in GPU_MODELS {
            for view in VIEWS.iter() {
                let line = line_for(rows, model, &ModelOptions::default(), view);
                let line = line.unwrap_or_else(|| panic!("{model} on {}", view.id));
                assert!(line.contains(view.title), "{line}");
            }
        }
    }

    #[test]
    fn a_report_setting_is_matched_else_the_papers_values_are_shown() {
        let view = &VIEWS[0];
        let row = |setting: &str, rms| ErrorRow {
            model: ModelId::Nishita,
            setting: setting.into(),
            view: view.id.into(),
            rms_percent: Some(rms),
            max_percent: Some(2.0 * rms),
            gpu_ms: Some(12.0),
            cpu_frame_s: 1.0,
        };
        let rows = [row("", 27.2), row("samples=16", 27.8)];
        let options = |items: &[&str]| ModelOptions::parse(items).unwrap();
        assert_eq!(
            line_for(&rows, ModelId::Nishita, &options(&["samples=16"]), view).unwrap(),
            "27.8 % (largest 55.6 %) on ground, noon · 12 ms GPU"
        );
        assert_eq!(
            line_for(&rows, ModelId::Nishita, &options(&["samples=7"]), view).unwrap(),
            "27.2 % (largest 54.4 %) on ground, noon · 12 ms GPU (paper's values)"
        );
        assert_eq!(line_for(&rows, ModelId::Riley, &options(&[]), view), None);
    }
}
