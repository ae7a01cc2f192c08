//! The rays a model is judged on: those whose reference luminance is known to within
//! `MAX_RELATIVE_STD_ERROR`. Where the reference's Monte Carlo has not converged (the
//! ground in nautical twilight, lit only by light scattered several times from air
//! hundreds of kilometres away), a relative error against it would measure the
//! reference's noise, not the model; such rays are counted out and the report says how
//! many rays of each view it judged.

use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::RayRadiance;

/// Largest relative standard error of the reference's luminance on a judged ray.
pub const MAX_RELATIVE_STD_ERROR: f64 = 0.05;

/// Whether the report judges models on this ray of the reference. The luminance's
/// standard error is taken as the luminance of the per-wavelength standard errors, an
/// upper bound whatever their correlation.
pub fn is_judged(reference: &RayRadiance, color: &SpectrumToColor) -> bool {
    let luminance = color.luminance_cd_m2(&reference.radiance);
    let std_error = color.luminance_cd_m2(&reference.radiance_std_error);
    luminance.is_finite() && luminance > 0.0 && std_error <= MAX_RELATIVE_STD_ERROR * luminance
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(radiance: f64, std_error: f64) -> RayRadiance {
        RayRadiance {
            radiance: vec![radiance; 3],
            transmittance: vec![1.0; 3],
            radiance_std_error: vec![std_error; 3],
        }
    }

    #[test]
    fn rays_are_judged_only_where_the_reference_is_known_to_five_percent() {
        let color = SpectrumToColor::new(&[680.0, 550.0, 440.0]).unwrap();
        assert!(is_judged(&ray(1e-2, 4.9e-4), &color));
        assert!(!is_judged(&ray(1e-2, 5.1e-4), &color));
        assert!(!is_judged(&ray(0.0, 0.0), &color));
        assert!(!is_judged(&ray(f64::NAN, 0.0), &color));
    }
}
