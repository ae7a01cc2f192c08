//! The phase function of a hexagonal crystal by ray tracing plus diffraction, tabulated
//! in bins of scattering angle and normalised.
//!
//! Rays fall on a disc around the crystal's bounding sphere, normal to the incident
//! direction, at points uniform on the disc: rays that hit sample the crystal's
//! orientations weighted by their projected area, as light does, and the fraction that
//! hits estimates the mean projected area. Each hit gives unit weight to geometric optics
//! (reflected, refracted, absorbed) and unit weight to diffraction (the extinction
//! paradox, Q_ext = 2). The diffraction part is the Airy pattern of each orientation's
//! projected area (`diffraction.rs`) averaged over orientations drawn alike, integrated
//! over every bin and scaled to carry exactly its weight. A bin's value is its weight
//! over the total and over its solid angle, so the table integrates to 1 over the sphere.
//!
//! Deterministic: the rays are cut into fixed batches, each with its own seeded stream,
//! summed in order.

use std::f64::consts::PI;

use glam::DVec3;
use num_complex::Complex64;
use rayon::prelude::*;
use thiserror::Error;

use super::crystal::HexagonalPrism;
use super::diffraction::airy_pattern;
use super::orientation::{Orientation, OrientationError};
use super::ray_tracer::{IceOptics, trace};
use crate::numerics::sampling::{Sampler, mix_seed, orthonormal_basis};

/// Rays per batch (one seeded stream each).
pub(super) const BATCH: usize = 4096;
/// Orientations averaged for the diffraction pattern, and points per bin integrating it.
const DIFFRACTION_ORIENTATIONS: usize = 256;
const POINTS_PER_BIN: usize = 8;

/// The range of rays traced, and of the bin width in degrees.
pub const RAYS_RANGE: [usize; 2] = [1_000, 100_000_000];
pub const BIN_RANGE_DEG: [f64; 2] = [0.01, 1.0];

#[derive(Clone, Debug, Error, PartialEq)]
pub enum IcePhaseError {
    #[error("rays {0} is outside [1000, 1e8]")]
    Rays(usize),
    #[error("bin width {0} deg is outside [0.01, 1] deg and must divide 180 deg")]
    Bin(f64),
    #[error(
        "refractive index {re}{im:+}i of ice must have a real part in (1, 10] and an \
         imaginary part in [0, 10]"
    )]
    RefractiveIndex { re: f64, im: f64 },
    #[error("wavelength {0} nm must be finite and positive")]
    Wavelength(f64),
    #[error("sun radius {0} rad is outside [0, 0.05] rad")]
    SunRadius(f64),
    #[error("oriented plates: {0}")]
    Orientation(#[from] OrientationError),
}

/// How many rays, the bin width and the seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySettings {
    pub rays: usize,
    pub bin_deg: f64,
    pub seed: u64,
}

/// A crystal's phase function in bins of scattering angle, with its optics.
#[derive(Clone, Debug, PartialEq)]
pub struct IcePhaseTable {
    /// The bins' centres, degrees.
    pub angles_deg: Vec<f64>,
    /// The phase function averaged over each bin, sr^-1.
    pub phase: Vec<f64>,
    /// Q_sca over the mean projected area (2 without absorption).
    pub scattering_efficiency: f64,
    pub asymmetry: f64,
    /// The mean projected area estimated from the rays that hit, m^2.
    pub projected_area_m2: f64,
    /// Rays that hit the crystal.
    pub hits: usize,
    /// The largest weight any ray left inside (below the threshold or past the limit).
    pub largest_dropped: f64,
}

impl IcePhaseTable {
    /// Q_ext over the mean projected area: 2 in geometric optics with diffraction.
    pub fn extinction_efficiency(&self) -> f64 {
        2.0
    }

