//! The phase function of horizontally oriented plates over the sky's two angles, for one
//! elevation of the sun. Randomly oriented crystals scatter alike at every azimuth
//! around the sun, falling plates do not: their sundogs (parhelia) lie beside the sun at
//! its elevation, their parhelic circle runs through the sun parallel to the horizon
//! (Greenler 1980, chapter 2; Tape 1994, chapter 4). The table is over the direction the
//! scattered light comes from as an observer sees it: its elevation above the horizon,
//! -90 to 90 degrees, and its azimuth from the sun's, 0 to 180 degrees (the plates
//! scatter alike to either side of the sun's vertical, so a bin holds both sides).
//!
//! The rays are those of `phase_table.rs`, their crystal frames drawn in the sky's frame
//! ([`plate_frame`]) so that what leaves is binned by its direction in the sky; each
//! ray's incident direction is drawn uniformly over the sun's disc, which averages the
//! table over the disc. Diffraction, symmetric about the sun, is the orientations'
//! averaged Airy pattern of `phase_table.rs` spread over the bins by their angle from
//! the sun, scaled to carry exactly the hits' weight. A bin's value is its weight over
//! the total and over its solid angle: the table integrates to 1 over the sphere.

use std::f64::consts::PI;

use glam::DVec3;
use num_complex::Complex64;
use rayon::prelude::*;

use super::crystal::HexagonalPrism;
use super::orientation::{Orientation, plate_frame};
use super::phase_table::{
    BATCH, IcePhaseError, RAYS_RANGE, RaySettings, bin_solid_angle, diffraction_bins,
};
use super::ray_tracer::{IceOptics, trace};
use crate::numerics::sampling::{Sampler, mix_seed, orthonormal_basis, uniform_in_cone};

/// Batches traced together before their sums are added in order (bounds the memory of
/// their histograms; the order keeps the table the same on any number of threads).
const BATCHES_AT_ONCE: usize = 16;
/// The bin width of the diffraction pattern before it is spread over the sky, degrees.
const DIFFRACTION_BIN_DEG: f64 = 0.05;

/// Bins of the sky: elevation from -90 degrees, azimuth from the sun's, each of a width
/// dividing 180 degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyGrid {
    pub elevation_bin_deg: f64,
    pub azimuth_bin_deg: f64,
}

/// The range of both bin widths, degrees.
pub const SKY_BIN_RANGE_DEG: [f64; 2] = [0.05, 5.0];

impl SkyGrid {
    pub fn elevation_bins(&self) -> usize {
        (180.0 / self.elevation_bin_deg).round() as usize
    }

    pub fn azimuth_bins(&self) -> usize {
        (180.0 / self.azimuth_bin_deg).round() as usize
    }

    /// Both widths in range and dividing 180 degrees.
    fn check(&self) -> Result<(), IcePhaseError> {
        for w in [self.elevation_bin_deg, self.azimuth_bin_deg] {
            let n = (180.0 / w).round();
            if !(SKY_BIN_RANGE_DEG[0]..=SKY_BIN_RANGE_DEG[1]).contains(&w)
                || (n * w - 180.0).abs() > 1e-9
            {
                return Err(IcePhaseError::Bin(w));
            }
        }
        Ok(())
    }

    /// The solid angle of elevation row `row`, both sides of the sun's vertical, per
    /// azimuth bin.
    pub fn bin_solid_angle(&self, row: usize) -> f64 {
        let lo = (-90.0 + row as f64 * self.elevation_bin_deg).to_radians();
        let hi = lo + self.elevation_bin_deg.to_radians();
        2.0 * self.azimuth_bin_deg.to_radians() * (hi.sin() - lo.sin())
    }

