//! The voxel cloud's image by half-angle slicing (Kniss et al. 2002; Riley et al. 2004
//! sections 4.2 and 5), the CPU twin of the GPU's passes: for each slice in order
//! (`half_angle.rs`), first the eye buffer takes the slice's light, then the light
//! buffer (`light_buffer.rs`) is advanced across it.
//!
//! Eye: a pixel whose ray meets slice k inside the box at p, with extinction sigma,
//! albedo a and path Delta_v = spacing / |v . h| between slices, reads the light buffer
//! at p (I, tau) and gets the slice's opacity alpha = 1 - exp(-sigma Delta_v) and source
//! S = a E_sun J, J from I and tau as the layer's march makes it: Riley's Eq. 26,
//! I (A_(floor(a tau)+1)(theta) + xi), or the octaves of tau. Front to back (facing
//! away from the sun) the buffer keeps L += T alpha S, T *= 1 - alpha; back to front
//! (facing the sun) L = alpha S + (1 - alpha) L, T *= 1 - alpha: the same sum taken from
//! the other end. Pixels whose ray misses the slice inside the box are left as they are.

use super::camera::{VolumeCamera, VolumeSun};
use super::cloud::VoxelCloud;
use super::half_angle::HalfAngle;
use super::image::VolumeImage;
use super::light_buffer::LightBuffer;
use super::march_image::check_wavelengths;
use super::settings::VolumeSettings;
use crate::clouds::error::CloudError;
use crate::clouds::layer::march::{octaves_source, riley_source};
use crate::clouds::layer::orders::ScatteringOrders;
use crate::clouds::layer::settings::LayerMethod;
use crate::clouds::medium::CloudMedium;

/// The image of `cloud` through `camera`, lit by `sun`, with the tables `orders` (one per
/// wavelength of the sun), by `settings.slices` slices and a light buffer of
/// `settings.light_buffer_px` texels on a side.
pub fn slicing_image(
    cloud: &VoxelCloud,
    camera: &VolumeCamera,
    sun: &VolumeSun,
    orders: &ScatteringOrders,
    settings: &VolumeSettings,
) -> Result<VolumeImage, CloudError> {
    settings.check()?;
    check_wavelengths(sun, orders)?;
    let corners = cloud.corners();
    let slices = HalfAngle::new(camera, sun.direction, &corners, settings.slices)?;
    let waves = sun.irradiance.len();
    let mut light = LightBuffer::new(
        slices.light,
        &corners,
        settings.light_buffer_px as usize,
        waves,
    );
    let mut image = VolumeImage::clear(camera.width_px, camera.height_px, waves);
    let directions: Vec<_> = (0..image.transmittance.len())
        .map(|k| {
            let width = camera.width_px as usize;
            camera.direction((k % width) as f64 + 0.5, (k / width) as f64 + 0.5)
        })
        .collect();
    let albedo = cloud.albedo();
    let mut intensity = vec![0.0; waves];
    for k in 0..slices.slices {
        for (pixel, &direction) in directions.iter().enumerate() {
            let Some((p, path)) = slices.view_hit(camera.position_m, direction, k) else {
                continue;
            };
            let sigma = cloud.extinction(p);
            if sigma <= 0.0 {
                continue;
            }
            let alpha = 1.0 - (-sigma * path).exp();
            let tau = light.read(p, &mut intensity);
            let nu = direction.dot(sun.direction);
            let transmittance = image.transmittance[pixel];
            for (w, radiance) in image.radiance[pixel * waves..(pixel + 1) * waves]
                .iter_mut()
                .enumerate()
            {
                let j = match settings.light {
                    LayerMethod::Riley => riley_source(
                        orders,
                        w,
                        intensity[w],
                        tau,
                        albedo,
                        nu,
                        settings.backscatter_xi,
                    ),
                    // `check` refuses the slab methods for a volume.
                    LayerMethod::Octaves | LayerMethod::Eddington | LayerMethod::FourStream => {
                        octaves_source(orders, w, tau, nu, settings.octaves)
                    }
                };
                let source = albedo * sun.irradiance[w] * j;
                *radiance = if slices.front_to_back {
                    *radiance + transmittance * alpha * source
                } else {
                    alpha * source + (1.0 - alpha) * *radiance
                };
            }
            image.transmittance[pixel] = transmittance * (1.0 - alpha);
        }
        light.advance(cloud, &slices, k, orders);
    }
    Ok(image)
}
