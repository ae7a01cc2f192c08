//! Cross-sections, asymmetry and phase function of spheres averaged over a size
//! distribution: a trapezoid rule in ln r over the range the distribution needs, its
//! intervals halved (reusing every radius already computed) until no average changes by
//! more than a tolerance. The radii are computed in parallel.

use std::f64::consts::PI;

use num_complex::Complex64;
use rayon::prelude::*;

use super::amplitudes::unpolarised_intensity;
use super::coefficients::{MieCoefficients, check_inputs};
use super::efficiencies::Efficiencies;
use super::error::MieError;
use super::limits::MIN_SIZE_PARAMETER;
use super::size_distribution::SizeDistribution;

/// Intervals of the first trapezoid rule, and the fewest at which it may stop.
const FIRST_INTERVALS: usize = 16;
const MIN_INTERVALS: usize = 64;
/// How much more the phase function may change than the cross-sections: near 180
/// degrees it is dominated by the sharp resonances of weakly absorbing spheres, which
/// any rule samples only by chance, and settles slowly (docs/particles.md).
pub const PHASE_TOLERANCE_FACTOR: f64 = 10.0;
/// The widest step in size parameter at which the rule may stop.
const MAX_SIZE_PARAMETER_STEP: f64 = 0.5;
/// The most intervals before the average is declared unsettled.
pub const MAX_INTERVALS: usize = 1 << 17;

/// What spheres of one material scatter at one wavelength, per particle on average.
#[derive(Clone, Debug, PartialEq)]
pub struct ParticleOptics {
    pub extinction_cross_section_m2: f64,
    pub scattering_cross_section_m2: f64,
    /// pi <r^2>: the efficiencies are the cross-sections over it.
    pub geometric_cross_section_m2: f64,
    /// g, the mean cosine of the scattering angle.
    pub asymmetry: f64,
    /// The phase function at the cosines asked for, sr^-1, unit integral over the sphere.
    pub phase: Vec<f64>,
    /// How many radii the average took (1 for one radius).
    pub radii: usize,
}

impl ParticleOptics {
    pub fn extinction_efficiency(&self) -> f64 {
        self.extinction_cross_section_m2 / self.geometric_cross_section_m2
    }

    pub fn scattering_efficiency(&self) -> f64 {
        self.scattering_cross_section_m2 / self.geometric_cross_section_m2
    }
}

/// One radius's contribution: the number weight, then weight times pi r^2, C_ext, C_sca,
/// g C_sca and dC_sca/dOmega at each cosine.
pub(super) fn sample(
    m: Complex64,
    wavenumber: f64,
    radius_m: f64,
    weight: f64,
    cosines: &[f64],
) -> Result<Vec<f64>, MieError> {
    let coefficients = MieCoefficients::new(m, wavenumber * radius_m)?;
    let q = Efficiencies::of(&coefficients);
    let area = PI * radius_m * radius_m;
    let mut values = Vec::with_capacity(5 + cosines.len());
    values.extend([
        weight,
        weight * area,
        weight * q.extinction * area,
        weight * q.scattering * area,
        weight * q.asymmetry * q.scattering * area,
    ]);
    let k2 = wavenumber * wavenumber;
    values.extend(
        cosines
            .iter()
            .map(|&mu| weight * unpolarised_intensity(&coefficients, mu) / k2),
    );
    Ok(values)
}

/// The averages from the weighted sums of [`sample`].
pub(super) fn averages(sums: &[f64], radii: usize) -> ParticleOptics {
    let scattering = sums[3] / sums[0];
    ParticleOptics {
        geometric_cross_section_m2: sums[1] / sums[0],
        extinction_cross_section_m2: sums[2] / sums[0],
        scattering_cross_section_m2: scattering,
        asymmetry: sums[4] / sums[3],
        phase: sums[5..].iter().map(|s| s / sums[3]).collect(),
        radii,
    }
}

