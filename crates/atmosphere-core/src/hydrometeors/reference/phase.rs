//! Directions drawn for a volume's channel phase table P_c (`channel_phase.rs`): each
//! channel follows its own paths (as each wavelength does in the cloud path tracer),
//! its directions drawn from |P_c| at the table's bin edges (the cloud path tracer's
//! [`PhaseTableSampler`], linear in the angle) and its weight multiplied by P_c / q,
//! with q that proposal's density: the table's integral, up to the sign and the
//! difference between the two interpolations. P_c may dip below zero where the bows'
//! saturated colours leave a channel slightly negative; the weight carries the sign.
//! (One path for the three channels, drawn from their mean, was tried: the weights'
//! ratios multiply over the many forward scatterings of a thick rain shaft, where the
//! channels' diffraction peaks differ, and a few paths came to dominate.)
//!
//! The forward peak (diffraction, seen with the sun's disc) is taken as no scattering
//! at all, delta-M's truncation (Wiscombe 1977): within [`FORWARD_PEAK_DEG`] of the
//! forward direction P_c is replaced by its value there, the fraction f_c it loses is
//! taken off the extinction (beta' = beta (1 - f_c)) and the rest is P_c' = P_c, t /
//! (1 - f_c), so that beta' P_c' = beta P_c at every angle past the peak. Light
//! diffracted by less than that angle arrives as if unscattered. Without it, the sun's
//! next-event estimate after a scattering meets the peak's thousands of sr^-1 on the
//! rare paths that head for the sun, and a few paths in a hundred thousand carry the
//! answer.

use crate::clouds::reference::phase_sampler::PhaseTableSampler;
use crate::hydrometeors::channel_phase::ChannelPhase;
use crate::hydrometeors::error::HydrometeorError;
use crate::numerics::sampling::Sampler;

/// The forward peak's half-width taken as no scattering, degrees.
pub const FORWARD_PEAK_DEG: f64 = 1.0;

/// The truncated channel tables P_c' and their samplers.
#[derive(Clone, Debug)]
pub struct ChannelSampler {
    phase: ChannelPhase,
    /// f_c: the share of each channel's scattering in the forward peak.
    pub peak_fraction: [f64; 3],
    proposals: [PhaseTableSampler; 3],
}

impl ChannelSampler {
    /// The sampler of `phase`, a table by angle (falling plates' tables over the sky are
    /// refused: their value depends on the direction seen, not only on the angle).
    pub fn new(phase: &ChannelPhase) -> Result<ChannelSampler, HydrometeorError> {
        if phase.sky.is_some() {
            return Err(HydrometeorError::Setting {
                what: "path-traced reference (falling plates' table over the sky)",
                value: 0.0,
                range: "tables by scattering angle only",
            });
        }
        let nodes = (180.0 / phase.bin_deg).round() as usize + 1;
        let step = std::f64::consts::PI / (nodes - 1) as f64;
        let mut peak_fraction = [0.0; 3];
        let proposals = std::array::from_fn(|c| {
            let edge = phase.value_at(FORWARD_PEAK_DEG)[c];
            // The peak above its value at the edge, by the trapezoid rule over the
            // nodes' rings.
            let peak = |k: usize| {
                let angle = k as f64 * phase.bin_deg;
                let excess = (phase.value_at(angle)[c] - edge).max(0.0);
                if angle <= FORWARD_PEAK_DEG {
                    excess
                } else {
                    0.0
                }
            };
            peak_fraction[c] = (0..nodes - 1)
                .map(|k| {
                    let ring = 2.0
                        * std::f64::consts::PI
                        * ((k as f64 * step).cos() - ((k + 1) as f64 * step).cos());
                    0.5 * (peak(k) + peak(k + 1)) * ring
                })
                .sum::<f64>()
                .clamp(0.0, 0.99);
            PhaseTableSampler::from_nodes(
                (0..nodes)
                    .map(|k| truncated(phase, c, k as f64 * phase.bin_deg, edge).abs())
                    .collect(),
            )
        });
        Ok(ChannelSampler {
            phase: phase.clone(),
            peak_fraction,
            proposals,
        })
    }

    /// The truncated table P_c' at the bins of the channel table (what a march would
    /// take with the extinction beta (1 - f_c)).
    pub fn truncated_table(&self) -> ChannelPhase {
        let bins = self.phase.values.len();
        let values = (0..bins)
            .map(|b| {
                let angle = (b as f64 + 0.5) * self.phase.bin_deg;
                std::array::from_fn(|c| {
                    let edge = self.phase.value_at(FORWARD_PEAK_DEG)[c];
                    let v = if angle < FORWARD_PEAK_DEG {
                        edge
                    } else {
                        self.phase.values[b][c]
                    };
                    v / (1.0 - self.peak_fraction[c])
                })
            })
            .collect();
        ChannelPhase {
            values,
            ..self.phase.clone()
        }
    }

    /// P_c' at the cosine `cos` of the scattering angle.
    pub fn phase(&self, cos: f64) -> [f64; 3] {
        let angle = cos.clamp(-1.0, 1.0).acos().to_degrees();
        std::array::from_fn(|c| {
            let edge = self.phase.value_at(FORWARD_PEAK_DEG)[c];
            truncated(&self.phase, c, angle, edge) / (1.0 - self.peak_fraction[c])
        })
    }

    /// A cosine drawn for channel `c` and the factor P_c / q its weight takes.
    pub fn sample(&self, c: usize, sampler: &mut Sampler) -> (f64, f64) {
        let proposal = &self.proposals[c];
        let (cos, total) = proposal.sample(sampler);
        let q = proposal.value(cos) / total;
        if q <= 0.0 {
            return (cos, 0.0);
        }
        (cos, self.phase(cos)[c] / q)
    }
}

/// Channel `c` of `phase` at `angle_deg`, flat at `edge` within the forward peak.
fn truncated(phase: &ChannelPhase, c: usize, angle_deg: f64, edge: f64) -> f64 {
    if angle_deg < FORWARD_PEAK_DEG {
        edge
    } else {
        phase.value_at(angle_deg)[c]
    }
}
