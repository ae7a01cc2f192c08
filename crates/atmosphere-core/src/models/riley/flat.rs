//! Riley et al. 2004, section 4.1: single scattering in a flat, exponentially stratified
//! atmosphere of one species, in closed form, and the flattened view ray it is applied to
//! in the camera's tangent frame (the paper's geometry, `sphere=false`).
//!
//! With density exp(-gamma y), sea-level scattering beta (extinction = scattering),
//! camera at height y0 looking along a direction of vertical component p_y, sun at
//! vertical component l_y > 0, Eq. (11) gives the transmittance between two points and
//! Eq. (12) the sunlight reaching a point. Substituting both in Eq. (14) and integrating
//! over the ray gives Eq. (15). Writing u = exp(-gamma y) and a = beta / gamma:
//!
//! L = I P(nu) l_y / (p_y - l_y) exp(-a u0 / p_y) [exp(-c u1) - exp(-c u0)],
//! c = a (1/l_y - 1/p_y),
//!
//! with u0 at the camera and u1 at the end of the ray. The printed Eq. (15) lacks the
//! factor exp(-a u0 / p_y), the transmittance from the camera to infinity along the ray;
//! re-deriving from Eq. (11)-(14) restores it, and the reference agrees with the restored
//! form (tests/reference_physics.rs).
//!
//! As printed, the form divides by p_y - l_y and by p_y and multiplies exponentials that
//! overflow when p_y < 0. [`FlatExponential::single_scattering`] evaluates the same
//! integral without either division: with tau the optical depth of the ray (Eq. 11,
//! `tau = a (u0 - u1) / p_y = a u0 (K gamma) phi(p_y K gamma)`, phi(x) = (1 - e^-x) / x),
//! the integrand's exponent is linear in u, so
//!
//! L = I P tau exp(f_max) phi(tau |p_y - l_y| / l_y),
//!
//! with f = -(sun optical depth) - (view optical depth from the camera), taken at whichever
//! end of the ray it is larger. Every factor is bounded, phi is evaluated by `expm1` (and
//! a series near 0), and the limits p_y = l_y, p_y = 0 and infinite horizontal rays come
//! out of the same expression. See docs/models/riley.md.

use crate::optics::geometry::{distance_to_exit, ray_hits_ground};

/// `(1 - exp(-x)) / x`, 1 at x = 0, accurate for every x (0 at +infinity).
pub fn phi(x: f64) -> f64 {
    if x.abs() < 1e-5 {
        // Three terms of the series: the next, x^3 / 24, is below 5e-17.
        1.0 - x / 2.0 + x * x / 6.0
    } else if x == f64::INFINITY {
        0.0
    } else {
        -(-x).exp_m1() / x
    }
}

/// A flat atmosphere of one exponentially stratified, non-absorbing species.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatExponential {
    /// Scattering (= extinction) coefficient at height 0, m^-1.
    pub beta_sea_level_per_m: f64,
    /// 1 / gamma, m.
    pub scale_height_m: f64,
    /// The sun's irradiance at infinity.
    pub irradiance: f64,
}

impl FlatExponential {
    /// Relative density exp(-y / H) at the end of a ray from `height_m` with vertical
    /// component `view_up` after `length_m` (infinite length: 0 going up, infinite going
    /// down, unchanged for a horizontal ray).
    fn end_density(&self, height_m: f64, view_up: f64, length_m: f64) -> f64 {
        let u0 = (-height_m / self.scale_height_m).exp();
        if length_m.is_infinite() {
            if view_up > 0.0 {
                0.0
            } else if view_up < 0.0 {
                f64::INFINITY
            } else {
                u0
            }
        } else {
            (-(height_m + view_up * length_m) / self.scale_height_m).exp()
        }
    }

    /// Optical depth (Eq. 11) of a ray from height `height_m` with vertical direction
    /// component `view_up` (any sign, 0 included) over `length_m` (infinite allowed).
    pub fn optical_depth(&self, height_m: f64, view_up: f64, length_m: f64) -> f64 {
        let (beta, h) = (self.beta_sea_level_per_m, self.scale_height_m);
        if beta == 0.0 || length_m == 0.0 {
            return 0.0;
        }
        if length_m.is_infinite() && view_up <= 0.0 {
            return f64::INFINITY;
        }
        let u0 = (-height_m / h).exp();
        let x = view_up * length_m / h;
        if x.abs() <= 1.0 {
            // a u0 (u0 - u1) / (u0 p_y) without the cancellation of u0 - u1.
            beta * u0 * length_m * phi(x)
        } else {
            let u1 = self.end_density(height_m, view_up, length_m);
            beta * h * (u0 - u1) / view_up
        }
    }

    /// Single-scattered radiance (Riley et al. 2004 Eq. 15, restored as above) of a ray
    /// from height `camera_height_m` with vertical direction component `view_up` (any
    /// sign; 0 and `sun_up` included) running `length_m` (infinite allowed), sun at
    /// vertical component `sun_up` (no light at `sun_up <= 0`), phase function value
    /// `phase` (sr^-1). Finite and continuous in every argument.
    pub fn single_scattering(
        &self,
        camera_height_m: f64,
        view_up: f64,
        sun_up: f64,
        length_m: f64,
        phase: f64,
    ) -> f64 {
        let (beta, h) = (self.beta_sea_level_per_m, self.scale_height_m);
        if sun_up <= 0.0 || beta == 0.0 || length_m == 0.0 {
            return 0.0;
        }
        let a = beta * h;
        let u0 = (-camera_height_m / h).exp();
        let u1 = self.end_density(camera_height_m, view_up, length_m);
        let tau = self.optical_depth(camera_height_m, view_up, length_m);
        // The exponent of the integrand: sun optical depth plus view optical depth from
        // the camera, at the camera and at the end of the ray.
        let f_camera = -a * u0 / sun_up;
        let f_end = if u1.is_infinite() || tau.is_infinite() {
            f64::NEG_INFINITY
        } else {
            -a * u1 / sun_up - tau
        };
        let f_max = f_camera.max(f_end);
        let spread = (view_up - sun_up).abs() / sun_up;
        // tau phi(tau spread), whose limit at tau = infinity is 1 / spread.
        let tau_phi = if tau.is_infinite() {
            1.0 / spread
        } else {
            tau * phi(tau * spread)
        };
        self.irradiance * phase * tau_phi * f_max.exp()
    }
}

