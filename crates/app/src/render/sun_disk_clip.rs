//! Whether the sun's disk is brighter than the HDR image holds: the image is f16
//! (`render_wgpu::gpu::formats::HDR_FORMAT`) and the pixel passes clip radiance to its
//! largest value, so a sun brighter or smaller than about the Earth's from Venus is drawn
//! dimmer than it is (the sky around it is not clipped).

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::optics::sun_disk::centre_radiance;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

/// The largest f16, the most one channel of the HDR image holds, W m^-2 sr^-1 nm^-1.
pub const HDR_MAX_RADIANCE: f64 = 65504.0;

/// A warning when the radiance at the centre of the sun's disk passes
/// [`HDR_MAX_RADIANCE`] at a GPU wavelength.
pub fn sun_disk_clip_warning(atmosphere: &Atmosphere) -> Option<String> {
    let (radiance, nm) = RGB_WAVELENGTHS_NM
        .iter()
        .map(|&nm| {
            let e = atmosphere.coefficients(nm).solar_irradiance_w_m2_nm;
            (
                centre_radiance(e, atmosphere.sun.angular_radius_rad, nm),
                nm,
            )
        })
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    (radiance > HDR_MAX_RADIANCE).then(|| {
        format!(
            "the sun's disk ({radiance:.3e} W m^-2 sr^-1 nm^-1 at its centre at {nm} nm) is brighter than the HDR image holds ({HDR_MAX_RADIANCE}); it is drawn clipped, the sky is not"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::atmosphere::spectral::Spectral;

    #[test]
    fn the_shipped_suns_fit_and_a_small_or_bright_one_is_named() {
        for name in ["earth", "clear", "hazy", "mars"] {
            let a = Atmosphere::preset(name).unwrap();
            assert_eq!(sun_disk_clip_warning(&a), None, "{name}");
        }
        let mut a = Atmosphere::preset("earth").unwrap();
        a.sun.angular_radius_rad = 1e-3;
        let warning = sun_disk_clip_warning(&a).unwrap();
        assert!(warning.contains("drawn clipped"), "{warning}");
        let mut a = Atmosphere::preset("earth").unwrap();
        a.sun.irradiance_w_m2_nm = Spectral::SolarAstmG173 { scale: 4.0 };
        assert!(sun_disk_clip_warning(&a).is_some());
    }
}
