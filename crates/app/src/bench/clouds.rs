//! `atmos bench --clouds QUALITY`: what the cloud layer adds to a hillaire frame of a
//! flight view at 2.9 km (inside the default layer, 100 m below its top) over the
//! generated cover, against the
//! hillaire sky pass. Each frame with clouds is interleaved with the same frame without
//! them, so that the difference is measured under the same load; the difference of each
//! pair's wall-clock times is the clouds' cost (on a CPU adapter such as lavapipe the
//! cloud steps' timestamps are not to be trusted: docs/clouds.md, "Cost"). Medians of
//! `--frames` pairs after a warm-up pair. Each quality is measured with its preset's
//! sun light and again with the other (`sun_light = march`, a shadow march per sample;
//! `map`, the frame's sun map), for comparison, without the cloud's shadow in the air;
//! then the quality as a user gets it, the clouds with that shadow (the cloud shafts'
//! own pass), in rounds of three frames (without clouds, with clouds, with clouds and
//! their shadow): what both add to the frame without clouds, and the shadow's share.

use atmosphere_core::clouds::spheres::handover::CloudForm;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use std::fmt::Write as _;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::{LayerSettings, SunLight};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::SkyModel;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_cloud_shafts::CLOUD_SHAFTS;
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::frame::{Frame, LocalView, location_rotation};

use crate::bench::timing::{median, step_gpu_ms, timed};
use crate::progress::Progress;
use crate::render::cloud_flags::{CloudFlags, droplet_orders};

/// The flight view: 2.9 km over the Atlantic at (25 N, 30 W), looking 2 degrees below the
/// horizon towards azimuth 200 (from north towards east), the sun 30 degrees up at
/// azimuth 120.
const FLIGHT: LocalView = LocalView {
    altitude_m: 2_900.0,
    view_zenith_deg: 92.0,
    view_azimuth_deg: -200.0,
    sun_zenith_deg: 60.0,
    sun_azimuth_deg: -120.0,
};
pub const LATITUDE_DEG: f64 = 25.0;
pub const LONGITUDE_DEG: f64 = -30.0;

/// What one quality measured, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct CloudTimes {
    pub quality: MarchQuality,
    pub sun_light: SunLight,
    /// Median of the pairs' differences of wall-clock time, clouds less none.
    pub added_wall_ms: f64,
    /// Median wall-clock time of the frame without clouds.
    pub clear_wall_ms: f64,
    /// Median GPU time of the hillaire pass in the frames without clouds.
    pub sky_pass_ms: Option<f64>,
}

/// The hillaire frame of `view` over (25 N, 30 W) in `atmosphere` at `size`, 60 degrees
/// of vertical field (the flight view, and the views of `clouds_whole_frames.rs`).
pub fn bench_frame(view: &LocalView, atmosphere: &Atmosphere, size: (u32, u32)) -> Frame {
    let place = location_rotation(LATITUDE_DEG, LONGITUDE_DEG);
    let atmosphere = atmosphere.clone();
    Frame {
        camera_position_m: place * view.position_m(atmosphere.bottom_radius_m),
        orientation: place * view.orientation(),
        vertical_fov_deg: 60.0,
        sun_direction: place * view.sun_direction(),
        atmosphere,
        model: ModelId::Hillaire,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: size.0,
        height: size.1,
        terrain: None,
    }
}

/// The settings the bench measures for `quality`: its preset, and the same with the
/// other sun light.
fn variants(quality: MarchQuality) -> [LayerSettings; 2] {
    let settings = quality.apply(LayerSettings::default());
    let other = match settings.sun_light {
        SunLight::March => SunLight::Map,
        SunLight::Map => SunLight::March,
    };
    [
        settings,
        LayerSettings {
            sun_light: other,
            ..settings
        },
    ]
}

/// Frames the bench renders for `quality` (the warm-up round included: a pair for each
/// of its variants, three frames for the cloud shafts).
pub fn frames_per_quality(quality: MarchQuality, frames: usize) -> usize {
    (1 + frames) * (2 * variants(quality).len() + 3)
}

/// What one quality's clouds with their shadow in the air (the quality as a user gets
/// it) added to the frame without clouds, and the shadow's share, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaftTimes {
    pub quality: MarchQuality,
    /// Median of the rounds' differences of wall-clock time, the frame with clouds and
    /// their shadow less the frame without clouds.
    pub total_added_wall_ms: f64,
    /// Median of the rounds' differences, the frame with clouds and their shadow less
    /// the frame with clouds alone.
    pub added_wall_ms: f64,
    /// Median wall-clock time of the frame without clouds.
    pub clear_wall_ms: f64,
    /// The hillaire pass as the clouds' rounds of the same quality timed it
    /// ([`CloudTimes::sky_pass_ms`]): lavapipe's timestamps in these rounds, frames
    /// without clouds included, read from 0.1 ms to the pass's time.
    pub sky_pass_ms: Option<f64>,
    /// Median GPU time of the pass of the cloud's shadow in the air (`cloud_shafts`).
    pub air_pass_ms: Option<f64>,
}

