//! The optics of rain: Lorenz-Mie spheres averaged over the Marshall-Palmer (1948)
//! distribution by a trapezoid rule in drop diameter over the radii it covers, the
//! intervals halved (every radius already computed reused) until, from one halving to the
//! next, the cross-sections, g and the phase function at the angles asked for change by
//! at most a tolerance (the phase function relative to the larger of it and 1 / (4 pi),
//! with [`PHASE_TOLERANCE_FACTOR`](super::polydisperse::PHASE_TOLERANCE_FACTOR) times the tolerance).
//!
//! Drops of 0.1 to 3 mm have size parameters of 1e3 to 5e4 in visible light: a step in x
//! of half a unit, as the cloud averages take, would need 1e5 radii. At one scattering
//! angle the interference of a drop's rays makes the intensity oscillate in x with a
//! period of order one; a rule whose nodes are far apart samples that oscillation at
//! aliased frequencies, and the sum over the smooth weight cancels it to O(1 / intervals),
//! so the averages settle with thousands of radii, not 1e5 (docs/particles.md).

use std::f64::consts::PI;

use num_complex::Complex64;
use rayon::prelude::*;

use super::coefficients::check_inputs;
use super::error::MieError;
use super::marshall_palmer::{MarshallPalmer, RADIUS_RANGE_M};
use super::polydisperse::{ParticleOptics, averages, relative_change, sample};

/// Intervals of the first rule (plus one), and the fewest at which the rules may stop.
const FIRST_INTERVALS: usize = 16;
const MIN_INTERVALS: usize = 64;
/// The most intervals before the average is declared unsettled.
pub const MAX_RAIN_INTERVALS: usize = (1 << 13) + 1;

/// The sums of [`sample`] at these radii, each weighted by n(D), halved for the first
/// and the last (the trapezoid rule; its step cancels in the averages), in parallel.
fn sum_radii(
    m: Complex64,
    wavenumber: f64,
    rain: &MarshallPalmer,
    radii_m: &[f64],
    cosines: &[f64],
) -> Result<Vec<f64>, MieError> {
    let last = radii_m.len() - 1;
    radii_m
        .par_iter()
        .enumerate()
        .map(|(i, &r)| {
            let half = i == 0 || i == last;
            let weight = rain.density_per_m3_mm(r) * if half { 0.5 } else { 1.0 };
            sample(m, wavenumber, r, weight, cosines)
        })
        .try_reduce(
            || vec![0.0; 5 + cosines.len()],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(a, b)| *a += b);
                Ok(a)
            },
        )
}

/// The optics of rain of relative refractive index `m` at `wavelength_m` (in air) by the
/// trapezoid rule with `intervals` intervals in diameter; the phase function at `cosines`.
pub fn rain_optics(
    m: Complex64,
    wavelength_m: f64,
    rain: &MarshallPalmer,
    cosines: &[f64],
    intervals: usize,
) -> Result<ParticleOptics, MieError> {
    let wavenumber = checked_wavenumber(m, wavelength_m)?;
    let intervals = intervals.max(1);
    let [lo, hi] = RADIUS_RANGE_M;
    let h = (hi - lo) / intervals as f64;
    let radii: Vec<f64> = (0..=intervals).map(|i| lo + h * i as f64).collect();
    let sums = sum_radii(m, wavenumber, rain, &radii, cosines)?;
    Ok(averages(&sums, intervals + 1))
}

/// The optics of rain as [`rain_optics`], with 2^k + 1 intervals for k = 4, 5, ... until
/// no average changes by more than `tolerance` (the phase function by
/// [`PHASE_TOLERANCE_FACTOR`](super::polydisperse::PHASE_TOLERANCE_FACTOR) times it) from
/// one rule to the next. The rules share no inner node: nested rules (halved intervals)
/// alias the drops' interference alike and can agree while both are wrong.
pub fn rain_optics_converged(
    m: Complex64,
    wavelength_m: f64,
    rain: &MarshallPalmer,
    cosines: &[f64],
    tolerance: f64,
) -> Result<ParticleOptics, MieError> {
    checked_wavenumber(m, wavelength_m)?;
    let mut intervals = FIRST_INTERVALS + 1;
    let mut previous = rain_optics(m, wavelength_m, rain, cosines, intervals)?;
    loop {
        intervals = 2 * intervals - 1;
        let current = rain_optics(m, wavelength_m, rain, cosines, intervals)?;
        let change = relative_change(&previous, &current);
        if change <= tolerance && intervals >= MIN_INTERVALS {
            return Ok(current);
        }
        if intervals >= MAX_RAIN_INTERVALS {
            return Err(MieError::NotConverged {
                change,
                nodes: intervals + 1,
                tolerance,
            });
        }
        previous = current;
    }
}

/// 2 pi / lambda, once the wavelength and the largest drop's size parameter are checked.
fn checked_wavenumber(m: Complex64, wavelength_m: f64) -> Result<f64, MieError> {
    if !(wavelength_m.is_finite() && wavelength_m > 0.0) {
        return Err(MieError::Wavelength(wavelength_m * 1e9));
    }
    let wavenumber = 2.0 * PI / wavelength_m;
    check_inputs(m, wavenumber * RADIUS_RANGE_M[1])?;
    Ok(wavenumber)
}
