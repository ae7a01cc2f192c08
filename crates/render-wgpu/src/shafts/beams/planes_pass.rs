//! The virtual planes of Dobashi, Yamamoto and Nishita 2000 on the GPU, as the paper
//! draws them: a compute pass finds where each pixel's ray ends
//! (`shaders/shafts/beams/ray_end.wgsl`, the depth the planes are tested against), then
//! a render pass draws every plane's lattice mesh once per light with additive blending
//! (`shaders/shafts/beams/planes.wgsl`): xi at the lattice points, the light's
//! distribution, light map and shadow map at each fragment. CPU twin: atmosphere-core's
//! `beams/methods/planes2000.rs`.

use atmosphere_core::beams::methods::planes2000::Planes2000;
use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::{
    ComputePipeline, in_stage, shader_module, storage_texture_entry, texel_groups, texture_2d,
    texture_entry, uniform_entry,
};
use crate::gpu::timer::GpuTimer;
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::{BeamImage, RADIANCE_FORMAT};
use crate::shafts::beams::limits;
use crate::shafts::beams::scene_buffers::{SceneBuffers, scene_entries};

/// Where each pixel's ray ends, m.
const RAY_END_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// The planes' own parameters (WGSL `PlanesParams`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct PlanesUniform {
    /// Planes, lattice points on a side, lights, 0.
    pub planes_lattice_lights: [u32; 4],
    /// x: the spacing of the planes along the view direction, m.
    pub spacing_m: [f32; 4],
}

/// A beams scene with the planes of a prepared CPU `planes2000`.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuPlanes {
    pub scene: GpuScene,
    pub planes: PlanesUniform,
}

impl GpuPlanes {
    /// The scene and planes of `method` (its wavelengths three).
    pub fn new(method: &Planes2000) -> GpuPlanes {
        let scene = GpuScene::from_parts(method.scattering(), method.shadow_maps(), 0);
        let settings = method.settings();
        let planes = PlanesUniform {
            planes_lattice_lights: [
                settings.planes as u32,
                settings.lattice as u32,
                scene.lights.len() as u32,
                0,
            ],
            spacing_m: [
                (settings.far_m / settings.planes as f64) as f32,
                0.0,
                0.0,
                0.0,
            ],
        };
        GpuPlanes { scene, planes }
    }
}

/// The triangles of a lattice of `n` x `n` points, row by row from the top: each cell
/// split along its diagonal from top left to bottom right, as `Planes2000` interpolates.
fn lattice_indices(n: u32) -> Vec<u32> {
    let mut indices = Vec::with_capacity(6 * (n as usize - 1).pow(2));
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let (a, b) = (j * n + i, j * n + i + 1);
            let (c, d) = (a + n, b + n);
            indices.extend([a, b, d, a, d, c]);
        }
    }
    indices
}

/// The planes' pipelines, made once per device.
#[derive(Debug)]
pub struct PlanesPass {
    ray_end: ComputePipeline,
    planes: wgpu::RenderPipeline,
    scene_layout: wgpu::BindGroupLayout,
    planes_layout: wgpu::BindGroupLayout,
}

