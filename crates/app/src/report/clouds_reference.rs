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

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use anyhow::{Context, bail};
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use rayon::prelude::*;

use crate::cloud_rays::CloudAnswer;
use crate::files::write_atomically;
use crate::probe_clouds::AIR_MODEL;
use crate::progress::Progress;
use crate::report::clouds_scene::ViewScene;
use crate::report::clouds_views::CloudView;

/// The reference's answers, per view, per ray.
pub type CloudReference = Vec<Vec<CloudAnswer>>;

const TITLE: &str =
    "# atmos report clouds: path-traced reference radiance, one fingerprint per view";
const VIEW_MARK: &str = "# view ";

/// A stable 64-bit hash (FNV-1a) of what a view's reference depends on.
pub fn fingerprint(view: &CloudView, settings: &ModelSettings) -> String {
    let text = format!(
        "{view:?}{AIR_MODEL}{:?}{:?}",
        settings.wavelengths_nm, settings.options
    );
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for byte in text.bytes() {
        hash ^= u64::from(byte);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{hash:016x}")
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
    let mut cached = BTreeMap::new();
    if path.exists() {
        match read(path, waves) {
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
        let rays = scene.rays.len();
        match cached.remove(scene.view.id()) {
            Some((k, answers)) if k == *key && answers.len() == rays && !recompute(&scene.view) => {
                reference.push(answers);
            }
            found => {
                let why = if recompute(&scene.view) {
                    "asked to recompute it"
                } else if found.is_some() {
                    "its view or settings changed"
                } else {
                    "not in the cache"
                };
                eprintln!(
                    "report: computing view {} of {} ({why})",
                    scene.view.id(),
                    path.display()
                );
                reference.push(Vec::new());
                missing.push(i);
            }
        }
    }
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
    let mut text = format!("{TITLE}\n{}\n", header(waves));
    for ((scene, answers), key) in scenes.iter().zip(reference).zip(keys) {
        if answers.is_empty() {
            continue;
        }
        text.push_str(&format!(
            "{VIEW_MARK}{} fingerprint {key}\n",
            scene.view.id()
        ));
        for (i, a) in answers.iter().enumerate() {
            let mut fields = vec![scene.view.id().to_string(), i.to_string()];
            fields.extend(
                a.radiance
                    .radiance
                    .iter()
                    .chain(&a.radiance.transmittance)
                    .chain(&a.radiance.radiance_std_error)
                    .map(|x| format!("{x:e}")),
            );
            fields.push(format!("{:e}", a.cloud_transmittance));
            fields.push(a.paths.unwrap_or(0).to_string());
            text.push_str(&fields.join(","));
            text.push('\n');
        }
    }
    write_atomically(path, text.as_bytes())
}

type Cached = BTreeMap<String, (String, Vec<CloudAnswer>)>;

/// Every view in the file by id; an error naming the line for a file of another layout.
fn read(path: &Path, waves: usize) -> anyhow::Result<Cached> {
    let text = fs::read_to_string(path)?;
    let mut lines = text.lines();
    if lines.next() != Some(TITLE) {
        bail!("its first line is not \"{TITLE}\"");
    }
    if lines.next() != Some(header(waves).as_str()) {
        bail!("its second line is not the header for {waves} wavelengths");
    }
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
        if fields.len() != 4 + 3 * waves {
            bail!(
                "{}: {} fields, expected {}",
                bad(),
                fields.len(),
                4 + 3 * waves
            );
        }
        let answers = match &current {
            Some(id) if id == fields[0] => &mut views.get_mut(id).expect("inserted above").1,
            _ => bail!("{}: a row of view {} outside its section", bad(), fields[0]),
        };
        if fields[1] != answers.len().to_string() {
            bail!("{}: ray {}, expected {}", bad(), fields[1], answers.len());
        }
        let numbers = fields[2..3 + 3 * waves]
            .iter()
            .map(|f| f.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
            .with_context(bad)?;
        let paths: u64 = fields[3 + 3 * waves].parse().with_context(bad)?;
        answers.push(CloudAnswer {
            radiance: RayRadiance {
                radiance: numbers[..waves].to_vec(),
                transmittance: numbers[waves..2 * waves].to_vec(),
                radiance_std_error: numbers[2 * waves..3 * waves].to_vec(),
            },
            cloud_transmittance: numbers[3 * waves],
            paths: Some(paths),
        });
    }
    Ok(views)
}
