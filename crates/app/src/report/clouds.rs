//! `atmos report --section clouds`: each cloud method and setting (`clouds_rows.rs`)
//! against the path-traced reference (`clouds_reference.rs`, cached) on four fixed
//! views (`clouds_views.rs`), with its CPU time and its GPU frame time
//! (`clouds_gpu.rs`): `clouds.md`, `clouds_errors.csv` and two Pareto plots
//! (`clouds_error_vs_time.png`, `clouds_error_vs_gpu_time.png`).

use anyhow::{Context, bail};
use atmosphere_core::clouds::layer::droplets::droplet_orders_cached;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::ModelSettings;

use crate::cli::ReportArgs;
use crate::files::write_atomically;
use crate::report::clouds_errors::{RowResult, errors_csv, row_result};
use crate::report::clouds_markdown::{Measured, markdown, points};
use crate::report::clouds_reference::load_or_compute;
use crate::report::clouds_rows::{CloudRow, answer, cloud_rows};
use crate::report::clouds_scene::ViewScene;
use crate::report::clouds_views::cloud_views;
use crate::report::plot;
use crate::table_cache_dir::table_cache;

/// The reference cache's file name in the report's folder.
pub const REFERENCE_FILE: &str = "clouds_reference.csv";
/// Rays per view: 4 x 3.
pub const RAYS: (usize, usize) = (4, 3);

/// The rows `--variant` names (every row when none), each checked.
pub fn rows_of(variants: &[String]) -> anyhow::Result<Vec<CloudRow>> {
    if variants.is_empty() {
        return Ok(cloud_rows());
    }
    variants.iter().map(|v| CloudRow::parse(v)).collect()
}

/// Runs the section into `args.out`.
pub fn report_clouds(args: &ReportArgs) -> anyhow::Result<()> {
    let rows = rows_of(&args.variant)?;
    let settings = ModelSettings::default();
    let views = cloud_views(RAYS.0, RAYS.1);
    for id in &args.recompute_view {
        if !views.iter().any(|v| v.id() == id) {
            let known: Vec<&str> = views.iter().map(|v| v.id()).collect();
            bail!(
                "--recompute-view {id}: no such clouds view (the views: {})",
                known.join(", ")
            );
        }
    }
    let orders = droplet_orders_cached(&settings.wavelengths_nm, &table_cache())
        .context("the droplets' phase functions")?;
    let scenes = views
        .into_iter()
        .map(|v| ViewScene::new(v, &settings, &orders))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let reference = load_or_compute(&args.out.join(REFERENCE_FILE), &scenes, &settings, |view| {
        args.recompute_reference || args.recompute_view.iter().any(|id| id == view.id())
    })?;
    if args.reference_only {
        return Ok(());
    }
    let color = SpectrumToColor::new(&settings.wavelengths_nm)?;
    let mut results: Vec<RowResult> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        eprintln!("report: clouds {}/{} {row}", i + 1, rows.len());
        let answers = scenes
            .iter()
            .map(|scene| answer(row, scene))
            .collect::<anyhow::Result<Vec<_>>>()?;
        results.push(row_result(*row, &answers, &reference, &color));
    }
    let gpu = if args.no_gpu {
        None
    } else {
        Some(crate::report::clouds_gpu::measure_all(
            &rows, &scenes, &orders,
        )?)
    };
    let measured = Measured {
        scenes: &scenes,
        reference: &reference,
        results: &results,
        gpu: gpu.as_ref(),
        color: &color,
    };
    write_atomically(&args.out.join("clouds.md"), markdown(&measured).as_bytes())?;
    write_atomically(
        &args.out.join("clouds_errors.csv"),
        errors_csv(&results, &scenes).as_bytes(),
    )?;
    let (cpu, gpu_points) = points(&measured);
    plot::draw(
        &args.out.join("clouds_error_vs_time.png"),
        &crate::report::clouds_markdown::CPU_AXIS,
        &cpu,
    )?;
    if !gpu_points.is_empty() {
        plot::draw(
            &args.out.join("clouds_error_vs_gpu_time.png"),
            &crate::report::clouds_markdown::GPU_AXIS,
            &gpu_points,
        )?;
    }
    eprintln!("report: wrote {}", args.out.join("clouds.md").display());
    Ok(())
}
