//! The weights of an interval's samples in its mean of I_l H (not the paper's).
//!
//! Dobashi et al. 2002 Eq. 6 approximate an interval's integral of I_l H g by the plain
//! mean of I_l H over its m_k samples (Eq. 10) times f_l, the integral of g (Eq. 7):
//! exact where one factor is constant over the interval. Where a ray passes within an
//! interval's length of a light, g (its 1 / s^2) changes by orders of magnitude across
//! the interval and the spot's cone crosses it, and the plain mean weighs the samples far
//! from the light as much as the one beside it. With `weighted_samples=true` each
//! sample is weighted by g at it instead, so that the mean is g's own weighting of I_l H
//! sampled at the same planes, and f_l still comes from the table:
//!
//!   f = f_l * sum_j g_j (I_l H)_j / sum_j g_j,
//!
//! the plain mean where g is constant. g_j (Eq. 3 without sigma_s, which cancels) is the
//! phase function at the sample's scattering angle times 1 / s^2 (1 for a parallel
//! light) times the attenuation over the light's path to the sample and on to the camera.

use crate::beams::light::Light;
use crate::beams::ray::SceneRay;
use crate::optics::phase::PhaseFunction;

/// Whether every sample of an interval is weighted by g at it (`true`) or all alike
/// (`false`, the paper's Eq. 10).
pub const WEIGHTED_SAMPLES: &str = "weighted_samples";

/// g at `t_m` along `ray` for `light`, per wavelength of `extinction_per_m` into `out`,
/// its attenuation taken relative to a path of `base_m` (the interval's first sample's
/// light path plus camera distance, so that values stay within f64's range; `None`:
/// this sample's own), and this sample's path length, which the interval's first
/// sample passes on as `base_m` to the later ones.
pub fn smooth_factor(
    light: &Light,
    phase: &PhaseFunction,
    extinction_per_m: &[f64],
    ray: &SceneRay,
    t_m: f64,
    base_m: Option<f64>,
    out: &mut [f64],
) -> f64 {
    let geometry = light.geometry(ray.at(t_m));
    let path_m = geometry.distance_m + t_m;
    let angular = phase.eval(geometry.to_light.dot(ray.direction)) * geometry.inverse_square;
    let base_m = base_m.unwrap_or(path_m);
    for (g, sigma_t) in out.iter_mut().zip(extinction_per_m) {
        *g = angular * (-sigma_t * (path_m - base_m)).exp();
    }
    path_m
}
