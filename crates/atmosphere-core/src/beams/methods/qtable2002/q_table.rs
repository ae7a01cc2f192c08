//! The pre-integrated table q(u, v, lambda) of Dobashi et al. 2002, section 4.2.1, Eq. 9:
//!
//!   q(u, v) = integral over u' from u to u + dt of
//!             sigma_s F(acos(-u' / s)) exp(-sigma_t (s + u' - u)) / s^2 du',
//!   s = sqrt(u'^2 + v^2),
//!
//! in the frame of Fig. 2: the origin at the light, U along the view ray, v the distance
//! from the light to the ray, so the scattering of one plane interval [t_k, t_k + dt] of
//! a ray is f_l = c_k q(u, v) with c_k = exp(-sigma_t t_k) (Eq. 8-9). dt is fixed for
//! the whole table (the interval of the sampling planes).
//!
//! Parameterisation (the paper gives none): u on nodes even in asinh(u / dt), so they
//! crowd where the ray passes the light and the integrand changes over the interval's
//! own length; v on nodes even in ln v from the smallest light radius, since q grows as
//! 1 / v near the light. Values between nodes are bilinear in those coordinates, and
//! outside the table the nearest edge is read. Each entry is integrated by the
//! substitution u' = v tan(theta) (du' / s^2 = d(theta) / v), whose integrand is smooth,
//! with the 8-point Gauss-Legendre rule on panels in theta.

use rayon::prelude::*;

use crate::beams::in_scattering::EXTINGUISHED_OPTICAL_DEPTH;
use crate::beams::medium::MediumSpectra;
use crate::numerics::quadrature::{GAUSS_LEGENDRE_8, mapped};
use crate::optics::phase::PhaseFunction;

/// The region of (u, v) a table covers, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QExtent {
    pub u_min_m: f64,
    pub u_max_m: f64,
    /// The smallest distance of a ray from the light, m (> 0): nearer rays read this row.
    pub v_min_m: f64,
    pub v_max_m: f64,
}

/// q at the nodes of a grid, one layer per wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct QTable {
    interval_m: f64,
    extinction_per_m: Vec<f64>,
    x_range: (f64, f64),
    y_range: (f64, f64),
    nodes: [usize; 2],
    /// q at (wavelength, v node, u node), m^-2 sr^-1.
    values: Vec<f64>,
}

impl QTable {
    /// The table of interval `interval_m` for `medium` and `phase` over `extent`, with
    /// `nodes[0]` nodes along u and `nodes[1]` along v (each at least 2).
    pub fn new(
        medium: &MediumSpectra,
        phase: &PhaseFunction,
        extent: QExtent,
        nodes: [usize; 2],
        interval_m: f64,
    ) -> QTable {
        let x_range = (
            (extent.u_min_m / interval_m).asinh(),
            (extent.u_max_m / interval_m).asinh(),
        );
        let y_range = (
            extent.v_min_m.ln(),
            extent.v_max_m.max(extent.v_min_m * 2.0).ln(),
        );
        let mut table = QTable {
            interval_m,
            extinction_per_m: medium.extinction_per_m.clone(),
            x_range,
            y_range,
            nodes,
            values: Vec::new(),
        };
        let wavelengths = medium.extinction_per_m.len();
        let grid = &table;
        let values = (0..wavelengths * nodes[1])
            .into_par_iter()
            .flat_map_iter(|row| {
                let (w, j) = (row / nodes[1], row % nodes[1]);
                let v = grid.node_v(j);
                let (sigma_s, sigma_t) = (medium.scattering_per_m[w], medium.extinction_per_m[w]);
                (0..nodes[0])
                    .map(move |i| {
                        let u = grid.node_u(i);
                        q_integral(sigma_s, sigma_t, phase, u, v, interval_m)
                    })
                    .collect::<Vec<f64>>()
            })
            .collect();
        table.values = values;
        table
    }

    /// The interval the table integrates over, m.
    pub fn interval_m(&self) -> f64 {
        self.interval_m
    }

    /// The largest entry over every wavelength, m^-2 sr^-1.
    pub fn max_value(&self) -> f64 {
        self.values.iter().copied().fold(0.0, f64::max)
    }

