//! The reference radiance of every ray of the report's views, computed once and kept in
//! `reference.csv` beside the report: the reference takes minutes to hours, the models
//! seconds, so regenerating the report after a model changes reuses it. Each view's rows
//! carry a fingerprint of that view, its atmosphere and the reference's settings for it,
//! so adding or changing a view computes only that view and keeps the others.
//!
//! A view may pool several batches, independent runs of the reference
//! (`reference_batches.rs`); the fingerprint is that of one batch's settings, so asking
//! for more batches computes only the new ones.
//! The file's layout is `reference_cache_file.rs`'s.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use atmosphere_core::reference::{MAX_PATHS, ReferenceSettings, SHARED_GROUND, TOWARDS_LIGHT};
use rayon::prelude::*;

use crate::progress::Progress;
use crate::report::reference_batches::{batch_settings, pool_batch};
use crate::report::reference_cache_file::{CachedView, read, write};
use crate::report::reference_ground_rays::{
    ground_rays, recompute_ground_rays, without_shared_ground,
};
use crate::report::view_sections::fingerprint_of;
use crate::report::views::ReportView;

/// The reference's answers, per view, per ray.
pub type ReferenceRadiance = Vec<Vec<RayRadiance>>;

/// The reference's settings for `view`: `base`, with the path cap `twilight_max_paths`
/// where the sun is below the horizon and higher orders are computed (there the light of
/// order two and up is nearly all the radiance and its paths are the least efficient),
/// and where the sun is more than 6 deg down: from inside the atmosphere, the later
/// events of the paths in the umbra drawn towards the light (`towards_light`) at
/// `UMBRA_PATH_FACTOR` times the cap, and the light of the ground in the umbra shared
/// by the rays that end on it (`shared_ground`); from above it, `NAUTICAL_PATH_FACTOR`
/// times the cap. A cap equal to the reference's default is left unset, so the fingerprints stay
/// those of the plain settings.
pub fn reference_settings(
    view: &ReportView,
    base: &ModelSettings,
    twilight_max_paths: usize,
) -> ModelSettings {
    let mut settings = base.clone();
    if view.is_daytime() || base.max_orders == Some(1) {
        return settings;
    }
    let (factor, towards_light) = if view.sun_zenith_deg <= NAUTICAL_SUN_ZENITH_DEG {
        (1, false)
    } else if umbra_seen_from_inside(view, base) {
        (UMBRA_PATH_FACTOR, true)
    } else {
        (NAUTICAL_PATH_FACTOR, false)
    };
    let cap = twilight_max_paths
        .saturating_mul(factor)
        .min(*MAX_PATHS.range.end());
    if cap != ReferenceSettings::default().max_paths {
        settings.options.set(MAX_PATHS.key, cap);
    }
    if towards_light {
        settings.options.set(TOWARDS_LIGHT, true);
        settings.options.set(SHARED_GROUND, true);
    }
    settings
}

/// Whether `view`'s camera lies below the top of its atmosphere (an unknown preset
/// counts as not: its reference fails by name later).
fn camera_inside_atmosphere(view: &ReportView) -> bool {
    Atmosphere::preset(view.atmosphere)
        .is_ok_and(|a| view.altitude_m < a.top_radius_m - a.bottom_radius_m)
}

/// The sun's zenith angle past which twilight is nautical (the sun more than 6 deg
/// below the horizon).
const NAUTICAL_SUN_ZENITH_DEG: f64 = 96.0;

/// How many times the twilight cap a view in nautical twilight from above the
/// atmosphere takes: single scattering is dark on nearly all of its rays, so even the
/// guided estimator's paths (towards the lit air above the shadow) leave most rays
/// above 5 % standard error at the twilight cap, and the report could judge no model
/// there.
const NAUTICAL_PATH_FACTOR: usize = 8;

/// How many times the twilight cap a view in nautical twilight from inside the
/// atmosphere takes, its later events drawn towards the light: their error per path is
/// below the directions-guided estimate's, which lies low there, at a higher cost per
/// path (docs/models/reference.md, "Sixteen independent runs").
const UMBRA_PATH_FACTOR: usize = 2;