impl PlanesPass {
    /// The pipelines; an error where the device cannot blend `Rgba32Float` targets.
    pub fn new(gpu: &GpuContext) -> Result<PlanesPass, RenderError> {
        if !gpu
            .device
            .features()
            .contains(wgpu::Features::FLOAT32_BLENDABLE)
        {
            return Err(RenderError::Unsupported(
                "planes2000 sums its planes by blending into an Rgba32Float image; this \
                 device lacks FLOAT32_BLENDABLE (use --model march)"
                    .into(),
            ));
        }
        let mut entries = scene_entries();
        entries.push(storage_texture_entry(
            10,
            RAY_END_FORMAT,
            wgpu::TextureViewDimension::D2,
        ));
        let ray_end = ComputePipeline::new(
            gpu,
            "shafts/beams/ray_end.wgsl",
            "main",
            "beams ray end",
            &entries,
        )?;
        let device = &gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let scene_entries: Vec<_> = scene_entries()
            .into_iter()
            .map(|e| in_stage(stages, e))
            .collect();
        let scene_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("beams planes scene"),
            entries: &scene_entries,
        });
        let planes_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("beams planes"),
            entries: &[
                in_stage(stages, uniform_entry(0, size_of::<PlanesUniform>())),
                in_stage(
                    wgpu::ShaderStages::FRAGMENT,
                    texture_entry(1, wgpu::TextureViewDimension::D2),
                ),
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("beams planes"),
            bind_group_layouts: &[Some(&scene_layout), Some(&planes_layout)],
            immediate_size: 0,
        });
        let module = shader_module(device, "shafts/beams/planes.wgsl")?;
        let add = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let planes = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("beams planes"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: RADIANCE_FORMAT,
                    blend: Some(wgpu::BlendState {
                        color: add,
                        alpha: add,
                    }),
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        if let Some(source) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Validation {
                what: "the beams planes pipeline",
                source,
            }
            .into());
        }
        Ok(PlanesPass {
            ray_end,
            planes,
            scene_layout,
            planes_layout,
        })
    }

    /// Renders `planes` after checking its scene against the device's limits; the two
    /// passes' GPU time in milliseconds, together, comes with the image where the device
    /// has timestamps.
    pub fn render(
        &self,
        gpu: &GpuContext,
        planes: &GpuPlanes,
    ) -> Result<(BeamImage, Option<f64>), RenderError> {
        let scene = &planes.scene;
        limits::check(scene, &gpu.device.limits())?;
        let [width, height, ..] = scene.uniform.size_steps_lights;
        let [count, n, lights, _] = planes.planes.planes_lattice_lights;
        let image = BeamImage::new(gpu, width, height);
        let device = &gpu.device;
        let buffers = SceneBuffers::new(gpu, scene);
        let usage = wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING;
        let ray_end = texture_2d(
            device,
            "beams ray end",
            (width, height),
            RAY_END_FORMAT,
            usage,
        );
        let ray_end_view = ray_end.create_view(&Default::default());
        let mut resources: Vec<(u32, wgpu::BindingResource<'_>)> = buffers
            .resources()
            .into_iter()
            .enumerate()
            .map(|(b, r)| (b as u32, r))
            .collect();
        resources.push((10, wgpu::BindingResource::TextureView(&ray_end_view)));
        let ray_end_group = self.ray_end.bind_group_numbered(gpu, &resources);
        let scene_group = crate::gpu::pipeline::ordered_bind_group(
            device,
            Some("beams planes scene"),
            &self.scene_layout,
            &buffers.resources(),
        );
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("beams planes params"),
            contents: bytemuck::bytes_of(&planes.planes),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let planes_group = crate::gpu::pipeline::ordered_bind_group(
            device,
            Some("beams planes"),
            &self.planes_layout,
            &[
                uniform.as_entire_binding(),
                wgpu::BindingResource::TextureView(&ray_end_view),
            ],
        );
        let indices = lattice_indices(n);
        let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("beams lattice"),
            contents: bytemuck::cast_slice(&indices),
            usage: wgpu::BufferUsages::INDEX,
        });
        let timer = GpuTimer::new(gpu, 2);
        let mut encoder = device.create_command_encoder(&Default::default());
        self.ray_end.dispatch(
            &mut encoder,
            "beams ray end",
            &ray_end_group,
            texel_groups(&ray_end),
            timer.as_ref().map(|t| t.compute_writes(0)),
        );
        {
            let target = image.radiance.create_view(&Default::default());
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("beams planes"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color {
                            r: 0.0,
                            g: 0.0,
                            b: 0.0,
                            a: 1.0,
                        }),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: timer.as_ref().map(|t| t.render_writes(1)),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.planes);
            pass.set_bind_group(0, &scene_group, &[]);
            pass.set_bind_group(1, &planes_group, &[]);
            pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..indices.len() as u32, 0, 0..count * lights);
        }
        if let Some(t) = &timer {
            t.resolve(&mut encoder, 2);
        }
        gpu.queue.submit([encoder.finish()]);
        let ms = match &timer {
            Some(t) => Some(t.read(gpu, 2)?.iter().sum()),
            None => None,
        };
        Ok((image, ms))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lattice_is_two_triangles_a_cell_split_from_top_left_to_bottom_right() {
        assert_eq!(lattice_indices(2), vec![0, 1, 3, 0, 3, 2]);
        let indices = lattice_indices(20);
        assert_eq!(indices.len(), 6 * 19 * 19);
        assert_eq!(indices.iter().max(), Some(&399));
    }
}