/// The largest relative change of any average between two rules: the cross-sections' and g's relative to their value, the phase function's
/// relative to the larger of its value and the isotropic 1 / (4 pi), over
/// [`PHASE_TOLERANCE_FACTOR`].
pub(super) fn relative_change(old: &ParticleOptics, new: &ParticleOptics) -> f64 {
    let isotropic = 1.0 / (4.0 * PI);
    let phase = old
        .phase
        .iter()
        .zip(&new.phase)
        .map(|(&a, &b)| (a - b).abs() / b.max(isotropic) / PHASE_TOLERANCE_FACTOR);
    let pairs = [
        (
            old.extinction_cross_section_m2,
            new.extinction_cross_section_m2,
        ),
        (
            old.scattering_cross_section_m2,
            new.scattering_cross_section_m2,
        ),
        (old.asymmetry, new.asymmetry),
    ];
    pairs
        .into_iter()
        .map(|(a, b)| ((a - b) / b).abs())
        .chain(phase)
        .fold(0.0, f64::max)
}

/// The sums of [`sample`] over these ln r, in parallel.
fn sum_samples(
    m: Complex64,
    wavenumber: f64,
    distribution: &SizeDistribution,
    log_radii: &[f64],
    cosines: &[f64],
) -> Result<Vec<f64>, MieError> {
    log_radii
        .par_iter()
        .map(|&u| {
            let weight = distribution.log_density(u).exp();
            sample(m, wavenumber, u.exp(), weight, cosines)
        })
        .try_reduce(
            || vec![0.0; 5 + cosines.len()],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(a, b)| *a += b);
                Ok(a)
            },
        )
}

/// The optics of spheres of relative refractive index `m` at `wavelength_m` (in the
/// medium), averaged over `distribution` until, when the radii double, the cross-sections
/// and g change by at most `tolerance` (relative) and the phase function by at most
/// [`PHASE_TOLERANCE_FACTOR`] times it (relative to the larger of its value and
/// 1 / (4 pi)), with steps in x of at most 0.5; the phase function at `cosines`.
pub fn particle_optics(
    m: Complex64,
    wavelength_m: f64,
    distribution: &SizeDistribution,
    cosines: &[f64],
    tolerance: f64,
) -> Result<ParticleOptics, MieError> {
    if !(wavelength_m.is_finite() && wavelength_m > 0.0) {
        return Err(MieError::Wavelength(wavelength_m * 1e9));
    }
    let wavenumber = 2.0 * PI / wavelength_m;
    let [lo, hi] = distribution.log_radius_range();
    // Radii below the smallest size parameter scatter as x^4, nothing at this weight; the
    // largest radius bounds every x, checked before any work.
    check_inputs(m, wavenumber * hi.exp())?;
    let lo = lo.max((MIN_SIZE_PARAMETER / wavenumber).ln()).min(hi);
    if lo == hi {
        let sums = sample(m, wavenumber, lo.exp(), 1.0, cosines)?;
        return Ok(averages(&sums, 1));
    }
    let mut intervals = FIRST_INTERVALS;
    let mut h = (hi - lo) / intervals as f64;
    let nodes: Vec<f64> = (0..=intervals).map(|i| lo + h * i as f64).collect();
    // The ends weigh e^-25 of the peak: a plain sum is the trapezoid rule up to h.
    let mut sums = sum_samples(m, wavenumber, distribution, &nodes, cosines)?;
    let mut previous = averages(&sums, intervals + 1);
    loop {
        let midpoints: Vec<f64> = (0..intervals).map(|i| lo + h * (i as f64 + 0.5)).collect();
        let added = sum_samples(m, wavenumber, distribution, &midpoints, cosines)?;
        sums.iter_mut().zip(&added).for_each(|(s, a)| *s += a);
        intervals *= 2;
        h *= 0.5;
        let current = averages(&sums, intervals + 1);
        let change = relative_change(&previous, &current);
        let x_step = wavenumber * (hi.exp() - lo.exp()) / intervals as f64;
        if change <= tolerance && intervals >= MIN_INTERVALS && x_step <= MAX_SIZE_PARAMETER_STEP {
            return Ok(current);
        }
        if intervals >= MAX_INTERVALS {
            return Err(MieError::NotConverged {
                change,
                nodes: intervals + 1,
                tolerance,
            });
        }
        previous = current;
    }
}
