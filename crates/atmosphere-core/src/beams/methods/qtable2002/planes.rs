//! The sampling planes of one light and the sub-planes between them: Dobashi et al. 2002
//! section 4.2.1 (the planes span the depths of the light beam's bounding volume, a
//! pyramid from the light to a distance d0, (t_max - t_min) / dt + 1 of them) and
//! section 4.2.2 (m_k samples in plane interval k, the main plane and m_k - 1 sub-planes,
//! m_k chosen from f_l on the ray through the centre of the screen so that
//! max over lambda of f_l(d_k) / m_k stays at least epsilon).
//!
//! The paper's epsilon is a share of I_max, the brightest value its frame buffer holds
//! (0.01 of 1.0), with I_l <= 1. Radiance here has physical units, so f_l is taken as a
//! share of the whole f_l of the centre ray (the sum over its intervals): a sub-plane
//! is inserted where it adds at least epsilon of the centre pixel's unshadowed light.
//!
//! Bounding volumes: a spot's pyramid over its cone (apex at the light, base square at
//! d0 along its axis); a point light's cube of half-side d0; a parallel light's beam
//! rectangle swept d0 along its direction, or all depths up to d0 for an unbounded beam.

use glam::DVec3;

use crate::beams::camera::Camera;
use crate::beams::light::{Light, LightShape};
use crate::beams::medium::MediumSpectra;
use crate::beams::occluders::Occluders;
use crate::beams::plan::volume_corners;
use crate::optics::phase::PhaseFunction;

use super::interval::f_l;
use super::q_table::QTable;

/// One light's planes: depths `first_depth_m + k * dt` along the camera's view
/// direction, k < `samples.len()`.
#[derive(Clone, Debug, PartialEq)]
pub struct LightPlanes {
    pub first_depth_m: f64,
    /// m_k: the samples of interval k (1 is the main plane alone).
    pub samples: Vec<usize>,
    /// The largest f_l over the wavelengths of interval k on the centre ray, m^-2 sr^-1.
    pub centre_f_l: Vec<f64>,
    /// Interval k's share of the sum of `centre_f_l` (0 where that sum is 0).
    pub centre_share: Vec<f64>,
}

/// Whether each ray counts its own sub-planes from its own f_l of each interval
/// (`true`; not the paper's: a pixel's walk can, drawn planes cannot) or every ray takes
/// the centre ray's m_k (`false`, the paper's section 4.2.2). The threshold is the same
/// either way, epsilon of the centre ray's whole f_l, so the centre ray's counts do not
/// change; a ray that passes a light within an interval's length, whose f_l there is
/// far above the centre ray's, gets the sub-planes its beam needs.
pub const SUBPLANES_PER_RAY: &str = "subplanes_per_ray";

/// How the sub-planes are counted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubPlaneRule {
    /// The paper's epsilon, a share of the centre ray's f_l.
    pub epsilon: f64,
    /// The most sub-planes in one interval.
    pub max_subplanes: usize,
}

impl SubPlaneRule {
    /// m_k for an interval of share `f`: the largest m with f / m >= epsilon (the
    /// paper's "minimum number" bounds m from above), at least 1 and at most
    /// 1 + `max_subplanes`.
    pub fn samples(&self, f: f64) -> usize {
        let most = 1 + self.max_subplanes;
        if self.epsilon <= 0.0 {
            return most;
        }
        ((f / self.epsilon).floor() as usize).clamp(1, most)
    }
}

/// What the planes of every light share.
#[derive(Clone, Copy, Debug)]
pub struct PlaneContext<'a> {
    pub table: &'a QTable,
    pub medium: &'a MediumSpectra,
    pub phase: &'a PhaseFunction,
    pub camera: &'a Camera,
}

