//! The diffuse light inside a cloud by the delta-Eddington approximation: the layer
//! around a view sample taken as a homogeneous plane-parallel slab lit from above by
//! the sun's parallel beam, its diffuse radiance I(tau, mu) = I_0(tau) + mu I_1(tau)
//! solved in closed form (Shettle and Weinman 1970, "The transfer of solar irradiance
//! through inhomogeneous turbid atmospheres evaluated by Eddington's approximation",
//! Eq. 5-12; Joseph, Wiscombe and Weinman 1976, "The delta-Eddington approximation for
//! radiative flux transfer", Eq. 2-5 and 12-14 for the scaling of the forward peak).
//!
//! The forward peak's share f = g^2 of the scattered light is put back into the beam:
//! tau' = (1 - omega f) tau, omega' = (1 - f) omega / (1 - omega f), g' = g / (1 + g).
//! With tau measured downwards from the top, mu the cosine from the upward vertical and
//! S = F_s / (4 pi) for a beam of irradiance F_s arriving at cosine mu0, the moments of
//! the transfer equation are
//!     dI_0/dtau = (1 - omega' g') I_1 + 3 omega' g' mu0 S e^(-tau/mu0),
//!     dI_1/dtau = 3 (1 - omega') I_0 - 3 omega' S e^(-tau/mu0),
//! solved by I_0 = C_1 e^(-k (tau* - tau)) + C_2 e^(-k tau) + a e^(-tau/mu0),
//! I_1 = P (C_1 e^(-k (tau* - tau)) - C_2 e^(-k tau)) + b e^(-tau/mu0), with
//! k^2 = 3 (1 - omega') (1 - omega' g'), P = k / (1 - omega' g'),
//! a = 3 omega' mu0^2 S (1 + g' (1 - omega')) / (k^2 mu0^2 - 1),
//! b = 3 mu0 (omega' S - (1 - omega') a), and C_1, C_2 from Marshak's conditions: no
//! diffuse light enters at the top (I_0 = 2/3 I_1) nor at the black base
//! (I_0 = -2/3 I_1). The exponentials are written so that none grows, whatever the
//! depth. The sky's light is a second solution, without beam (a = b = 0), whose diffuse
//! flux entering the top is the sky's irradiance: pi (I_0 - 2/3 I_1) = E_sky there.
//!
//! What the march needs is the light the diffuse field scatters towards the eye per
//! unit of (unscaled) extinction and albedo: the scaled source omega' sigma'
//! (I_0 + g' mu I_1) is omega sigma (1 - f) (I_0 + g' mu I_1), mu the cosine of the
//! scattered light's direction from the upward vertical.

/// The smallest absorption 1 - omega taken: a conservative slab's homogeneous
/// solutions 1 and tau are the limit of e^(+-k tau), which this keeps apart.
pub const MIN_ABSORPTION: f64 = 1e-6;
/// The lowest sun cosine taken: a grazing beam enters the slab at this cosine.
pub const MIN_SUN_COSINE: f64 = 0.02;

/// The delta-scaled slab of a view sample: I_0, I_1 per unit beam irradiance and per
/// unit sky irradiance, and the scaling's f, g' and tau'/mu0.
struct Moments {
    beam: (f64, f64),
    sky: (f64, f64),
    f: f64,
    g_s: f64,
    beam_depth: f64,
}