/// Measures the cloud shafts of `quality` on `renderer` in `atmosphere` at `size`,
/// `frames` rounds after a warm-up round, each the frame without clouds, with clouds,
/// and with clouds and their shadow in the air, interleaved; `sky_pass_ms` the hillaire
/// pass the clouds' rounds of the quality timed.
fn measure_shafts(
    renderer: &mut Renderer,
    (frame, model): (&Frame, &dyn SkyModel),
    (quality, sky_pass_ms): (MarchQuality, Option<f64>),
    frames: usize,
    progress: &Progress,
) -> anyhow::Result<ShaftTimes> {
    let settings = quality.apply(LayerSettings::default());
    let without = FrameClouds {
        settings,
        light: frame_light(model, frame, &settings)?,
        form: CloudForm::Auto,
        spheres: SphereSettings::default(),
        prune: true,
        shafts: false,
    };
    let with = FrameClouds {
        shafts: true,
        ..without.clone()
    };
    let (mut total, mut added, mut clear, mut air) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for k in 0..=frames {
        renderer.set_clouds(None)?;
        let (_, none_ms) = timed(renderer, frame)?;
        progress.inc();
        renderer.set_clouds(Some(without.clone()))?;
        let (_, plain_ms) = timed(renderer, frame)?;
        progress.inc();
        renderer.set_clouds(Some(with.clone()))?;
        let (shafts, shafts_ms) = timed(renderer, frame)?;
        progress.inc();
        anyhow::ensure!(
            !shafts.skipped.iter().any(|(name, _)| *name == CLOUD_SHAFTS),
            "the flight view's plan has no cloud shafts: {shafts}"
        );
        if k > 0 {
            total.push(shafts_ms - none_ms);
            added.push(shafts_ms - plain_ms);
            clear.push(none_ms);
            air.extend(step_gpu_ms(&shafts, CLOUD_SHAFTS));
        }
    }
    let pass = |times: &[f64]| (times.len() == frames).then(|| median(times)).flatten();
    Ok(ShaftTimes {
        quality,
        total_added_wall_ms: median(&total).unwrap_or(f64::NAN),
        added_wall_ms: median(&added).unwrap_or(f64::NAN),
        clear_wall_ms: median(&clear).unwrap_or(f64::NAN),
        sky_pass_ms,
        air_pass_ms: pass(&air),
    })
}

/// One round of [`interleaved_pairs`]: the frame without clouds and with them, each
/// with its plan and wall-clock time, ms.
#[derive(Debug)]
pub struct Pair {
    pub clear: (FramePlan, f64),
    pub cloudy: (FramePlan, f64),
}

/// Renders `frame` on `renderer` without clouds and with `clouds`, interleaved, `frames`
/// times after a warm-up pair (shaders compile, tables and textures are made); every
/// frame with clouds must run the step `step`. Leaves the clouds on.
pub fn interleaved_pairs(
    renderer: &mut Renderer,
    frame: &Frame,
    clouds: &FrameClouds,
    (step, frames): (&str, usize),
    progress: &Progress,
) -> anyhow::Result<Vec<Pair>> {
    let mut pairs = Vec::new();
    for k in 0..=frames {
        renderer.set_clouds(None)?;
        let clear = timed(renderer, frame)?;
        progress.inc();
        renderer.set_clouds(Some(clouds.clone()))?;
        let cloudy = timed(renderer, frame)?;
        progress.inc();
        anyhow::ensure!(
            cloudy.0.runs(step),
            "the bench view's plan has no {step}: {}",
            cloudy.0
        );
        if k > 0 {
            pairs.push(Pair { clear, cloudy });
        }
    }
    Ok(pairs)
}

