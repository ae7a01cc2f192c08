//! The reference radiance of every ray of the report's views, computed once and kept in
//! `reference.csv` beside the report: the reference takes minutes, the models seconds, so
//! regenerating the report after a model changes reuses it. A fingerprint of the views,
//! their atmospheres and the reference's settings says when it is stale.

use std::fs;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use rayon::prelude::*;

use crate::files::write_atomically;
use crate::progress::Progress;
use crate::report::views::ReportView;

/// The reference's answers, per view, per ray.
pub type ReferenceRadiance = Vec<Vec<RayRadiance>>;

/// A stable 64-bit hash (FNV-1a) of everything the reference's answers depend on.
pub fn fingerprint(views: &[ReportView], settings: &ModelSettings) -> anyhow::Result<String> {
    let mut text = format!("{settings:?}");
    for view in views {
        let atmosphere = Atmosphere::preset(view.atmosphere)?;
        text.push_str(&format!("{view:?}{atmosphere:?}"));
    }
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    Ok(format!("{hash:016x}"))
}

/// Reads the cache at `path` if it holds exactly these views and settings; else computes
/// the reference (in parallel, with progress) and writes the cache.
pub fn load_or_compute(
    path: &Path,
    views: &[ReportView],
    settings: &ModelSettings,
    recompute: bool,
) -> anyhow::Result<ReferenceRadiance> {
    let key = fingerprint(views, settings)?;
    if !recompute && path.exists() {
        match read(path, views, settings.wavelengths_nm.len(), &key) {
            Ok(reference) => {
                eprintln!("report: reference radiance from {}", path.display());
                return Ok(reference);
            }
            Err(why) => eprintln!("report: recomputing the reference ({why:#})"),
        }
    }
    let reference = compute(views, settings)?;
    write(path, &reference, views, &key)?;
    Ok(reference)
}

fn compute(views: &[ReportView], settings: &ModelSettings) -> anyhow::Result<ReferenceRadiance> {
    let total = views.iter().map(|v| v.columns * v.rows).sum::<usize>();
    let progress = Progress::new("reference", "rays", total as u64);
    let mut all = Vec::with_capacity(views.len());
    for view in views {
        let atmosphere = Atmosphere::preset(view.atmosphere)?;
        let model = prepare(ModelId::Reference, &atmosphere, settings)?;
        let answers = view
            .rays(&atmosphere)
            .par_iter()
            .map(|ray| {
                let answer = model.radiance(ray);
                progress.inc();
                answer
            })
            .collect::<Result<Vec<_>, _>>()
            .with_context(|| format!("reference on view {}", view.id))?;
        all.push(answers);
    }
    progress.finish();
    Ok(all)
}

fn header(wavelengths: usize) -> String {
    let mut columns = vec!["view".to_string(), "ray".to_string()];
    for prefix in ["L", "T", "stderr"] {
        columns.extend((0..wavelengths).map(|w| format!("{prefix}_{w}")));
    }
    columns.join(",")
}

fn write(
    path: &Path,
    reference: &ReferenceRadiance,
    views: &[ReportView],
    key: &str,
) -> anyhow::Result<()> {
    let wavelengths = reference
        .first()
        .and_then(|v| v.first())
        .map_or(0, |r| r.radiance.len());
    let mut text = format!(
        "# atmos report reference radiance, fingerprint {key}\n{}\n",
        header(wavelengths)
    );
    for (view, answers) in views.iter().zip(reference) {
        for (i, a) in answers.iter().enumerate() {
            let numbers = a
                .radiance
                .iter()
                .chain(&a.transmittance)
                .chain(&a.radiance_std_error)
                .map(|x| format!("{x:e}"));
            let fields: Vec<String> = [view.id.to_string(), i.to_string()]
                .into_iter()
                .chain(numbers)
                .collect();
            text.push_str(&fields.join(","));
            text.push('\n');
        }
    }
    write_atomically(path, text.as_bytes())
}

fn read(
    path: &Path,
    views: &[ReportView],
    wavelengths: usize,
    key: &str,
) -> anyhow::Result<ReferenceRadiance> {
    let text = fs::read_to_string(path)?;
    let mut lines = text.lines();
    let first = lines.next().unwrap_or_default();
    if !first.ends_with(&format!("fingerprint {key}")) {
        bail!("views or settings changed since it was computed");
    }
    if lines.next() != Some(header(wavelengths).as_str()) {
        bail!("unexpected header");
    }
    let mut reference: ReferenceRadiance = views.iter().map(|_| Vec::new()).collect();
    for (n, line) in lines.enumerate() {
        let fields: Vec<&str> = line.split(',').collect();
        let bad = || format!("{} line {}", path.display(), n + 3);
        if fields.len() != 2 + 3 * wavelengths {
            bail!("{}: {} fields", bad(), fields.len());
        }
        let v = views
            .iter()
            .position(|v| v.id == fields[0])
            .with_context(|| format!("{}: unknown view {}", bad(), fields[0]))?;
        let numbers = fields[2..]
            .iter()
            .map(|f| f.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(bad)?;
        reference[v].push(RayRadiance {
            radiance: numbers[..wavelengths].to_vec(),
            transmittance: numbers[wavelengths..2 * wavelengths].to_vec(),
            radiance_std_error: numbers[2 * wavelengths..].to_vec(),
        });
    }
    for (view, answers) in views.iter().zip(&reference) {
        if answers.len() != view.columns * view.rows {
            bail!("view {} has {} rays", view.id, answers.len());
        }
    }
    Ok(reference)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::views::report_views;

    #[test]
    fn round_trips_and_notices_a_change_of_views() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let views = report_views(2, 1);
        let settings = ModelSettings::default();
        let reference: ReferenceRadiance = views
            .iter()
            .enumerate()
            .map(|(v, _)| {
                (0..2)
                    .map(|i| RayRadiance {
                        radiance: vec![0.1 * v as f64 + 1e-9 * i as f64; 3],
                        transmittance: vec![0.5; 3],
                        radiance_std_error: vec![1e-4; 3],
                    })
                    .collect()
            })
            .collect();
        let key = fingerprint(&views, &settings).unwrap();
        write(&path, &reference, &views, &key).unwrap();
        assert_eq!(read(&path, &views, 3, &key).unwrap(), reference);

        let other = report_views(3, 1);
        let other_key = fingerprint(&other, &settings).unwrap();
        assert_ne!(key, other_key);
        let e = read(&path, &other, 3, &other_key).unwrap_err();
        assert!(e.to_string().contains("changed"), "{e}");
    }
}