/// One straight piece of the flattened view ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leg {
    pub height_m: f64,
    pub view_up: f64,
    pub length_m: f64,
}

/// The flattened view ray from the atmosphere entry point at height `y0` (m above the
/// ground), radius `r`, direction cosine `p` to the local zenith: its legs and whether
/// it ends on the ground. Each leg keeps the slope `p` of the real ray at the camera (up
/// to sign), but a ray leaving the atmosphere is no longer than the real ray's chord to
/// the top: a flat ray near the horizon would otherwise run on for ever at the camera's
/// height, where the real one climbs out of the air.
pub fn flat_legs(y0: f64, r: f64, p: f64, bottom: f64, top: f64) -> (Vec<Leg>, bool) {
    if ray_hits_ground(r, p, bottom) {
        // Down to the flat ground, where the flat ray meets height 0.
        return (
            vec![Leg {
                height_m: y0,
                view_up: p,
                length_m: y0 / -p,
            }],
            true,
        );
    }
    let chord = distance_to_exit(r, p, top);
    if p >= 0.0 {
        (
            vec![Leg {
                height_m: y0,
                view_up: p,
                length_m: chord,
            }],
            false,
        )
    } else {
        // Down past the planet's limb: the real ray descends to its lowest point and
        // climbs back out; flat, it descends to that point's altitude and climbs again
        // at the mirrored slope for the rest of the chord.
        let perigee = (r * ((1.0 - p) * (1.0 + p)).sqrt() - bottom).clamp(0.0, y0);
        let down = ((y0 - perigee) / -p).min(chord);
        (
            vec![
                Leg {
                    height_m: y0,
                    view_up: p,
                    length_m: down,
                },
                Leg {
                    height_m: perigee,
                    view_up: -p,
                    length_m: chord - down,
                },
            ],
            false,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form against a brute-force midpoint sum of Eq. (14).
    #[test]
    fn closed_form_matches_direct_integration() {
        let atm = FlatExponential {
            beta_sea_level_per_m: 1.35e-5,
            scale_height_m: 8000.0,
            irradiance: 1.8,
        };
        let (y0, p_y, l_y, length, phase) = (500.0, 0.4, 0.7, 150_000.0, 0.05);
        let n = 200_000;
        let ds = length / n as f64;
        let mut sum = 0.0;
        for i in 0..n {
            let s = (i as f64 + 0.5) * ds;
            let y = y0 + p_y * s;
            let beta_y = atm.beta_sea_level_per_m * (-y / 8000.0).exp();
            let view_t = (-atm.beta_sea_level_per_m * 8000.0 / p_y
                * ((-y0 / 8000.0).exp() - (-y / 8000.0).exp()))
            .exp();
            let sun_t = (-atm.beta_sea_level_per_m * 8000.0 / l_y * (-y / 8000.0).exp()).exp();
            sum += view_t * beta_y * phase * atm.irradiance * sun_t * ds;
        }
        let closed = atm.single_scattering(y0, p_y, l_y, length, phase);
        assert!((closed / sum - 1.0).abs() < 1e-8, "{closed} vs {sum}");
    }

    #[test]
    fn phi_is_continuous_across_its_series() {
        for x in [1e-5f64, -1e-5, 1e-5 * (1.0 + 1e-9), 0.0] {
            let exact = if x == 0.0 { 1.0 } else { -(-x).exp_m1() / x };
            assert!((phi(x) - exact).abs() < 1e-15, "{x}");
        }
        assert_eq!(phi(f64::INFINITY), 0.0);
    }

    #[test]
    fn printed_form_and_stable_form_agree_away_from_the_stiff_cases() {
        let atm = FlatExponential {
            beta_sea_level_per_m: 3.31e-5,
            scale_height_m: 8000.0,
            irradiance: 1.9,
        };
        for &(y0, p, l, k) in &[
            (0.0, 0.3, 0.8, f64::INFINITY),
            (2000.0, -0.4, 0.5, 5000.0),
            (100.0, 0.9, 0.1, 20_000.0),
            (30_000.0, -0.2, 0.6, 150_000.0),
        ] {
            let u0 = (-y0 / 8000.0f64).exp();
            let u1 = if k == f64::INFINITY {
                0.0
            } else {
                (-(y0 + p * k) / 8000.0f64).exp()
            };
            let a = 3.31e-5 * 8000.0;
            let c = a * (1.0 / l - 1.0 / p);
            let printed =
                1.9 * 0.1 * l / (p - l) * (-a * u0 / p).exp() * ((-c * u1).exp() - (-c * u0).exp());
            let stable = atm.single_scattering(y0, p, l, k, 0.1);
            assert!(
                (stable / printed - 1.0).abs() < 1e-12,
                "{stable} vs {printed}"
            );
        }
    }
}