/// Measures each of `qualities` on `renderer` in `atmosphere` at `size`, `frames` pairs
/// each, and what the cloud shafts add to each.
pub fn measure(
    renderer: &mut Renderer,
    atmosphere: &Atmosphere,
    qualities: &[MarchQuality],
    (size, frames): ((u32, u32), usize),
    progress: &Progress,
) -> anyhow::Result<(Vec<CloudTimes>, Vec<ShaftTimes>)> {
    let frame = bench_frame(&FLIGHT, atmosphere, size);
    let cover = CloudFlags::default().cover_grid()?;
    renderer.set_cloud_inputs(&cover, &droplet_orders()?)?;
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
    let mut out = Vec::new();
    for (quality, settings) in qualities
        .iter()
        .flat_map(|&q| variants(q).into_iter().map(move |s| (q, s)))
    {
        let clouds = FrameClouds {
            settings,
            light: frame_light(model.as_ref(), &frame, &settings)?,
            form: CloudForm::Auto,
            spheres: SphereSettings::default(),
            prune: true,
            shafts: false,
        };
        let (mut added, mut clear, mut sky) = (Vec::new(), Vec::new(), Vec::new());
        for pair in interleaved_pairs(renderer, &frame, &clouds, ("clouds", frames), progress)? {
            added.push(pair.cloudy.1 - pair.clear.1);
            clear.push(pair.clear.1);
            sky.extend(step_gpu_ms(&pair.clear.0, "hillaire"));
        }
        out.push(CloudTimes {
            quality,
            sun_light: settings.sun_light,
            added_wall_ms: median(&added).unwrap_or(f64::NAN),
            clear_wall_ms: median(&clear).unwrap_or(f64::NAN),
            sky_pass_ms: (sky.len() == frames).then(|| median(&sky)).flatten(),
        });
    }
    let mut shafts = Vec::new();
    for &quality in qualities {
        let scene = (&frame, model.as_ref());
        let sky_pass_ms = out
            .iter()
            .find(|t| t.quality == quality)
            .and_then(|t| t.sky_pass_ms);
        let timed = (quality, sky_pass_ms);
        shafts.push(measure_shafts(renderer, scene, timed, frames, progress)?);
    }
    renderer.set_clouds(None)?;
    Ok((out, shafts))
}

/// The Markdown table of the cloud shafts' `results`.
pub fn shafts_markdown(results: &[ShaftTimes]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nClouds with their shadow in the air (the cloud shafts: a pass of their own, \
         `cloud_shafts`, which every model subtracts; on by default), the same view: each \
         round the frame without clouds, with clouds, and with clouds and their shadow, \
         interleaved; medians of the rounds' differences. The hillaire pass is the \
         table's above (lavapipe's timestamps in these rounds are not to be trusted).\n"
    );
    let _ = writeln!(
        out,
        "| cloud quality | clouds and shadow added, wall ms | the shadow's share, wall ms | frame without clouds, wall ms | hillaire pass, GPU ms | shadow pass, GPU ms | clouds and shadow / hillaire pass | shadow / hillaire pass |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    let cell =
        |v: Option<f64>, digits: usize| v.map_or_else(|| "-".into(), |x| format!("{x:.digits$}"));
    for r in results {
        let (sky, air) = (r.sky_pass_ms, r.air_pass_ms);
        let _ = writeln!(
            out,
            "| {} | {:.1} | {:.1} | {:.1} | {} | {} | {} | {} |",
            r.quality,
            r.total_added_wall_ms,
            r.added_wall_ms,
            r.clear_wall_ms,
            cell(sky, 1),
            cell(air, 1),
            cell(sky.map(|s| r.total_added_wall_ms / s), 2),
            cell(sky.map(|s| r.added_wall_ms / s), 2)
        );
    }
    out
}

/// The Markdown table of `results`.
pub fn markdown(adapter: &str, (width, height): (u32, u32), results: &[CloudTimes]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nClouds on {adapter}, {width}x{height} px: a hillaire frame 2.9 km up at \
         ({LATITUDE_DEG} N, {} W) over the generated cover, each frame with clouds \
         interleaved with the same frame without; medians.\n",
        -LONGITUDE_DEG
    );
    let _ = writeln!(
        out,
        "| cloud quality | sun light | added wall ms | frame without clouds, wall ms | added / frame without clouds | hillaire pass, GPU ms | added / hillaire pass |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    for r in results {
        let ratio = r.sky_pass_ms.map(|s| r.added_wall_ms / s);
        let _ = writeln!(
            out,
            "| {} | {} | {:.1} | {:.1} | {:.2} | {} | {} |",
            r.quality,
            r.sun_light,
            r.added_wall_ms,
            r.clear_wall_ms,
            r.added_wall_ms / r.clear_wall_ms,
            r.sky_pass_ms
                .map_or_else(|| "-".into(), |v| format!("{v:.1}")),
            ratio.map_or_else(|| "-".into(), |x| format!("{x:.2}"))
        );
    }
    out
}
