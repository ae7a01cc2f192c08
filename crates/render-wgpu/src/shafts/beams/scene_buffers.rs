//! A packed beams scene ([`GpuScene`]) uploaded: the uniform and the eight storage
//! buffers of bindings 0 to 8 of `shaders/shafts/beams/bindings.wgsl`, which every
//! beams pass reads.

use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::pipeline::{read_only_storage_buffer_entry, uniform_entry};
use crate::shafts::beams::gpu_scene::{BeamsUniform, GpuScene};

/// The layout entries of bindings 0 (the uniform) to 8, seen by compute passes.
pub fn scene_entries() -> Vec<wgpu::BindGroupLayoutEntry> {
    let mut entries = vec![uniform_entry(0, size_of::<BeamsUniform>())];
    entries.extend((1..=8).map(|binding| read_only_storage_buffer_entry(binding, 0)));
    entries
}

/// The scene's buffers on the device.
#[derive(Debug)]
pub struct SceneBuffers {
    uniform: wgpu::Buffer,
    storage: [wgpu::Buffer; 8],
}

impl SceneBuffers {
    /// Uploads `scene` (checked against the device's limits by the caller).
    pub fn new(gpu: &GpuContext, scene: &GpuScene) -> SceneBuffers {
        let device = &gpu.device;
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("beams params"),
            contents: bytemuck::bytes_of(&scene.uniform),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let storage = |label: &str, bytes: &[u8]| {
            // A binding holds at least one element: empty lists get a zeroed one.
            let contents = if bytes.is_empty() {
                &[0u8; 256][..]
            } else {
                bytes
            };
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        SceneBuffers {
            uniform,
            storage: [
                storage("beams lights", bytemuck::cast_slice(&scene.lights)),
                storage(
                    "beams light maps",
                    bytemuck::cast_slice(&scene.light_texels),
                ),
                storage("beams shadow views", bytemuck::cast_slice(&scene.views)),
                storage("beams shadow maps", bytemuck::cast_slice(&scene.depths)),
                storage("beams primitives", bytemuck::cast_slice(&scene.primitives)),
                storage("beams BVH nodes", bytemuck::cast_slice(&scene.nodes)),
                storage("beams triangles", bytemuck::cast_slice(&scene.triangles)),
                storage(
                    "beams phase table",
                    bytemuck::cast_slice(&scene.phase_table),
                ),
            ],
        }
    }

    /// Bindings 0 to 8 in order.
    pub fn resources(&self) -> Vec<wgpu::BindingResource<'_>> {
        let mut resources = vec![self.uniform.as_entire_binding()];
        resources.extend(self.storage.iter().map(|b| b.as_entire_binding()));
        resources
    }
}
