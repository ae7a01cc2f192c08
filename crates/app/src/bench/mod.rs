//! `atmos bench`: for each model on the GPU, on the current adapter, the time to build
//! its tables and to render a ground, a sunset and an orbit view, per step of the frame
//! plan, as a Markdown table; each model's frame time is also given as a ratio to the
//! 16-sample nishita frame, the cost baseline of the issue. Times are medians of several
//! frames after a warm-up frame (which compiles shaders and builds tables).

pub mod baseline;
pub mod beams;
pub mod clouds;
pub mod clouds_whole_frames;
pub mod flight;
pub mod optics;
pub mod shafts;
pub mod terrain;
pub mod timing;
pub mod variant;
pub mod views;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io::Write as _;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;
use render_wgpu::frame::plan::{FramePlan, StepKind};
use render_wgpu::sky::registry::GPU_MODELS;

use crate::camera_path::CameraPath;
use crate::cli::BenchArgs;
use crate::files::{check_writable, write_atomically};
use crate::progress::Progress;
use crate::render::scene::Scene;
use baseline::{BASELINE, baseline};
use timing::{median, timed};
use variant::Variant;
use views::{BENCH_VIEWS, BenchView};

/// The baseline, then each requested model with its defaults (every model on the GPU
/// when neither models nor variants are asked for), then the variants asked for.
pub fn variants(models: &[ModelId], extra: &[Variant]) -> Vec<Variant> {
    let mut out = vec![baseline()];
    let chosen: Vec<ModelId> = if models.is_empty() && extra.is_empty() {
        GPU_MODELS.to_vec()
    } else {
        models.to_vec()
    };
    out.extend(chosen.into_iter().map(|m| Variant::new(m, None, &[])));
    out.extend(extra.iter().cloned());
    out
}

/// The measured times of one model in one view, ms.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViewTimes {
    /// Median GPU time of each pass (table builds excluded), in plan order.
    pub passes: Vec<(&'static str, Option<f64>)>,
    /// Median of the frame's wall-clock time, from `render` to the GPU's end.
    pub frame_wall_ms: f64,
    /// Median of the sum of the passes' GPU times, where the adapter times them.
    pub frame_gpu_ms: Option<f64>,
}

