//! The diffuse light inside a cloud by the delta-M four-stream discrete-ordinate
//! solution of a homogeneous plane-parallel slab (Liou 1974, "Analytic two-stream and
//! four-stream solutions for radiative transfer", J. Atmos. Sci. 31; the forward peak by
//! Wiscombe 1977's delta-M method; the eigenproblem halved as by Stamnes and Swanson
//! 1981), seen towards the eye by the source-function technique (Toon et al. 1989).
//!
//! The azimuth-averaged transfer equation mu dI/dtau = I - J is written at the four
//! double-sided Gauss points +-mu_1, +-mu_2 of [-1, 1], tau measured downwards from the
//! top, mu from the upward vertical. The phase function keeps its first four Legendre
//! moments after delta-M's scaling with the fourth as the forward peak's share f:
//! chi'_l = (chi_l - f) / (1 - f), tau' = (1 - omega f) tau,
//! omega' = (1 - f) omega / (1 - omega f), p'(mu, mu') = sum_(l<4) (2l + 1) chi'_l
//! P_l(mu) P_l(mu'). With S = I(+mu_i) + I(-mu_i) and D = I(+mu_i) - I(-mu_i),
//! dS/dtau = B D - q_d e^(-tau/mu0) and dD/dtau = A S - q_s e^(-tau/mu0), where
//! A = M^-1 (1 - omega'/2 (P(+,+) + P(+,-)) W) holds the even moments,
//! B = M^-1 (1 - omega'/2 (P(+,+) - P(+,-)) W) the odd ones, M = diag(mu_i),
//! W = diag(w_i). The eigenvalues k^2 of A B come from its trace and its determinant
//! det A det B = (1 - omega')(1 - omega' chi'_2)(1 - omega' chi'_1)(1 - omega' chi'_3)
//! / (mu_1 mu_2)^2, written with the absorption itself so that a conservative slab's
//! small k is not a difference of nearly equal numbers. Each k gives two solutions,
//! built from sigma = e^(-k tau) + e^(-k (tau* - tau)) and
//! delta = (e^(-k (tau* - tau)) - e^(-k tau)) / k (which tend to 2 and 2 tau - tau* as
//! k goes to 0, the conservative slab's constant and linear solutions): with d an
//! eigenvector of A B and b = B d, (S, D) = (b sigma, k^2 d delta) and (b delta, d sigma).
//! The sun's beam adds a particular solution in e^(-tau/mu0); the four constants come
//! from no diffuse light entering at the top and none leaving the black base upwards.
//! The sky's light is a second solution, without beam, whose radiance entering the top is
//! isotropic with irradiance E_sky by the streams' own quadrature (a radiance
//! E_sky / (2 pi sum_i w_i mu_i), so that the slab receives E_sky exactly).

use std::f64::consts::PI;

