//! One frame of a method that draws planes (`planes_pass.rs`, `qtable_pass.rs`;
//! Dobashi, Yamamoto and Nishita 2000 section 5, Dobashi et al. 2002 section 4.2): the
//! scene checked against the device and uploaded, the ray-end pass recorded (the depth
//! the planes are tested against), the scene's bind group (group 0) and the method's
//! (group 1: its uniform, the ray end, then its own resources), the additive render
//! pass, and the submission with the two passes' GPU time.

use wgpu::util::DeviceExt;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::ordered_bind_group;
use crate::gpu::timer::GpuTimer;
use crate::shafts::beams::blended_planes::{BlendedPlanes, begin_planes_pass};
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::BeamImage;
use crate::shafts::beams::limits;
use crate::shafts::beams::ray_end_pass::RayEndPass;
use crate::shafts::beams::scene_buffers::SceneBuffers;

/// Where the ray ends bound at binding 1 of group 1 come from.
#[derive(Clone, Copy, Debug)]
pub enum RayEnds<'r> {
    /// Traced for the frame's own pixels by this pass, recorded first.
    Traced(&'r RayEndPass),
    /// Given (another frame's).
    Given(&'r wgpu::Texture),
}

/// A frame being recorded: the image, the encoder with the ray-end pass in it, and the
/// two bind groups of `planes`.
#[derive(Debug)]
pub struct PlanesFrame<'a> {
    planes: &'a BlendedPlanes,
    label: &'static str,
    image: BeamImage,
    encoder: wgpu::CommandEncoder,
    timer: Option<GpuTimer>,
    /// The timed passes: the ray ends' where traced, then the render pass.
    passes: u32,
    ray_end: wgpu::Texture,
    scene_group: wgpu::BindGroup,
    own_group: wgpu::BindGroup,
}

impl<'a> PlanesFrame<'a> {
    /// Checks `scene` against the device's limits, uploads it, records the ray-end pass
    /// where the ray ends are traced and binds `uniform` (binding 0 of group 1), the ray
    /// ends (binding 1) and `own` (bindings 2 on).
    pub fn begin(
        gpu: &GpuContext,
        ray_ends: RayEnds<'_>,
        planes: &'a BlendedPlanes,
        label: &'static str,
        scene: &GpuScene,
        uniform: &[u8],
        own: &[wgpu::BindingResource<'_>],
    ) -> Result<PlanesFrame<'a>, RenderError> {
        let device = &gpu.device;
        limits::check(scene, &device.limits())?;
        let [width, height, ..] = scene.uniform.size_steps_lights;
        let image = BeamImage::new(gpu, width, height);
        let buffers = SceneBuffers::new(gpu, scene);
        let timer = GpuTimer::new(gpu, 2);
        let mut encoder = device.create_command_encoder(&Default::default());
        let (ray_end, passes) = match ray_ends {
            RayEnds::Traced(pass) => (
                pass.encode(
                    gpu,
                    &buffers,
                    (width, height),
                    &mut encoder,
                    timer.as_ref().map(|t| t.compute_writes(0)),
                ),
                2,
            ),
            RayEnds::Given(texture) => (texture.clone(), 1),
        };
        let ray_end_view = ray_end.create_view(&Default::default());
        let scene_group = ordered_bind_group(
            device,
            Some(&format!("{label} scene")),
            &planes.scene_layout,
            &buffers.resources(),
        );
        let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(&format!("{label} params")),
            contents: uniform,
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let mut resources = vec![
            uniform.as_entire_binding(),
            wgpu::BindingResource::TextureView(&ray_end_view),
        ];
        resources.extend(own.iter().cloned());
        let own_group = ordered_bind_group(device, Some(label), &planes.own_layout, &resources);
        Ok(PlanesFrame {
            planes,
            label,
            image,
            encoder,
            timer,
            passes,
            ray_end,
            scene_group,
            own_group,
        })
    }

    /// Records the additive pass into the image, cleared first: the pipeline and both
    /// groups set, then `draw`.
    pub fn draw(&mut self, draw: impl FnOnce(&mut wgpu::RenderPass<'_>)) {
        self.draw_with_depth(None, draw);
    }

    /// [`PlanesFrame::draw`] with a depth image (cleared to 0) for the pipelines' tests.
    pub fn draw_with_depth(
        &mut self,
        depth: Option<&wgpu::TextureView>,
        draw: impl FnOnce(&mut wgpu::RenderPass<'_>),
    ) {
        let target = self.image.radiance.create_view(&Default::default());
        let mut pass = begin_planes_pass(
            &mut self.encoder,
            self.label,
            &target,
            depth,
            self.timer
                .as_ref()
                .map(|t| t.render_writes(self.passes - 1)),
        );
        pass.set_pipeline(&self.planes.pipeline);
        pass.set_bind_group(0, &self.scene_group, &[]);
        pass.set_bind_group(1, &self.own_group, &[]);
        draw(&mut pass);
    }

    /// The ray ends the frame's planes are tested against.
    pub fn ray_end(&self) -> &wgpu::Texture {
        &self.ray_end
    }

    /// Submits the frame; the image and, where the device has timestamps, the passes'
    /// GPU time in milliseconds, together.
    pub fn finish(mut self, gpu: &GpuContext) -> Result<(BeamImage, Option<f64>), RenderError> {
        if let Some(t) = &self.timer {
            t.resolve(&mut self.encoder, self.passes);
        }
        gpu.queue.submit([self.encoder.finish()]);
        let ms = match &self.timer {
            Some(t) => Some(t.read(gpu, self.passes)?.iter().sum()),
            None => None,
        };
        Ok((self.image, ms))
    }
}