    /// Nodes along u and along v.
    pub fn nodes(&self) -> [usize; 2] {
        self.nodes
    }

    /// The ranges the nodes span evenly: asinh(u / dt) and ln v.
    pub fn coordinate_ranges(&self) -> [(f64, f64); 2] {
        [self.x_range, self.y_range]
    }

    /// q at (wavelength, v node, u node), row-major in that order, m^-2 sr^-1.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    fn node_u(&self, i: usize) -> f64 {
        let a = i as f64 / (self.nodes[0] - 1) as f64;
        self.interval_m * (self.x_range.0 + a * (self.x_range.1 - self.x_range.0)).sinh()
    }

    fn node_v(&self, j: usize) -> f64 {
        let a = j as f64 / (self.nodes[1] - 1) as f64;
        (self.y_range.0 + a * (self.y_range.1 - self.y_range.0)).exp()
    }

    /// q(u, v) at wavelength `w`, bilinear between nodes, m^-2 sr^-1.
    pub fn q(&self, u_m: f64, v_m: f64, w: usize) -> f64 {
        let grid = |value: f64, (lo, hi): (f64, f64), n: usize| {
            let f = ((value - lo) / (hi - lo) * (n - 1) as f64).clamp(0.0, (n - 1) as f64);
            let i = (f.floor() as usize).min(n - 2);
            (i, f - i as f64)
        };
        let (i, a) = grid((u_m / self.interval_m).asinh(), self.x_range, self.nodes[0]);
        let v = v_m.max(self.y_range.0.exp());
        let (j, b) = grid(v.ln(), self.y_range, self.nodes[1]);
        let layer = &self.values[w * self.nodes[0] * self.nodes[1]..];
        let at = |i: usize, j: usize| layer[j * self.nodes[0] + i];
        (at(i, j) * (1.0 - a) + at(i + 1, j) * a) * (1.0 - b)
            + (at(i, j + 1) * (1.0 - a) + at(i + 1, j + 1) * a) * b
    }

    /// f_l over `length_m` of a ray from the point `t_m` from the camera, whose
    /// coordinates in the frame of Fig. 2 are (u_m, v_m) (Eq. 9: c_k q). A length past
    /// one interval (an oblique ray crosses the planes farther apart than their spacing)
    /// adds the following intervals, each attenuated by the interval before it; a part
    /// of an interval counts its share of q.
    pub fn segment(&self, t_m: f64, u_m: f64, v_m: f64, length_m: f64, w: usize) -> f64 {
        let sigma_t = self.extinction_per_m[w];
        let mut sum = 0.0;
        let mut start = 0.0;
        while start < length_m {
            let share = ((length_m - start) / self.interval_m).min(1.0);
            sum += (-sigma_t * start).exp() * self.q(u_m + start, v_m, w) * share;
            start += self.interval_m;
        }
        (-sigma_t * t_m).exp() * sum
    }
}

/// Eq. 9's integral at one (u, v), v > 0, by u' = v tan(theta).
fn q_integral(
    sigma_s: f64,
    sigma_t: f64,
    phase: &PhaseFunction,
    u: f64,
    v: f64,
    interval_m: f64,
) -> f64 {
    if sigma_s == 0.0 {
        return 0.0;
    }
    // Past an optical depth of EXTINGUISHED_OPTICAL_DEPTH from u the integrand is below
    // 1e-9 of its start: the integral stops there.
    let length = interval_m.min(EXTINGUISHED_OPTICAL_DEPTH / sigma_t);
    let (a, b) = ((u / v).atan(), ((u + length) / v).atan());
    // Panels enough for the attenuation across the interval (four e-folds a panel) and
    // the turn of theta.
    let panels = (4.0 + 0.25 * sigma_t * length + 8.0 * (b - a)).min(64.0) as usize;
    let step = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let lo = a + step * p as f64;
        for (theta, weight) in mapped(&GAUSS_LEGENDRE_8, lo, lo + step) {
            let (sin, cos) = theta.sin_cos();
            let s = v / cos;
            let along = v * sin / cos - u;
            sum += weight * phase.eval(-sin) * (-sigma_t * (s + along)).exp();
        }
    }
    sigma_s * sum / v
}