/// The positive Gauss-Legendre points of four on [-1, 1] and their weights.
pub const STREAMS: [f64; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
pub const WEIGHTS: [f64; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
/// The smallest absorption 1 - omega taken.
pub const MIN_ABSORPTION: f64 = 1e-6;
/// The lowest sun cosine taken.
pub const MIN_SUN_COSINE: f64 = 0.02;

type Vec2 = [f64; 2];
type Mat2 = [[f64; 2]; 2];

fn mat_vec(m: &Mat2, v: Vec2) -> Vec2 {
    [
        m[0][0] * v[0] + m[0][1] * v[1],
        m[1][0] * v[0] + m[1][1] * v[1],
    ]
}

fn mat_mul(a: &Mat2, b: &Mat2) -> Mat2 {
    let mut c = [[0.0; 2]; 2];
    for (i, row) in c.iter_mut().enumerate() {
        for (j, value) in row.iter_mut().enumerate() {
            *value = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

/// P_0..P_3 at `x`.
fn legendre(x: f64) -> [f64; 4] {
    [
        1.0,
        x,
        0.5 * (3.0 * x * x - 1.0),
        0.5 * x * (5.0 * x * x - 3.0),
    ]
}

/// The scaled phase function p'(mu, mu') of the module's equations, azimuth-averaged.
fn phase(chi: &[f64; 4], mu: f64, mu_prime: f64) -> f64 {
    let (a, b) = (legendre(mu), legendre(mu_prime));
    (0..4)
        .map(|l| (2 * l + 1) as f64 * chi[l] * a[l] * b[l])
        .sum()
}

/// (1 - e^(-k x)) / k for k, x >= 0, without the cancellation of small k x (x at k = 0;
/// below k x = 0.01 by its series to the fourth term).
fn one_minus_exp_over(k: f64, x: f64) -> f64 {
    let kx = k * x;
    if kx < 1e-2 {
        x * (1.0 - kx * (0.5 - kx * (1.0 / 6.0 - kx / 24.0)))
    } else {
        (1.0 - (-kx).exp()) / k
    }
}

/// The delta-M truncation of the droplets' moments `chi` (chi_0..=chi_4): the forward
/// peak's share f = chi_4 and the broad part's asymmetry (chi_1 - f) / (1 - f).
pub fn truncation(chi: &[f64; 5]) -> (f64, f64) {
    let f = chi[4].clamp(0.0, 0.999);
    (f, (chi[1] - f) / (1.0 - f))
}

/// A solved slab: the homogeneous solutions' vectors and the constants of the beam's
/// and the sky's solutions, everything the field at any depth needs.
#[derive(Clone, Debug)]
pub struct FourStreamSlab {
    chi: [f64; 4],
    f: f64,
    /// tau' / tau, the delta-M scaling of the optical depth.
    scale: f64,
    mu0: f64,
    total: f64,
    k: Vec2,
    d: [Vec2; 2],
    b: [Vec2; 2],
    zs: Vec2,
    zd: Vec2,
    beam: [f64; 4],
    sky: [f64; 4],
}

/// The slab of optical depth `tau` (unscaled) lit at the sun's cosine `mu0`.
fn solve(tau: f64, mu0: f64, albedo: f64, moments: &[f64; 5]) -> FourStreamSlab {
    let absorption = (1.0 - albedo).max(MIN_ABSORPTION);
    let (f, _) = truncation(moments);
    let scale = 1.0 - (1.0 - absorption) * f;
    let omega = 1.0 - absorption / scale;
    let chi: [f64; 4] = std::array::from_fn(|l| (moments[l] - f) / (1.0 - f));
    let total = tau.max(0.0) * scale;
    let mut a = [[0.0; 2]; 2];
    let mut b = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            let same = phase(&chi, STREAMS[i], STREAMS[j]);
            let opposite = phase(&chi, STREAMS[i], -STREAMS[j]);
            let identity = if i == j { 1.0 } else { 0.0 };
            a[i][j] = (identity - 0.5 * omega * (same + opposite) * WEIGHTS[j]) / STREAMS[i];
            b[i][j] = (identity - 0.5 * omega * (same - opposite) * WEIGHTS[j]) / STREAMS[i];
        }
    }
    let ab = mat_mul(&a, &b);
    let det = absorption / scale
        * (1.0 - omega * chi[2])
        * (1.0 - omega * chi[1])
        * (1.0 - omega * chi[3])
        / (STREAMS[0] * STREAMS[1]).powi(2);
    let trace = ab[0][0] + ab[1][1];
    let large = 0.5 * (trace + (trace * trace - 4.0 * det).max(0.0).sqrt());
    let k2 = [det / large, large];
    let k = [k2[0].sqrt(), k2[1].sqrt()];
    // An eigenvector of A B from whichever row of A B - k^2 is the larger.
    let d: [Vec2; 2] = std::array::from_fn(|q| {
        let first = [ab[0][1], k2[q] - ab[0][0]];
        let second = [k2[q] - ab[1][1], ab[1][0]];
        let v = if first[0].hypot(first[1]) >= second[0].hypot(second[1]) {
            first
        } else {
            second
        };
        let norm = v[0].hypot(v[1]);
        [v[0] / norm, v[1] / norm]
    });
    let bd = [mat_vec(&b, d[0]), mat_vec(&b, d[1])];
    let mut mu0 = mu0.clamp(MIN_SUN_COSINE, 1.0);
    if k.iter().any(|&k| (k * mu0 - 1.0).abs() < 1e-3) {
        mu0 *= 1.002;
    }
    // The beam's particular solution: (B A - 1/mu0^2) Z_s = B q_s - q_d / mu0,
    // Z_d = mu0 (q_s - A Z_s).
    let source = |mu: f64| omega / (4.0 * PI) * phase(&chi, mu, -mu0);
    let q_up = [source(STREAMS[0]), source(STREAMS[1])];
    let q_down = [source(-STREAMS[0]), source(-STREAMS[1])];
    let qs = [
        (q_up[0] + q_down[0]) / STREAMS[0],
        (q_up[1] + q_down[1]) / STREAMS[1],
    ];
    let qd = [
        (q_up[0] - q_down[0]) / STREAMS[0],
        (q_up[1] - q_down[1]) / STREAMS[1],
    ];
    let ba = mat_mul(&b, &a);
    let bqs = mat_vec(&b, qs);
    let rhs = [bqs[0] - qd[0] / mu0, bqs[1] - qd[1] / mu0];
    let m = [
        [ba[0][0] - 1.0 / (mu0 * mu0), ba[0][1]],
        [ba[1][0], ba[1][1] - 1.0 / (mu0 * mu0)],
    ];
    // Its determinant from the eigenvalues, not as a difference of products.
    let m_det = (k2[0] - 1.0 / (mu0 * mu0)) * (k2[1] - 1.0 / (mu0 * mu0));
    let zs = [
        (rhs[0] * m[1][1] - m[0][1] * rhs[1]) / m_det,
        (m[0][0] * rhs[1] - m[1][0] * rhs[0]) / m_det,
    ];
    let azs = mat_vec(&a, zs);
    let zd = [mu0 * (qs[0] - azs[0]), mu0 * (qs[1] - azs[1])];
    // The conditions: I(-mu_i) = (S - D) / 2 at the top, I(+mu_i) = (S + D) / 2 at the
    // base, for the constants of the solutions (q = 1, 2; sigma then delta).
    let mut matrix = [[0.0; 4]; 4];
    for (column, (q, kind)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
        for (row, (tau, sign)) in [(0.0, -1.0), (total, 1.0)].into_iter().enumerate() {
            let (s, dd) = mode(k[q], total, tau, kind, bd[q], d[q]);
            for i in 0..2 {
                matrix[2 * row + i][column] = s[i] + sign * dd[i];
            }
        }
    }
    let bottom = (-total / mu0).exp();
    let beam_rhs = [
        -(zs[0] - zd[0]),
        -(zs[1] - zd[1]),
        -(zs[0] + zd[0]) * bottom,
        -(zs[1] + zd[1]) * bottom,
    ];
    // The sky's isotropic radiance whose flux by the streams' quadrature is 1.
    let sky_radiance = 1.0 / (2.0 * PI * (WEIGHTS[0] * STREAMS[0] + WEIGHTS[1] * STREAMS[1]));
    let sky_rhs = [2.0 * sky_radiance, 2.0 * sky_radiance, 0.0, 0.0];
    let [beam, sky] = solve_4x4(matrix, [beam_rhs, sky_rhs]);
    FourStreamSlab {
        chi,
        f,
        scale,
        mu0,
        total,
        k,
        d,
        b: bd,
        zs,
        zd,
        beam,
        sky,
    }
}

/// (S, D) of solution `kind` (0: sigma, 1: delta) of eigenvalue `k` at scaled depth `tau`.
fn mode(k: f64, total: f64, tau: f64, kind: usize, b: Vec2, d: Vec2) -> (Vec2, Vec2) {
    let falling = (-k * tau).exp();
    let rising = (-k * (total - tau)).exp();
    let sigma = falling + rising;
    // (rising - falling) / k, each side's exponential factored out of the difference.
    let delta = if 2.0 * tau >= total {
        rising * one_minus_exp_over(k, 2.0 * tau - total)
    } else {
        -falling * one_minus_exp_over(k, total - 2.0 * tau)
    };
    match kind {
        0 => (
            [b[0] * sigma, b[1] * sigma],
            [k * k * d[0] * delta, k * k * d[1] * delta],
        ),
        _ => ([b[0] * delta, b[1] * delta], [d[0] * sigma, d[1] * sigma]),
    }
}

/// Gaussian elimination with partial pivoting for two right-hand sides.
fn solve_4x4(mut m: [[f64; 4]; 4], mut rhs: [[f64; 4]; 2]) -> [[f64; 4]; 2] {
    for col in 0..4 {
        let pivot = (col..4)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        m.swap(col, pivot);
        for r in rhs.iter_mut() {
            r.swap(col, pivot);
        }
        for row in col + 1..4 {
            let factor = m[row][col] / m[col][col];
            for c in col..4 {
                m[row][c] -= factor * m[col][c];
            }
            for r in rhs.iter_mut() {
                r[row] -= factor * r[col];
            }
        }
    }
    for r in rhs.iter_mut() {
        for row in (0..4).rev() {
            let known: f64 = (row + 1..4).map(|c| m[row][c] * r[c]).sum();
            r[row] = (r[row] - known) / m[row][row];
        }
    }
    rhs
}

impl FourStreamSlab {
    /// The slab of optical depth `tau` (unscaled, non-negative) lit at the sun's cosine
    /// `mu0` from the upward vertical, single-scattering albedo `albedo` in [0, 1], the
    /// droplets' Legendre moments `moments` (chi_0..=chi_4).
    pub fn new(tau: f64, mu0: f64, albedo: f64, moments: &[f64; 5]) -> FourStreamSlab {
        solve(tau, mu0, albedo, moments)
    }

    /// [`diffuse_source`] at optical depth `tau_above` (unscaled, clamped to the slab)
    /// below the top, towards a direction of cosine `mu_out` from the upward vertical.
    pub fn diffuse_source(&self, tau_above: f64, mu_out: f64) -> (f64, f64) {
        let tau = (tau_above.max(0.0) * self.scale).min(self.total);
        (
            self.source(self.field(tau, &self.beam, true), mu_out),
            self.source(self.field(tau, &self.sky, false), mu_out),
        )
    }

    /// I(+mu_i) and I(-mu_i) at scaled depth `tau` of the solution with `constants`,
    /// with the beam's particular part when `beam`.
    fn field(&self, tau: f64, constants: &[f64; 4], beam: bool) -> (Vec2, Vec2) {
        let (mut s, mut d) = ([0.0; 2], [0.0; 2]);
        for (column, (q, kind)) in [(0, 0), (0, 1), (1, 0), (1, 1)].into_iter().enumerate() {
            let (ms, md) = mode(self.k[q], self.total, tau, kind, self.b[q], self.d[q]);
            for i in 0..2 {
                s[i] += constants[column] * ms[i];
                d[i] += constants[column] * md[i];
            }
        }
        if beam {
            let e = (-tau / self.mu0).exp();
            for i in 0..2 {
                s[i] += self.zs[i] * e;
                d[i] += self.zd[i] * e;
            }
        }
        (
            [0.5 * (s[0] + d[0]), 0.5 * (s[1] + d[1])],
            [0.5 * (s[0] - d[0]), 0.5 * (s[1] - d[1])],
        )
    }

    /// (1 - f) (1/2) sum_j w_j (p'(mu, mu_j) I(+mu_j) + p'(mu, -mu_j) I(-mu_j)).
    fn source(&self, (up, down): (Vec2, Vec2), mu_out: f64) -> f64 {
        let sum: f64 = (0..2)
            .map(|j| {
                WEIGHTS[j]
                    * (phase(&self.chi, mu_out, STREAMS[j]) * up[j]
                        + phase(&self.chi, mu_out, -STREAMS[j]) * down[j])
            })
            .sum();
        ((1.0 - self.f) * 0.5 * sum).max(0.0)
    }
}

/// The diffuse field's source towards the eye, per unit of extinction times albedo,
/// sr^-1, per unit sun irradiance F_s and per unit sky irradiance E_sky, at optical
/// depth `tau_above` below the top of a slab of optical depth `tau_above + tau_below`
/// (unscaled, non-negative), lit at the sun's cosine `mu0` from the upward vertical,
/// single-scattering albedo `albedo` in [0, 1], the droplets' Legendre moments
/// `moments` (chi_0..=chi_4), the light leaving in a direction of cosine `mu_out` from
/// the upward vertical.
pub fn diffuse_source(
    tau_above: f64,
    tau_below: f64,
    mu0: f64,
    albedo: f64,
    moments: &[f64; 5],
    mu_out: f64,
) -> (f64, f64) {
    let above = tau_above.max(0.0);
    solve(above + tau_below.max(0.0), mu0, albedo, moments).diffuse_source(above, mu_out)
}

/// The diffuse fluxes through a depth of the slab, by the four streams' quadrature
/// 2 pi sum_i w_i mu_i I(+-mu_i): the beam's per unit beam irradiance on a plane facing
/// the beam, the sky's per unit sky irradiance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiffuseFluxes {
    pub beam_up: f64,
    pub beam_down: f64,
    pub sky_up: f64,
    pub sky_down: f64,
}

/// The diffuse fluxes at optical depth `tau_above` below the top of the slab of
/// [`diffuse_source`].
pub fn diffuse_fluxes(
    tau_above: f64,
    tau_below: f64,
    mu0: f64,
    albedo: f64,
    moments: &[f64; 5],
) -> DiffuseFluxes {
    let above = tau_above.max(0.0);
    let slab = solve(above + tau_below.max(0.0), mu0, albedo, moments);
    let tau = (above * slab.scale).min(slab.total);
    let flux = |values: Vec2| {
        2.0 * PI
            * (0..2)
                .map(|i| WEIGHTS[i] * STREAMS[i] * values[i])
                .sum::<f64>()
    };
    let (beam_up, beam_down) = slab.field(tau, &slab.beam, true);
    let (sky_up, sky_down) = slab.field(tau, &slab.sky, false);
    DiffuseFluxes {
        beam_up: flux(beam_up),
        beam_down: flux(beam_down),
        sky_up: flux(sky_up),
        sky_down: flux(sky_down),
    }
}
