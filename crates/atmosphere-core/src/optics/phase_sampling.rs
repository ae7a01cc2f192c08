//! Drawing scattering directions from a phase function, for Monte Carlo. Each sampler
//! returns the cosine of the scattering angle and a weight (phase / pdf), which is 1 for
//! exact samplers.

use crate::numerics::sampling::Sampler;
use crate::optics::phase::PhaseFunction;

/// A sampler prepared from a [`PhaseFunction`].
#[derive(Clone, Debug)]
pub enum PhaseSampler {
    Rayleigh,
    CornetteShanks {
        g: f64,
    },
    HenyeyGreenstein {
        g: f64,
    },
    NishitaHazy,
    /// Piecewise-constant proposal in nu with exact weights.
    Tabulated {
        phase: PhaseFunction,
        /// Cumulative probability at the end of each equal bin of nu over [-1, 1].
        cdf: Vec<f64>,
    },
}

const TABULATED_BINS: usize = 4096;

impl PhaseSampler {
    /// Bytes of its table (tabulated phase functions only).
    pub fn bytes(&self) -> usize {
        match self {
            PhaseSampler::Tabulated { cdf, .. } => std::mem::size_of_val(cdf.as_slice()),
            _ => 0,
        }
    }

    pub fn new(phase: &PhaseFunction) -> PhaseSampler {
        match phase {
            PhaseFunction::Rayleigh => PhaseSampler::Rayleigh,
            PhaseFunction::CornetteShanks { g } => PhaseSampler::CornetteShanks { g: *g },
            PhaseFunction::HenyeyGreenstein { g } => PhaseSampler::HenyeyGreenstein { g: *g },
            PhaseFunction::NishitaHazy => PhaseSampler::NishitaHazy,
            PhaseFunction::Tabulated { .. } => {
                let width = 2.0 / TABULATED_BINS as f64;
                let mut cdf = Vec::with_capacity(TABULATED_BINS);
                let mut acc = 0.0;
                for i in 0..TABULATED_BINS {
                    let lo = -1.0 + width * i as f64;
                    // Bin mass from the midpoint and both ends (Simpson).
                    let m = (phase.eval(lo)
                        + 4.0 * phase.eval(lo + 0.5 * width)
                        + phase.eval(lo + width))
                        / 6.0;
                    acc += m.max(1e-300) * width;
                    cdf.push(acc);
                }
                for c in &mut cdf {
                    *c /= acc;
                }
                PhaseSampler::Tabulated {
                    phase: phase.clone(),
                    cdf,
                }
            }
        }
    }

    /// (cosine of the scattering angle, weight = phase / pdf).
    pub fn sample(&self, sampler: &mut Sampler) -> (f64, f64) {
        match self {
            PhaseSampler::Rayleigh => (sample_rayleigh(sampler.uniform()), 1.0),
            PhaseSampler::HenyeyGreenstein { g } => {
                (sample_henyey_greenstein(*g, sampler.uniform()), 1.0)
            }
            PhaseSampler::CornetteShanks { g } => {
                // Cornette-Shanks is Henyey-Greenstein times 3/2 (1 + nu^2) / (2 + g^2):
                // accept a Henyey-Greenstein draw with probability (1 + nu^2) / 2.
                loop {
                    let nu = sample_henyey_greenstein(*g, sampler.uniform());
                    if 2.0 * sampler.uniform() < 1.0 + nu * nu {
                        return (nu, 1.0);
                    }
                }
            }
            PhaseSampler::NishitaHazy => {
                // Half the mass is isotropic; the other half has pdf 9/2 s^8 in
                // s = (1 + nu) / 2.
                if sampler.uniform() < 0.5 {
                    (2.0 * sampler.uniform() - 1.0, 1.0)
                } else {
                    (2.0 * sampler.uniform().powf(1.0 / 9.0) - 1.0, 1.0)
                }
            }
            PhaseSampler::Tabulated { phase, cdf } => {
                let u = sampler.uniform();
                let i = cdf.partition_point(|c| *c < u).min(cdf.len() - 1);
                let mass = cdf[i] - if i == 0 { 0.0 } else { cdf[i - 1] };
                let width = 2.0 / cdf.len() as f64;
                let nu = -1.0 + width * (i as f64 + sampler.uniform());
                // pdf over the sphere: mass / (2 pi width).
                let pdf = mass / (2.0 * std::f64::consts::PI * width);
                (nu, phase.eval(nu) / pdf)
            }
        }
    }
}

/// Exact inversion of the Rayleigh distribution: the CDF (nu^3 + 3 nu + 4) / 8 = u is a
/// depressed cubic solved by Cardano's formula.
pub fn sample_rayleigh(u: f64) -> f64 {
    let q = 4.0 * u - 2.0;
    let z = (q + (q * q + 1.0).sqrt()).cbrt();
    (z - 1.0 / z).clamp(-1.0, 1.0)
}

/// Exact inversion of Henyey-Greenstein.
pub fn sample_henyey_greenstein(g: f64, u: f64) -> f64 {
    if g.abs() < 1e-6 {
        return 2.0 * u - 1.0;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Histogram of sampled nu, weighted, against the phase function: every sampler
    /// reproduces its phase function within Monte Carlo noise.
    #[test]
    fn samplers_reproduce_their_phase_functions() {
        let phases = [
            PhaseFunction::Rayleigh,
            PhaseFunction::CornetteShanks { g: 0.8 },
            PhaseFunction::HenyeyGreenstein { g: -0.4 },
            PhaseFunction::NishitaHazy,
            PhaseFunction::Tabulated {
                angles_deg: vec![0.0, 30.0, 120.0, 180.0],
                values: vec![4.0, 1.0, 0.2, 0.6],
            },
        ];
        let bins = 20;
        let n = 200_000;
        for phase in phases {
            let sampler = PhaseSampler::new(&phase);
            let mut rng = Sampler::new(11);
            let mut hist = vec![0.0; bins];
            for _ in 0..n {
                let (nu, w) = sampler.sample(&mut rng);
                let b = (((nu + 1.0) / 2.0 * bins as f64) as usize).min(bins - 1);
                hist[b] += w / n as f64;
            }
            for (b, h) in hist.iter().enumerate() {
                let lo = -1.0 + 2.0 * b as f64 / bins as f64;
                let hi = lo + 2.0 / bins as f64;
                // Expected mass of the bin: 2 pi * integral of the phase over nu.
                let expected: f64 = (0..200)
                    .map(|k| {
                        let nu = lo + (hi - lo) * (k as f64 + 0.5) / 200.0;
                        2.0 * PI * phase.eval(nu) * (hi - lo) / 200.0
                    })
                    .sum();
                let sigma = (expected / n as f64).sqrt() * 3.0;
                assert!(
                    (h - expected).abs() < 5.0 * sigma + 1e-4,
                    "{phase:?} bin {b}: {h} vs {expected}"
                );
            }
        }
    }
}
