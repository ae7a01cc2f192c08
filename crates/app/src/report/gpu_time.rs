//! The report's GPU column: each model setting rendered as a 1280 x 720 frame of every
//! report view on the adapter at hand, by `atmos bench`'s machinery. A warm-up frame
//! builds the setting's tables for each atmosphere; then each measured frame is followed by a frame of the
//! bench's baseline (nishita, 16 samples) of the same view on a second renderer, so that
//! both see the same load of a noisy machine; the medians of each are kept, and their
//! ratio.

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use render_wgpu::Renderer;
use render_wgpu::frame::{Frame, LocalView};

use crate::bench::baseline;
use crate::bench::timing::{median, timed};
use crate::bench::variant::Variant;
use crate::progress::Progress;
use crate::report::views::ReportView;

/// The frame's size.
pub const WIDTH: u32 = 1280;
pub const HEIGHT: u32 = 720;
/// Frames measured per view and setting. One: a software adapter takes about a second
/// per frame on a busy two-core machine, and the mean over the views and the
/// interleaved baseline carry the noise.
pub const FRAMES: usize = 1;

/// What one setting's frames took: the median of each view, wall-clock time from
/// `render` until the GPU has finished, ms.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuFrameTime {
    /// In the order of the report's views.
    pub per_view_ms: Vec<f64>,
    /// The baseline's frames of the same views, interleaved with these.
    pub baseline_per_view_ms: Vec<f64>,
}

impl GpuFrameTime {
    /// The mean over the views.
    pub fn ms(&self) -> f64 {
        mean(&self.per_view_ms)
    }

    /// The mean frame time as a multiple of the baseline's.
    pub fn ratio(&self) -> f64 {
        self.ms() / mean(&self.baseline_per_view_ms)
    }
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}

/// The camera of `view` as a 1280 x 720 frame of `variant`; the report's horizontal field
/// of view kept.
pub fn frame_of(view: &ReportView, variant: &Variant) -> anyhow::Result<Frame> {
    let atmosphere = Atmosphere::preset(view.atmosphere)?;
    let local = LocalView {
        altitude_m: view.altitude_m,
        view_zenith_deg: 90.0 - view.look_elevation_deg,
        view_azimuth_deg: view.look_azimuth_deg,
        sun_zenith_deg: view.sun_zenith_deg,
        sun_azimuth_deg: 0.0,
    };
    let half_width = (0.5 * view.fov_deg.to_radians()).tan();
    let vertical_fov_deg = 2.0
        * (half_width * f64::from(HEIGHT) / f64::from(WIDTH))
            .atan()
            .to_degrees();
    Ok(Frame {
        camera_position_m: local.position_m(atmosphere.bottom_radius_m),
        orientation: local.orientation(),
        vertical_fov_deg,
        sun_direction: local.sun_direction(),
        atmosphere,
        model: variant.model,
        settings: variant.settings(),
        exposure_ev100: 14.0,
        width: WIDTH,
        height: HEIGHT,
        terrain: None,
    })
}

/// A renderer and what its last frame showed: a frame of another setting or atmosphere
/// builds tables, so it follows a warm-up frame of its own.
struct WarmRenderer {
    renderer: Renderer,
    last: Option<(&'static str, String)>,
}

impl WarmRenderer {
    /// The wall-clock time of a frame of `view` by `variant`, ms, after a warm-up frame
    /// where the setting or the atmosphere changed.
    fn frame_ms(&mut self, view: &ReportView, variant: &Variant) -> anyhow::Result<f64> {
        let frame = frame_of(view, variant)?;
        let shown = Some((view.atmosphere, variant.label.clone()));
        if self.last != shown {
            timed(&mut self.renderer, &frame)?;
            self.last = shown;
        }
        Ok(timed(&mut self.renderer, &frame)?.1)
    }
}

/// Measures every variant on every view; `None` for a setting the GPU refuses (the
/// reason goes to stderr). Returns the adapter's name and the times.
pub fn measure_all(
    variants: &[Variant],
    views: &[ReportView],
) -> anyhow::Result<(String, Vec<Option<GpuFrameTime>>)> {
    let mut measured = WarmRenderer {
        renderer: Renderer::headless().context("the GPU frame times need an adapter")?,
        last: None,
    };
    let mut baseline = WarmRenderer {
        renderer: Renderer::headless()?,
        last: None,
    };
    let adapter = measured.renderer.gpu().adapter_summary();
    let progress = Progress::new("gpu frames", "views", (variants.len() * views.len()) as u64);
    let reference = baseline::baseline();
    let mut times = Vec::with_capacity(variants.len());
    for variant in variants {
        match measure(
            &mut measured,
            &mut baseline,
            variant,
            &reference,
            views,
            &progress,
        ) {
            Ok(t) => times.push(Some(t)),
            Err(e) => {
                eprintln!("report: no GPU time for {}: {e:#}", variant.label);
                times.push(None);
            }
        }
    }
    progress.finish();
    Ok((adapter, times))
}

/// One variant on every view, the views of one atmosphere together (a change of
/// atmosphere rebuilds the tables); the times in the order of `views`.
fn measure(
    measured: &mut WarmRenderer,
    baseline: &mut WarmRenderer,
    variant: &Variant,
    reference: &Variant,
    views: &[ReportView],
    progress: &Progress,
) -> anyhow::Result<GpuFrameTime> {
    let mut order: Vec<usize> = (0..views.len()).collect();
    order.sort_by_key(|&i| views[i].atmosphere);
    let mut time = GpuFrameTime {
        per_view_ms: vec![f64::NAN; views.len()],
        baseline_per_view_ms: vec![f64::NAN; views.len()],
    };
    for i in order {
        let (mut walls, mut baseline_walls) = (Vec::new(), Vec::new());
        for _ in 0..FRAMES {
            walls.push(measured.frame_ms(&views[i], variant)?);
            baseline_walls.push(baseline.frame_ms(&views[i], reference)?);
        }
        time.per_view_ms[i] = median(&walls).unwrap_or(f64::NAN);
        time.baseline_per_view_ms[i] = median(&baseline_walls).unwrap_or(f64::NAN);
        progress.inc();
    }
    Ok(time)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::views::report_views;
    use glam::DVec3;

    #[test]
    fn a_frame_looks_where_the_view_looks_with_its_sun() {
        let variant = Variant::parse("riley").unwrap();
        for view in report_views(16, 9) {
            let atmosphere = Atmosphere::preset(view.atmosphere).unwrap();
            let rays = view.rays(&atmosphere);
            let frame = frame_of(&view, &variant).unwrap();
            let centre = (rays[0].direction + rays[rays.len() - 1].direction).normalize();
            let forward = frame.orientation * DVec3::NEG_Z;
            assert!(centre.dot(forward) > 1.0 - 1e-9, "{}", view.id);
            assert!(rays[0].sun_direction.dot(frame.sun_direction) > 1.0 - 1e-12);
            assert_eq!(frame.camera_position_m, rays[0].origin_m);
            // The horizontal field of view is the view's.
            let half = (0.5 * frame.vertical_fov_deg.to_radians()).tan() * 1280.0 / 720.0;
            assert!((2.0 * half.atan().to_degrees() - view.fov_deg).abs() < 1e-9);
        }
    }
}
