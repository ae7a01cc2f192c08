//! The Hillaire model prepared once with the paper's settings, and what the tests of its
//! tables and of the whole model compare it with.

use std::sync::OnceLock;

use atmosphere_core::models::hillaire::march::ViewMarch;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::view_segment::ViewSegment;

use super::earth;

pub fn full_model() -> &'static Hillaire {
    static MODEL: OnceLock<Hillaire> = OnceLock::new();
    MODEL.get_or_init(|| {
        Hillaire::prepare(
            &earth(),
            &ModelSettings::default(),
            HillaireSettings::default(),
        )
        .unwrap()
    })
}

/// The model's radiance of `ray` by a direct march of `samples` segments with the same
/// integrand (single scattering plus Psi_ms), without the per-view tables.
pub fn direct(model: &Hillaire, ray: &ViewRay, samples: usize) -> Vec<f64> {
    let a = earth();
    let segment = ViewSegment::new(&a, ray).unwrap().unwrap();
    let mu_s = segment.start.normalize().dot(segment.sun_direction);
    let nu = segment.direction.dot(segment.sun_direction);
    let mut march = ViewMarch::new(
        model.medium(),
        model.multiple_scattering(),
        segment.r,
        segment.mu,
        mu_s,
        nu,
    );
    march.run(segment.length, samples);
    march
        .radiance
        .iter()
        .zip(model.solar_irradiance_w_m2_nm())
        .map(|(l, e)| l * e)
        .collect()
}

/// Directions around a camera: zenith angles from 0 to 178 degrees, azimuths from the
/// sun 0 to 180, off the tables' texels.
pub fn directions() -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for k in 0..23 {
        for m in 0..9 {
            out.push((0.3 + 7.77 * k as f64, 1.1 + 22.13 * m as f64));
        }
    }
    out
}
