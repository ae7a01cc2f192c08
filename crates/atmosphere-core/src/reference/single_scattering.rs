//! Order one, by converged quadrature: sunlight scattered once by the air towards the
//! camera (Bruneton 2008 Eq. 5 with the sun disk integrated), plus sunlight reflected
//! once by a Lambertian ground where the ray ends on it.

use std::f64::consts::PI;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::optics::column::optical_depth;
use crate::reference::sun::disk_mean_transmittance;
use crate::reference::view_path::{RayEnd, ViewPath};

/// Single-scattered and once-reflected radiance at each wavelength of `spectra`,
/// W m^-2 sr^-1 nm^-1.
pub fn single_scattering(
    atmosphere: &Atmosphere,
    spectra: &Spectra,
    path: &ViewPath,
    sun: glam::DVec3,
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
            radiance[w] += node.weight * view_t * j * sun_t[w] * spectra.solar_irradiance[w];
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
