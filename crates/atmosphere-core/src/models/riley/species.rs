//! One species as the riley model sees it: a single exponential exp(-h / H) with its
//! extinction at the ground, fitted once from the atmosphere's density profile.

use crate::atmosphere::density::DensityProfile;
use crate::models::riley::flat::FlatExponential;

/// The single exponential `rho0 exp(-h / H)` standing for a density profile: returns
/// `(rho0, H)`. A profile of one purely exponential layer gives its own terms; any other
/// is fitted over the atmosphere's thickness by matching its column and its mean height
/// (the first two moments), so the vertical optical depth is kept.
pub fn effective_exponential(profile: &DensityProfile, thickness_m: f64) -> (f64, f64) {
    if let [layer] = profile.layers.as_slice()
        && layer.exp_term > 0.0
        && layer.exp_term <= 1.0
        && layer.exp_scale_per_m < 0.0
        && layer.linear_term_per_m == 0.0
        && layer.constant_term == 0.0
    {
        return (layer.exp_term, -1.0 / layer.exp_scale_per_m);
    }
    let (mut column, mut moment) = (0.0, 0.0);
    let dh = thickness_m / FIT_STEPS as f64;
    for i in 0..FIT_STEPS {
        let h = (i as f64 + 0.5) * dh;
        let rho = profile.density(h);
        column += rho * dh;
        moment += rho * h * dh;
    }
    if column <= 0.0 {
        return (0.0, thickness_m);
    }
    let scale_height = moment / column;
    (column / scale_height, scale_height)
}

/// Midpoint steps of the fit of a non-exponential profile (done once when preparing).
const FIT_STEPS: usize = 100_000;

/// One species as Riley's model sees it: a single exponential over a flat ground.
#[derive(Clone, Debug, PartialEq)]
pub struct Species {
    pub scale_height_m: f64,
    /// Extinction at the ground (density rho0 included), per wavelength, m^-1.
    pub extinction: Vec<f64>,
    /// Scattering / extinction per wavelength.
    pub albedo: Vec<f64>,
}

impl Species {
    pub fn new(
        profile: &DensityProfile,
        thickness_m: f64,
        scattering: &[f64],
        extinction: &[f64],
    ) -> Species {
        let (rho0, scale_height_m) = effective_exponential(profile, thickness_m);
        Species {
            scale_height_m,
            extinction: extinction.iter().map(|e| e * rho0).collect(),
            albedo: scattering
                .iter()
                .zip(extinction)
                .map(|(s, e)| if *e > 0.0 { (s / e).min(1.0) } else { 0.0 })
                .collect(),
        }
    }

    pub fn flat(&self, w: usize, irradiance: f64) -> FlatExponential {
        FlatExponential {
            beta_sea_level_per_m: self.extinction[w],
            scale_height_m: self.scale_height_m,
            irradiance,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_profiles_are_kept_and_others_fitted_by_moments() {
        assert_eq!(
            effective_exponential(&DensityProfile::exponential(1200.0), 60_000.0),
            (1.0, 1200.0)
        );
        // A tent's mean height is its centre; its column is half its base times 1.
        let (rho0, h) = effective_exponential(
            &DensityProfile::tent(10_000.0, 25_000.0, 40_000.0),
            60_000.0,
        );
        assert!((h - 25_000.0).abs() < 1e-3, "{h}");
        assert!((rho0 * h - 15_000.0).abs() < 1e-2, "{rho0}");
    }
}