    /// The integral over the sphere: the bins' values times their solid angles.
    pub fn integral(&self) -> f64 {
        let half = 0.5 * (self.angles_deg[1] - self.angles_deg[0]);
        self.angles_deg
            .iter()
            .zip(&self.phase)
            .map(|(a, p)| p * bin_solid_angle(a - half, a + half))
            .sum()
    }

    /// The phase function at `angle_deg`, linear between bin centres, the end bins'
    /// values beyond the first and last centres.
    pub fn value_at(&self, angle_deg: f64) -> f64 {
        let a = &self.angles_deg;
        let step = a[1] - a[0];
        let x = ((angle_deg - a[0]) / step).clamp(0.0, (a.len() - 1) as f64);
        let i = (x.floor() as usize).min(a.len() - 2);
        let t = x - i as f64;
        self.phase[i] * (1.0 - t) + self.phase[i + 1] * t
    }
}

/// 2 pi (cos a - cos b) for a bin from `a_deg` to `b_deg`.
pub(super) fn bin_solid_angle(a_deg: f64, b_deg: f64) -> f64 {
    2.0 * PI * (a_deg.to_radians().cos() - b_deg.to_radians().cos())
}

/// One batch's sums: weight per bin, weight times cos theta, hits, the largest dropped
/// weight.
struct Batch {
    bins: Vec<f64>,
    cosine_weight: f64,
    hits: usize,
    largest_dropped: f64,
}

fn trace_batch(
    crystal: &HexagonalPrism,
    optics: IceOptics,
    orientation: Orientation,
    rays: usize,
    bin_deg: f64,
    seed: u64,
) -> Batch {
    let bins = (180.0 / bin_deg).round() as usize;
    let mut batch = Batch {
        bins: vec![0.0; bins],
        cosine_weight: 0.0,
        hits: 0,
        largest_dropped: 0.0,
    };
    let mut sampler = Sampler::new(seed);
    let radius = crystal.bounding_radius_m();
    for _ in 0..rays {
        let d = orientation.sample_incident(&mut sampler);
        let (e1, e2) = orthonormal_basis(d);
        let r = radius * sampler.uniform().sqrt();
        let phi = 2.0 * PI * sampler.uniform();
        let origin = r * (phi.cos() * e1 + phi.sin() * e2) - 2.0 * radius * d;
        let Batch {
            bins: hist,
            cosine_weight,
            ..
        } = &mut batch;
        let outcome = trace(crystal, optics, origin, d, |out: DVec3, w| {
            let cosine = out.dot(d).clamp(-1.0, 1.0);
            let bin = ((cosine.acos().to_degrees() / bin_deg) as usize).min(bins - 1);
            hist[bin] += w;
            *cosine_weight += w * cosine;
        });
        if let Some(o) = outcome {
            batch.hits += 1;
            batch.largest_dropped = batch.largest_dropped.max(o.dropped);
        }
    }
    batch
}

/// The diffraction part per bin (summing to 1) and its mean cosine, averaged over
/// orientations drawn as the rays' are, each weighted by its projected area.
pub(super) fn diffraction_bins(
    crystal: &HexagonalPrism,
    wavenumber: f64,
    orientation: Orientation,
    bins: usize,
    bin_deg: f64,
    seed: u64,
) -> (Vec<f64>, f64) {
    let mut sampler = Sampler::new(mix_seed(&[seed, u64::MAX]));
    let discs: Vec<(f64, f64)> = (0..DIFFRACTION_ORIENTATIONS)
        .map(|_| {
            let area = crystal.projected_area_m2(orientation.sample_incident(&mut sampler));
            (area, wavenumber * (area / PI).sqrt())
        })
        .collect();
    let h = bin_deg.to_radians() / POINTS_PER_BIN as f64;
    let per_bin: Vec<(f64, f64)> = (0..bins)
        .into_par_iter()
        .map(|b| {
            let mut sums = (0.0, 0.0);
            for j in 0..POINTS_PER_BIN {
                let theta = (b * POINTS_PER_BIN + j) as f64 * h + 0.5 * h;
                let pattern: f64 = discs
                    .iter()
                    .map(|&(a, ka)| a * airy_pattern(ka, theta))
                    .sum();
                let w = pattern * 2.0 * PI * theta.sin() * h;
                sums.0 += w;
                sums.1 += w * theta.cos();
            }
            sums
        })
        .collect();
    let total: f64 = per_bin.iter().map(|s| s.0).sum();
    let cosine = per_bin.iter().map(|s| s.1).sum::<f64>() / total;
    (per_bin.iter().map(|s| s.0 / total).collect(), cosine)
}

