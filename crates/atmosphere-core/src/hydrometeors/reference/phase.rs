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
//! at all, delta-M's truncation (Wiscombe 1977, `hydrometeors/forward_peak.rs`): the
//! extinction beta (1 - f_c) and the truncated table P_c'. Without it, the sun's
//! next-event estimate after a scattering meets the peak's thousands of sr^-1 on the
//! rare paths that head for the sun, and a few paths in a hundred thousand carry the
//! answer.

use crate::clouds::reference::phase_sampler::PhaseTableSampler;
use crate::hydrometeors::channel_phase::ChannelPhase;
use crate::hydrometeors::error::HydrometeorError;
use crate::hydrometeors::forward_peak::PeakTruncation;
use crate::numerics::sampling::Sampler;

/// The truncated channel tables P_c' and their samplers.
#[derive(Clone, Debug)]
pub struct ChannelSampler {
    /// P_c', read as the march reads it (linear between bin centres).
    table: ChannelPhase,
    /// The forward peak: f_c, each channel's share of the scattering in it.
    pub peak: PeakTruncation,
    proposals: [PhaseTableSampler; 3],
}

impl ChannelSampler {
    /// The sampler of `phase`, the whole table by angle (falling plates' tables over the
    /// sky are refused: their value depends on the direction seen, not only on the
    /// angle).
    pub fn new(phase: &ChannelPhase) -> Result<ChannelSampler, HydrometeorError> {
        if phase.sky.is_some() {
            return Err(HydrometeorError::Setting {
                what: "path-traced reference (falling plates' table over the sky)",
                value: 0.0,
                range: "tables by scattering angle only",
            });
        }
        let peak = PeakTruncation::of(phase);
        let table = peak.table(phase);
        let nodes = (180.0 / phase.bin_deg).round() as usize + 1;
        let proposals = std::array::from_fn(|c| {
            PhaseTableSampler::from_nodes(
                (0..nodes)
                    .map(|k| table.value_at(k as f64 * phase.bin_deg)[c].abs())
                    .collect(),
            )
        });
        Ok(ChannelSampler {
            table,
            peak,
            proposals,
        })
    }

    /// P_c' at the cosine `cos` of the scattering angle.
    pub fn phase(&self, cos: f64) -> [f64; 3] {
        self.table
            .value_at(cos.clamp(-1.0, 1.0).acos().to_degrees())
    }

    /// The truncated tables P_c'.
    pub fn table(&self) -> &ChannelPhase {
        &self.table
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