/// How many batches of `reference_settings`' paths `view`'s reference pools: several
/// in nautical twilight from inside the atmosphere, where one run of the towards-light
/// paths at `UMBRA_PATH_FACTOR` times the cap leaves the judged rays' luminance as
/// uncertain as a good model's error (docs/models/reference.md, "Pooled batches"); one
/// elsewhere.
pub fn reference_batches(view: &ReportView, base: &ModelSettings) -> usize {
    if umbra_seen_from_inside(view, base) {
        UMBRA_BATCHES
    } else {
        1
    }
}

/// Whether `view` is the case whose paths are drawn towards the light and pooled from
/// batches: higher orders, the sun more than 6 deg down, the camera inside the
/// atmosphere.
fn umbra_seen_from_inside(view: &ReportView, base: &ModelSettings) -> bool {
    !view.is_daytime()
        && base.max_orders != Some(1)
        && view.sun_zenith_deg > NAUTICAL_SUN_ZENITH_DEG
        && camera_inside_atmosphere(view)
}

/// Batches in nautical twilight from inside the atmosphere: six take the standard
/// error of one to 0.41 of it (and the view's mirror rays pooled, `mirror_rays.rs`, to
/// 0.29).
const UMBRA_BATCHES: usize = 6;

/// A stable 64-bit hash (FNV-1a) of everything one view's reference answers depend on:
/// the view, its atmosphere and the reference's settings.
pub fn fingerprint(view: &ReportView, settings: &ModelSettings) -> anyhow::Result<String> {
    let atmosphere = Atmosphere::preset(view.atmosphere)?;
    Ok(fingerprint_of(&format!(
        "{settings:?}{view:?}{atmosphere:?}"
    )))
}

/// Reads the views of the cache at `path` whose fingerprint and batches match, computes
/// the others (in parallel, with progress; the views `recompute` names are computed
/// whatever the cache holds) with the settings `settings_for` gives each view, pooling
/// the batches `batches_for` asks (a view cached with fewer batches keeps them and gets
/// the rest; one cached with every batch but without `shared_ground` keeps its rays
/// that do not end on the ground, `reference_ground_rays.rs`), and writes the cache of
/// exactly these views.
pub fn load_or_compute(
    path: &Path,
    views: &[ReportView],
    settings_for: impl Fn(&ReportView) -> ModelSettings,
    batches_for: impl Fn(&ReportView) -> usize,
    recompute: impl Fn(&ReportView) -> bool,
) -> anyhow::Result<ReferenceRadiance> {
    let settings: Vec<ModelSettings> = views.iter().map(&settings_for).collect();
    let batches: Vec<usize> = views.iter().map(|v| batches_for(v).max(1)).collect();
    let wavelengths = settings
        .first()
        .map_or(0, |s: &ModelSettings| s.wavelengths_nm.len());
    let keys = views
        .iter()
        .zip(&settings)
        .map(|(v, s)| fingerprint(v, s))
        .collect::<anyhow::Result<Vec<String>>>()?;
    let mut cached = BTreeMap::new();
    if path.exists() {
        match read(path, wavelengths) {
            Ok(found) => cached = found,
            Err(why) => eprintln!(
                "report: recomputing every view of {} ({why:#})",
                path.display()
            ),
        }
    }
    let mut reference = Vec::with_capacity(views.len());
    let mut done = vec![0; views.len()];
    let mut missing = Vec::new();
    let mut ground_missing = Vec::new();
    for (i, (view, key)) in views.iter().zip(&keys).enumerate() {
        let found = cached.remove(view.id);
        let fits = |c: &CachedView| {
            c.answers.len() == view.columns * view.rows
                && c.batches <= batches[i]
                && !recompute(view)
        };
        let usable = found
            .as_ref()
            .is_some_and(|c| c.fingerprint == *key && fits(c));
        let sky_key = without_shared_ground(&settings[i])
            .map(|s| fingerprint(view, &s))
            .transpose()?;
        let sky_usable = found.as_ref().is_some_and(|c| {
            Some(&c.fingerprint) == sky_key.as_ref() && c.batches == batches[i] && fits(c)
        });
        match found {
            Some(c) if usable && c.batches == batches[i] => reference.push(c.answers),
            Some(c) if sky_usable => {
                eprintln!(
                    "report: computing the ground's rays of view {} of {} again (shared_ground)",
                    view.id,
                    path.display()
                );
                reference.push(c.answers);
                ground_missing.push(i);
            }
            Some(c) if usable => {
                eprintln!(
                    "report: adding batches {}-{} to view {} of {}",
                    c.batches + 1,
                    batches[i],
                    view.id,
                    path.display()
                );
                done[i] = c.batches;
                reference.push(c.answers);
                missing.push(i);
            }
            found => {
                let why = if recompute(view) {
                    "asked to recompute it"
                } else if found.is_some() {
                    "its view, atmosphere, settings or batches changed"
                } else {
                    "not in the cache"
                };
                eprintln!(
                    "report: computing view {} of {} ({why})",
                    view.id,
                    path.display()
                );
                reference.push(Vec::new());
                missing.push(i);
            }
        }
    }
    if missing.is_empty() && ground_missing.is_empty() {
        eprintln!("report: reference radiance from {}", path.display());
        return Ok(reference);
    }
    let mut total = missing
        .iter()
        .map(|&i| views[i].columns * views[i].rows * (batches[i] - done[i]))
        .sum::<usize>();
    for &i in &ground_missing {
        total += ground_rays(&views[i])?.len() * batches[i];
    }
    let progress = Progress::new("reference", "rays", total as u64);
    for &i in &ground_missing {
        reference[i] = recompute_ground_rays(
            &views[i],
            &settings[i],
            batches[i],
            &reference[i],
            &progress,
        )?;
        done[i] = batches[i];
        write(path, &reference, views, &keys, &done)?;
    }
    for &i in &missing {
        for batch in done[i]..batches[i] {
            let answers = compute(&views[i], &batch_settings(&settings[i], batch), &progress)?;
            reference[i] = if batch == 0 {
                answers
            } else {
                pool_batch(&reference[i], batch, &answers)
            };
            done[i] = batch + 1;
            // Written after each batch, so an interrupted run keeps what it finished.
            write(path, &reference, views, &keys, &done)?;
        }
    }
    progress.finish();
    Ok(reference)
}