/// The phase function of `crystal` of relative refractive index `m` at `wavelength_m`
/// (in air), its crystals oriented as `orientation`.
pub fn ice_phase_table(
    crystal: &HexagonalPrism,
    m: Complex64,
    wavelength_m: f64,
    orientation: Orientation,
    settings: RaySettings,
) -> Result<IcePhaseTable, IcePhaseError> {
    if !(RAYS_RANGE[0]..=RAYS_RANGE[1]).contains(&settings.rays) {
        return Err(IcePhaseError::Rays(settings.rays));
    }
    let bin_deg = settings.bin_deg;
    let bins = (180.0 / bin_deg).round();
    if !(BIN_RANGE_DEG[0]..=BIN_RANGE_DEG[1]).contains(&bin_deg)
        || (bins * bin_deg - 180.0).abs() > 1e-9
    {
        return Err(IcePhaseError::Bin(bin_deg));
    }
    if !(m.re > 1.0 && m.re <= 10.0 && (0.0..=10.0).contains(&m.im)) {
        return Err(IcePhaseError::RefractiveIndex { re: m.re, im: m.im });
    }
    if !(wavelength_m.is_finite() && wavelength_m > 0.0) {
        return Err(IcePhaseError::Wavelength(wavelength_m * 1e9));
    }
    let bins = bins as usize;
    let wavenumber = 2.0 * PI / wavelength_m;
    let optics = IceOptics {
        index: m.re,
        absorption_per_m: 2.0 * wavenumber * m.im,
    };
    let batches = settings.rays.div_ceil(BATCH);
    let results: Vec<Batch> = (0..batches)
        .into_par_iter()
        .map(|i| {
            let rays = BATCH.min(settings.rays - i * BATCH);
            let seed = mix_seed(&[settings.seed, i as u64]);
            trace_batch(crystal, optics, orientation, rays, bin_deg, seed)
        })
        .collect();
    let mut rays_bins = vec![0.0; bins];
    let (mut cosine_weight, mut hits, mut largest_dropped) = (0.0, 0, 0.0f64);
    for b in &results {
        rays_bins.iter_mut().zip(&b.bins).for_each(|(s, v)| *s += v);
        cosine_weight += b.cosine_weight;
        hits += b.hits;
        largest_dropped = largest_dropped.max(b.largest_dropped);
    }
    let hits_f = hits.max(1) as f64;
    let (diffraction, diffraction_cosine) = diffraction_bins(
        crystal,
        wavenumber,
        orientation,
        bins,
        bin_deg,
        settings.seed,
    );
    let scattered = hits_f + rays_bins.iter().sum::<f64>();
    let angles_deg: Vec<f64> = (0..bins).map(|b| (b as f64 + 0.5) * bin_deg).collect();
    let phase = (0..bins)
        .map(|b| {
            let lo = b as f64 * bin_deg;
            (hits_f * diffraction[b] + rays_bins[b]) / scattered / bin_solid_angle(lo, lo + bin_deg)
        })
        .collect();
    let radius = crystal.bounding_radius_m();
    Ok(IcePhaseTable {
        angles_deg,
        phase,
        scattering_efficiency: scattered / hits_f,
        asymmetry: (hits_f * diffraction_cosine + cosine_weight) / scattered,
        projected_area_m2: PI * radius * radius * hits as f64 / settings.rays as f64,
        hits,
        largest_dropped,
    })
}
