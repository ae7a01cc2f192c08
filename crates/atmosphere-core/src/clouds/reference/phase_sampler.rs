//! Exact sampling of the droplets' phase function as the layer's table holds it (A_1 of
//! `layer/orders.rs`, linear in the scattering angle between 1024 angles): a bin of the
//! table is chosen by its share of the integral over the sphere, and within the bin a
//! cosine drawn uniformly is kept with probability p(theta) / max(p at the bin's ends)
//! (rejection; p is linear in theta, so its largest value is at an end). The drawn
//! cosines follow p exactly, so a path's weight does not wander over hundreds of
//! scatterings as a proposal's ratio p / pdf would make it; the weight is the table's
//! integral, 1 up to its quadrature. [`PhaseTableSampler::from_nodes`] takes any table
//! at equal steps of the angle, which the rain and ice volumes' path tracer draws its
//! directions from (`hydrometeors/reference/`).

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
        PhaseTableSampler::from_nodes(orders.table(w)[..ANGLES].to_vec())
    }

    /// The sampler of a table of `values` (at least two, none negative) at equal steps
    /// of the scattering angle from 0 to pi, linear in the angle between them.
    pub fn from_nodes(values: Vec<f64>) -> PhaseTableSampler {
        let angles = values.len();
        let step = std::f64::consts::PI / (angles - 1) as f64;
        let mut total = 0.0;
        let cumulative = (0..angles - 1)
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
        self.cumulative[self.cumulative.len() - 1]
    }

    fn step(&self) -> f64 {
        std::f64::consts::PI / (self.values.len() - 1) as f64
    }

    /// The table's value at the cosine `cos` of the scattering angle (linear in the
    /// angle): the drawn cosines' density over the sphere is this over the integral.
    pub fn value(&self, cos: f64) -> f64 {
        let last = self.values.len() - 1;
        let x = (cos.clamp(-1.0, 1.0).acos() / self.step()).clamp(0.0, last as f64);
        let k = (x.floor() as usize).min(last - 1);
        let s = x - k as f64;
        self.values[k] * (1.0 - s) + self.values[k + 1] * s
    }

    /// A cosine of the scattering angle drawn from the table, and the weight to carry
    /// (the table's integral).
    pub fn sample(&self, sampler: &mut Sampler) -> (f64, f64) {
        let total = self.integral();
        let u = sampler.uniform() * total;
        let k = self
            .cumulative
            .partition_point(|&c| c <= u)
            .min(self.values.len() - 2);
        let step = self.step();
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
