//! Exact sampling of the droplets' phase function as the layer's table holds it (A_1 of
//! `layer/orders.rs`, linear in the scattering angle between 1024 angles): a bin of the
//! table is chosen by its share of the integral over the sphere, and within the bin a
//! cosine drawn uniformly is kept with probability p(theta) / max(p at the bin's ends)
//! (rejection; p is linear in theta, so its largest value is at an end). The drawn
//! cosines follow p exactly, so a path's weight does not wander over hundreds of
//! scatterings as a proposal's ratio p / pdf would make it; the weight is the table's
//! integral, 1 up to its quadrature.

use crate::clouds::layer::orders::{ANGLES, ScatteringOrders};
use crate::numerics::sampling::Sampler;

/// Simpson panels per bin for its share of the integral.
const PANELS: usize = 8;

/// The sampler of one wavelength's A_1.
#[derive(Clone, Debug)]
pub struct PhaseTableSampler {
    values: Vec<f64>,
    /// Cumulative integral over the sphere up to the end of each bin.
    cumulative: Vec<f64>,
}

impl PhaseTableSampler {
    /// The sampler of A_1 at wavelength `w` of `orders`.
    pub fn new(orders: &ScatteringOrders, w: usize) -> PhaseTableSampler {
        let values = orders.table(w)[..ANGLES].to_vec();
        let step = std::f64::consts::PI / (ANGLES - 1) as f64;
        let mut total = 0.0;
        let cumulative = (0..ANGLES - 1)
            .map(|k| {
                let h = step / (2 * PANELS) as f64;
                let f = |i: usize| {
                    let s = i as f64 / (2 * PANELS) as f64;
                    let p = values[k] * (1.0 - s) + values[k + 1] * s;
                    p * (k as f64 * step + i as f64 * h).sin()
                };
                let inner: f64 = (1..2 * PANELS)
                    .map(|i| if i % 2 == 1 { 4.0 * f(i) } else { 2.0 * f(i) })
                    .sum();
                total += 2.0 * std::f64::consts::PI * h / 3.0 * (f(0) + inner + f(2 * PANELS));
                total
            })
            .collect();
        PhaseTableSampler { values, cumulative }
    }

    /// The table's integral over the sphere (1 for a normalised table).
    pub fn integral(&self) -> f64 {
        self.cumulative[ANGLES - 2]
    }

    /// A cosine of the scattering angle drawn from the table, and the weight to carry
    /// (the table's integral).
    pub fn sample(&self, sampler: &mut Sampler) -> (f64, f64) {
        let total = self.integral();
        let u = sampler.uniform() * total;
        let k = self.cumulative.partition_point(|&c| c <= u).min(ANGLES - 2);
        let step = std::f64::consts::PI / (ANGLES - 1) as f64;
        let (theta0, theta1) = (k as f64 * step, (k + 1) as f64 * step);
        let (cos0, cos1) = (theta0.cos(), theta1.cos());
        let (p0, p1) = (self.values[k], self.values[k + 1]);
        let top = p0.max(p1);
        // p is at least min(p0, p1) / top of the top within the bin: the expected number
        // of tries is at most top / min, bounded for the droplets' smooth table.
        for _ in 0..1000 {
            let cos = cos1 + (cos0 - cos1) * sampler.uniform();
            let s = ((cos.clamp(-1.0, 1.0).acos() - theta0) / step).clamp(0.0, 1.0);
            let p = p0 * (1.0 - s) + p1 * s;
            if sampler.uniform() * top <= p {
                return (cos, total);
            }
        }
        ((cos0 + cos1) / 2.0, total)
    }
}