/// The moments at optical depth `tau_above` below the top of a slab of optical depth
/// `tau_above + tau_below` (the module's equations).
fn moments(tau_above: f64, tau_below: f64, mu0: f64, albedo: f64, g: f64) -> Moments {
    let f = g * g;
    let absorption = (1.0 - albedo).max(MIN_ABSORPTION);
    let omega = 1.0 - absorption;
    let scale = 1.0 - omega * f;
    let tau = tau_above.max(0.0) * scale;
    let total = tau + tau_below.max(0.0) * scale;
    let omega_s = 1.0 - absorption / scale;
    let g_s = g / (1.0 + g);
    let diffusion = 1.0 - omega_s * g_s;
    let k = (3.0 * absorption / scale * diffusion).sqrt();
    let p = k / diffusion;
    let mut mu0 = mu0.clamp(MIN_SUN_COSINE, 1.0);
    if (k * mu0 - 1.0).abs() < 1e-3 {
        mu0 *= 1.002;
    }
    let s = 1.0 / (4.0 * std::f64::consts::PI);
    let a =
        3.0 * omega_s * mu0 * mu0 * s * (1.0 + g_s * (1.0 - omega_s)) / (k * k * mu0 * mu0 - 1.0);
    let b = 3.0 * mu0 * (omega_s * s - (1.0 - omega_s) * a);
    let u0 = (-k * total).exp();
    let m = 1.0 - 2.0 * p / 3.0;
    let q = 1.0 + 2.0 * p / 3.0;
    // det = (u0 m)^2 - q^2, factored so that its small first factor is not a difference.
    let det = -((1.0 - u0) + 2.0 * p / 3.0 * (1.0 + u0)) * (u0 * m + q);
    let rising = (-k * (total - tau)).exp();
    let falling = (-k * tau).exp();
    // The homogeneous part of I_0 and I_1 for the conditions' right-hand sides r1, r2.
    let solve = |r1: f64, r2: f64| {
        let c1 = (r1 * u0 * m - q * r2) / det;
        let c2 = (u0 * m * r2 - q * r1) / det;
        (c1 * rising + c2 * falling, p * (c1 * rising - c2 * falling))
    };
    let beam = (-tau / mu0).exp();
    let (h0, h1) = solve(
        2.0 * b / 3.0 - a,
        -(a + 2.0 * b / 3.0) * (-total / mu0).exp(),
    );
    Moments {
        beam: (h0 + a * beam, h1 + b * beam),
        sky: solve(1.0 / std::f64::consts::PI, 0.0),
        f,
        g_s,
        beam_depth: tau / mu0,
    }
}

/// The diffuse field's source towards the eye, per unit of extinction times albedo,
/// sr^-1, per unit sun irradiance F_s and per unit sky irradiance E_sky:
/// (1 - f) (I_0 + g' mu_out I_1) of either solution at optical depth
/// `tau_above` below the top of a slab of optical depth `tau_above + tau_below`
/// (unscaled, non-negative), lit at the sun's cosine `mu0` from the upward vertical,
/// single-scattering albedo `albedo` in [0, 1], asymmetry `g` in (-1, 1), the light
/// leaving in a direction of cosine `mu_out` from the upward vertical.
pub fn diffuse_source(
    tau_above: f64,
    tau_below: f64,
    mu0: f64,
    albedo: f64,
    g: f64,
    mu_out: f64,
) -> (f64, f64) {
    let m = moments(tau_above, tau_below, mu0, albedo, g);
    let source = |(i0, i1): (f64, f64)| ((1.0 - m.f) * (i0 + m.g_s * mu_out * i1)).max(0.0);
    (source(m.beam), source(m.sky))
}

/// The flux through the depth `tau_above` of the slab of [`diffuse_source`] downwards,
/// per unit beam irradiance on a plane facing the beam: the diffuse
/// pi (I_0 - 2/3 I_1) by Eddington's two-term radiance plus the scaled beam's
/// mu0 e^(-tau'/mu0).
pub fn downward_flux(tau_above: f64, tau_below: f64, mu0: f64, albedo: f64, g: f64) -> f64 {
    let m = moments(tau_above, tau_below, mu0, albedo, g);
    let (i0, i1) = m.beam;
    let mu0 = mu0.clamp(MIN_SUN_COSINE, 1.0);
    std::f64::consts::PI * (i0 - 2.0 / 3.0 * i1) + mu0 * (-m.beam_depth).exp()
}

/// The diffuse flux leaving the top of the slab of [`diffuse_source`] upwards, per unit
/// beam irradiance on a plane facing the beam: pi (I_0 + 2/3 I_1) at depth 0.
pub fn upward_flux_at_top(tau: f64, mu0: f64, albedo: f64, g: f64) -> f64 {
    let (i0, i1) = moments(0.0, tau, mu0, albedo, g).beam;
    std::f64::consts::PI * (i0 + 2.0 / 3.0 * i1)
}
