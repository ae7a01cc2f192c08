//! The ranges an atmosphere's values must lie in beyond being physically possible: those
//! every model computes right (checked by [`Atmosphere::validate`]) and the narrower ones
//! of the real-time models and the GPU's f32 ([`Atmosphere::check_real_time_range`]).

use crate::atmosphere::density::DensityProfile;
use crate::atmosphere::spectral::Spectral;
use crate::atmosphere::{Atmosphere, AtmosphereError};

/// Largest ground radius, m, for every model: the flat-planet tests of the reference and
/// of Riley's model run at 6.36e9 m.
pub const MAX_BOTTOM_RADIUS_M: f64 = 1e10;

/// Largest solar irradiance, W m^-2 nm^-1 at any visible wavelength: about 500 times the
/// Earth's, the sun at 0.045 au. With the smallest sun disk the disk's luminance stays
/// below 1e18 cd/m^2, and its square within f32 on the GPU.
pub const MAX_IRRADIANCE_W_M2_NM: f64 = 1e3;

/// Smallest angular radius of the sun's disk, rad: the sun seen from 470 au.
pub const MIN_SUN_ANGULAR_RADIUS_RAD: f64 = 1e-5;

/// Largest scattering, extinction or absorption coefficient at density 1, m^-1, at any
/// visible wavelength: a visibility of 4 m, denser than any fog.
pub const MAX_COEFFICIENT_PER_M: f64 = 1.0;

/// Largest growth of a density layer's exponential term across the atmosphere,
/// `exp_scale_per_m * thickness`: exp(80) = 5.5e34 stays within f32.
pub const MAX_DENSITY_GROWTH: f64 = 80.0;

/// Largest magnitude of a density layer's `exp_term`, `constant_term` and
/// `linear_term_per_m * thickness`: the density is clamped to [0, 1], so larger terms
/// only saturate, and these stay within f32.
pub const MAX_DENSITY_TERM: f64 = 1e6;

/// Ground radii, m, of the real-time models and the GPU: Mars (3.39e6 m), Venus and the
/// Earth (6.36e6 m) are the validated planets; within this range the sky from the ground
/// agrees with the reference as at the Earth's radius. Beyond it Bruneton's tables drift
/// (5 % at 1e9 m) and the f32 geometry of the shaders loses the ground.
pub const REAL_TIME_BOTTOM_RADIUS_M: [f64; 2] = [1e5, 1e8];

/// Smallest thickness of the atmosphere as a fraction of the ground radius for the
/// real-time models: f32 resolves 6e-8 of a radius, so at least a thousand steps span
/// the atmosphere.
pub const REAL_TIME_MIN_THICKNESS_RATIO: f64 = 1e-4;

/// Highest camera altitude above the ground, m: at 1e10 m the Earth spans two pixels of
/// a 60-degree, 1280-pixel view, and beyond about 1e14 m the square of the distance in
/// f64 no longer holds the planet's radius squared, so rays miss the planet.
pub const MAX_ALTITUDE_M: f64 = 1e10;

/// The visible wavelengths every model samples within, nm.
const VISIBLE_NM: [f64; 2] = [360.0, 830.0];

fn invalid(field: &str, message: String) -> Result<(), AtmosphereError> {
    Err(AtmosphereError::Invalid {
        field: field.to_string(),
        message,
    })
}

/// The largest value of `spectrum` in the visible range and its wavelength, nm: it is
/// linear between the table points and 1 nm apart suffices for the tabulated recipes
/// (10 nm tables).
fn visible_maximum(spectrum: &Spectral) -> (f64, f64) {
    let knots = match spectrum {
        Spectral::Table { wavelengths_nm, .. } => wavelengths_nm.clone(),
        _ => Vec::new(),
    };
    let whole_nm = (VISIBLE_NM[0] as u32..=VISIBLE_NM[1] as u32).map(f64::from);
    whole_nm
        .chain(
            knots
                .into_iter()
                .filter(|nm| (VISIBLE_NM[0]..=VISIBLE_NM[1]).contains(nm)),
        )
        .map(|nm| (spectrum.at(nm), nm))
        .fold((0.0, VISIBLE_NM[0]), |best, next| {
            if next.0 > best.0 || next.0.is_nan() {
                next
            } else {
                best
            }
        })
}

fn check_spectrum(
    field: &str,
    spectrum: &Spectral,
    max: f64,
    unit: &str,
) -> Result<(), AtmosphereError> {
    let (value, nm) = visible_maximum(spectrum);
    if value <= max {
        return Ok(());
    }
    invalid(
        field,
        format!("reaches {value:e} {unit} at {nm} nm; at most {max:e} {unit} in 360..830 nm"),
    )
}

fn check_profile(
    field: &str,
    profile: &DensityProfile,
    thickness_m: f64,
) -> Result<(), AtmosphereError> {
    for (i, l) in profile.layers.iter().enumerate() {
        if l.exp_term != 0.0 && l.exp_scale_per_m * thickness_m > MAX_DENSITY_GROWTH {
            return invalid(
                field,
                format!(
                    "layer {i}: exp_scale_per_m {} times the thickness {thickness_m} m exceeds {MAX_DENSITY_GROWTH} (the density would grow past f32)",
                    l.exp_scale_per_m
                ),
            );
        }
        let terms = [
            ("exp_term", l.exp_term),
            ("constant_term", l.constant_term),
            (
                "linear_term_per_m times the thickness",
                l.linear_term_per_m * thickness_m,
            ),
        ];
        for (name, v) in terms {
            if v.abs() > MAX_DENSITY_TERM {
                return invalid(
                    field,
                    format!("layer {i}: {name} {v:e} must lie within +-{MAX_DENSITY_TERM:e}"),
                );
            }
        }
    }
    Ok(())
}

