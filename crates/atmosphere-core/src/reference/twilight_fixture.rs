//! The scene the guiding tests share: the Earth at 440 nm (the wavelength whose
//! twilight converges slowest) with the sun 12 deg below the horizon (nautical
//! twilight), in the x-z plane.

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::models::settings::ModelSettings;

/// The Earth, settings at 440 nm alone, and the unit vector towards a sun at a zenith
/// angle of 102 deg.
pub(crate) fn nautical_twilight_at_440() -> (Atmosphere, ModelSettings, DVec3) {
    let earth = Atmosphere::preset("earth").unwrap();
    let settings = ModelSettings {
        wavelengths_nm: vec![440.0],
        ..ModelSettings::default()
    };
    let z = 102f64.to_radians();
    (earth, settings, DVec3::new(z.sin(), 0.0, z.cos()))
}
