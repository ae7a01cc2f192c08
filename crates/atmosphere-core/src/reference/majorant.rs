//! Upper bounds of the extinction above a given altitude, for delta tracking: a path
//! segment that stays above altitude h never meets denser air than the bound at h.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::density::DensityProfile;

/// Bins of altitude over the atmosphere's thickness.
const BINS: usize = 512;

/// For each altitude bin, the largest relative density of each species at or above it.
#[derive(Clone, Debug)]
pub struct DensityBounds {
    bin_height_m: f64,
    /// `bounds[i][k]`: largest density of species k above the bottom of bin i.
    bounds: Vec<[f64; 3]>,
}

impl DensityBounds {
    pub fn new(atmosphere: &Atmosphere) -> DensityBounds {
        let bin_height_m = atmosphere.thickness_m() / BINS as f64;
        let profiles = [
            &atmosphere.rayleigh.density,
            &atmosphere.mie.density,
            &atmosphere.ozone.density,
        ];
        // Profiles are monotone between breakpoints, so the maximum over a bin is at its
        // ends or at a breakpoint inside it.
        let mut per_bin = vec![[0.0f64; 3]; BINS];
        for (k, profile) in profiles.iter().enumerate() {
            let breaks = profile.breakpoints_m();
            for (i, bin) in per_bin.iter_mut().enumerate() {
                let (lo, hi) = (bin_height_m * i as f64, bin_height_m * (i + 1) as f64);
                let mut m = profile.density(lo).max(profile.density(hi));
                for b in breaks.iter().filter(|b| **b >= lo && **b <= hi) {
                    m = m.max(density_near(profile, *b));
                }
                bin[k] = m;
            }
        }
        // Suffix maxima: the largest at or above each bin.
        let mut bounds = per_bin.clone();
        for i in (0..BINS - 1).rev() {
            for k in 0..3 {
                bounds[i][k] = bounds[i][k].max(bounds[i + 1][k]);
            }
        }
        DensityBounds {
            bin_height_m,
            bounds,
        }
    }

    /// Upper bound of each species' density at or above `altitude_m`.
    pub fn above(&self, altitude_m: f64) -> [f64; 3] {
        let i = ((altitude_m / self.bin_height_m).floor().max(0.0) as usize).min(BINS - 1);
        self.bounds[i]
    }
}

/// The largest density just around a breakpoint, where a layer changes formula.
fn density_near(profile: &DensityProfile, altitude_m: f64) -> f64 {
    let eps = 1e-6 * altitude_m.abs().max(1.0);
    profile
        .density(altitude_m)
        .max(profile.density(altitude_m - eps))
        .max(profile.density(altitude_m + eps))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_are_never_below_the_density_above() {
        for name in ["earth", "hazy", "mars"] {
            let a = Atmosphere::preset(name).unwrap();
            let bounds = DensityBounds::new(&a);
            let profiles = [&a.rayleigh.density, &a.mie.density, &a.ozone.density];
            for i in 0..2000 {
                let h = a.thickness_m() * i as f64 / 2000.0;
                let b = bounds.above(h);
                for j in i..2000 {
                    let h2 = a.thickness_m() * j as f64 / 2000.0;
                    for k in 0..3 {
                        assert!(
                            profiles[k].density(h2) <= b[k] + 1e-15,
                            "{name} {k} {h} {h2}"
                        );
                    }
                }
            }
        }
    }
}