/// Checks the ranges every model computes right; called by [`Atmosphere::validate`] once
/// the values are known to be finite and possible.
pub(crate) fn check_model_ranges(a: &Atmosphere) -> Result<(), AtmosphereError> {
    if a.bottom_radius_m > MAX_BOTTOM_RADIUS_M {
        return invalid(
            "bottom_radius_m",
            format!(
                "{:e} m must be at most {MAX_BOTTOM_RADIUS_M:e} m, the largest planet the models are tested on",
                a.bottom_radius_m
            ),
        );
    }
    let coefficients = [
        ("rayleigh.scattering_per_m", &a.rayleigh.scattering_per_m),
        ("mie.scattering_per_m", &a.mie.scattering_per_m),
        ("mie.extinction_per_m", &a.mie.extinction_per_m),
        ("ozone.absorption_per_m", &a.ozone.absorption_per_m),
    ];
    for (field, spectrum) in coefficients {
        check_spectrum(field, spectrum, MAX_COEFFICIENT_PER_M, "m^-1")?;
    }
    check_spectrum(
        "sun.irradiance_w_m2_nm",
        &a.sun.irradiance_w_m2_nm,
        MAX_IRRADIANCE_W_M2_NM,
        "W m^-2 nm^-1",
    )?;
    let profiles = [
        ("rayleigh.density", &a.rayleigh.density),
        ("mie.density", &a.mie.density),
        ("ozone.density", &a.ozone.density),
    ];
    for (field, profile) in profiles {
        check_profile(field, profile, a.thickness_m())?;
    }
    Ok(())
}

impl Atmosphere {
    /// Checks that this (valid) atmosphere lies in the range of the real-time models and
    /// the GPU ([`REAL_TIME_BOTTOM_RADIUS_M`], [`REAL_TIME_MIN_THICKNESS_RATIO`]); the
    /// reference alone computes beyond it.
    pub fn check_real_time_range(&self) -> Result<(), AtmosphereError> {
        let [low, high] = REAL_TIME_BOTTOM_RADIUS_M;
        let radius = self.bottom_radius_m;
        if !(low..=high).contains(&radius) {
            return invalid(
                "bottom_radius_m",
                format!(
                    "{radius:e} m is outside [{low:e}, {high:e}] m, the range of the real-time models and the GPU (only the reference computes beyond it)"
                ),
            );
        }
        let least = REAL_TIME_MIN_THICKNESS_RATIO * radius;
        if self.thickness_m() < least {
            return invalid(
                "top_radius_m",
                format!(
                    "the atmosphere is {} m thick; the real-time models and the GPU need at least {REAL_TIME_MIN_THICKNESS_RATIO:e} of bottom_radius_m ({least} m)",
                    self.thickness_m()
                ),
            );
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::density::DensityLayer;

    fn field_of(result: Result<(), AtmosphereError>) -> String {
        match result {
            Err(AtmosphereError::Invalid { field, .. }) => field,
            other => panic!("expected an invalid field, got {other:?}"),
        }
    }

    #[test]
    fn presets_lie_in_every_range() {
        for name in ["earth", "clear", "hazy", "mars"] {
            let a = Atmosphere::preset(name).unwrap();
            a.validate().unwrap();
            a.check_real_time_range().unwrap();
        }
    }

    #[test]
    fn a_sun_past_f32_is_refused() {
        let mut a = Atmosphere::preset("earth").unwrap();
        a.sun.irradiance_w_m2_nm = Spectral::SolarAstmG173 { scale: 1e300 };
        assert_eq!(field_of(a.validate()), "sun.irradiance_w_m2_nm");
        a.sun.irradiance_w_m2_nm = Spectral::SolarAstmG173 { scale: 400.0 };
        a.validate().unwrap();
        // A power law that explodes in the blue is caught at 360 nm.
        a.sun.irradiance_w_m2_nm = Spectral::PowerLaw {
            value_at_1um: 1.0,
            exponent: 100.0,
        };
        let message = a.validate().unwrap_err().to_string();
        assert!(message.contains("at 360 nm"), "{message}");
    }

    #[test]
    fn coefficients_and_profiles_past_f32_are_refused() {
        let earth = Atmosphere::preset("earth").unwrap();
        let mut a = earth.clone();
        a.mie.scattering_per_m = Spectral::Constant { value: 2.0 };
        a.mie.extinction_per_m = Spectral::Constant { value: 2.0 };
        assert_eq!(field_of(a.validate()), "mie.scattering_per_m");
        let mut a = earth.clone();
        a.rayleigh.density.layers[0].exp_scale_per_m = 0.01;
        assert_eq!(field_of(a.validate()), "rayleigh.density");
        let mut a = earth;
        a.ozone.density.layers.push(DensityLayer {
            constant_term: -1e300,
            ..DensityLayer::default()
        });
        assert_eq!(field_of(a.validate()), "ozone.density");
    }

    #[test]
    fn radii_outside_the_models_ranges_are_named() {
        let mut a = Atmosphere::preset("earth").unwrap();
        a.bottom_radius_m = 1e12;
        a.top_radius_m = 1e12 + 60e3;
        assert_eq!(field_of(a.validate()), "bottom_radius_m");
        a.bottom_radius_m = 1e9;
        a.top_radius_m = 1e9 + 60e3;
        a.validate().unwrap();
        let message = a.check_real_time_range().unwrap_err().to_string();
        assert!(message.contains("[1e5, 1e8] m"), "{message}");
        a.bottom_radius_m = 6.36e6;
        a.top_radius_m = 6.36e6 + 100.0;
        assert_eq!(field_of(a.check_real_time_range()), "top_radius_m");
    }
}
