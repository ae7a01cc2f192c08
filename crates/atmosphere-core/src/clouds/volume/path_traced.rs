//! The voxel cloud's image by the cloud path tracer (`reference/camera_path.rs`: all
//! orders of scattering, the droplets' A_1 at each wavelength drawn exactly, next-event
//! estimation of the sun with ratio tracking): the ground truth that the ray march and
//! half-angle slicing are measured against. The scene has no air and no sky, as theirs:
//! the sun's irradiance is the scene's wherever the cloud lets it through, and a path
//! that leaves the box finds nothing (the black background the other two composite
//! over). Each pixel's ray follows `paths` paths per wavelength from a first collision
//! on its crossing of the box, drawn by delta tracking (a path that crosses without one
//! adds nothing); its transmittance is the midpoint rule along the crossing. As a
//! setting ([`PathTracing::forward_peak_deg`]) the droplets' forward peak is taken as
//! no scattering (`reference/forward_peak.rs`): a biased but far less noisy answer.

use rayon::prelude::*;

use glam::DVec3;

use super::camera::{VolumeCamera, VolumeSun};
use super::cloud::VoxelCloud;
use super::image::VolumeImage;
use super::march_image::check_wavelengths;
use crate::clouds::error::CloudError;
use crate::clouds::estimate::Tally;
use crate::clouds::layer::orders::ANGLES;
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::medium::CloudMedium;
use crate::clouds::reference::camera_path::{PathLight, PathMedium, first_collision, trace_from};
use crate::clouds::reference::forward_peak::{
    ForwardPeakCut, MAX_FORWARD_PEAK_DEG, truncated_phase,
};
use crate::numerics::sampling::{Sampler, mix_seed};

/// The most paths per pixel and wavelength.
pub const MAX_PATHS_PER_PIXEL: u64 = 1 << 20;
/// The transmittance's midpoint steps per voxel side.
const TRANSMITTANCE_STEPS_PER_VOXEL: f64 = 4.0;

/// How the path tracer runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathTracing {
    /// Paths per pixel and wavelength, in [1, MAX_PATHS_PER_PIXEL].
    pub paths: u64,
    /// The random sequence.
    pub seed: u64,
    /// The cone around the forward direction, degrees in [0, MAX_FORWARD_PEAK_DEG],
    /// within which scattering is taken as none (0: every scattering as it is, the
    /// exact answer).
    pub forward_peak_deg: f64,
}

impl PathTracing {
    /// Refuses a path count or a cone out of range, naming it.
    pub fn check(&self) -> Result<(), CloudError> {
        if !(1..=MAX_PATHS_PER_PIXEL).contains(&self.paths) {
            return Err(CloudError(format!(
                "volume path tracer: {} paths per pixel, expected 1 to {MAX_PATHS_PER_PIXEL}",
                self.paths
            )));
        }
        if !(0.0..=MAX_FORWARD_PEAK_DEG).contains(&self.forward_peak_deg) {
            return Err(CloudError(format!(
                "volume path tracer: forward peak {} deg, expected 0 to {MAX_FORWARD_PEAK_DEG}",
                self.forward_peak_deg
            )));
        }
        Ok(())
    }
}

/// The image with each pixel's standard error.
#[derive(Clone, Debug)]
pub struct PathTracedImage {
    pub image: VolumeImage,
    /// The standard error of each value of `image.radiance`, laid out as it.
    pub standard_error: Vec<f64>,
    /// Paths per pixel and wavelength.
    pub paths: u64,
}

impl PathTracedImage {
    /// The RMS difference of `other`'s radiance from this image's over all pixels and
    /// wavelengths, with this image's own noise (the mean of its variances) taken out of
    /// the mean square, divided by this image's mean radiance: how far `other` is from
    /// the converged image, as far as this one can tell (0 when nothing is left after
    /// its noise).
    pub fn relative_rms_error(&self, other: &VolumeImage) -> f64 {
        let n = self.image.radiance.len().max(1) as f64;
        let square: f64 = self
            .image
            .radiance
            .iter()
            .zip(&other.radiance)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
            / n;
        let noise: f64 = self.standard_error.iter().map(|s| s * s).sum::<f64>() / n;
        let mean = self.image.radiance.iter().sum::<f64>() / n;
        if mean > 0.0 {
            (square - noise).max(0.0).sqrt() / mean
        } else {
            0.0
        }
    }

