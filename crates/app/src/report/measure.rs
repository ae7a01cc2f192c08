//! Runs one model setting over the report's views: its error against the reference
//! (luminance and CIEDE2000 after a fixed exposure), its table build time and memory, and
//! its time per ray, measured on one thread.

use std::hint::black_box;
use std::time::{Duration, Instant};

use anyhow::Context;
use atmosphere_core::analysis::color_difference::{D65_WHITE, ciede2000, xyz_to_lab};
use atmosphere_core::analysis::error_statistics::{RelativeErrorStats, percentile_sorted};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};

use crate::report::gpu_time::GpuFrameTime;
use crate::report::judged_rays::is_judged;
use crate::report::reference_cache::ReferenceRadiance;
use crate::report::views::ReportView;

/// Pixels of the frame whose time the report gives.
pub const FRAME_PIXELS: f64 = 1280.0 * 720.0;

/// The exposure maps the median reference luminance of a view to this (18 % grey).
const MIDDLE_GREY: f64 = 0.18;

/// Warm passes over a view repeat until they have taken this long.
const MIN_TIMING: Duration = Duration::from_millis(200);

/// One model with one choice of settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    pub model: ModelId,
    /// Highest order (`None`: the model's own choice).
    pub max_orders: Option<u32>,
    pub options: ModelOptions,
}

impl Variant {
    pub fn new(model: ModelId, max_orders: Option<u32>, options: &[&str]) -> Variant {
        Variant {
            model,
            max_orders,
            options: ModelOptions::parse(options).expect("report variants are key=value"),
        }
    }

    /// "nishita samples=16", "bruneton orders=2", "riley".
    pub fn label(&self) -> String {
        let mut label = self.model.to_string();
        if let Some(n) = self.max_orders {
            label.push_str(&format!(" orders={n}"));
        }
        if !self.options.is_empty() {
            label.push_str(&format!(" {}", self.options));
        }
        label
    }

    fn settings(&self, base: &ModelSettings) -> ModelSettings {
        ModelSettings {
            max_orders: self.max_orders,
            options: self.options.clone(),
            ..base.clone()
        }
    }
}

/// The results of one view.
#[derive(Clone, Debug)]
pub struct ViewResult {
    pub luminance: RelativeErrorStats,
    pub mean_ciede2000: f64,
    /// Warm evaluation time per ray.
    pub seconds_per_ray: f64,
    /// What the first pass over the view took beyond a warm pass: tables a model builds
    /// per view (camera position and sun), which a frame would build once.
    pub per_view_seconds: f64,
}

impl ViewResult {
    /// A 1280 x 720 frame of this view on one thread.
    pub fn frame_seconds(&self) -> f64 {
        self.per_view_seconds + self.seconds_per_ray * FRAME_PIXELS
    }
}

/// The results of one variant over all views.
#[derive(Clone, Debug)]
pub struct VariantResult {
    pub variant: Variant,
    /// Table build of the first view's atmosphere, seconds (best of a few for quick
    /// builds).
    pub build_seconds: f64,
    pub table_bytes: usize,
    pub views: Vec<ViewResult>,
    pub all: RelativeErrorStats,
    pub daytime: RelativeErrorStats,
    /// Daytime error against the reference's single scattering: the numerical error of
    /// single-scattering models, apart from the light of higher orders they leave out.
    pub daytime_vs_single: RelativeErrorStats,
    pub mean_ciede2000: f64,
    /// The 1280 x 720 frame on the GPU, where it was measured.
    pub gpu: Option<GpuFrameTime>,
}

impl VariantResult {
    pub fn seconds_per_ray(&self) -> f64 {
        mean(self.views.iter().map(|v| v.seconds_per_ray))
    }