impl LightPlanes {
    /// The planes of `light` between the `depths` of its bounding volume, spaced by the
    /// table's interval, with the sub-planes of `rule`.
    pub fn new(
        context: &PlaneContext<'_>,
        light: &Light,
        depths: (f64, f64),
        rule: SubPlaneRule,
    ) -> LightPlanes {
        let dt = context.table.interval_m();
        let (lo, hi) = depths;
        let count = if hi > lo {
            ((hi - lo) / dt).floor() as usize + 1
        } else {
            0
        };
        let cam = context.camera;
        let centre_f_l: Vec<f64> = (0..count)
            .map(|k| {
                let d = lo + k as f64 * dt;
                (0..context.medium.extinction_per_m.len())
                    .map(|w| {
                        f_l(
                            context.table,
                            context.medium,
                            context.phase,
                            light,
                            cam.position_m,
                            cam.forward,
                            d,
                            dt,
                            w,
                        )
                    })
                    .fold(0.0, f64::max)
            })
            .collect();
        let total: f64 = centre_f_l.iter().sum();
        let centre_share: Vec<f64> = centre_f_l
            .iter()
            .map(|&f| if total > 0.0 { f / total } else { 0.0 })
            .collect();
        LightPlanes {
            first_depth_m: lo,
            samples: centre_share.iter().map(|&f| rule.samples(f)).collect(),
            centre_f_l,
            centre_share,
        }
    }

    /// The f_l that one sample of an interval stands for on a ray that counts its own
    /// sub-planes (`SUBPLANES_PER_RAY`): epsilon of the centre ray's whole f_l; 0 where
    /// epsilon is 0 (the most samples everywhere), infinite where the centre ray gets no
    /// light (one sample everywhere, as the centre ray's counts are then).
    pub fn sample_unit(&self, rule: &SubPlaneRule) -> f64 {
        let total: f64 = self.centre_f_l.iter().sum();
        if rule.epsilon <= 0.0 {
            0.0
        } else if total > 0.0 {
            rule.epsilon * total
        } else {
            f64::INFINITY
        }
    }

    /// m for an interval whose largest f_l over the wavelengths is `f_l` (m^-2 sr^-1) on
    /// a ray that counts its own sub-planes: f_l over [`Self::sample_unit`], at least 1
    /// and at most 1 + `max_subplanes`.
    pub fn samples_for(&self, rule: &SubPlaneRule, f_l: f64) -> usize {
        let most = 1 + rule.max_subplanes;
        let unit = self.sample_unit(rule);
        if unit <= 0.0 {
            return most;
        }
        ((f_l / unit).floor() as usize).clamp(1, most)
    }

    /// The sub-planes of every interval together.
    pub fn subplane_count(&self) -> usize {
        self.samples.iter().map(|m| m - 1).sum()
    }
}

/// The nearest and farthest depth, along the camera's view, of `light`'s bounding volume
/// reaching `d0_m` from it, cut to [0, `extinguished_m`].
pub fn volume_depths(light: &Light, d0_m: f64, camera: &Camera, extinguished_m: f64) -> (f64, f64) {
    let depth = |p: DVec3| (p - camera.position_m).dot(camera.forward);
    let Some(corners) = volume_corners(light, d0_m) else {
        return (0.0, d0_m.min(extinguished_m));
    };
    let (lo, hi) = corners
        .iter()
        .map(|&p| depth(p))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    (lo.max(0.0), hi.min(extinguished_m))
}

/// d0 when none is set: for a spot, the farthest distance along its axis at which its
/// axis and the four edges of its pyramid meet an occluder (every ray must meet one,
/// else the beam runs on); otherwise, and at most, where the medium has extinguished the
/// light.
pub fn default_d0(light: &Light, occluders: &Occluders, extinguished_m: f64) -> f64 {
    let LightShape::Spot {
        position_m,
        frame,
        tan_cone,
        ..
    } = &light.shape
    else {
        return extinguished_m;
    };
    let mut farthest: f64 = 0.0;
    let edges = [
        (0.0, 0.0),
        (1.0, 1.0),
        (1.0, -1.0),
        (-1.0, 1.0),
        (-1.0, -1.0),
    ];
    for (sx, sy) in edges {
        let d = (frame.z + (frame.x * sx + frame.y * sy) * *tan_cone).normalize();
        match occluders.nearest(*position_m, d, extinguished_m) {
            Some(t) => farthest = farthest.max(t * d.dot(frame.z)),
            None => return extinguished_m,
        }
    }
    farthest.min(extinguished_m)
}
