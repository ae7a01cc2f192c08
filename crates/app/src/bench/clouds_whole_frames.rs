//! `atmos bench --clouds QUALITY`, whole frames: what the clouds add to a whole hillaire
//! frame over the generated cover as a user gets them, from above the layer: the cloud
//! spheres from orbit, 400 km up, and the layer's march on a flight above the deck, 5 km
//! up (each step at the quality's resolution divisor, as `render` and the viewer take
//! it, the model's second run for the air in front of the cloud, the composite and the
//! cloud's shadow in the air), against the frame without clouds, which is the hillaire
//! sky pass (with its tables below the atmosphere's top) and the tone map. Each frame
//! with clouds is interleaved with the same frame without them; medians of the pairs'
//! differences of wall-clock time after a warm-up pair, as the flight view's rows inside
//! the layer (`clouds.rs`). Both sides are wall-clock times of the same rounds:
//! lavapipe's timestamps of the hillaire pass read anything from 0 to the pass's time in
//! such rounds.

use std::fmt::Write as _;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::spheres::handover::{CloudForm, sphere_weight};
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::models::registry::prepare;
use render_wgpu::Renderer;
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::frame::LocalView;
use render_wgpu::frame::plan::FramePlan;

use crate::bench::clouds::{LATITUDE_DEG, LONGITUDE_DEG, bench_frame, interleaved_pairs};
use crate::bench::timing::median;
use crate::progress::Progress;

/// The views, over (25 N, 30 W): from orbit, 400 km up looking 60 degrees below the
/// horizon towards azimuth 200, the sun 40 degrees up at azimuth 120; above the deck,
/// 5 km up (2 km over the default layer's top) looking 15 degrees down towards azimuth
/// 200, the sun 30 degrees up at azimuth 120.
const VIEWS: [(&str, LocalView); 2] = [
    (
        "orbit",
        LocalView {
            altitude_m: 400_000.0,
            view_zenith_deg: 150.0,
            view_azimuth_deg: -200.0,
            sun_zenith_deg: 50.0,
            sun_azimuth_deg: -120.0,
        },
    ),
    (
        "above the deck",
        LocalView {
            altitude_m: 5_000.0,
            view_zenith_deg: 105.0,
            view_azimuth_deg: -200.0,
            sun_zenith_deg: 60.0,
            sun_azimuth_deg: -120.0,
        },
    ),
];

/// What the clouds of one quality added to one view's frame, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewTimes {
    pub view: &'static str,
    pub quality: MarchQuality,
    /// Median of the pairs' differences of wall-clock time, spheres less none.
    pub added_wall_ms: f64,
    /// Median wall-clock time of the frame without clouds.
    pub clear_wall_ms: f64,
    /// The cloud steps the frame with clouds ran, as its plan names them.
    pub steps: Vec<&'static str>,
}

/// Frames the views render for one quality (the warm-up pairs included).
pub fn frames_per_quality(frames: usize) -> usize {
    VIEWS.len() * 2 * (1 + frames)
}

/// The cloud steps `plan` ran, in order.
fn cloud_steps(plan: &FramePlan) -> Vec<&'static str> {
    plan.steps
        .iter()
        .map(|s| s.name)
        .filter(|name| name.starts_with("cloud"))
        .collect()
}

/// Measures the clouds of each of `qualities` on each view, `frames` pairs each; the
/// renderer's cloud inputs are set by the caller.
pub fn measure(
    renderer: &mut Renderer,
    atmosphere: &Atmosphere,
    qualities: &[MarchQuality],
    (size, frames): ((u32, u32), usize),
    progress: &Progress,
) -> anyhow::Result<Vec<ViewTimes>> {
    let mut out = Vec::new();
    for (view, local) in &VIEWS {
        let frame = bench_frame(local, atmosphere, size);
        let model = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
        // The step of the cloud's form at the view's altitude, which the frame must run.
        let step = match sphere_weight(CloudForm::Auto, local.altitude_m) > 0.0 {
            true => "cloud_spheres",
            false => "clouds",
        };
        for &quality in qualities {
            let settings = quality.apply(LayerSettings::default());
            let clouds = FrameClouds {
                settings,
                light: frame_light(model.as_ref(), &frame, &settings)?,
                form: CloudForm::Auto,
                spheres: SphereSettings {
                    resolution_divisor: quality.sphere_resolution_divisor(),
                    ..SphereSettings::default()
                },
                prune: true,
                shafts: true,
            };
            let pairs = interleaved_pairs(renderer, &frame, &clouds, (step, frames), progress)?;
            let added: Vec<f64> = pairs.iter().map(|p| p.cloudy.1 - p.clear.1).collect();
            let clear: Vec<f64> = pairs.iter().map(|p| p.clear.1).collect();
            let steps = pairs
                .last()
                .map(|p| cloud_steps(&p.cloudy.0))
                .unwrap_or_default();
            out.push(ViewTimes {
                view,
                quality,
                added_wall_ms: median(&added).unwrap_or(f64::NAN),
                clear_wall_ms: median(&clear).unwrap_or(f64::NAN),
                steps,
            });
        }
    }
    renderer.set_clouds(None)?;
    Ok(out)
}

/// The Markdown table of `results`.
pub fn markdown(results: &[ViewTimes]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "\nWhole frames from above the layer: a hillaire frame over ({LATITUDE_DEG} N, {} W) \
         and the generated cover, 400 km up looking 60 degrees down with the sun 40 degrees \
         up (the cloud spheres) and 5 km up looking 15 degrees down with the sun 30 degrees \
         up (the layer's march above the deck); each frame with the clouds (and their \
         shadow in the air) interleaved with the same frame without clouds; medians. The \
         frame without clouds is the hillaire pass and the tone map.\n",
        -LONGITUDE_DEG
    );
    let _ = writeln!(
        out,
        "| view | cloud quality | cloud steps | added wall ms | frame without clouds, wall ms | added / frame without clouds |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|");
    for r in results {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {:.1} | {:.1} | {:.2} |",
            r.view,
            r.quality,
            r.steps.join(", "),
            r.added_wall_ms,
            r.clear_wall_ms,
            r.added_wall_ms / r.clear_wall_ms,
        );
    }
    out
}
