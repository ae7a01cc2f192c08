//! `atmos report`: every model setting against the reference on a fixed set of views:
//! error, build time, time per ray and memory, CPU and GPU frame times, as `README.md`,
//! `error_vs_time.png`, `error_vs_gpu_time.png` and `errors.csv`; the light beams of
//! the shipped beams scenes as `beams.md` and its plots (`beams.rs`); the terrain's light
//! shafts as `shafts.md` and its plots (`shafts.rs`); the clouds as `clouds.md` and its
//! plots (`clouds.rs`); the rain and ice volumes as `optics.md` and its plots
//! (`optics.rs`).

pub mod beams;
pub mod clouds;
pub mod clouds_errors;
pub mod clouds_gpu;
pub mod clouds_markdown;
pub mod clouds_reference;
pub mod clouds_rows;
pub mod clouds_scene;
pub mod clouds_views;
pub mod error_table;
pub mod gpu_time;
pub mod judged_rays;
pub mod markdown;
pub mod measure;
pub mod mirror_rays;
pub mod optics;
pub mod optics_errors;
pub mod optics_gpu;
pub mod optics_markdown;
pub mod optics_reference;
pub mod optics_rows;
pub mod optics_scene;
pub mod optics_views;
pub mod paired_frames;
pub mod plot;
pub mod reference_batches;
pub mod reference_cache;
pub mod reference_cache_file;
pub mod reference_ground_rays;
pub mod shafts;
pub mod variants;
pub mod view_sections;
pub mod views;

use std::fs;

use anyhow::{Context, bail};
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::reference::{MAX_PATHS, ReferenceSettings};

use crate::cli::{ReportArgs, ReportSection};
use crate::files::write_atomically;
use crate::report::markdown::{Provenance, write_report};
use crate::report::measure::{Variant, measure};
use crate::report::plot::{CPU_AXIS, GPU_AXIS, Point};
use crate::report::variants::{DEFAULT_OUT, report_variants};

/// Runs the report: the sections `--section` asks for.
pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let all = [
        ReportSection::Skies,
        ReportSection::Beams,
        ReportSection::Shafts,
        ReportSection::Clouds,
        ReportSection::Optics,
    ];
    if !all.iter().any(|s| args.writes(*s)) {
        bail!(
            "nothing to report: --model and --variant narrow the skies section, which --section leaves out"
        );
    }
    let with_rows = [
        ReportSection::Skies,
        ReportSection::Clouds,
        ReportSection::Optics,
    ];
    if with_rows.iter().filter(|s| args.writes(**s)).count() > 1 && !args.variant.is_empty() {
        bail!("--variant narrows one section at a time: skies, clouds or optics (--section)");
    }
    fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    if args.writes(ReportSection::Skies) {
        report_skies(args)?;
    }
    if args.writes(ReportSection::Clouds) {
        clouds::report_clouds(args)?;
    }
    if args.writes(ReportSection::Optics) {
        optics::report_optics(args)?;
    }
    if args.reference_only {
        return Ok(());
    }
    if args.writes(ReportSection::Beams) {
        report_beams(args)?;
    }
    if args.writes(ReportSection::Shafts) {
        report_shafts(args)?;
    }
    Ok(())
}

/// The sky models' section: `README.md`, `errors.csv` and the two plots.
fn report_skies(args: &ReportArgs) -> anyhow::Result<()> {
    let (columns, rows) = args.rays;
    let views = views::report_views(columns, rows);
    let base = ModelSettings {
        target_relative_error: args.reference_error,
        ..ModelSettings::default()
    };
    base.validate()?;
    MAX_PATHS
        .check(args.twilight_max_paths)
        .context("--twilight-max-paths")?;
    let mut variants = if args.variant.is_empty() {
        report_variants()
    } else {
        args.variant
            .iter()
            .map(|text| {
                let v = crate::bench::variant::Variant::parse(text)?;
                Ok(Variant {
                    model: v.model,
                    max_orders: v.max_orders,
                    options: v.options,
                })
            })
            .collect::<anyhow::Result<Vec<_>>>()?
    };
    if !args.model.is_empty() {
        variants.retain(|v| args.model.contains(&v.model));
    }
    if variants.is_empty() {
        bail!("no report settings for the models {:?}", args.model);
    }
    for id in &args.recompute_view {
        if !views.iter().any(|v| v.id == id) {
            let known: Vec<&str> = views.iter().map(|v| v.id).collect();
            bail!(
                "--recompute-view {id}: no such view (the views: {})",
                known.join(", ")
            );
        }
    }
    let recompute = |view: &views::ReportView| {
        args.recompute_reference || args.recompute_view.iter().any(|id| id == view.id)
    };
    let reference = reference_cache::load_or_compute(
        &args.out.join("reference.csv"),
        &views,
        |view| reference_cache::reference_settings(view, &base, args.twilight_max_paths),
        |view| reference_cache::reference_batches(view, &base),
        recompute,
    )?;
    let single_base = ModelSettings {
        max_orders: Some(1),
        ..base.clone()
    };
    let single = reference_cache::load_or_compute(
        &args.out.join("reference_single.csv"),
        &views,
        |_| single_base.clone(),
        |_| 1,
        recompute,
    )?;
    if args.reference_only {
        eprintln!("report: reference caches written to {}", args.out.display());
        return Ok(());
    }
    let reference = mirror_rays::pool_mirror_rays(&views, reference);
    let single = mirror_rays::pool_mirror_rays(&views, single);
    let color = SpectrumToColor::new(&base.wavelengths_nm)?;
    let mut results = Vec::with_capacity(variants.len());
    for (i, variant) in variants.iter().enumerate() {
        eprintln!("report: {}/{} {}", i + 1, variants.len(), variant.label());
        results.push(measure(
            variant, &views, &reference, &single, &base, &color,
        )?);
    }
    let adapter = if args.no_gpu {
        None
    } else {
        let gpu_variants = variants
            .iter()
            .map(|v| crate::bench::variant::Variant::parse(&v.label()))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let (adapter, times) = gpu_time::measure_all(&gpu_variants, &views)?;
        for (result, time) in results.iter_mut().zip(times) {
            result.gpu = time;
        }
        Some(adapter)
    };
    let provenance = Provenance {
        command: command_line(args),
        threads_note: format!(
            "Times are wall-clock on one thread of a machine with {} logical CPUs; table \
             builds use all of them.",
            std::thread::available_parallelism().map_or(1, |n| n.get())
        ),
        reference_target_error: base.target_relative_error,
        gpu_adapter: adapter,
    };
    let text = write_report(&provenance, &views, &reference, &results, &color);
    write_atomically(&args.out.join("README.md"), text.as_bytes())?;
    let table = error_table::to_csv(&error_table::rows(&results, &views));
    write_atomically(&args.out.join("errors.csv"), table.as_bytes())?;
    let points: Vec<Point> = results.iter().map(Point::cpu).collect();
    plot::draw(&args.out.join("error_vs_time.png"), &CPU_AXIS, &points)?;
    if provenance.gpu_adapter.is_some() {
        let points: Vec<Point> = results.iter().filter_map(Point::gpu).collect();
        plot::draw(&args.out.join("error_vs_gpu_time.png"), &GPU_AXIS, &points)?;
    }
    eprintln!("report: wrote {}", args.out.join("README.md").display());
    Ok(())
}

