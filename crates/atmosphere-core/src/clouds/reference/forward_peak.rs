//! The droplets' forward peak taken as no scattering, delta-M's truncation (Wiscombe
//! 1977), as a setting of the path tracer: within `cone_deg` of the forward direction
//! the phase function is capped at its value at the cone's edge; the fraction f it
//! loses (the peak above that value) is light that goes on as if unscattered, so the
//! medium's extinction becomes beta (1 - omega f) and its albedo
//! omega (1 - f) / (1 - omega f), and the rest of the phase function is renormalised,
//! p' = p_t / (1 - f). Everything scattered by more than the cone's angle is unchanged
//! (beta' omega' p' = beta omega p there); light scattered by less arrives along the
//! direction it had. The sun's next-event estimate then meets p' at most p(cone)
//! instead of the peak's thousands of sr^-1: a path heading for the sun no longer
//! carries the pixel's answer alone.

use glam::DVec3;

use super::phase_sampler::PhaseTableSampler;
use crate::clouds::medium::CloudMedium;
use crate::clouds::phase::CloudPhase;

/// The widest cone taken as forward, degrees.
pub const MAX_FORWARD_PEAK_DEG: f64 = 20.0;

/// A phase table at equal steps of the angle from 0 to pi, flattened within `cone_deg`
/// of the forward direction and renormalised, and the fraction f of the original's
/// integral that the flattening took (0 for `cone_deg` 0).
pub fn truncated_phase(values: &[f64], cone_deg: f64) -> (PhaseTableSampler, f64) {
    let step_deg = 180.0 / (values.len() - 1) as f64;
    let at = |angle_deg: f64| {
        let x = (angle_deg / step_deg).clamp(0.0, (values.len() - 1) as f64);
        let k = (x.floor() as usize).min(values.len() - 2);
        let s = x - k as f64;
        values[k] * (1.0 - s) + values[k + 1] * s
    };
    let edge = at(cone_deg);
    let flat: Vec<f64> = values
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            if (k as f64) * step_deg < cone_deg {
                v.min(edge)
            } else {
                v
            }
        })
        .collect();
    let whole = PhaseTableSampler::from_nodes(values.to_vec()).integral();
    let kept = PhaseTableSampler::from_nodes(flat.clone()).integral();
    let fraction = (1.0 - kept / whole).clamp(0.0, 1.0);
    let scale = 1.0 / kept;
    (
        PhaseTableSampler::from_nodes(flat.into_iter().map(|v| v * scale).collect()),
        fraction,
    )
}

/// A medium whose droplets' forward peak (the fraction `fraction` of their scattering)
/// is taken as no scattering.
#[derive(Debug)]
pub struct ForwardPeakCut<'a, M: CloudMedium + ?Sized> {
    pub medium: &'a M,
    /// f: the share of the scattering within the cone.
    pub fraction: f64,
}

impl<M: CloudMedium + ?Sized> CloudMedium for ForwardPeakCut<'_, M> {
    fn extinction(&self, position: DVec3) -> f64 {
        let omega = self.medium.single_scattering_albedo(position);
        self.medium.extinction(position) * (1.0 - omega * self.fraction)
    }

    fn light_extinction(&self, position: DVec3) -> f64 {
        let omega = self.medium.single_scattering_albedo(position);
        self.medium.light_extinction(position) * (1.0 - omega * self.fraction)
    }

    fn single_scattering_albedo(&self, position: DVec3) -> f64 {
        let omega = self.medium.single_scattering_albedo(position);
        let lost = 1.0 - omega * self.fraction;
        if lost > 0.0 {
            (omega * (1.0 - self.fraction) / lost).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    fn phase(&self) -> &CloudPhase {
        self.medium.phase()
    }

    /// The medium's own bound: the scaled extinction never exceeds it.
    fn majorant(&self) -> f64 {
        self.medium.majorant()
    }

    fn distance_to_boundary(&self, position: DVec3, direction: DVec3) -> f64 {
        self.medium.distance_to_boundary(position, direction)
    }
}
