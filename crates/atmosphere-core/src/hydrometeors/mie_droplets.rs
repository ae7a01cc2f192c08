//! The phase function of lognormally distributed water droplets by Lorenz-Mie theory, in
//! bins of angle: what shows the interference geometric optics leaves out, the
//! supernumerary bows of small rain drops (Airy 1838; van de Hulst 1957, section 13.23)
//! and the glory and cloudbow of cloud droplets (van de Hulst 1957, section 17.4; Riley
//! et al. 2004, section 3.1, Fig. 4 and 5).
//!
//! The drops are a lognormal distribution of an effective radius and sigma
//! (`optics/mie/size_distribution.rs`), sampled by `radii` midpoints in ln r over
//! [`SIGMAS_SPANNED`] standard deviations either side of the peak of n(r) r^2 (what
//! scattering weighs). The mean phase function is
//!     p(theta) = sum_i n_i I_i(theta) / (pi sum_i n_i x_i^2 Q_sca,i),
//! with I = (|S1|^2 + |S2|^2) / 2 (Bohren and Huffman 1983, Eq. 4.74), the mean of each
//! bin over its solid angle by the midpoint rule at sub-angles: a drop of size parameter
//! x ripples in angle with a period of about pi / x rad (the rays reflected outside and
//! refracted through it interfere), so a bin from 90 degrees on holds
//! `SAMPLES_PER_RIPPLE` angles per period (at most `MAX_SUBSAMPLES`; forward of
//! 90 degrees one, at its centre), and the forward peak (width about 1 / x) its own
//! `FORWARD_SUBSAMPLES` in the first degree. What is left of the ripple the sun's disc
//! averages away (`sun_disk_blur.rs`).

use std::f64::consts::PI;

use num_complex::Complex64;

use super::error::{HydrometeorError, check_range};
use crate::optics::mie::amplitudes::unpolarised_intensity;
use crate::optics::mie::coefficients::MieCoefficients;
use crate::optics::mie::efficiencies::Efficiencies;
use crate::optics::mie::size_distribution::SizeDistribution;

/// Effective radii accepted, m: cloud droplets to small rain drops (a 0.6 mm drop at
/// 380 nm has x = 1e4).
pub const DROPLET_RADIUS_RANGE_M: [f64; 2] = [1e-6, 6e-4];
/// Lognormal sigmas accepted (narrow: the rings and supernumeraries wash out in wider
/// distributions).
pub const DROPLET_SIGMA_RANGE: [f64; 2] = [0.01, 0.5];
/// Radii of the size average accepted.
pub const DROPLET_RADII_RANGE: [f64; 2] = [4.0, 512.0];
/// Standard deviations of ln r sampled either side of the peak.
pub const SIGMAS_SPANNED: f64 = 3.5;
/// Angles per period of the drops' ripple in angle.
const SAMPLES_PER_RIPPLE: f64 = 4.0;
/// At most this many angles per bin away from the forward peak.
const MAX_SUBSAMPLES: usize = 8;
/// The ripple is sampled from this angle on (the bows, the glory); forward of it, where
/// these scenes do not look, each bin is read at its centre.
const RIPPLE_SAMPLED_FROM_DEG: f64 = 90.0;
/// Angles per bin in the first degree.
const FORWARD_SUBSAMPLES: usize = 32;

/// Lognormal water droplets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Droplets {
    pub effective_radius_m: f64,
    pub sigma: f64,
    /// Radii of the size average.
    pub radii: usize,
}

impl Droplets {
    /// The settings checked, by name and range.
    pub fn check(&self) -> Result<(), HydrometeorError> {
        check_range(
            "droplet effective radius (m)",
            self.effective_radius_m,
            DROPLET_RADIUS_RANGE_M,
            "[1e-6, 6e-4] m",
        )?;
        check_range(
            "droplet lognormal sigma",
            self.sigma,
            DROPLET_SIGMA_RANGE,
            "[0.01, 0.5]",
        )?;
        check_range(
            "droplet radii of the size average",
            self.radii as f64,
            DROPLET_RADII_RANGE,
            "[4, 512]",
        )?;
        Ok(())
    }

    /// The radii (m) and their number weights (per unit ln r, times the step).
    pub fn nodes(&self) -> Result<Vec<(f64, f64)>, HydrometeorError> {
        self.check()?;
        let distribution = SizeDistribution::lognormal(self.effective_radius_m, self.sigma)?;
        // ln of the median radius, r_eff e^(-5 sigma^2 / 2), plus 2 sigma^2.
        let peak = self.effective_radius_m.ln() - 0.5 * self.sigma * self.sigma;
        let half = SIGMAS_SPANNED * self.sigma;
        let du = 2.0 * half / self.radii as f64;
        Ok((0..self.radii)
            .map(|i| {
                let u = peak - half + du * (i as f64 + 0.5);
                (u.exp(), distribution.log_density(u).exp() * du)
            })
            .collect())
    }

    /// The phase function in bins of `bin_deg` from 0 to 180 degrees (each bin's mean
    /// over its solid angle), sr^-1, for refractive index `m` at `wavelength_m`.
    pub fn phase_bins(
        &self,
        m: Complex64,
        wavelength_m: f64,
        bin_deg: f64,
    ) -> Result<Vec<f64>, HydrometeorError> {
        let nodes = self.nodes()?;
        let k = 2.0 * PI / wavelength_m;
        let x_max = k * nodes.last().map_or(0.0, |n| n.0);
        let ripple_rad = PI / x_max;
        let bins = (180.0 / bin_deg).round() as usize;
        let bin_rad = bin_deg.to_radians();
        let subsamples =
            ((SAMPLES_PER_RIPPLE * bin_rad / ripple_rad).ceil() as usize).clamp(1, MAX_SUBSAMPLES);
        // Each bin's sub-angles' cosines and weights (sin theta d theta over the bin's
        // solid angle / 2 pi).
        let angles: Vec<Vec<(f64, f64)>> = (0..bins)
            .map(|b| {
                let lo = b as f64 * bin_rad;
                let end_deg = (b as f64 + 1.0) * bin_deg;
                let count = if end_deg <= 1.0 {
                    FORWARD_SUBSAMPLES
                } else if end_deg <= RIPPLE_SAMPLED_FROM_DEG {
                    1
                } else {
                    subsamples
                };
                let h = bin_rad / count as f64;
                let solid = lo.cos() - (lo + bin_rad).cos();
                (0..count)
                    .map(|j| {
                        let t = lo + h * (j as f64 + 0.5);
                        (t.cos(), t.sin() * h / solid)
                    })
                    .collect()
            })
            .collect();
        let mut sum = vec![0.0; bins];
        let mut scattering = 0.0;
        for &(r, weight) in &nodes {
            let c = MieCoefficients::new(m, k * r)?;
            let x = c.size_parameter;
            scattering += weight * x * x * Efficiencies::of(&c).scattering;
            for (s, bin) in sum.iter_mut().zip(&angles) {
                *s += weight
                    * bin
                        .iter()
                        .map(|&(mu, w)| w * unpolarised_intensity(&c, mu))
                        .sum::<f64>();
            }
        }
        Ok(sum.iter().map(|s| s / (PI * scattering)).collect())
    }
}
