//! Altitude profiles of the number density of air molecules, aerosols and ozone,
//! relative to a reference density, as layers in the manner of Bruneton 2017's
//! `DensityProfileLayer`.

use serde::{Deserialize, Serialize};

/// One layer of a profile: `exp_term * exp(exp_scale_per_m * h) + linear_term_per_m * h
/// + constant_term`, clamped to [0, 1], with `h` the altitude above the ground in metres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DensityLayer {
    /// Thickness of the layer in metres; the last layer of a profile extends to infinity
    /// and its width is ignored.
    #[serde(default)]
    pub width_m: f64,
    #[serde(default)]
    pub exp_term: f64,
    #[serde(default)]
    pub exp_scale_per_m: f64,
    #[serde(default)]
    pub linear_term_per_m: f64,
    #[serde(default)]
    pub constant_term: f64,
}

impl DensityLayer {
    /// `exp(-h / scale_height_m)`: the barometric profile.
    pub fn exponential(scale_height_m: f64) -> Self {
        DensityLayer {
            width_m: 0.0,
            exp_term: 1.0,
            exp_scale_per_m: -1.0 / scale_height_m,
            linear_term_per_m: 0.0,
            constant_term: 0.0,
        }
    }

    fn density(&self, altitude_m: f64) -> f64 {
        let d = self.exp_term * (self.exp_scale_per_m * altitude_m).exp()
            + self.linear_term_per_m * altitude_m
            + self.constant_term;
        d.clamp(0.0, 1.0)
    }
}

/// A profile of one or more stacked layers, from the ground up.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DensityProfile {
    pub layers: Vec<DensityLayer>,
}

impl DensityProfile {
    /// One exponential layer.
    pub fn exponential(scale_height_m: f64) -> Self {
        DensityProfile {
            layers: vec![DensityLayer::exponential(scale_height_m)],
        }
    }

    /// The tent of the ozone layer: zero below `bottom_m`, rising linearly to 1 at
    /// `peak_m`, falling linearly to zero at `top_m` (Bruneton 2017's demo uses
    /// 10, 25, 40 km).
    pub fn tent(bottom_m: f64, peak_m: f64, top_m: f64) -> Self {
        let rise = 1.0 / (peak_m - bottom_m);
        let fall = 1.0 / (top_m - peak_m);
        DensityProfile {
            layers: vec![
                DensityLayer {
                    width_m: peak_m,
                    linear_term_per_m: rise,
                    constant_term: -bottom_m * rise,
                    ..DensityLayer::default()
                },
                DensityLayer {
                    linear_term_per_m: -fall,
                    constant_term: top_m * fall,
                    ..DensityLayer::default()
                },
            ],
        }
    }

    /// Relative density at `altitude_m` above the ground, in [0, 1].
    pub fn density(&self, altitude_m: f64) -> f64 {
        let mut bottom = 0.0;
        let last = self.layers.len().saturating_sub(1);
        for (i, layer) in self.layers.iter().enumerate() {
            if i == last || altitude_m < bottom + layer.width_m {
                return layer.density(altitude_m);
            }
            bottom += layer.width_m;
        }
        0.0
    }

    /// Altitudes (m) where the profile's formula changes, where quadrature must split.
    pub fn breakpoints_m(&self) -> Vec<f64> {
        let mut out = Vec::new();
        let mut bottom = 0.0;
        for layer in self.layers.iter().take(self.layers.len().saturating_sub(1)) {
            bottom += layer.width_m;
            out.push(bottom);
        }
        // Kinks where a linear layer reaches the clamp at 0 or 1 inside its span.
        let mut bottom = 0.0;
        for layer in &self.layers {
            if layer.exp_term == 0.0 && layer.linear_term_per_m != 0.0 {
                for level in [0.0, 1.0] {
                    let h = (level - layer.constant_term) / layer.linear_term_per_m;
                    if h > bottom && h.is_finite() {
                        out.push(h);
                    }
                }
            }
            bottom += layer.width_m;
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
        out
    }

    /// The smallest length over which the density may change by a factor e, used to
    /// size quadrature steps: the shortest scale height of an exponential layer, or the
    /// width of a linear rise.
    pub fn shortest_scale_m(&self) -> f64 {
        self.layers
            .iter()
            .map(|l| {
                let exp_scale = if l.exp_term != 0.0 && l.exp_scale_per_m != 0.0 {
                    1.0 / l.exp_scale_per_m.abs()
                } else {
                    f64::INFINITY
                };
                let lin_scale = if l.linear_term_per_m != 0.0 {
                    1.0 / l.linear_term_per_m.abs()
                } else {
                    f64::INFINITY
                };
                exp_scale.min(lin_scale)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Why this profile is not usable, if it is not.
    pub fn problem(&self) -> Option<String> {
        if self.layers.is_empty() {
            return Some("needs at least one layer".into());
        }
        for (i, l) in self.layers.iter().enumerate() {
            let values = [
                l.width_m,
                l.exp_term,
                l.exp_scale_per_m,
                l.linear_term_per_m,
                l.constant_term,
            ];
            if values.iter().any(|v| !v.is_finite()) {
                return Some(format!("layer {i} has a non-finite term"));
            }
            if l.width_m < 0.0 {
                return Some(format!("layer {i} width_m {} is negative", l.width_m));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_profile_falls_by_e_per_scale_height() {
        let p = DensityProfile::exponential(8000.0);
        assert_eq!(p.density(0.0), 1.0);
        assert!((p.density(8000.0) - (-1.0f64).exp()).abs() < 1e-15);
    }

    #[test]
    fn ozone_tent_rises_peaks_and_falls() {
        let p = DensityProfile::tent(10_000.0, 25_000.0, 40_000.0);
        assert_eq!(p.density(5_000.0), 0.0);
        assert!((p.density(17_500.0) - 0.5).abs() < 1e-12);
        assert!((p.density(25_000.0) - 1.0).abs() < 1e-12);
        assert!((p.density(32_500.0) - 0.5).abs() < 1e-12);
        assert_eq!(p.density(45_000.0), 0.0);
        assert_eq!(p.breakpoints_m(), vec![10_000.0, 25_000.0, 40_000.0]);
    }
}