    /// The RMS of the standard errors divided by the mean radiance: the noise left in
    /// this image.
    pub fn relative_noise(&self) -> f64 {
        let n = self.image.radiance.len().max(1) as f64;
        let noise: f64 = self.standard_error.iter().map(|s| s * s).sum::<f64>() / n;
        let mean = self.image.radiance.iter().sum::<f64>() / n;
        if mean > 0.0 { noise.sqrt() / mean } else { 0.0 }
    }
}

/// The scene's sun, unattenuated outside the cloud; nothing beyond the box.
struct SunAlone<'a>(&'a VolumeSun);

impl PathLight for SunAlone<'_> {
    fn sun_direction(&self) -> DVec3 {
        self.0.direction
    }

    fn sun_irradiance(&self, _x: DVec3, out: &mut [f64]) {
        out.copy_from_slice(&self.0.irradiance);
    }

    fn surroundings(&self, _direction: DVec3, out: &mut [f64]) {
        out.fill(0.0);
    }
}

/// The image of `cloud` through `camera`, lit by `sun`, with the droplets' tables
/// `orders` (one per wavelength of the sun), traced as `tracing` says; `row_done` is
/// called once per finished row of pixels (for progress).
pub fn path_traced_image(
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sun: &VolumeSun,
    orders: &ScatteringOrders,
    tracing: &PathTracing,
    row_done: &(dyn Fn() + Sync),
) -> Result<PathTracedImage, CloudError> {
    check_wavelengths(sun, orders)?;
    tracing.check()?;
    let waves = sun.irradiance.len();
    let (phases, fractions): (Vec<_>, Vec<_>) = (0..waves)
        .map(|w| truncated_phase(&orders.table(w)[..ANGLES], tracing.forward_peak_deg))
        .unzip();
    let media: Vec<ForwardPeakCut<VoxelCloud>> = fractions
        .iter()
        .map(|&fraction| ForwardPeakCut {
            medium: cloud,
            fraction,
        })
        .collect();
    let light = SunAlone(sun);
    let width = camera.width_px as usize;
    let mut image = VolumeImage::clear(camera.width_px, camera.height_px, waves);
    let mut standard_error = vec![0.0; image.radiance.len()];
    image
        .radiance
        .par_chunks_mut(width * waves)
        .zip(standard_error.par_chunks_mut(width * waves))
        .zip(image.transmittance.par_chunks_mut(width))
        .enumerate()
        .for_each(|(y, ((radiance, error), transmittance))| {
            for x in 0..width {
                let direction = camera.direction(x as f64 + 0.5, y as f64 + 0.5);
                let Some((t0, t1)) = cloud.crossing(camera.position_m, direction) else {
                    continue;
                };
                let start = camera.position_m + direction * t0;
                transmittance[x] = crossing_transmittance(cloud, start, direction, t1 - t0);
                for (w, cut) in media.iter().enumerate() {
                    let medium = PathMedium {
                        medium: cut,
                        phases: &phases,
                    };
                    let mut tally = Tally::default();
                    for path in 0..tracing.paths {
                        let key = [tracing.seed, (y * width + x) as u64, w as u64, path];
                        let mut sampler = Sampler::new(mix_seed(&key));
                        tally.add(
                            match first_collision(cut, start, direction, t1 - t0, &mut sampler) {
                                Some(p) => {
                                    trace_from(&medium, &light, w, p, direction, &mut sampler)
                                }
                                None => 0.0,
                            },
                        );
                    }
                    let estimate = tally.estimate();
                    radiance[x * waves + w] = estimate.mean;
                    error[x * waves + w] = estimate.standard_error;
                }
            }
            row_done();
        });
    Ok(PathTracedImage {
        image,
        standard_error,
        paths: tracing.paths,
    })
}

/// exp(-int sigma) over `length` from `start` along `d` by the midpoint rule, a few
/// steps per voxel.
fn crossing_transmittance(cloud: &VoxelCloud, start: DVec3, d: DVec3, length: f64) -> f64 {
    let steps = (length / cloud.voxel_m() * TRANSMITTANCE_STEPS_PER_VOXEL)
        .ceil()
        .max(1.0);
    let dt = length / steps;
    let depth: f64 = (0..steps as usize)
        .map(|i| cloud.extinction(start + d * ((i as f64 + 0.5) * dt)))
        .sum::<f64>()
        * dt;
    (-depth).exp()
}
