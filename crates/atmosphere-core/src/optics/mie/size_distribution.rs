//! Size distributions of spheres, written as number densities per unit ln r, and the
//! range of ln r an average over them needs.
//!
//! - lognormal: n(r) dr proportional to exp(-(ln r - ln r_m)^2 / (2 sigma^2)) d ln r, with
//!   median radius r_m and sigma the standard deviation of ln r; its effective radius
//!   <r^3> / <r^2> is r_m exp(5 sigma^2 / 2) (Hansen and Travis 1974, Eq. 2.53 to 2.56);
//! - modified gamma (Deirmendjian 1969): n(r) proportional to r^alpha exp(-(alpha / gamma)
//!   (r / r_c)^gamma), mode radius r_c.

use super::error::MieError;

/// The range of sigma (standard deviation of ln r) of a lognormal distribution.
pub const SIGMA_RANGE: [f64; 2] = [0.01, 1.0];
/// The range of alpha of a modified gamma distribution.
pub const ALPHA_RANGE: [f64; 2] = [0.5, 100.0];
/// The range of gamma of a modified gamma distribution.
pub const GAMMA_RANGE: [f64; 2] = [0.1, 10.0];

/// How far below its peak the cross-section weight n(r) r^2 may fall at the ends of the
/// range averaged over: e^-25, about 1e-11.
const LOG_WEIGHT_DROP: f64 = 25.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SizeDistribution {
    /// Spheres of one radius.
    Monodisperse {
        radius_m: f64,
    },
    Lognormal {
        median_radius_m: f64,
        sigma: f64,
    },
    ModifiedGamma {
        mode_radius_m: f64,
        alpha: f64,
        gamma: f64,
    },
}

fn check(
    what: &'static str,
    value: f64,
    range: [f64; 2],
    text: &'static str,
) -> Result<(), MieError> {
    if (range[0]..=range[1]).contains(&value) {
        Ok(())
    } else {
        Err(MieError::Distribution {
            what,
            value,
            range: text,
        })
    }
}

fn check_radius(radius_m: f64) -> Result<(), MieError> {
    if radius_m.is_finite() && radius_m > 0.0 {
        Ok(())
    } else {
        Err(MieError::Distribution {
            what: "radius (m)",
            value: radius_m,
            range: "(0, infinity)",
        })
    }
}

impl SizeDistribution {
    /// A lognormal distribution of this effective radius.
    pub fn lognormal(effective_radius_m: f64, sigma: f64) -> Result<SizeDistribution, MieError> {
        check_radius(effective_radius_m)?;
        check("lognormal sigma", sigma, SIGMA_RANGE, "[0.01, 1]")?;
        Ok(SizeDistribution::Lognormal {
            median_radius_m: effective_radius_m * (-2.5 * sigma * sigma).exp(),
            sigma,
        })
    }

    /// A modified gamma distribution of this effective radius.
    pub fn modified_gamma(
        effective_radius_m: f64,
        alpha: f64,
        gamma: f64,
    ) -> Result<SizeDistribution, MieError> {
        check_radius(effective_radius_m)?;
        check("modified gamma alpha", alpha, ALPHA_RANGE, "[0.5, 100]")?;
        check("modified gamma gamma", gamma, GAMMA_RANGE, "[0.1, 10]")?;
        let unit = SizeDistribution::ModifiedGamma {
            mode_radius_m: 1.0,
            alpha,
            gamma,
        };
        Ok(SizeDistribution::ModifiedGamma {
            mode_radius_m: effective_radius_m / unit.effective_radius_m(),
            alpha,
            gamma,
        })
    }

    /// The natural log of the number density per unit ln r at u = ln r, up to a constant.
    pub fn log_density(&self, u: f64) -> f64 {
        match *self {
            SizeDistribution::Monodisperse { radius_m } => {
                if u == radius_m.ln() {
                    0.0
                } else {
                    f64::NEG_INFINITY
                }
            }
            SizeDistribution::Lognormal {
                median_radius_m,
                sigma,
            } => -(u - median_radius_m.ln()).powi(2) / (2.0 * sigma * sigma),
            SizeDistribution::ModifiedGamma {
                mode_radius_m,
                alpha,
                gamma,
            } => {
                let ln_ratio = u - mode_radius_m.ln();
                (alpha + 1.0) * ln_ratio - alpha / gamma * (gamma * ln_ratio).exp()
            }
        }
    }

    /// The range of ln r outside which n(r) r^2 (what scattering weighs) is below e^-25 of
    /// its peak; a single point for one radius.
    pub fn log_radius_range(&self) -> [f64; 2] {
        let (peak, scale) = match *self {
            SizeDistribution::Monodisperse { radius_m } => return [radius_m.ln(); 2],
            SizeDistribution::Lognormal {
                median_radius_m,
                sigma,
            } => (median_radius_m.ln() + 2.0 * sigma * sigma, sigma),
            SizeDistribution::ModifiedGamma {
                mode_radius_m,
                alpha,
                gamma,
            } => (
                mode_radius_m.ln() + ((alpha + 3.0) / alpha).ln() / gamma,
                1.0 / (gamma * (alpha + 3.0)).sqrt(),
            ),
        };
        let weight = |u: f64| self.log_density(u) + 2.0 * u;
        let top = weight(peak);
        let step = 0.05 * scale;
        let mut range = [peak, peak];
        for (end, direction) in range.iter_mut().zip([-1.0, 1.0]) {
            while top - weight(*end) < LOG_WEIGHT_DROP {
                *end += direction * step;
            }
        }
        range
    }

    /// <r^3> / <r^2>, m: closed form for lognormal, a fine quadrature otherwise.
    pub fn effective_radius_m(&self) -> f64 {
        match *self {
            SizeDistribution::Monodisperse { radius_m } => radius_m,
            SizeDistribution::Lognormal {
                median_radius_m,
                sigma,
            } => median_radius_m * (2.5 * sigma * sigma).exp(),
            SizeDistribution::ModifiedGamma { .. } => {
                let moment = |k: f64| self.log_moment(k);
                moment(3.0) / moment(2.0)
            }
        }
    }

    /// The integral of n(r) r^k d ln r up to a constant, by a trapezoid rule with 4000
    /// intervals (spectrally accurate for this smooth, vanishing integrand).
    fn log_moment(&self, k: f64) -> f64 {
        let [lo, hi] = self.log_radius_range();
        let (lo, hi) = (lo - 2.0, hi + 2.0);
        let intervals = 4000;
        let h = (hi - lo) / intervals as f64;
        (0..=intervals)
            .map(|i| {
                let u = lo + h * i as f64;
                (self.log_density(u) + k * u).exp()
            })
            .sum::<f64>()
            * h
    }
}
