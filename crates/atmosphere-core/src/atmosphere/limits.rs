//! The ranges an atmosphere's values must lie in beyond being physically possible: those
//! every model computes right (checked by `Atmosphere::validate`) and the narrower ones
//! of the real-time models and the GPU's f32 (`Atmosphere::check_real_time_range`). Each
//! check here answers why a part is out of range, if it is.

use crate::atmosphere::density::DensityProfile;
use crate::atmosphere::spectral::Spectral;

/// Largest ground radius, m, for every model: the flat-planet tests of the reference and
/// of Riley's model run at 6.36e9 m.
pub const MAX_BOTTOM_RADIUS_M: f64 = 1e10;

/// Largest thickness of the atmosphere as a fraction of the ground radius, for every
/// model: a shell no thicker than the planet's radius (Venus's air is 4 % of it); far
/// beyond, a density profile's terms overflow over the thickness.
pub const MAX_THICKNESS_RATIO: f64 = 1.0;

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

/// Why `spectrum` (a valid recipe) passes `max`, in `unit`, somewhere in 360..830 nm.
pub fn spectrum_above(spectrum: &Spectral, max: f64, unit: &str) -> Option<String> {
    let (value, nm) = visible_maximum(spectrum);
    (value > max || value.is_nan()).then(|| {
        format!("reaches {value:e} {unit} at {nm} nm; at most {max:e} {unit} in 360..830 nm")
    })
}

/// Why `profile` (a valid profile) leaves f32 over an atmosphere `thickness_m` thick.
pub fn profile_past_f32(profile: &DensityProfile, thickness_m: f64) -> Option<String> {
    for (i, l) in profile.layers.iter().enumerate() {
        // Checked even where exp_term is 0: 0 times an overflowed exponential is NaN.
        if l.exp_scale_per_m * thickness_m > MAX_DENSITY_GROWTH {
            return Some(format!(
                "layer {i}: exp_scale_per_m {} times the thickness {thickness_m} m exceeds {MAX_DENSITY_GROWTH} (the density would grow past f32)",
                l.exp_scale_per_m
            ));
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
                return Some(format!(
                    "layer {i}: {name} {v:e} must lie within +-{MAX_DENSITY_TERM:e}"
                ));
            }
        }
    }
    None
}

/// The field and why, if a planet of this ground radius and atmosphere thickness (m) is
/// outside the range of the real-time models and the GPU.
pub fn real_time_problem(bottom_radius_m: f64, thickness_m: f64) -> Option<(&'static str, String)> {
    let [low, high] = REAL_TIME_BOTTOM_RADIUS_M;
    if !(low..=high).contains(&bottom_radius_m) {
        return Some((
            "bottom_radius_m",
            format!(
                "{bottom_radius_m:e} m is outside [{low:e}, {high:e}] m, the range of the real-time models and the GPU (only the reference computes beyond it)"
            ),
        ));
    }
    let least = REAL_TIME_MIN_THICKNESS_RATIO * bottom_radius_m;
    (thickness_m < least).then(|| {
        (
            "top_radius_m",
            format!(
                "the atmosphere is {thickness_m} m thick; the real-time models and the GPU need at least {REAL_TIME_MIN_THICKNESS_RATIO:e} of bottom_radius_m ({least} m)"
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::density::DensityLayer;

    #[test]
    fn a_spectrum_is_caught_where_it_peaks() {
        let sun = Spectral::SolarAstmG173 { scale: 1e300 };
        assert!(spectrum_above(&sun, MAX_IRRADIANCE_W_M2_NM, "W").is_some());
        let sun = Spectral::SolarAstmG173 { scale: 400.0 };
        assert!(spectrum_above(&sun, MAX_IRRADIANCE_W_M2_NM, "W").is_none());
        // A power law that explodes in the blue is caught at 360 nm.
        let blue = Spectral::PowerLaw {
            value_at_1um: 1.0,
            exponent: 100.0,
        };
        let message = spectrum_above(&blue, 1.0, "m^-1").unwrap();
        assert!(message.contains("at 360 nm"), "{message}");
        // A table's peak between whole nanometres is found.
        let peak = Spectral::Table {
            wavelengths_nm: vec![500.0, 500.5, 501.0],
            values: vec![0.0, 2.0, 0.0],
        };
        let message = spectrum_above(&peak, 1.0, "m^-1").unwrap();
        assert!(message.contains("at 500.5 nm"), "{message}");
    }

    #[test]
    fn profiles_past_f32_are_caught() {
        let earth = DensityProfile::exponential(8_000.0);
        assert!(profile_past_f32(&earth, 60e3).is_none());
        let growing = DensityProfile::exponential(-100.0);
        assert!(
            profile_past_f32(&growing, 60e3)
                .unwrap()
                .contains("exp_scale_per_m")
        );
        // The ozone tent's layers have exp_term 0; their exponential must not overflow.
        let mut tent = DensityProfile::tent(10e3, 25e3, 40e3);
        tent.layers[0].exp_scale_per_m = 1e12;
        assert!(profile_past_f32(&tent, 60e3).is_some());
        let huge = DensityProfile {
            layers: vec![DensityLayer {
                constant_term: -1e300,
                ..DensityLayer::default()
            }],
        };
        assert!(
            profile_past_f32(&huge, 60e3)
                .unwrap()
                .contains("constant_term")
        );
    }

    #[test]
    fn the_real_time_range_names_its_field() {
        assert!(real_time_problem(6.36e6, 60e3).is_none());
        let (field, message) = real_time_problem(1e9, 60e3).unwrap();
        assert_eq!(field, "bottom_radius_m");
        assert!(message.contains("[1e5, 1e8] m"), "{message}");
        assert_eq!(real_time_problem(6.36e6, 100.0).unwrap().0, "top_radius_m");
    }
}
