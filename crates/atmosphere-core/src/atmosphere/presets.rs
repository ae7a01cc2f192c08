//! The shipped atmospheres. Each number cites where it comes from.

use std::path::Path;

use crate::atmosphere::density::DensityProfile;
use crate::atmosphere::spectral::Spectral;
use crate::atmosphere::{Absorber, Atmosphere, AtmosphereError, Mie, Rayleigh, Sun};
use crate::optics::phase::PhaseFunction;

/// Peak number density of ozone for 300 Dobson units in the 10-25-40 km tent profile
/// (Bruneton 2017 demo: 300 DU = 300 * 2.687e20 m^-2 spread over a tent of 15 km
/// half-width).
pub const EARTH_OZONE_PEAK_NUMBER_DENSITY_PER_M3: f64 = 5.374e18;

/// Earth as in Bruneton 2017's demo, so that results compare number for number.
pub fn earth() -> Atmosphere {
    Atmosphere {
        name: "earth".into(),
        bottom_radius_m: 6_360_000.0,
        top_radius_m: 6_420_000.0,
        rayleigh: Rayleigh {
            // 1.24062e-6 * lambda_um^-4 m^-1 (Bruneton 2017 demo, kRayleigh).
            scattering_per_m: Spectral::PowerLaw {
                value_at_1um: 1.24062e-6,
                exponent: 4.0,
            },
            density: DensityProfile::exponential(8_000.0),
        },
        mie: Mie {
            scattering_per_m: Spectral::Constant { value: 3.996e-6 },
            extinction_per_m: Spectral::Constant { value: 4.44e-6 },
            density: DensityProfile::exponential(1_200.0),
            phase: PhaseFunction::CornetteShanks { g: 0.8 },
        },
        ozone: Absorber {
            absorption_per_m: Spectral::OzoneSerdyuchenko {
                number_density_per_m3: EARTH_OZONE_PEAK_NUMBER_DENSITY_PER_M3,
            },
            density: DensityProfile::tent(10_000.0, 25_000.0, 40_000.0),
        },
        ground_albedo: 0.1,
        sun: Sun {
            irradiance_w_m2_nm: Spectral::SolarAstmG173 { scale: 1.0 },
            angular_radius_rad: 0.004675,
        },
    }
}

/// A very clean day: Earth with half the aerosol of `earth`, whose aerosol already gives
/// a meteorological range near 230 km by Koschmieder's V = 3.912 / beta.
pub fn clear() -> Atmosphere {
    let mut a = earth().with_aerosol_scale(0.5);
    a.name = "clear".into();
    a
}

/// Haze: a boundary-layer aerosol for a meteorological range of about 15 km
/// (Koschmieder: extinction 3.912 / 15 km = 2.6e-4 m^-1 at 550 nm, of which Rayleigh
/// takes 1.36e-5), Angstrom exponent 1.3 and single-scattering albedo 0.9, typical of
/// continental haze (Hess, Koepke and Schult 1998, OPAC), scale height 1.5 km.
pub fn hazy() -> Atmosphere {
    let mut a = earth();
    a.name = "hazy".into();
    // 2.47e-4 m^-1 at 550 nm = value_at_1um * 0.55^-1.3.
    let extinction_at_1um = 2.47e-4 * 0.55f64.powf(1.3);
    a.mie = Mie {
        scattering_per_m: Spectral::PowerLaw {
            value_at_1um: 0.9 * extinction_at_1um,
            exponent: 1.3,
        },
        extinction_per_m: Spectral::PowerLaw {
            value_at_1um: extinction_at_1um,
            exponent: 1.3,
        },
        density: DensityProfile::exponential(1_500.0),
        phase: PhaseFunction::CornetteShanks { g: 0.7 },
    };
    a
}

/// Mars in a moderately dusty season.
/// - Mean radius 3389.5 km (NASA Mars fact sheet); atmosphere cut at 100 km (9 scale
///   heights).
/// - CO2 at the surface: 610 Pa and 210 K give 2.1e23 m^-3; Rayleigh cross-section of CO2
///   1.23e-30 m^2 at 532 nm (Sneep and Ubachs 2005), so 2.58e-7 m^-1 at 532 nm, i.e.
///   2.07e-8 m^-1 at 1 um with lambda^-4; scale height 11.1 km.
/// - Dust: visible optical depth 0.5, well mixed with the gas (scale height 11.1 km), so
///   4.5e-5 m^-1 at the surface; grey extinction; single-scattering albedo 0.92, 0.96,
///   0.98 at 440, 550, 680 nm and Henyey-Greenstein g = 0.63 (Tomasko et al. 1999,
///   Wolff et al. 2009): the absorption of blue light gives the butterscotch sky.
/// - No ozone to speak of; ground albedo 0.25; the sun at 1.524 au: irradiance times
///   1 / 1.524^2 = 0.4306 and angular radius 0.004675 / 1.524 rad.
pub fn mars() -> Atmosphere {
    let dust_extinction = 4.5e-5;
    Atmosphere {
        name: "mars".into(),
        bottom_radius_m: 3_389_500.0,
        top_radius_m: 3_489_500.0,
        rayleigh: Rayleigh {
            scattering_per_m: Spectral::PowerLaw {
                value_at_1um: 2.07e-8,
                exponent: 4.0,
            },
            density: DensityProfile::exponential(11_100.0),
        },
        mie: Mie {
            scattering_per_m: Spectral::Table {
                wavelengths_nm: vec![440.0, 550.0, 680.0],
                values: vec![
                    0.92 * dust_extinction,
                    0.96 * dust_extinction,
                    0.98 * dust_extinction,
                ],
            },
            extinction_per_m: Spectral::Constant {
                value: dust_extinction,
            },
            density: DensityProfile::exponential(11_100.0),
            phase: PhaseFunction::HenyeyGreenstein { g: 0.63 },
        },
        ozone: Absorber {
            absorption_per_m: Spectral::Constant { value: 0.0 },
            density: DensityProfile::exponential(11_100.0),
        },
        ground_albedo: 0.25,
        sun: Sun {
            irradiance_w_m2_nm: Spectral::SolarAstmG173 {
                scale: 1.0 / (1.524 * 1.524),
            },
            angular_radius_rad: 0.004675 / 1.524,
        },
    }
}

impl Atmosphere {
    /// A preset by name: `earth`, `clear`, `hazy` or `mars`.
    pub fn preset(name: &str) -> Result<Atmosphere, AtmosphereError> {
        match name {
            "earth" => Ok(earth()),
            "clear" => Ok(clear()),
            "hazy" => Ok(hazy()),
            "mars" => Ok(mars()),
            other => Err(AtmosphereError::UnknownPreset(other.to_string())),
        }
    }

    /// A preset name, or else a path to a TOML file.
    pub fn from_preset_or_file(name_or_path: &str) -> Result<Atmosphere, AtmosphereError> {
        match Atmosphere::preset(name_or_path) {
            Ok(atmosphere) => Ok(atmosphere),
            Err(_) if name_or_path.ends_with(".toml") || Path::new(name_or_path).exists() => {
                Atmosphere::load(Path::new(name_or_path))
            }
            Err(e) => Err(e),
        }
    }
}