    pub fn frame_seconds(&self) -> f64 {
        mean(self.views.iter().map(ViewResult::frame_seconds))
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// Measures `variant` on every view.
pub fn measure(
    variant: &Variant,
    views: &[ReportView],
    reference: &ReferenceRadiance,
    single: &ReferenceRadiance,
    base: &ModelSettings,
    color: &SpectrumToColor,
) -> anyhow::Result<VariantResult> {
    let settings = variant.settings(base);
    let label = variant.label();
    let mut prepared: Vec<(&str, Box<dyn SkyModel>)> = Vec::new();
    let mut build_seconds = None;
    let mut table_bytes = 0;
    let mut results = Vec::with_capacity(views.len());
    let mut all_pairs = Vec::new();
    let mut day_pairs = Vec::new();
    let mut single_pairs = Vec::new();
    for ((view, reference), single) in views.iter().zip(reference).zip(single) {
        let atmosphere = Atmosphere::preset(view.atmosphere)?;
        if !prepared.iter().any(|(name, _)| *name == view.atmosphere) {
            let (model, seconds) = timed_prepare(variant.model, &atmosphere, &settings)
                .with_context(|| format!("preparing {label}"))?;
            build_seconds.get_or_insert(seconds);
            table_bytes = table_bytes.max(model.table_bytes());
            prepared.push((view.atmosphere, model));
        }
        let model = &prepared
            .iter()
            .find(|(name, _)| *name == view.atmosphere)
            .expect("prepared above")
            .1;
        let rays = view.rays(&atmosphere);
        let (answers, timing) = timed_passes(model.as_ref(), &rays)
            .with_context(|| format!("{label} on view {}", view.id))?;
        table_bytes = table_bytes.max(model.table_bytes());
        let judged: Vec<bool> = reference.iter().map(|r| is_judged(r, color)).collect();
        let pairs: Vec<(f64, f64)> = answers
            .iter()
            .zip(reference)
            .zip(&judged)
            .filter(|(_, judged)| **judged)
            .map(|((m, r), _)| {
                (
                    color.luminance_cd_m2(&m.radiance),
                    color.luminance_cd_m2(&r.radiance),
                )
            })
            .collect();
        all_pairs.extend(&pairs);
        if view.is_daytime() {
            day_pairs.extend(&pairs);
            single_pairs.extend(
                answers
                    .iter()
                    .zip(single)
                    .zip(&judged)
                    .filter(|(_, judged)| **judged)
                    .map(|((m, r), _)| {
                        (
                            color.luminance_cd_m2(&m.radiance),
                            color.luminance_cd_m2(&r.radiance),
                        )
                    }),
            );
        }
        results.push(ViewResult {
            luminance: RelativeErrorStats::new(pairs.iter().copied()),
            mean_ciede2000: mean_ciede2000(&answers, reference, color),
            seconds_per_ray: timing.warm_pass / rays.len() as f64,
            per_view_seconds: (timing.cold_pass - timing.warm_pass).max(0.0),
        });
    }
    Ok(VariantResult {
        variant: variant.clone(),
        build_seconds: build_seconds.unwrap_or(0.0),
        table_bytes,
        all: RelativeErrorStats::new(all_pairs),
        daytime: RelativeErrorStats::new(day_pairs),
        daytime_vs_single: RelativeErrorStats::new(single_pairs),
        mean_ciede2000: mean(results.iter().map(|v| v.mean_ciede2000)),
        views: results,
        gpu: None,
    })
}

/// Prepares the model; builds under half a second are repeated (up to five times) and
/// the fastest is kept.
fn timed_prepare(
    id: ModelId,
    atmosphere: &Atmosphere,
    settings: &ModelSettings,
) -> anyhow::Result<(Box<dyn SkyModel>, f64)> {
    let mut best = f64::INFINITY;
    let mut model = None;
    for _ in 0..5 {
        let start = Instant::now();
        let m = prepare(id, atmosphere, settings)?;
        best = best.min(start.elapsed().as_secs_f64());
        model = Some(m);
        if best > 0.5 {
            break;
        }
    }
    Ok((model.expect("at least one build"), best))
}

struct Timing {
    cold_pass: f64,
    warm_pass: f64,
}

/// Evaluates the rays once (cold: per-view tables are built), then again until
/// [`MIN_TIMING`] has passed; all on this thread.
fn timed_passes(
    model: &dyn SkyModel,
    rays: &[ViewRay],
) -> anyhow::Result<(Vec<RayRadiance>, Timing)> {
    let start = Instant::now();
    let answers = rays
        .iter()
        .map(|ray| model.radiance(ray))
        .collect::<Result<Vec<_>, _>>()?;
    let cold_pass = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut passes = 0u32;
    while passes == 0 || start.elapsed() < MIN_TIMING {
        for ray in rays {
            black_box(model.radiance(black_box(ray))?);
        }
        passes += 1;
    }
    let warm_pass = start.elapsed().as_secs_f64() / f64::from(passes);
    Ok((
        answers,
        Timing {
            cold_pass,
            warm_pass,
        },
    ))
}

/// Mean CIEDE2000 between model and reference colours after one exposure per view: the
/// one that puts the reference's median luminance at 18 % of white.
fn mean_ciede2000(
    answers: &[RayRadiance],
    reference: &[RayRadiance],
    color: &SpectrumToColor,
) -> f64 {
    let mut luminances: Vec<f64> = reference
        .iter()
        .map(|r| color.luminance_cd_m2(&r.radiance))
        .collect();
    luminances.sort_by(f64::total_cmp);
    let median = percentile_sorted(&luminances, 0.5);
    if median.is_nan() || median <= 0.0 {
        return 0.0;
    }
    let exposure = MIDDLE_GREY / median;
    let lab = |r: &RayRadiance| {
        let xyz = color
            .xyz_cd_m2(&r.radiance)
            .map(|c| (c * exposure).max(0.0));
        xyz_to_lab(xyz, D65_WHITE)
    };
    mean(
        answers
            .iter()
            .zip(reference)
            .map(|(m, r)| ciede2000(lab(m), lab(r))),
    )
}
