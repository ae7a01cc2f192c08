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

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::reference::path::PathLight;
use atmosphere_core::hydrometeors::reference::ray::VolumeTracedRay;
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::models::sky_model::RayRadiance;

use crate::cloud_rays::CloudAnswer;
use crate::files::write_atomically;
use crate::progress::Progress;
use crate::report::optics_scene::{OpticsScene, Tables};

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
const VIEW_MARK: &str = "# view ";
const PARTS: [&str; 6] = ["L", "T", "stderr", "sun_single", "sun_multiple", "sky"];

/// A stable 64-bit hash (FNV-1a) of what a view's reference depends on.
pub fn fingerprint(scene: &OpticsScene) -> String {
    let text = format!(
        "{:?}{}{:?}{REFERENCE_VERSION}",
        scene.view, scene.scene_text, REFERENCE_TABLES
    );
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{hash:016x}")
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
    let mut cached = BTreeMap::new();
    if path.exists() {
        match read(path) {
            Ok(found) => cached = found,
            Err(why) => eprintln!(
                "report: recomputing every view of {} ({why:#})",
                path.display()
            ),
        }
    }
    let mut reference = Vec::with_capacity(scenes.len());
    let mut missing = Vec::new();
    for (i, (scene, key)) in scenes.iter().zip(&keys).enumerate() {
        match cached.remove(scene.view.id) {
            Some((k, rays)) if k == *key && rays.len() == scene.rays.len() && !recompute(scene) => {
                reference.push(rays);
            }
            found => {
                let why = if recompute(scene) {
                    "asked to recompute it"
                } else if found.is_some() {
                    "its view, scene or path tracer changed"
                } else {
                    "not in the cache"
                };
                eprintln!(
                    "report: computing view {} of {} ({why})",
                    scene.view.id,
                    path.display()
                );
                reference.push(Vec::new());
                missing.push(i);
            }
        }
    }
    if missing.is_empty() {
        eprintln!("report: optics reference from {}", path.display());
        return Ok(reference);
    }
    let total: usize = missing.iter().map(|&i| scenes[i].rays.len()).sum();
    let progress = Progress::new("optics reference", "rays", total as u64);
    for &i in &missing {
        let scene = &scenes[i];
        // The whole table (the path tracer truncates it) and its own light around the
        // volume (the march's sky light is not read).
        let lit = scene.lit(
            REFERENCE_TABLES,
            (ForwardPeak::Extinction, SkyLight::Horizontal),
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
    let mut text = format!("{TITLE}\n{}\n", header());
    for ((scene, rays), key) in scenes.iter().zip(reference).zip(keys) {
        if rays.is_empty() {
            continue;
        }
        text.push_str(&format!("{VIEW_MARK}{} fingerprint {key}\n", scene.view.id));
        for (i, r) in rays.iter().enumerate() {
            let light = &r.volume_light;
            let mut fields = vec![scene.view.id.to_string(), i.to_string()];
            fields.extend(
                r.radiance
                    .radiance
                    .iter()
                    .chain(&r.radiance.transmittance)
                    .chain(&r.radiance.radiance_std_error)
                    .chain(&light.sun_single)
                    .chain(&light.sun_multiple)
                    .chain(&light.sky)
                    .chain([&r.volume_transmittance])
                    .map(|x| format!("{x:e}")),
            );
            fields.push(r.paths.to_string());
            text.push_str(&fields.join(","));
            text.push('\n');
        }
    }
    write_atomically(path, text.as_bytes())
}

type Cached = BTreeMap<String, (String, Vec<VolumeTracedRay>)>;

/// Every view in the file by id; an error naming the line for a file of another layout.
fn read(path: &Path) -> anyhow::Result<Cached> {
    let text = fs::read_to_string(path)?;
    let mut lines = text.lines();
    if lines.next() != Some(TITLE) {
        bail!("its first line is not \"{TITLE}\"");
    }
    if lines.next() != Some(header().as_str()) {
        bail!("its second line is not the header");
    }
    let fields_per_row = 4 + 3 * PARTS.len();
    let mut views: Cached = BTreeMap::new();
    let mut current: Option<String> = None;
    for (n, line) in lines.enumerate() {
        let bad = || format!("{} line {}", path.display(), n + 3);
        if let Some(rest) = line.strip_prefix(VIEW_MARK) {
            let Some((id, key)) = rest.split_once(" fingerprint ") else {
                bail!("{}: expected \"# view <id> fingerprint <hex>\"", bad());
            };
            if views
                .insert(id.to_string(), (key.to_string(), Vec::new()))
                .is_some()
            {
                bail!("{}: view {id} appears twice", bad());
            }
            current = Some(id.to_string());
            continue;
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != fields_per_row {
            bail!(
                "{}: {} fields, expected {fields_per_row}",
                bad(),
                fields.len()
            );
        }
        let rays = match &current {
            Some(id) if id == fields[0] => &mut views.get_mut(id).expect("inserted above").1,
            _ => bail!("{}: a row of view {} outside its section", bad(), fields[0]),
        };
        if fields[1] != rays.len().to_string() {
            bail!("{}: ray {}, expected {}", bad(), fields[1], rays.len());
        }
        let numbers = fields[2..fields_per_row - 1]
            .iter()
            .map(|f| f.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(bad)?;
        let paths: u64 = fields[fields_per_row - 1].parse().with_context(bad)?;
        let part = |k: usize| -> [f64; 3] { std::array::from_fn(|c| numbers[3 * k + c]) };
        rays.push(VolumeTracedRay {
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
        });
    }
    Ok(views)
}