    /// The bin (row-major: elevation row, azimuth column) of the unit direction `seen`
    /// in the sky's frame (z up, the sun's azimuth along +x).
    pub fn bin_of(&self, seen: DVec3) -> usize {
        let elevation = seen.z.clamp(-1.0, 1.0).asin().to_degrees();
        let azimuth = seen.y.abs().atan2(seen.x).to_degrees();
        let row =
            (((elevation + 90.0) / self.elevation_bin_deg) as usize).min(self.elevation_bins() - 1);
        let column = ((azimuth / self.azimuth_bin_deg) as usize).min(self.azimuth_bins() - 1);
        row * self.azimuth_bins() + column
    }

    /// The unit direction of bin `(row, column)`'s centre.
    pub fn centre(&self, row: usize, column: usize) -> DVec3 {
        let h = (-90.0 + (row as f64 + 0.5) * self.elevation_bin_deg).to_radians();
        let a = ((column as f64 + 0.5) * self.azimuth_bin_deg).to_radians();
        DVec3::new(h.cos() * a.cos(), h.cos() * a.sin(), h.sin())
    }
}

/// Falling plates' phase function over the sky, sr^-1, row-major (elevation rows from
/// -90 degrees, azimuth columns from the sun's), with the rays that hit.
#[derive(Clone, Debug, PartialEq)]
pub struct IceSkyTable {
    pub grid: SkyGrid,
    pub phase: Vec<f64>,
    pub hits: usize,
}

/// The plates and the light: tilt spread and sun elevation (degrees, their ranges those
/// of [`Orientation::horizontal_plates`]) and the sun's angular radius, rad (0: a point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlateSky {
    pub tilt_spread_deg: f64,
    pub sun_elevation_deg: f64,
    pub sun_radius_rad: f64,
}

/// One batch of rays binned over the sky, and the rays that hit.
fn trace_batch(
    crystal: &HexagonalPrism,
    optics: IceOptics,
    plates: PlateSky,
    grid: SkyGrid,
    rays: usize,
    seed: u64,
) -> (Vec<f64>, usize) {
    let mut bins = vec![0.0; grid.elevation_bins() * grid.azimuth_bins()];
    let mut hits = 0;
    let mut sampler = Sampler::new(seed);
    let radius = crystal.bounding_radius_m();
    let e = plates.sun_elevation_deg.to_radians();
    let towards_sun = DVec3::new(e.cos(), 0.0, e.sin());
    for _ in 0..rays {
        let sun = if plates.sun_radius_rad > 0.0 {
            uniform_in_cone(towards_sun, plates.sun_radius_rad, &mut sampler)
        } else {
            towards_sun
        };
        let [a, b, axis] = plate_frame(plates.tilt_spread_deg, &mut sampler);
        let to_crystal = |v: DVec3| DVec3::new(v.dot(a), v.dot(b), v.dot(axis));
        let d = to_crystal(-sun);
        let (e1, e2) = orthonormal_basis(d);
        let r = radius * sampler.uniform().sqrt();
        let phi = 2.0 * PI * sampler.uniform();
        let origin = r * (phi.cos() * e1 + phi.sin() * e2) - 2.0 * radius * d;
        let hit = trace(crystal, optics, origin, d, |out: DVec3, w| {
            // Light leaving along `out` is seen from the opposite direction.
            let sky = out.x * a + out.y * b + out.z * axis;
            bins[grid.bin_of(-sky)] += w;
        });
        hits += usize::from(hit.is_some());
    }
    (bins, hits)
}

