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
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::{in_stage, texture_entry, uniform_entry};
use crate::shafts::beams::blended_planes::BlendedPlanes;
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::BeamImage;
use crate::shafts::beams::planes_frame::{PlanesFrame, RayEnds};
use crate::shafts::beams::ray_end_pass::RayEndPass;

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
    ray_end: RayEndPass,
    planes: BlendedPlanes,
}

impl PlanesPass {
    /// The pipelines; an error where the device cannot blend `Rgba32Float` targets.
    pub fn new(gpu: &GpuContext) -> Result<PlanesPass, RenderError> {
        let stages = wgpu::ShaderStages::VERTEX_FRAGMENT;
        let planes = BlendedPlanes::new(
            gpu,
            "shafts/beams/planes.wgsl",
            "beams planes2000",
            &[
                in_stage(stages, uniform_entry(0, size_of::<PlanesUniform>())),
                in_stage(
                    wgpu::ShaderStages::FRAGMENT,
                    texture_entry(1, wgpu::TextureViewDimension::D2),
                ),
            ],
            &[],
        )?;
        Ok(PlanesPass {
            ray_end: RayEndPass::new(gpu)?,
            planes,
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
        let [count, n, lights, _] = planes.planes.planes_lattice_lights;
        let mut frame = PlanesFrame::begin(
            gpu,
            RayEnds::Traced(&self.ray_end),
            &self.planes,
            "beams planes2000",
            &planes.scene,
            bytemuck::bytes_of(&planes.planes),
            &[],
        )?;
        let indices = lattice_indices(n);
        let index_buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("beams lattice"),
                contents: bytemuck::cast_slice(&indices),
                usage: wgpu::BufferUsages::INDEX,
            });
        frame.draw(|pass| {
            pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..indices.len() as u32, 0, 0..count * lights);
        });
        frame.finish(gpu)
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
