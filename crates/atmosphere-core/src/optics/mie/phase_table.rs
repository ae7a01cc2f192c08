//! Mie phase functions tabulated in scattering angle, with steps that resolve the
//! forward diffraction peak and the glory: a uniform step of at most 0.1 degree and
//! pi / (40 x) (a fortieth of the period of the interference structure of spheres of
//! size parameter x), refined towards 0 and 180 degrees down to a tenth of it, each step
//! 1.1 times the one before.

use num_complex::Complex64;

use super::error::MieError;
use super::polydisperse::{ParticleOptics, particle_optics};
use super::size_distribution::SizeDistribution;
use crate::optics::phase::PhaseFunction;

/// A phase function at increasing scattering angles from 0 to 180 degrees, sr^-1.
#[derive(Clone, Debug, PartialEq)]
pub struct PhaseTable {
    pub angles_deg: Vec<f64>,
    pub phase: Vec<f64>,
}

/// The angles of a table for spheres of size parameter up to `max_size_parameter`.
pub fn table_angles_deg(max_size_parameter: f64) -> Vec<f64> {
    let step = 0.1f64.min((180.0 / 40.0) / max_size_parameter.max(1e-3));
    // Steps from step / 10 growing by 1.1 until they reach `step`, from 0 outwards.
    let mut graded = vec![0.0];
    let mut h = step / 10.0;
    while h < step {
        graded.push(graded.last().unwrap() + h);
        h *= 1.1;
    }
    let edge = *graded.last().unwrap();
    let uniform = ((180.0 - 2.0 * edge) / step).ceil() as usize;
    let uniform_step = (180.0 - 2.0 * edge) / uniform as f64;
    let mut angles = graded.clone();
    angles.extend((1..uniform).map(|i| edge + uniform_step * i as f64));
    angles.extend(graded.iter().rev().map(|a| 180.0 - a));
    angles
}

impl PhaseTable {
    /// The table of spheres of relative refractive index `m` at `wavelength_m`, averaged
    /// over `distribution` within `tolerance`; with their optics.
    pub fn new(
        m: Complex64,
        wavelength_m: f64,
        distribution: &SizeDistribution,
        tolerance: f64,
    ) -> Result<(PhaseTable, ParticleOptics), MieError> {
        let largest_radius = distribution.log_radius_range()[1].exp();
        let x = 2.0 * std::f64::consts::PI * largest_radius / wavelength_m;
        let angles_deg = table_angles_deg(x);
        let cosines: Vec<f64> = angles_deg.iter().map(|a| a.to_radians().cos()).collect();
        let mut optics = particle_optics(m, wavelength_m, distribution, &cosines, tolerance)?;
        let phase = std::mem::take(&mut optics.phase);
        Ok((PhaseTable { angles_deg, phase }, optics))
    }

    /// The table as a phase function atmos renders with (interpolated in angle).
    pub fn to_phase_function(&self) -> PhaseFunction {
        PhaseFunction::Tabulated {
            angles_deg: self.angles_deg.clone(),
            values: self.phase.clone(),
        }
    }

    /// The integral over the sphere, 2 pi int p sin(theta) d theta, by the trapezoid rule
    /// on the table's angles.
    pub fn integral(&self) -> f64 {
        let f: Vec<(f64, f64)> = self
            .angles_deg
            .iter()
            .zip(&self.phase)
            .map(|(a, p)| (a.to_radians(), p * a.to_radians().sin()))
            .collect();
        2.0 * std::f64::consts::PI
            * f.windows(2)
                .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
                .sum::<f64>()
    }
}
