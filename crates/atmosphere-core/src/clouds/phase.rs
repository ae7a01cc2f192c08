//! A cloud's phase function with its importance sampler: the Mie table of its droplets,
//! or Henyey-Greenstein for tests.

use super::error::CloudError;
use crate::numerics::sampling::Sampler;
use crate::optics::mie::phase_table::PhaseTable;
use crate::optics::phase::PhaseFunction;
use crate::optics::phase_sampling::PhaseSampler;
use crate::optics::prepared_phase::PreparedPhase;

/// A phase function (sr^-1) and the sampler drawing scattering angles from it.
#[derive(Clone, Debug)]
pub struct CloudPhase {
    function: PreparedPhase,
    sampler: PhaseSampler,
}

impl CloudPhase {
    /// Refuses parameters that do not describe a phase function.
    pub fn new(function: PhaseFunction) -> Result<CloudPhase, CloudError> {
        if let Some(problem) = function.problem() {
            return Err(CloudError(format!("cloud phase function: {problem}")));
        }
        let sampler = PhaseSampler::new(&function);
        Ok(CloudPhase {
            function: PreparedPhase::new(function),
            sampler,
        })
    }

    /// The droplets' Mie table, sampled by inverse CDF on a piecewise-constant proposal
    /// with exact weights.
    pub fn from_table(table: &PhaseTable) -> Result<CloudPhase, CloudError> {
        CloudPhase::new(table.to_phase_function())
    }

    pub fn function(&self) -> &PhaseFunction {
        self.function.function()
    }

    /// The phase function at the cosine `nu` of the scattering angle, sr^-1.
    pub fn eval(&self, nu: f64) -> f64 {
        self.function.eval(nu)
    }

    /// (cosine of the scattering angle, weight = phase / pdf); the weight is 1 for
    /// exact samplers (Henyey-Greenstein).
    pub fn sample(&self, sampler: &mut Sampler) -> (f64, f64) {
        self.sampler.sample(sampler)
    }
}
