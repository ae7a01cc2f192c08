//! `atmos report --section optics`: each setting of the rain and ice volumes
//! (`optics_rows.rs`) against the volumes' path tracer (`optics_reference.rs`, cached)
//! on three views of the shipped scenes (`optics_views.rs`), with its CPU time and its
//! GPU frame time (`optics_gpu.rs`): `optics.md`, `optics_errors.csv` and two Pareto
//! plots (`optics_error_vs_time.png`, `optics_error_vs_gpu_time.png`).

use std::path::PathBuf;

use anyhow::bail;
use atmosphere_core::color::SpectrumToColor;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

use crate::cli::ReportArgs;
use crate::files::write_atomically;
use crate::report::optics_errors::{RowResult, errors_csv, row_result};
use crate::report::optics_markdown::{CPU_AXIS, GPU_AXIS, Measured, markdown, points};
use crate::report::optics_reference::load_or_compute;
use crate::report::optics_rows::{OpticsRow, answer, optics_rows};
use crate::report::optics_scene::OpticsScene;
use crate::report::optics_views::optics_views;
use crate::report::plot;

/// The reference cache's file name in the report's folder.
pub const REFERENCE_FILE: &str = "optics_reference.csv";

/// The shipped optics scenes' folder.
pub fn scenes_folder() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/optics")
}

/// The rows `--variant` names (every row when none), each checked.
pub fn rows_of(variants: &[String]) -> anyhow::Result<Vec<OpticsRow>> {
    if variants.is_empty() {
        return Ok(optics_rows());
    }
    variants.iter().map(|v| OpticsRow::parse(v)).collect()
}

/// Runs the section into `args.out`.
pub fn report_optics(args: &ReportArgs) -> anyhow::Result<()> {
    let rows = rows_of(&args.variant)?;
    let views = optics_views();
    for id in &args.recompute_view {
        if !views.iter().any(|v| v.id == id) {
            let known: Vec<&str> = views.iter().map(|v| v.id).collect();
            bail!(
                "--recompute-view {id}: no such optics view (the views: {})",
                known.join(", ")
            );
        }
    }
    let folder = scenes_folder();
    let scenes = views
        .into_iter()
        .map(|v| OpticsScene::new(v, &folder))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let reference = load_or_compute(&args.out.join(REFERENCE_FILE), &scenes, |scene| {
        args.recompute_reference || args.recompute_view.iter().any(|id| id == scene.view.id)
    })?;
    if args.reference_only {
        return Ok(());
    }
    let color = SpectrumToColor::new(&RGB_WAVELENGTHS_NM)?;
    let mut results: Vec<RowResult> = Vec::with_capacity(rows.len());
    for (i, row) in rows.iter().enumerate() {
        eprintln!("report: optics {}/{} {row}", i + 1, rows.len());
        let answers = scenes
            .iter()
            .map(|scene| answer(row, scene))
            .collect::<anyhow::Result<Vec<_>>>()?;
        results.push(row_result(*row, &answers, &reference, &color));
    }
    let gpu = if args.no_gpu {
        None
    } else {
        Some(crate::report::optics_gpu::measure_all(&rows, &scenes)?)
    };
    let measured = Measured {
        scenes: &scenes,
        reference: &reference,
        results: &results,
        gpu: gpu.as_ref(),
        color: &color,
    };
    write_atomically(&args.out.join("optics.md"), markdown(&measured).as_bytes())?;
    write_atomically(
        &args.out.join("optics_errors.csv"),
        errors_csv(&results, &scenes).as_bytes(),
    )?;
    let (cpu, gpu_points) = points(&measured);
    plot::draw(&args.out.join("optics_error_vs_time.png"), &CPU_AXIS, &cpu)?;
    if !gpu_points.is_empty() {
        plot::draw(
            &args.out.join("optics_error_vs_gpu_time.png"),
            &GPU_AXIS,
            &gpu_points,
        )?;
    }
    eprintln!("report: wrote {}", args.out.join("optics.md").display());
    Ok(())
}
