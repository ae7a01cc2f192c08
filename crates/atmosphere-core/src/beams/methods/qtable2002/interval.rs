//! f_l of one light over a piece of a view ray: the smooth factor of Dobashi et al. 2002
//! Eq. 7, the integral of g (Eq. 3) without the light's intensity and visibility. A
//! point light or spot reads the q table in the frame of Fig. 2 (Eq. 9); for a parallel
//! light, "straightforward to extend" in the paper's words, g = sigma_s F(alpha)
//! exp(-sigma_t (s + t)) has a constant phase angle and s linear in t, so its integral
//! is closed: sigma_s F exp(-sigma_t (s_0 + t_0)) (1 - exp(-k L)) / k with
//! k = sigma_t (1 + ds/dt).

use glam::DVec3;

use crate::beams::light::{Light, LightShape};
use crate::beams::medium::MediumSpectra;
use crate::optics::phase::PhaseFunction;

use super::q_table::QTable;

/// f_l of `light` at wavelength `w` over [t_m, t_m + length_m] of the ray from `origin`
/// along the unit `direction`, m^-2 sr^-1 (a parallel light: sr^-1).
#[allow(clippy::too_many_arguments)]
pub fn f_l(
    table: &QTable,
    medium: &MediumSpectra,
    phase: &PhaseFunction,
    light: &Light,
    origin: DVec3,
    direction: DVec3,
    t_m: f64,
    length_m: f64,
    w: usize,
) -> f64 {
    match &light.shape {
        LightShape::Point { position_m, .. } | LightShape::Spot { position_m, .. } => {
            let (u, v) = light_frame_uv(*position_m, origin, direction, t_m);
            table.segment(t_m, u, v, length_m, w)
        }
        LightShape::Parallel {
            position_m, frame, ..
        } => {
            let along = frame.z.dot(direction);
            let s0 = frame.z.dot(origin + direction * t_m - *position_m).max(0.0);
            let (sigma_s, sigma_t) = (medium.scattering_per_m[w], medium.extinction_per_m[w]);
            let k = sigma_t * (1.0 + along);
            let integral = if k * length_m < 1e-9 {
                length_m
            } else {
                -(-k * length_m).exp_m1() / k
            };
            sigma_s * phase.eval(-along) * (-sigma_t * (s0 + t_m)).exp() * integral
        }
    }
}

/// The coordinates (u, v) of the point `t_m` along the ray in the frame of Fig. 2: u
/// along the ray from the foot of the light's perpendicular, v the light's distance from
/// the ray.
pub fn light_frame_uv(light: DVec3, origin: DVec3, direction: DVec3, t_m: f64) -> (f64, f64) {
    let rel = origin - light;
    let along = rel.dot(direction);
    let v = (rel - direction * along).length();
    (along + t_m, v)
}
