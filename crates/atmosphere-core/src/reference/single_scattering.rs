//! Order one, by converged quadrature: sunlight scattered once by the air towards the
//! camera (Bruneton 2008 Eq. 5 with the sun disk integrated), plus sunlight reflected
//! once by a Lambertian ground where the ray ends on it; with a terrain's shadow, the
//! sunlight at each node times the node's sun visibility (the light shafts' ground
//! truth: Bruneton and Neyret 2008, section 5, Eq. 9's occlusion applied to single
//! scattering).

use std::f64::consts::PI;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::optics::column::optical_depth;
use crate::reference::sun::disk_mean_transmittance;
use crate::reference::view_path::{RayEnd, ViewPath};
use crate::shafts::SunVisibility;

/// Single-scattered and once-reflected radiance at each wavelength of `spectra`,
/// W m^-2 sr^-1 nm^-1; `shadow`, when given, is the terrain's shadow in the air (the
/// ground term keeps the sphere's own test: the terrain pass lights its surface).
pub fn single_scattering(
    atmosphere: &Atmosphere,
    spectra: &Spectra,
    path: &ViewPath,
    sun: glam::DVec3,
    shadow: Option<&dyn SunVisibility>,
) -> Vec<f64> {
    let n = spectra.extinction.len();
    let mut radiance = vec![0.0; n];
    let mut sun_t = vec![0.0; n];
    let nu = path.direction.dot(sun);
    let phase_r = crate::optics::phase::rayleigh(nu);
    let phase_m = atmosphere.mie.phase.eval(nu);
    for node in &path.nodes {
        let scattering_r = node.densities[0] * phase_r;
        let scattering_m = node.densities[1] * phase_m;
        if scattering_r == 0.0 && scattering_m == 0.0 {
            continue;
        }
        let visible = shadow.map_or(1.0, |s| s.sun_visible(node.position, sun));
        if visible == 0.0 {
            continue;
        }
        disk_mean_transmittance(
            atmosphere,
            node.position,
            sun,
            None,
            &spectra.extinction,
            &mut sun_t,
        );
        for w in 0..n {
            let view_t = (-optical_depth(node.column_from_camera, spectra.extinction[w])).exp();
            let j = spectra.rayleigh_scattering[w] * scattering_r
                + spectra.mie_scattering[w] * scattering_m;
            radiance[w] +=
                node.weight * view_t * j * visible * sun_t[w] * spectra.solar_irradiance[w];
        }
    }
    if let RayEnd::Ground(point) = path.end {
        let normal = point.normalize();
        disk_mean_transmittance(
            atmosphere,
            point,
            sun,
            Some(normal),
            &spectra.extinction,
            &mut sun_t,
        );
        for w in 0..n {
            let view_t = (-optical_depth(path.total_column, spectra.extinction[w])).exp();
            radiance[w] +=
                view_t * atmosphere.ground_albedo / PI * spectra.solar_irradiance[w] * sun_t[w];
        }
    }
    radiance
}
