//! The voxel cloud's image by the ray march: each pixel's ray crosses the box, and the
//! cloud layer's march (`layer/march.rs`: Riley et al. 2004's multiple scattering or the
//! octaves, the sun by a shadow march per sample) runs along the crossing.

use rayon::prelude::*;

use super::camera::{VolumeCamera, VolumeSun};
use super::cloud::VoxelCloud;
use super::image::VolumeImage;
use super::settings::VolumeSettings;
use crate::clouds::error::CloudError;
use crate::clouds::layer::march::{MarchRay, march};
use crate::clouds::layer::orders::ScatteringOrders;

/// The image of `cloud` through `camera`, lit by `sun`, with the tables `orders` (one per
/// wavelength of the sun) and the march's steps and light of `settings`.
pub fn march_image(
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sun: &VolumeSun,
    orders: &ScatteringOrders,
    settings: &VolumeSettings,
) -> Result<VolumeImage, CloudError> {
    settings.check()?;
    check_wavelengths(sun, orders)?;
    let layer = settings.march_settings();
    let light = sun.cloud_light();
    let waves = sun.irradiance.len();
    let mut image = VolumeImage::clear(camera.width_px, camera.height_px, waves);
    let width = camera.width_px as usize;
    image
        .radiance
        .par_chunks_mut(waves)
        .zip(image.transmittance.par_iter_mut())
        .enumerate()
        .for_each(|(k, (radiance, transmittance))| {
            let (x, y) = ((k % width) as f64 + 0.5, (k / width) as f64 + 0.5);
            let direction = camera.direction(x, y);
            let Some((t0, t1)) = cloud.crossing(camera.position_m, direction) else {
                return;
            };
            let ray = MarchRay {
                origin: camera.position_m,
                direction,
                t0,
                t1,
            };
            let segment = march(cloud, &ray, &light, orders, &layer);
            radiance.copy_from_slice(&segment.radiance);
            *transmittance = segment.transmittance[0];
        });
    Ok(image)
}

/// `Ok` when `orders` has a table for each of the sun's wavelengths.
pub fn check_wavelengths(sun: &VolumeSun, orders: &ScatteringOrders) -> Result<(), CloudError> {
    if orders.wavelengths() == sun.irradiance.len() {
        Ok(())
    } else {
        Err(CloudError(format!(
            "volume: the scattering tables hold {} wavelengths, the sun {}",
            orders.wavelengths(),
            sun.irradiance.len()
        )))
    }
}
