//! What the cloud spheres pass reads besides its parameters, as storage buffers in the
//! layout `shaders/clouds/spheres/params.wgsl` documents: the cloud textures T_k (optical
//! depths), the attenuation textures G_k (ratios, remade when the sun moves) and the droplets' phase function
//! A_1 at three wavelengths, followed by their Legendre moments chi_1..chi_4 per
//! wavelength (the slab lights').

use atmosphere_core::clouds::layer::orders::{ANGLES, ScatteringOrders};
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;

/// The spheres' textures and phase function on the GPU.
#[derive(Debug)]
pub struct SphereInputs {
    pub cloud_depths: wgpu::Buffer,
    pub sun_ratios: wgpu::Buffer,
    pub single_phase: wgpu::Buffer,
}

impl SphereInputs {
    /// Uploads the textures of `spheres` and the first row of `orders` (three
    /// wavelengths: 680, 550, 440 nm); a texture larger than the device's storage
    /// binding is refused naming both sizes.
    pub fn new(
        gpu: &GpuContext,
        spheres: &CloudSpheres,
        orders: &ScatteringOrders,
    ) -> Result<SphereInputs, RenderError> {
        if orders.wavelengths() != 3 {
            return Err(RenderError::Frame(format!(
                "cloud phase tables for {} wavelengths; the GPU renders 3 (680, 550, 440 nm)",
                orders.wavelengths()
            )));
        }
        let limit = gpu.device.limits().max_storage_buffer_binding_size;
        let upload = |label: &str, values: &[f32]| {
            let bytes = 4 * values.len() as u64;
            if bytes > limit {
                return Err(RenderError::Frame(format!(
                    "{label}: {bytes} bytes exceed this GPU's storage binding of {limit} bytes"
                )));
            }
            Ok(gpu
                .device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytemuck::cast_slice(values),
                    usage: wgpu::BufferUsages::STORAGE,
                }))
        };
        let mut phase: Vec<f32> = (0..3)
            .flat_map(|w| orders.table(w)[..ANGLES].iter().map(|&a| a as f32))
            .collect();
        for w in 0..3 {
            phase.extend(orders.moments(w)[1..].iter().map(|&chi| chi as f32));
        }
        Ok(SphereInputs {
            cloud_depths: upload("cloud sphere textures", spheres.clouds().values())?,
            sun_ratios: upload(
                "cloud sphere attenuation textures",
                spheres.attenuation().values(),
            )?,
            single_phase: upload("cloud sphere phase function", &phase)?,
        })
    }
}
