//! A view whose reference settings differ from its cached ones only by `shared_ground`
//! keeps the rays that do not end on the ground and computes the others again.
//!
//! `shared_ground=true` changes how the reference estimates the light the ground
//! reflects in the umbra (`atmosphere_core::reference`, `ground_light.rs`) and nothing
//! else: a ray that does not end on the ground draws exactly the same paths with it or
//! without. So the cache of a view computed without it still holds the answers of its
//! rays of the sky, batches and all, and turning it on costs the ground's rays alone
//! (in nautical twilight a small part of the view's time) instead of the whole view.

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance};
use atmosphere_core::optics::column::Fineness;
use atmosphere_core::reference::{RayEnd, SHARED_GROUND, ViewPath};
use rayon::prelude::*;

use crate::progress::Progress;
use crate::report::reference_batches::{batch_settings, pool_batch};
use crate::report::views::ReportView;

/// `settings` less `shared_ground`, whose rays of the sky are the same; `None` where
/// `settings` do not share the ground's light.
pub fn without_shared_ground(settings: &ModelSettings) -> Option<ModelSettings> {
    if !settings
        .options
        .items()
        .any(|(k, v)| k == SHARED_GROUND && v == "true")
    {
        return None;
    }
    let mut without = settings.clone();
    without.options.remove(SHARED_GROUND);
    Some(without)
}

/// The indices of `view`'s rays that end on the ground.
pub fn ground_rays(view: &ReportView) -> anyhow::Result<Vec<usize>> {
    let atmosphere = Atmosphere::preset(view.atmosphere)?;
    let mut indices = Vec::new();
    for (i, ray) in view.rays(&atmosphere).iter().enumerate() {
        let path = ViewPath::new(&atmosphere, ray, Fineness::VIEW)?;
        if matches!(path.end, RayEnd::Ground(_)) {
            indices.push(i);
        }
    }
    Ok(indices)
}

/// `cached`, `view`'s answers pooled over `batches` batches, with the rays that end on
/// the ground computed again with `settings` in every batch and pooled the same way.
pub fn recompute_ground_rays(
    view: &ReportView,
    settings: &ModelSettings,
    batches: usize,
    cached: &[RayRadiance],
    progress: &Progress,
) -> anyhow::Result<Vec<RayRadiance>> {
    let atmosphere = Atmosphere::preset(view.atmosphere)?;
    let rays = view.rays(&atmosphere);
    let ground = ground_rays(view)?;
    let mut pooled: Vec<RayRadiance> = Vec::new();
    for batch in 0..batches {
        let model = prepare(
            ModelId::Reference,
            &atmosphere,
            &batch_settings(settings, batch),
        )?;
        let answers = ground
            .par_iter()
            .map(|&i| {
                let answer = model.radiance(&rays[i]);
                progress.inc();
                answer
            })
            .collect::<Result<Vec<_>, _>>()
            .with_context(|| format!("reference on the ground rays of view {}", view.id))?;
        pooled = if batch == 0 {
            answers
        } else {
            pool_batch(&pooled, batch, &answers)
        };
    }
    let mut spliced = cached.to_vec();
    for (&i, answer) in ground.iter().zip(pooled) {
        spliced[i] = answer;
    }
    Ok(spliced)
}