/// The phase function over `grid` of falling plates `crystal` of relative refractive
/// index `m` at `wavelength_m` (in air), lit as `plates` says, by `settings.rays` rays
/// (`settings.bin_deg` is not used: the grid gives the bins).
pub fn plate_sky_table(
    crystal: &HexagonalPrism,
    m: Complex64,
    wavelength_m: f64,
    plates: PlateSky,
    grid: SkyGrid,
    settings: RaySettings,
) -> Result<IceSkyTable, IcePhaseError> {
    if !(RAYS_RANGE[0]..=RAYS_RANGE[1]).contains(&settings.rays) {
        return Err(IcePhaseError::Rays(settings.rays));
    }
    grid.check()?;
    if !(m.re > 1.0 && m.re <= 10.0 && (0.0..=10.0).contains(&m.im)) {
        return Err(IcePhaseError::RefractiveIndex { re: m.re, im: m.im });
    }
    if !(wavelength_m.is_finite() && wavelength_m > 0.0) {
        return Err(IcePhaseError::Wavelength(wavelength_m * 1e9));
    }
    if !(0.0..=0.05).contains(&plates.sun_radius_rad) {
        return Err(IcePhaseError::SunRadius(plates.sun_radius_rad));
    }
    let orientation =
        Orientation::horizontal_plates(plates.tilt_spread_deg, plates.sun_elevation_deg)?;
    let wavenumber = 2.0 * PI / wavelength_m;
    let optics = IceOptics {
        index: m.re,
        absorption_per_m: 2.0 * wavenumber * m.im,
    };
    let cells = grid.elevation_bins() * grid.azimuth_bins();
    let batches = settings.rays.div_ceil(BATCH);
    let mut rays_bins = vec![0.0; cells];
    let mut hits = 0;
    for first in (0..batches).step_by(BATCHES_AT_ONCE) {
        let results: Vec<(Vec<f64>, usize)> = (first..batches.min(first + BATCHES_AT_ONCE))
            .into_par_iter()
            .map(|i| {
                let rays = BATCH.min(settings.rays - i * BATCH);
                let seed = mix_seed(&[settings.seed, i as u64]);
                trace_batch(crystal, optics, plates, grid, rays, seed)
            })
            .collect();
        for (bins, h) in &results {
            rays_bins.iter_mut().zip(bins).for_each(|(s, v)| *s += v);
            hits += h;
        }
    }
    let hits_f = hits.max(1) as f64;
    let e = plates.sun_elevation_deg.to_radians();
    let sun = DVec3::new(e.cos(), 0.0, e.sin());
    let diffraction =
        diffraction_over(crystal, wavenumber, (orientation, sun), grid, settings.seed);
    let scattered = hits_f + rays_bins.iter().sum::<f64>();
    let columns = grid.azimuth_bins();
    let phase = (0..cells)
        .map(|c| {
            (hits_f * diffraction[c] + rays_bins[c]) / scattered / grid.bin_solid_angle(c / columns)
        })
        .collect();
    Ok(IceSkyTable { grid, phase, hits })
}

/// The diffraction weight per sky bin, summing to 1: the pattern per solid angle at each
/// bin centre's angle from the unit `sun`, times the bin's solid angle.
fn diffraction_over(
    crystal: &HexagonalPrism,
    wavenumber: f64,
    (orientation, sun): (Orientation, DVec3),
    grid: SkyGrid,
    seed: u64,
) -> Vec<f64> {
    let bins = (180.0 / DIFFRACTION_BIN_DEG).round() as usize;
    let (pattern, _) = diffraction_bins(
        crystal,
        wavenumber,
        orientation,
        bins,
        DIFFRACTION_BIN_DEG,
        seed,
    );
    let columns = grid.azimuth_bins();
    let weights: Vec<f64> = (0..grid.elevation_bins() * columns)
        .map(|c| {
            let (row, column) = (c / columns, c % columns);
            let angle = grid
                .centre(row, column)
                .dot(sun)
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees();
            let b = ((angle / DIFFRACTION_BIN_DEG) as usize).min(bins - 1);
            let lo = b as f64 * DIFFRACTION_BIN_DEG;
            let density = pattern[b] / bin_solid_angle(lo, lo + DIFFRACTION_BIN_DEG);
            density * grid.bin_solid_angle(row)
        })
        .collect();
    let total: f64 = weights.iter().sum();
    weights.iter().map(|w| w / total).collect()
}
