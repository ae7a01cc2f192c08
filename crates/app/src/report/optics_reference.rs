//! The path-traced reference of every ray of the optics section's views, computed once
//! and kept in `optics_reference.csv` beside the report, as the clouds section keeps
//! its own (`clouds_reference.rs`). Each view's rows carry a fingerprint of the view
//! (its rays' angles, the path tracer's stopping rule), of its scene file's text, of
//! the reference's tables and of [`REFERENCE_VERSION`], so that a changed view, scene
//! or path tracer computes that view again.
//!
//! The file: a title line, the column header (`view, ray`, then per channel the
//! radiance `L_c`, the whole ray's transmittance `T_c`, the radiance's standard error
//! `stderr_c` and the volume's light seen from the camera in three parts: the sun's
//! single scattering `sun_single_c`, its higher orders `sun_multiple_c`, the sky's
//! light `sky_c`; then `T_volume`, `paths`), then per view a line
//! `# view <id> fingerprint <16 hex digits>` followed by its rays in order.

use std::path::Path;

use anyhow::Context;
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::reference::path::PathLight;
use atmosphere_core::hydrometeors::reference::ray::VolumeTracedRay;
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::models::sky_model::RayRadiance;

use crate::cloud_rays::CloudAnswer;
use crate::progress::Progress;
use crate::report::optics_scene::{OpticsScene, Tables};
use crate::report::view_sections::{self, RayRow, Wanted, fingerprint_of};

/// The reference's answers, per view, per ray.
pub type OpticsReference = Vec<Vec<VolumeTracedRay>>;

/// The tables the reference traces with: the shipped scenes' (32 wavelengths, the sun's
/// disc), reduced to the frame's three wavelengths as the renderer reduces them.
pub const REFERENCE_TABLES: Tables = Tables {
    wavelengths: 32,
    sun_disc: true,
};
/// Raised whenever the path tracer changes what it answers (`hydrometeors/reference/`).
pub const REFERENCE_VERSION: u32 = 2;

const TITLE: &str =
    "# atmos report optics: path-traced reference radiance, one fingerprint per view";
const PARTS: [&str; 6] = ["L", "T", "stderr", "sun_single", "sun_multiple", "sky"];

/// A stable 64-bit hash (FNV-1a) of what a view's reference depends on.
pub fn fingerprint(scene: &OpticsScene) -> String {
    let text = format!(
        "{:?}{}{:?}{REFERENCE_VERSION}",
        scene.view, scene.scene_text, REFERENCE_TABLES
    );
    fingerprint_of(&text)
}

/// A traced ray as the errors compare it.
pub fn as_answer(ray: &VolumeTracedRay) -> CloudAnswer {
    CloudAnswer {
        radiance: ray.radiance.clone(),
        cloud_transmittance: ray.volume_transmittance,
        paths: Some(ray.paths),
    }
}

/// The views of the cache at `path` whose fingerprint matches and that `recompute`
/// does not name; the others computed (their rays in parallel) and the cache written
/// after each.
pub fn load_or_compute(
    path: &Path,
    scenes: &[OpticsScene],
    recompute: impl Fn(&OpticsScene) -> bool,
) -> anyhow::Result<OpticsReference> {
    let keys: Vec<String> = scenes.iter().map(fingerprint).collect();
    let wanted: Vec<Wanted> = scenes
        .iter()
        .zip(&keys)
        .map(|(scene, key)| Wanted {
            id: scene.view.id,
            fingerprint: key,
            rays: scene.rays.len(),
            recompute: recompute(scene),
        })
        .collect();
    let (mut reference, missing) = view_sections::cached(path, TITLE, &header(), &wanted);
    if missing.is_empty() {
        eprintln!("report: optics reference from {}", path.display());
        return Ok(reference);
    }
    let total: usize = missing.iter().map(|&i| scenes[i].rays.len()).sum();
    let progress = Progress::new("optics reference", "rays", total as u64);
    for &i in &missing {
        let scene = &scenes[i];
        // The whole table (the path tracer truncates it) and its own light around the
        // volume (the march's sky light and probes are not read).
        let lit = scene.lit(
            REFERENCE_TABLES,
            (
                ForwardPeak::Extinction,
                SkyLight::Horizontal,
                MultipleScattering::None,
            ),
        )?;
        reference[i] = scene
            .reference(&lit, &scene.view.paths, &progress)
            .with_context(|| format!("optics reference on view {}", scene.view.id))?;
        // Written after each view, so an interrupted run keeps what it finished.
        write(path, &reference, scenes, &keys)?;
    }
    progress.finish();
    Ok(reference)
}

fn header() -> String {
    let mut columns = vec!["view".to_string(), "ray".to_string()];
    for prefix in PARTS {
        columns.extend((0..3).map(|c| format!("{prefix}_{c}")));
    }
    columns.push("T_volume".into());
    columns.push("paths".into());
    columns.join(",")
}

fn write(
    path: &Path,
    reference: &[Vec<VolumeTracedRay>],
    scenes: &[OpticsScene],
    keys: &[String],
) -> anyhow::Result<()> {
    let views = scenes
        .iter()
        .zip(reference)
        .zip(keys)
        .map(|((scene, rays), key)| (scene.view.id, key.as_str(), rays.as_slice()));
    view_sections::write(path, TITLE, &header(), views)
}

impl RayRow for VolumeTracedRay {
    fn numbers(&self) -> Vec<f64> {
        let (r, light) = (&self.radiance, &self.volume_light);
        r.radiance
            .iter()
            .chain(&r.transmittance)
            .chain(&r.radiance_std_error)
            .chain(&light.sun_single)
            .chain(&light.sun_multiple)
            .chain(&light.sky)
            .chain([&self.volume_transmittance])
            .copied()
            .collect()
    }

    fn paths(&self) -> u64 {
        self.paths
    }

    fn from_numbers(numbers: &[f64], paths: u64) -> Self {
        let part = |k: usize| -> [f64; 3] { std::array::from_fn(|c| numbers[3 * k + c]) };
        VolumeTracedRay {
            radiance: RayRadiance {
                radiance: part(0).to_vec(),
                transmittance: part(1).to_vec(),
                radiance_std_error: part(2).to_vec(),
            },
            volume_light: PathLight {
                sun_single: part(3),
                sun_multiple: part(4),
                sky: part(5),
            },
            volume_transmittance: numbers[3 * PARTS.len()],
            paths,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The committed cache reads back and writes out byte for byte as it is.
    #[test]
    fn the_committed_cache_reads_back_and_writes_out_unchanged() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/report/optics_reference.csv");
        let text = std::fs::read_to_string(&path).unwrap();
        let views: view_sections::Sections<VolumeTracedRay> =
            view_sections::read(&path, TITLE, &header()).unwrap();
        assert_eq!(views.len(), 3, "{:?}", views.keys());
        let again = view_sections::rewritten::<VolumeTracedRay>(&path, TITLE, &header()).unwrap();
        assert!(again == text, "the cache changed");
    }
}
