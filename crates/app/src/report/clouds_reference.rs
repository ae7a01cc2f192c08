//! The path-traced reference of every ray of the clouds section's views, computed once
//! and kept in `clouds_reference.csv` beside the report, as the skies section keeps
//! its reference (`reference_cache.rs`): thick clouds are slow to trace. Each view's
//! rows carry a fingerprint of the view (camera, cloud, cover, the path tracer's
//! stopping rule) and of the air model, so that a changed view alone is computed again.
//!
//! The file: a title line, the column header (`view, ray`, the radiance `L_<w>`, the
//! whole ray's transmittance `T_<w>` and the radiance's standard error `stderr_<w>` per
//! wavelength, `T_cloud`, `paths`), then per view a line
//! `# view <id> fingerprint <16 hex digits>` followed by its rays in order.

use std::path::Path;

use anyhow::Context;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use rayon::prelude::*;

use crate::cloud_rays::CloudAnswer;
use crate::probe_clouds::AIR_MODEL;
use crate::progress::Progress;
use crate::report::clouds_scene::ViewScene;
use crate::report::clouds_views::CloudView;
use crate::report::view_sections::{self, RayRow, Wanted, fingerprint_of};

/// The reference's answers, per view, per ray.
pub type CloudReference = Vec<Vec<CloudAnswer>>;

const TITLE: &str =
    "# atmos report clouds: path-traced reference radiance, one fingerprint per view";

/// A stable 64-bit hash (FNV-1a) of what a view's reference depends on.
pub fn fingerprint(view: &CloudView, settings: &ModelSettings) -> String {
    let text = format!(
        "{view:?}{AIR_MODEL}{:?}{:?}",
        settings.wavelengths_nm, settings.options
    );
    fingerprint_of(&text)
}

/// The views of the cache at `path` whose fingerprint matches and that `recompute`
/// does not name; the others computed (their rays in parallel) and the cache written
/// after each.
pub fn load_or_compute(
    path: &Path,
    scenes: &[ViewScene],
    settings: &ModelSettings,
    recompute: impl Fn(&CloudView) -> bool,
) -> anyhow::Result<CloudReference> {
    let waves = settings.wavelengths_nm.len();
    let keys: Vec<String> = scenes
        .iter()
        .map(|s| fingerprint(&s.view, settings))
        .collect();
    let wanted: Vec<Wanted> = scenes
        .iter()
        .zip(&keys)
        .map(|(scene, key)| Wanted {
            id: scene.view.id(),
            fingerprint: key,
            rays: scene.rays.len(),
            recompute: recompute(&scene.view),
        })
        .collect();
    let (mut reference, missing) = view_sections::cached(path, TITLE, &header(waves), &wanted);
    if missing.is_empty() {
        eprintln!("report: clouds reference from {}", path.display());
        return Ok(reference);
    }
    let total: usize = missing.iter().map(|&i| scenes[i].rays.len()).sum();
    let progress = Progress::new("clouds reference", "rays", total as u64);
    for &i in &missing {
        let scene = &scenes[i];
        reference[i] = scene
            .rays
            .par_iter()
            .map(|ray| {
                let answer = scene.reference(ray);
                progress.inc();
                answer
            })
            .collect::<anyhow::Result<Vec<_>>>()
            .with_context(|| format!("clouds reference on view {}", scene.view.id()))?;
        // Written after each view, so an interrupted run keeps what it finished.
        write(path, &reference, scenes, &keys, waves)?;
    }
    progress.finish();
    Ok(reference)
}

fn header(waves: usize) -> String {
    let mut columns = vec!["view".to_string(), "ray".to_string()];
    for prefix in ["L", "T", "stderr"] {
        columns.extend((0..waves).map(|w| format!("{prefix}_{w}")));
    }
    columns.push("T_cloud".into());
    columns.push("paths".into());
    columns.join(",")
}

fn write(
    path: &Path,
    reference: &[Vec<CloudAnswer>],
    scenes: &[ViewScene],
    keys: &[String],
    waves: usize,
) -> anyhow::Result<()> {
    let views = scenes
        .iter()
        .zip(reference)
        .zip(keys)
        .map(|((scene, answers), key)| (scene.view.id(), key.as_str(), answers.as_slice()));
    view_sections::write(path, TITLE, &header(waves), views)
}

impl RayRow for CloudAnswer {
    fn numbers(&self) -> Vec<f64> {
        let r = &self.radiance;
        r.radiance
            .iter()
            .chain(&r.transmittance)
            .chain(&r.radiance_std_error)
            .chain([&self.cloud_transmittance])
            .copied()
            .collect()
    }

    fn paths(&self) -> u64 {
        self.paths.unwrap_or(0)
    }

    fn from_numbers(numbers: &[f64], paths: u64) -> Self {
        let waves = (numbers.len() - 1) / 3;
        CloudAnswer {
            radiance: RayRadiance {
                radiance: numbers[..waves].to_vec(),
                transmittance: numbers[waves..2 * waves].to_vec(),
                radiance_std_error: numbers[2 * waves..3 * waves].to_vec(),
            },
            cloud_transmittance: numbers[3 * waves],
            paths: Some(paths),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed cache reads back and writes out byte for byte as it is, so that
    /// the report keeps its 27 minutes of paths.
    #[test]
    fn the_committed_cache_reads_back_and_writes_out_unchanged() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/report/clouds_reference.csv");
        let text = std::fs::read_to_string(&path).unwrap();
        let views: view_sections::Sections<CloudAnswer> =
            view_sections::read(&path, TITLE, &header(3)).unwrap();
        assert_eq!(views.len(), 4, "{:?}", views.keys());
        let again = view_sections::rewritten::<CloudAnswer>(&path, TITLE, &header(3)).unwrap();
        assert!(again == text, "the cache changed");
    }
}
