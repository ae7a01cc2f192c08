//! `errors.csv`: each model setting's error on each report view beside its frame times,
//! small and machine-readable, for the viewer's model panel (which embeds it).
//!
//! Columns: `model`, `setting` (the setting's `key=value` items, `orders=N` first; empty
//! for the paper's values), `view` (a report view's id), `rms_percent` (relative RMS
//! luminance error over the rays the report judges; empty where the reference is not
//! converged on any ray of the view), `max_percent` (the largest relative error of those
//! rays; empty where `rms_percent` is), `gpu_ms` (a 1280 x 720 frame on the report's GPU adapter; empty
//! where not measured), `cpu_frame_s` (the same frame on one CPU thread).

use anyhow::{Context, bail};
use atmosphere_core::models::id::ModelId;

use crate::report::measure::VariantResult;
use crate::report::views::ReportView;

/// The header line.
const HEADER: &str = "model,setting,view,rms_percent,max_percent,gpu_ms,cpu_frame_s";

/// One setting on one view.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorRow {
    pub model: ModelId,
    /// `key=value` items separated by spaces; empty for the paper's values.
    pub setting: String,
    pub view: String,
    /// `None` where the report judged no ray of the view (`judged_rays.rs`).
    pub rms_percent: Option<f64>,
    /// The largest relative error of the judged rays; `None` with `rms_percent`.
    pub max_percent: Option<f64>,
    pub gpu_ms: Option<f64>,
    pub cpu_frame_s: f64,
}

/// The rows of `results`, setting by setting, view by view.
pub fn rows(results: &[VariantResult], views: &[ReportView]) -> Vec<ErrorRow> {
    let mut rows = Vec::new();
    for r in results {
        let label = r.variant.label();
        let setting = label
            .strip_prefix(r.variant.model.as_str())
            .unwrap_or_default()
            .trim()
            .to_string();
        for (i, (view, result)) in views.iter().zip(&r.views).enumerate() {
            rows.push(ErrorRow {
                model: r.variant.model,
                setting: setting.clone(),
                view: view.id.to_string(),
                rms_percent: (result.luminance.count > 0).then_some(100.0 * result.luminance.rms),
                max_percent: (result.luminance.count > 0).then_some(100.0 * result.luminance.max),
                gpu_ms: r.gpu.as_ref().and_then(|g| g.per_view_ms.get(i).copied()),
                cpu_frame_s: result.frame_seconds(),
            });
        }
    }
    rows
}

/// The CSV text of `rows`.
pub fn to_csv(rows: &[ErrorRow]) -> String {
    let mut text = format!("{HEADER}\n");
    for r in rows {
        text.push_str(&format!(
            "{},{},{},{},{},{},{:.4}\n",
            r.model,
            r.setting,
            r.view,
            percent(r.rms_percent),
            percent(r.max_percent),
            r.gpu_ms.map_or_else(String::new, |ms| format!("{ms:.2}")),
            r.cpu_frame_s
        ));
    }
    text
}

/// A percentage to three decimals; empty for `None`.
fn percent(value: Option<f64>) -> String {
    value.map_or_else(String::new, |p| format!("{p:.3}"))
}

/// Reads the CSV; a malformed line is an error naming it.
pub fn parse(text: &str) -> anyhow::Result<Vec<ErrorRow>> {
    let mut lines = text.lines();
    if lines.next() != Some(HEADER) {
        bail!("the error table's first line is not \"{HEADER}\"");
    }
    lines
        .enumerate()
        .map(|(n, line)| {
            let at = || format!("error table line {}", n + 2);
            let fields: Vec<&str> = line.split(',').collect();
            let [model, setting, view, rms, max, gpu, cpu] = fields[..] else {
                bail!("{}: {} fields, expected 7", at(), fields.len());
            };
            let number = |text: &str| text.parse::<f64>().with_context(at);
            let optional = |text: &str| {
                if text.is_empty() {
                    Ok(None)
                } else {
                    number(text).map(Some)
                }
            };
            Ok(ErrorRow {
                model: model
                    .parse()
                    .map_err(|_| anyhow::anyhow!("{}: no model '{model}'", at()))?,
                setting: setting.to_string(),
                view: view.to_string(),
                rms_percent: optional(rms)?,
                max_percent: optional(max)?,
                gpu_ms: optional(gpu)?,
                cpu_frame_s: number(cpu)?,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_names_a_bad_line() {
        let rows = vec![
            ErrorRow {
                model: ModelId::Bruneton,
                setting: "orders=2 view_samples=30".into(),
                view: "noon".into(),
                rms_percent: Some(6.5),
                max_percent: Some(14.125),
                gpu_ms: Some(12.25),
                cpu_frame_s: 0.37,
            },
            ErrorRow {
                model: ModelId::Riley,
                setting: String::new(),
                view: "nautical".into(),
                rms_percent: None,
                max_percent: None,
                gpu_ms: None,
                cpu_frame_s: 0.47,
            },
        ];
        assert_eq!(parse(&to_csv(&rows)).unwrap(), rows);
        let bad = to_csv(&rows).replace("12.25", "fast");
        let e = format!("{:#}", parse(&bad).unwrap_err());
        assert!(e.contains("line 2"), "{e}");
        let e = format!("{:#}", parse("model,view\n").unwrap_err());
        assert!(e.contains("first line"), "{e}");
    }
}
