//! The clouds section's GPU column: each row rendered as a hillaire frame of each view
//! with its clouds (the frame passes: the layer's march or the cloud spheres, and the
//! composite), interleaved with the same frame without clouds as `atmos bench
//! --clouds` does (`bench/clouds.rs`), so that both see the same load of a shared
//! machine: a warm-up pair (shaders, tables, the sun map or the spheres' textures),
//! then [`FRAMES`] pairs, medians of the wall-clock times from `render` until the GPU
//! has finished.

use anyhow::{Context, ensure};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::frame::Frame;

use crate::bench::timing::{median, timed};
use crate::probe_clouds::AIR_MODEL;
use crate::progress::Progress;
use crate::report::clouds_rows::CloudRow;
use crate::report::clouds_scene::ViewScene;
use crate::report::clouds_views::placed_camera;
use crate::report::paired_frames::{GpuTimes, PairedFrame};

/// The frames' size: a quarter of 1280 x 720 in each direction, for the offline
/// march's full frames are too slow on a software adapter (docs/clouds.md, "Cost").
pub const SIZE: (u32, u32) = (320, 180);
/// Measured pairs after the warm-up pair.
pub const FRAMES: usize = 1;

/// The hillaire frame of `scene`'s view at [`SIZE`], its horizontal field of view kept.
pub fn frame_of(scene: &ViewScene) -> Frame {
    let atmosphere = scene.atmosphere().clone();
    let (camera, orientation, sun) = placed_camera(&scene.view, atmosphere.bottom_radius_m);
    let half_width = (0.5 * scene.view.camera.fov_deg.to_radians()).tan();
    let vertical_fov_deg = 2.0
        * (half_width * f64::from(SIZE.1) / f64::from(SIZE.0))
            .atan()
            .to_degrees();
    Frame {
        camera_position_m: camera,
        orientation,
        vertical_fov_deg,
        sun_direction: sun,
        atmosphere,
        model: AIR_MODEL,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: SIZE.0,
        height: SIZE.1,
        terrain: None,
    }
}

/// Every row on every view where it is measured.
pub fn measure_all(
    rows: &[CloudRow],
    scenes: &[ViewScene],
    orders: &ScatteringOrders,
) -> anyhow::Result<GpuTimes> {
    let mut renderer = Renderer::headless().context("the GPU frame times need an adapter")?;
    let adapter = renderer.gpu().adapter_summary();
    let measured = |row: &CloudRow, scene: &ViewScene| {
        !matches!(row, CloudRow::Spheres { .. }) || scene.view.spheres
    };
    let total = rows
        .iter()
        .flat_map(|r| scenes.iter().filter(move |s| measured(r, s)))
        .count();
    let progress = Progress::new("gpu cloud frames", "frames", total as u64);
    let mut per_row = vec![vec![None; scenes.len()]; rows.len()];
    for (v, scene) in scenes.iter().enumerate() {
        renderer.set_cloud_inputs(scene.cover(), orders)?;
        let frame = frame_of(scene);
        for (r, row) in rows.iter().enumerate() {
            if measured(row, scene) {
                per_row[r][v] = Some(
                    measure(&mut renderer, &frame, row, scene)
                        .with_context(|| format!("{row} on view {}", scene.view.id()))?,
                );
                progress.inc();
            }
        }
    }
    renderer.set_clouds(None)?;
    progress.finish();
    Ok(GpuTimes { adapter, per_row })
}

fn measure(
    renderer: &mut Renderer,
    frame: &Frame,
    row: &CloudRow,
    scene: &ViewScene,
) -> anyhow::Result<PairedFrame> {
    let settings = scene.cloud_with(&row.cloud_settings());
    let clouds = FrameClouds {
        settings,
        light: frame_light(scene.air(), frame, &settings)?,
        form: row.form(),
        spheres: SphereSettings::default(),
        prune: true,
        // The cloud's shadow in the air as the rows' errors take it.
        shafts: scene.view.shafts,
    };
    let step = match row {
        CloudRow::Layer { .. } => "clouds",
        CloudRow::Spheres { .. } => "cloud_spheres",
    };
    let (mut cloudy, mut clear) = (Vec::new(), Vec::new());
    for k in 0..=FRAMES {
        renderer.set_clouds(None)?;
        let (_, clear_ms) = timed(renderer, frame)?;
        renderer.set_clouds(Some(clouds.clone()))?;
        let (plan, cloudy_ms) = timed(renderer, frame)?;
        ensure!(plan.runs(step), "the frame's plan has no {step}: {plan}");
        if k > 0 {
            cloudy.push(cloudy_ms);
            clear.push(clear_ms);
        }
    }
    Ok(PairedFrame {
        with_ms: median(&cloudy).unwrap_or(f64::NAN),
        without_ms: median(&clear).unwrap_or(f64::NAN),
    })
}