/// What one variant measured.
#[derive(Clone, Debug, PartialEq)]
pub struct VariantTimes {
    pub variant: Variant,
    /// Median GPU time of each table build when every table is rebuilt, ms.
    pub tables: Vec<(&'static str, Option<f64>)>,
    /// Median wall-clock time of a ground frame that rebuilds every table, ms; less the
    /// ground view's plain frame, the tables' own time (timestamps on a CPU adapter such
    /// as lavapipe are indicative only).
    pub rebuild_wall_ms: f64,
    pub views: Vec<ViewTimes>,
}

fn frame(
    variant: &Variant,
    view: &BenchView,
    atmosphere: &Atmosphere,
    args: &BenchArgs,
) -> anyhow::Result<Frame> {
    Ok(Frame {
        camera_position_m: view.view.position_m(atmosphere.bottom_radius_m),
        orientation: view.view.orientation(),
        vertical_fov_deg: view.fov_deg,
        sun_direction: view.view.sun_direction(),
        atmosphere: atmosphere.clone(),
        model: variant.model,
        settings: variant.settings(),
        exposure_ev100: 14.0,
        width: args.width,
        height: args.height,
        terrain: None,
    })
}

/// Median GPU time per step of `kind` over `plans`, in the first plan's order.
fn step_medians(plans: &[FramePlan], kind: StepKind) -> Vec<(&'static str, Option<f64>)> {
    let mut times: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    let mut order = Vec::new();
    let mut untimed = Vec::new();
    for plan in plans {
        for step in plan.steps.iter().filter(|s| s.kind == kind) {
            if !order.contains(&step.name) {
                order.push(step.name);
            }
            match step.gpu_ms {
                Some(ms) => times.entry(step.name).or_default().push(ms),
                None => untimed.push(step.name),
            }
        }
    }
    order
        .into_iter()
        .map(|name| {
            let ms = times.get(name).and_then(|t| median(t));
            (name, if untimed.contains(&name) { None } else { ms })
        })
        .collect()
}

/// A copy of `atmosphere` that differs in the last bit of the Rayleigh scale height,
/// so every table that depends on the atmosphere is rebuilt, while the image stays the
/// same to rounding.
fn nudged(atmosphere: &Atmosphere, k: usize) -> Atmosphere {
    let mut a = atmosphere.clone();
    if let Some(layer) = a.rayleigh.density.layers.first_mut() {
        let s = layer.exp_scale_per_m;
        layer.exp_scale_per_m = if k.is_multiple_of(2) {
            s
        } else {
            s * (1.0 + f64::EPSILON)
        };
    }
    a
}

/// Measures one variant: every table rebuilt `frames` times, then each view.
fn measure(
    renderer: &mut Renderer,
    variant: &Variant,
    atmosphere: &Atmosphere,
    args: &BenchArgs,
    progress: &Progress,
) -> anyhow::Result<VariantTimes> {
    let first = frame(variant, &BENCH_VIEWS[0], atmosphere, args)?;
    timed(renderer, &first)?;
    progress.inc();
    let mut rebuilds = Vec::new();
    let mut rebuild_wall = Vec::new();
    for k in 1..=args.frames {
        let mut f = first.clone();
        f.atmosphere = nudged(atmosphere, k);
        let (plan, wall) = timed(renderer, &f)?;
        rebuilds.push(plan);
        rebuild_wall.push(wall);
        progress.inc();
    }
    let mut views = Vec::new();
    for view in BENCH_VIEWS {
        let f = frame(variant, view, atmosphere, args)?;
        timed(renderer, &f)?;
        progress.inc();
        let mut plans = Vec::new();
        let mut walls = Vec::new();
        for _ in 0..args.frames {
            let (plan, wall) = timed(renderer, &f)?;
            plans.push(plan);
            walls.push(wall);
            progress.inc();
        }
        let totals: Option<Vec<f64>> = plans.iter().map(FramePlan::total_gpu_ms).collect();
        views.push(ViewTimes {
            passes: step_medians(&plans, StepKind::Pass),
            frame_wall_ms: median(&walls).unwrap_or(f64::NAN),
            frame_gpu_ms: totals.and_then(|t| median(&t)),
        });
    }
    Ok(VariantTimes {
        variant: variant.clone(),
        tables: step_medians(&rebuilds, StepKind::TableBuild),
        rebuild_wall_ms: median(&rebuild_wall).unwrap_or(f64::NAN),
        views,
    })
}

fn ms(value: Option<f64>) -> String {
    value.map_or_else(|| "-".to_string(), |v| format!("{v:.1}"))
}

fn steps(list: &[(&'static str, Option<f64>)]) -> String {
    if list.is_empty() {
        return "none".into();
    }
    list.iter()
        .map(|(name, t)| format!("{name} {}", ms(*t)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The Markdown tables of `results` measured on `adapter`.
pub fn markdown(adapter: &str, args: &BenchArgs, results: &[VariantTimes]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "atmos bench on {adapter}: {}x{} px, medians of {} frames after one warm-up frame; \
         GPU times from timestamp queries (`-` where the adapter has none), wall-clock from \
         `render` until the GPU has finished.\n",
        args.width, args.height, args.frames
    );
    let _ = writeln!(
        out,
        "| model | table builds, GPU ms | all tables rebuilt, wall ms |"
    );
    let _ = writeln!(out, "|---|---|---|");
    for r in results {
        let _ = writeln!(
            out,
            "| {} | {} | {:.1} |",
            r.variant.label,
            steps(&r.tables),
            r.rebuild_wall_ms
        );
    }
    let baseline = results.iter().find(|r| r.variant.label == BASELINE);
    let _ = writeln!(
        out,
        "\n| model | view | passes, GPU ms | frame GPU ms | frame wall ms | wall / {BASELINE} |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for r in results {
        for (view, t) in BENCH_VIEWS.iter().zip(&r.views) {
            let ratio = baseline
                .and_then(|b| {
                    b.views
                        .iter()
                        .zip(BENCH_VIEWS)
                        .find(|(_, v)| v.name == view.name)
                })
                .map(|(b, _)| t.frame_wall_ms / b.frame_wall_ms);
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {:.1} | {} |",
                r.variant.label,
                view.name,
                steps(&t.passes),
                ms(t.frame_gpu_ms),
                t.frame_wall_ms,
                ratio.map_or_else(|| "-".to_string(), |x| format!("{x:.2}"))
            );
        }
    }
    out
}

/// Runs `atmos bench`: measures, prints the tables, and writes them to `--out` if given.
pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.out {
        check_writable(path)?;
    }
    if args.frames == 0 {
        bail!("--frames must be at least 1");
    }
    if let Some(path) = &args.flight {
        let size = (args.width, args.height);
        let camera_path = CameraPath::load(path)?;
        let flight_frames = flight::frames(&camera_path, path, args.flight_fps, size)?;
        let mut renderer = Renderer::headless()?;
        let adapter = renderer.gpu().adapter_summary();
        let frames = flight::measure(&mut renderer, &flight_frames)?;
        let text = flight::markdown(path, &adapter, size, &frames);
        std::io::stdout().lock().write_all(text.as_bytes())?;
        if let Some(out) = &args.out {
            write_atomically(out, text.as_bytes())?;
        }
        return Ok(());
    }
    if let Some(path) = &args.terrain_scene {
        let size = (args.width, args.height);
        let frame = terrain::scene_frame(path, size)?;
        let mut renderer = Renderer::headless()?;
        let adapter = renderer.gpu().adapter_summary();
        let times = terrain::measure(&mut renderer, &frame, args.frames)?;
        let text = terrain::markdown(path, &adapter, size, &times);
        std::io::stdout().lock().write_all(text.as_bytes())?;
        if let Some(out) = &args.out {
            write_atomically(out, text.as_bytes())?;
        }
        return Ok(());
    }
    if let Some(path) = &args.optics_scene {
        let size = (args.width, args.height);
        let mut renderer = Renderer::headless()?;
        let adapter = renderer.gpu().adapter_summary();
        let times = optics::measure(&mut renderer, path, size, args.frames)?;
        let text = optics::markdown(path, &adapter, size, &times);
        std::io::stdout().lock().write_all(text.as_bytes())?;
        if let Some(out) = &args.out {
            write_atomically(out, text.as_bytes())?;
        }
        return Ok(());
    }
    if let Some(path) = &args.shafts_scene {
        let size = (args.width, args.height);
        let mut renderer = Renderer::headless()?;
        let adapter = renderer.gpu().adapter_summary();
        let total = shafts::frames_per_scene(args.frames) as u64;
        let progress = Progress::new("bench", "frames", total);
        let overrides = Scene {
            width: Some(size.0),
            height: Some(size.1),
            ..Scene::default()
        };
        let times = shafts::measure(&mut renderer, path, (&overrides, args.frames), &progress)?;
        progress.finish();
        let text = shafts::markdown(path, &adapter, size, &times);
        std::io::stdout().lock().write_all(text.as_bytes())?;
        if let Some(out) = &args.out {
            write_atomically(out, text.as_bytes())?;
        }
        return Ok(());
    }
    for m in &args.model {
        Renderer::check_model(*m)?;
    }
    let atmosphere = Atmosphere::from_preset_or_file(&args.atmosphere)
        .with_context(|| format!("--atmosphere {}", args.atmosphere))?;
    let extra = args
        .variant
        .iter()
        .map(|text| Variant::parse(text))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let beam_variants = match (&args.beams_scene, args.beams_variant.is_empty()) {
        (None, _) => Vec::new(),
        (Some(_), true) => vec![beams::BeamVariant::parse("march")?],
        (Some(_), false) => args
            .beams_variant
            .iter()
            .map(|text| beams::BeamVariant::parse(text))
            .collect::<anyhow::Result<Vec<_>>>()?,
    };
    let cloud_qualities = args
        .clouds
        .iter()
        .map(|q| {
            q.parse::<MarchQuality>()
                .map_err(|e| anyhow::anyhow!("--clouds: {e}"))
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let only_extras = args.beams_scene.is_some() || !cloud_qualities.is_empty();
    let variants = if only_extras && args.model.is_empty() && extra.is_empty() {
        vec![baseline()]
    } else {
        variants(&args.model, &extra)
    };
    let mut renderer = Renderer::headless()?;
    let adapter = renderer.gpu().adapter_summary();
    let per_variant = 1 + args.frames + BENCH_VIEWS.len() * (1 + args.frames);
    let total = variants.len() * per_variant
        + beam_variants.len() * beams::frames_per_variant(args.frames)
        + cloud_qualities
            .iter()
            .map(|&q| {
                clouds::frames_per_quality(q, args.frames)
                    + clouds_whole_frames::frames_per_quality(args.frames)
            })
            .sum::<usize>();
    let progress = Progress::new("bench", "frames", total as u64);
    let mut results = Vec::new();
    for variant in &variants {
        results.push(measure(
            &mut renderer,
            variant,
            &atmosphere,
            args,
            &progress,
        )?);
    }
    let mut beam_results = Vec::new();
    if let Some(path) = &args.beams_scene {
        let base = frame(&baseline(), &BENCH_VIEWS[0], &atmosphere, args)?;
        let size = ((args.width, args.height), args.frames);
        beam_results = beams::measure(&mut renderer, &base, path, &beam_variants, size, &progress)?;
    }
    let size = ((args.width, args.height), args.frames);
    let (cloud_results, shaft_results) = clouds::measure(
        &mut renderer,
        &atmosphere,
        &cloud_qualities,
        size,
        &progress,
    )?;
    let whole_results = clouds_whole_frames::measure(
        &mut renderer,
        &atmosphere,
        &cloud_qualities,
        size,
        &progress,
    )?;
    progress.finish();
    let mut text = markdown(&adapter, args, &results);
    if let Some(path) = &args.beams_scene {
        text.push_str(&beams::markdown(path, BASELINE, &beam_results));
    }
    if !cloud_results.is_empty() {
        let size = (args.width, args.height);
        text.push_str(&clouds::markdown(&adapter, size, &cloud_results));
        text.push_str(&clouds::shafts_markdown(&shaft_results));
        text.push_str(&clouds_whole_frames::markdown(&whole_results));
    }
    std::io::stdout().lock().write_all(text.as_bytes())?;
    if let Some(path) = &args.out {
        write_atomically(path, text.as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_and_variants() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.0));
        assert_eq!(median(&[]), None);
        let v = variants(&[ModelId::Nishita], &[]);
        assert_eq!(v[0].label, BASELINE);
        assert_eq!(v[1].label, "nishita");
        assert!(v[1].options.is_empty());
        assert_eq!(variants(&[], &[]).len(), 1 + GPU_MODELS.len());
        let extra = Variant::parse("hillaire ms_samples=4").unwrap();
        let v = variants(&[], std::slice::from_ref(&extra));
        assert_eq!(v, vec![baseline(), extra]);
    }

    #[test]
    fn nudging_changes_the_atmosphere_by_one_rounding() {
        let earth = Atmosphere::preset("earth").unwrap();
        assert_eq!(nudged(&earth, 0), earth);
        let n = nudged(&earth, 1);
        assert_ne!(n, earth);
        let (a, b) = (
            earth.rayleigh.density.layers[0].exp_scale_per_m,
            n.rayleigh.density.layers[0].exp_scale_per_m,
        );
        assert!(((a - b) / a).abs() <= 2.0 * f64::EPSILON);
    }
}
