//! The cloud's shadow in the air taken from the field itself, for the path-traced
//! reference (`clouds/reference/`): at each sample below the layer's base the sun's
//! transmittance through the layer by a midpoint march of the view density (every
//! octave the field has) along the sun, with no map between, over the whole part of the
//! ray below the base, in samples of at most `sample_m`. The frames' sun map
//! (`sun_map.rs`, Dobashi, Yamamoto and Nishita 2002 section 5.4) is what it checks:
//! its cells, its fill's steps and its reach.

use glam::DVec3;

use super::air_shadow::CloudShade;
use super::field::CloudLayer;
use super::sun_map::base_crossing;
use crate::clouds::medium::CloudMedium;
use crate::shafts::MIN_SHAFT_SAMPLES;

/// The most samples of one ray's span.
pub const MAX_DIRECT_SAMPLES: usize = 4096;
/// The path-traced reference's steps towards the sun and longest sample, m
/// ([`DirectCloudShade::reference`]; `tests/cloud_direct_shade.rs` shows them converged).
pub const REFERENCE_STEPS: usize = 64;
pub const REFERENCE_SAMPLE_M: f64 = 100.0;

/// The layer's own shade of the air below its base.
#[derive(Clone, Copy, Debug)]
pub struct DirectCloudShade<'a> {
    pub layer: &'a CloudLayer,
    /// Midpoint steps of each march towards the sun through the layer.
    pub steps: usize,
    /// The longest sample along a view ray, m.
    pub sample_m: f64,
}

impl<'a> DirectCloudShade<'a> {
    /// The shade the path-traced reference takes for `layer`.
    pub fn reference(layer: &'a CloudLayer) -> DirectCloudShade<'a> {
        DirectCloudShade {
            layer,
            steps: REFERENCE_STEPS,
            sample_m: REFERENCE_SAMPLE_M,
        }
    }

    /// The optical depth from `point_m` below the base through the layer along the unit
    /// `sun`; 0 where the sun's ray never reaches the base's sphere from inside it.
    pub fn optical_depth(&self, point_m: DVec3, sun: DVec3) -> f64 {
        let shell = self.layer.shell();
        let start = point_m + sun * base_crossing(point_m, sun, shell.base_radius_m);
        let length = shell.exit_distance(start, sun);
        let ds = length / self.steps as f64;
        (0..self.steps)
            .map(|k| self.layer.extinction(start + sun * ((k as f64 + 0.5) * ds)) * ds)
            .sum()
    }
}

impl CloudShade for DirectCloudShade<'_> {
    fn base_radius_m(&self) -> f64 {
        self.layer.shell().base_radius_m
    }

    fn sun_transmittance(&self, point_m: DVec3, sun: DVec3) -> f64 {
        (-self.optical_depth(point_m, sun)).exp()
    }

    fn reach_m(&self) -> f64 {
        f64::INFINITY
    }

    fn samples(&self, span_m: f64) -> usize {
        ((span_m / self.sample_m).ceil() as usize).clamp(MIN_SHAFT_SAMPLES, MAX_DIRECT_SAMPLES)
    }
}