/// The beams section: `beams.md` and its two plots in the report's folder.
fn report_beams(args: &ReportArgs) -> anyhow::Result<()> {
    eprintln!("report: light beams on {} scenes", beams::BEAM_SCENES.len());
    let gpu = if args.no_gpu {
        None
    } else {
        Some(render_wgpu::GpuContext::headless()?)
    };
    let rows = beams::measure(
        &beams::shipped_folder(),
        &beams::BEAM_SCENES,
        &beams::BEAM_VARIANTS,
        beams::RAYS_ACROSS,
        gpu.as_ref(),
    )?;
    let text = beams::markdown(&rows, beams::RAYS_ACROSS);
    write_atomically(&args.out.join("beams.md"), text.as_bytes())?;
    let (cpu, gpu_points) = beams::points(&rows, &beams::BEAM_VARIANTS);
    plot::draw(
        &args.out.join("beams_error_vs_time.png"),
        &beams::BEAMS_CPU_AXIS,
        &cpu,
    )?;
    if !gpu_points.is_empty() {
        plot::draw(
            &args.out.join("beams_error_vs_gpu_time.png"),
            &beams::BEAMS_GPU_AXIS,
            &gpu_points,
        )?;
    }
    Ok(())
}

/// The light-shafts section: `shafts.md` and its two plots in the report's folder.
fn report_shafts(args: &ReportArgs) -> anyhow::Result<()> {
    eprintln!(
        "report: light shafts on {} scenes",
        shafts::SHAFT_SCENES.len()
    );
    let mut renderer = if args.no_gpu {
        None
    } else {
        Some(render_wgpu::Renderer::headless()?)
    };
    let rows = shafts::measure(
        &shafts::shipped_folder(),
        &shafts::SHAFT_SCENES,
        &shafts::SHAFT_VARIANTS,
        args.rays,
        renderer.as_mut(),
    )?;
    let text = shafts::markdown(&rows, args.rays);
    write_atomically(&args.out.join("shafts.md"), text.as_bytes())?;
    let (cpu, gpu_points) = shafts::points(&rows, &shafts::SHAFT_VARIANTS);
    plot::draw(
        &args.out.join("shafts_error_vs_time.png"),
        &shafts::SHAFTS_CPU_AXIS,
        &cpu,
    )?;
    if !gpu_points.is_empty() {
        plot::draw(
            &args.out.join("shafts_error_vs_gpu_time.png"),
            &shafts::SHAFTS_GPU_AXIS,
            &gpu_points,
        )?;
    }
    Ok(())
}

/// The command that regenerates this report.
fn command_line(args: &ReportArgs) -> String {
    let mut command = "cargo run --release -p atmos -- report".to_string();
    if args.out != std::path::Path::new(DEFAULT_OUT) {
        command.push_str(&format!(" --out {}", args.out.display()));
    }
    if args.rays != (16, 9) {
        command.push_str(&format!(" --rays {}x{}", args.rays.0, args.rays.1));
    }
    for m in &args.model {
        command.push_str(&format!(" --model {m}"));
    }
    for v in &args.variant {
        command.push_str(&format!(" --variant '{v}'"));
    }
    if args.no_gpu {
        command.push_str(" --no-gpu");
    }
    for section in &args.section {
        command.push_str(&format!(" --section {section:?}").to_lowercase());
    }
    if args.twilight_max_paths != ReferenceSettings::default().max_paths {
        command.push_str(&format!(
            " --twilight-max-paths {}",
            args.twilight_max_paths
        ));
    }
    if args.reference_error != ModelSettings::default().target_relative_error {
        command.push_str(&format!(" --reference-error {}", args.reference_error));
    }
    command
}