fn compute(
    view: &ReportView,
    settings: &ModelSettings,
    progress: &Progress,
) -> anyhow::Result<Vec<RayRadiance>> {
    let atmosphere = Atmosphere::preset(view.atmosphere)?;
    let model = prepare(ModelId::Reference, &atmosphere, settings)?;
    view.rays(&atmosphere)
        .par_iter()
        .map(|ray| {
            let answer = model.radiance(ray);
            progress.inc();
            answer
        })
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| format!("reference on view {}", view.id))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::reference_cache_file::tests::answers;
    use crate::report::views::report_views;
    use std::fs;

    #[test]
    fn each_view_has_its_own_fingerprint_and_another_grid_changes_them() {
        let views = report_views(2, 1);
        let settings = ModelSettings::default();
        let mut keys: Vec<String> = views
            .iter()
            .map(|v| fingerprint(v, &settings).unwrap())
            .collect();
        let first = keys[0].clone();
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), views.len());
        let other = fingerprint(&report_views(3, 1)[0], &settings).unwrap();
        assert_ne!(other, first);
    }

    #[test]
    fn only_the_missing_or_changed_views_are_computed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let settings = ModelSettings {
            max_orders: Some(1),
            ..ModelSettings::default()
        };
        let views: Vec<ReportView> = report_views(2, 1).into_iter().take(3).collect();
        // The cache holds made-up answers for the first two views, the second under a
        // stale fingerprint: the first is kept as it is, the others are computed.
        let made_up: ReferenceRadiance = vec![answers(7, 2), answers(8, 2), Vec::new()];
        let mut keys: Vec<String> = views
            .iter()
            .map(|v| fingerprint(v, &settings).unwrap())
            .collect();
        keys[1] = "0000000000000000".into();
        write(&path, &made_up, &views, &keys, &vec![1; views.len()]).unwrap();
        let reference =
            load_or_compute(&path, &views, |_| settings.clone(), |_| 1, |_| false).unwrap();
        assert_eq!(reference[0], made_up[0]);
        assert_ne!(reference[1], made_up[1]);
        assert_eq!(reference[2].len(), 2);
        assert!(reference[1][0].radiance[0] > 0.0);
        // The file now holds all three under their own fingerprints.
        let again = read(&path, 3).unwrap();
        assert_eq!(again.len(), 3);
        assert_eq!(
            again[views[1].id].fingerprint,
            fingerprint(&views[1], &settings).unwrap()
        );
        assert_eq!(again[views[2].id].answers, reference[2]);
    }

    #[test]
    fn a_view_asked_for_is_computed_again_and_the_others_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let settings = ModelSettings {
            max_orders: Some(1),
            ..ModelSettings::default()
        };
        let views: Vec<ReportView> = report_views(2, 1).into_iter().take(2).collect();
        let made_up: ReferenceRadiance = vec![answers(7, 2), answers(8, 2)];
        let keys: Vec<String> = views
            .iter()
            .map(|v| fingerprint(v, &settings).unwrap())
            .collect();
        write(&path, &made_up, &views, &keys, &vec![1; views.len()]).unwrap();
        let again = views[1].id;
        let reference = load_or_compute(
            &path,
            &views,
            |_| settings.clone(),
            |_| 1,
            |v| v.id == again,
        )
        .unwrap();
        assert_eq!(reference[0], made_up[0]);
        assert_ne!(reference[1], made_up[1]);
        assert!(reference[1][0].radiance[0] > 0.0);
    }

    #[test]
    fn turning_on_shared_ground_computes_the_ground_rays_alone_in_every_batch() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let mut without = ModelSettings::default();
        without.options.set(MAX_PATHS.key, 256);
        let mut with = without.clone();
        with.options.set(SHARED_GROUND, true);
        // Sunset from the ground on a 1 x 2 grid: a ray of the sky above a ray of the
        // ground (lit, so quick: the splicing is what is tested here).
        let views: Vec<ReportView> = report_views(1, 2)
            .into_iter()
            .filter(|v| v.id == "sunset")
            .collect();
        assert_eq!(ground_rays(&views[0]).unwrap(), vec![1]);
        let made_up = answers(3, 2);
        let old_key = fingerprint(&views[0], &without).unwrap();
        write(
            &path,
            std::slice::from_ref(&made_up),
            &views,
            std::slice::from_ref(&old_key),
            &[2],
        )
        .unwrap();
        let spliced = load_or_compute(&path, &views, |_| with.clone(), |_| 2, |_| false).unwrap();
        assert_eq!(spliced[0][0], made_up[0]);
        let ground = |batch| {
            compute(&views[0], &batch_settings(&with, batch), &Progress::Quiet).unwrap()[1].clone()
        };
        let pooled = pool_batch(&[ground(0)], 1, &[ground(1)]);
        assert_eq!(spliced[0][1], pooled[0]);
        let cached = read(&path, 3).unwrap();
        assert_eq!(cached[views[0].id].batches, 2);
        assert_eq!(
            cached[views[0].id].fingerprint,
            fingerprint(&views[0], &with).unwrap()
        );
        assert_eq!(cached[views[0].id].answers, spliced[0]);
    }

    #[test]
    fn a_view_asked_for_more_batches_keeps_the_ones_it_has_and_pools_the_rest() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("reference.csv");
        let mut settings = ModelSettings::default();
        settings.options.set(MAX_PATHS.key, 1024);
        let views: Vec<ReportView> = report_views(2, 1)
            .into_iter()
            .filter(|v| v.id == "twilight")
            .collect();
        let key = fingerprint(&views[0], &settings).unwrap();
        // A made-up first batch, brighter than the view's own answers.
        let first: Vec<RayRadiance> = (0..2)
            .map(|_| RayRadiance {
                radiance: vec![1.0; 3],
                transmittance: vec![0.5; 3],
                radiance_std_error: vec![0.1; 3],
            })
            .collect();
        write(
            &path,
            std::slice::from_ref(&first),
            &views,
            std::slice::from_ref(&key),
            &[1],
        )
        .unwrap();
        let two = load_or_compute(&path, &views, |_| settings.clone(), |_| 2, |_| false).unwrap();
        let second = compute(&views[0], &batch_settings(&settings, 1), &Progress::Quiet).unwrap();
        assert_eq!(two[0], pool_batch(&first, 1, &second));
        let cached = read(&path, 3).unwrap();
        assert_eq!(cached[views[0].id].batches, 2);
        assert_eq!(cached[views[0].id].fingerprint, key);
        assert!(fs::read_to_string(&path).unwrap().contains(" batches 2\n"));
        // Asked again for two, nothing is computed; for one, the view starts afresh.
        let again = load_or_compute(&path, &views, |_| settings.clone(), |_| 2, |_| false).unwrap();
        assert_eq!(again, two);
        let one = load_or_compute(&path, &views, |_| settings.clone(), |_| 1, |_| false).unwrap();
        assert_eq!(
            one[0],
            compute(&views[0], &settings, &Progress::Quiet).unwrap()
        );
        assert_eq!(read(&path, 3).unwrap()[views[0].id].batches, 1);
    }

    #[test]
    fn the_twilight_cap_changes_only_the_fingerprints_of_views_without_sun() {
        let base = ModelSettings::default();
        let default_cap = ReferenceSettings::default().max_paths;
        for view in report_views(2, 1) {
            let plain = fingerprint(&view, &base).unwrap();
            let same = reference_settings(&view, &base, default_cap);
            let nautical = view.sun_zenith_deg > NAUTICAL_SUN_ZENITH_DEG;
            assert_eq!(
                fingerprint(&view, &same).unwrap() != plain,
                nautical,
                "{}",
                view.id
            );
            let raised = reference_settings(&view, &base, 4 * default_cap);
            assert_eq!(
                fingerprint(&view, &raised).unwrap() != plain,
                !view.is_daytime(),
                "{}",
                view.id
            );
        }
        let single = ModelSettings {
            max_orders: Some(1),
            ..base
        };
        let twilight = &report_views(2, 1)[2];
        assert_eq!(reference_settings(twilight, &single, 1 << 20), single);
    }

    #[test]
    fn nautical_twilight_takes_its_factor_of_the_cap_within_its_range() {
        let base = ModelSettings::default();
        let views = report_views(2, 1);
        let by_id = |id| views.iter().find(|v| v.id == id).unwrap();
        let (nautical, terminator) = (by_id("nautical"), by_id("orbit-twilight"));
        let civil = by_id("twilight");
        let option = |view, twilight_cap, key| {
            let settings = reference_settings(view, &base, twilight_cap);
            settings
                .options
                .items()
                .find(|(k, _)| *k == key)
                .map(|(_, value)| value.to_string())
        };
        let cap = |view, twilight_cap| {
            option(view, twilight_cap, MAX_PATHS.key).map(|v| v.parse::<usize>().unwrap())
        };
        assert_eq!(cap(nautical, 1 << 17), Some(1 << 18));
        assert_eq!(cap(terminator, 1 << 17), Some(1 << 20));
        assert_eq!(cap(civil, 1 << 17), None);
        assert_eq!(cap(civil, 1 << 18), Some(1 << 18));
        assert_eq!(cap(terminator, 1 << 25), Some(*MAX_PATHS.range.end()));
        // Drawn towards the light from the ground in nautical twilight alone.
        assert_eq!(
            option(nautical, 1 << 17, TOWARDS_LIGHT),
            Some("true".into())
        );
        // And its ground's light shared by its ground rays there alone.
        assert_eq!(
            option(nautical, 1 << 17, SHARED_GROUND),
            Some("true".into())
        );
        for view in [terminator, civil] {
            assert_eq!(option(view, 1 << 17, TOWARDS_LIGHT), None, "{}", view.id);
            assert_eq!(option(view, 1 << 17, SHARED_GROUND), None, "{}", view.id);
        }
        // And pooled from batches there alone, for the whole reference, not its single
        // scattering.
        for view in &views {
            let expected = if view.id == "nautical" {
                UMBRA_BATCHES
            } else {
                1
            };
            assert_eq!(reference_batches(view, &base), expected, "{}", view.id);
        }
        let single = ModelSettings {
            max_orders: Some(1),
            ..base.clone()
        };
        assert_eq!(reference_batches(nautical, &single), 1);
    }
}
