//! Directions drawn for a volume's channel phase table P_c (`channel_phase.rs`): one
//! path carries the three channels, so the directions are drawn from a proposal,
//! the mean over the channels of |P_c| at the table's bin edges (the cloud path
//! tracer's [`PhaseTableSampler`], linear in the angle), and each channel's weight is
//! multiplied by P_c / q, with q the proposal's density (importance sampling, unbiased
//! where q > 0 wherever some P_c is not 0). P_c may dip below zero where the bows'
//! saturated colours leave a channel slightly negative; the weight carries the sign.

use crate::clouds::reference::phase_sampler::PhaseTableSampler;
use crate::hydrometeors::channel_phase::ChannelPhase;
use crate::hydrometeors::error::HydrometeorError;
use crate::numerics::sampling::Sampler;

/// The proposal over a channel table by angle.
#[derive(Clone, Debug)]
pub struct ChannelSampler {
    phase: ChannelPhase,
    proposal: PhaseTableSampler,
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
        let values = (0..nodes)
            .map(|k| {
                let v = phase.value_at(k as f64 * phase.bin_deg);
                v.iter().map(|c| c.abs()).sum::<f64>() / 3.0
            })
            .collect();
        Ok(ChannelSampler {
            phase: phase.clone(),
            proposal: PhaseTableSampler::from_nodes(values),
        })
    }

    /// P_c at the cosine `cos` of the scattering angle.
    pub fn phase(&self, cos: f64) -> [f64; 3] {
        self.phase
            .value_at(cos.clamp(-1.0, 1.0).acos().to_degrees())
    }

    /// A cosine drawn from the proposal and the factor P_c / q that each channel's
    /// weight takes.
    pub fn sample(&self, sampler: &mut Sampler) -> (f64, [f64; 3]) {
        let (cos, total) = self.proposal.sample(sampler);
        let q = self.proposal.value(cos) / total;
        let p = self.phase(cos);
        if q <= 0.0 {
            return (cos, [0.0; 3]);
        }
        (cos, p.map(|v| v / q))
    }
}
