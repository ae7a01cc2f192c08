//! The sky model's second run in a frame with clouds (`cloud_front`): its passes again,
//! each ray ended where it enters the cloud (L_front of atmosphere-core's
//! `clouds/layer/composite.rs`), for the composite. Every pixel's, on the full image's
//! entries; or, from above the layer with the cloud (the spheres, or the layer's march)
//! at a reduced resolution, one ray's per `divisor` x `divisor` pixels
//! (`frame_clouds.rs`'s `front_divisor`), ended where it enters the sphere of the
//! layer's top, which is where every pixel's cloud starts (`clouds/front_rays.wgsl`
//! finds the entries and the atmosphere's transmittance to them first;
//! `front_targets.rs`). The composite reads them at each pixel (`frame_composite.wgsl`'s
//! `reduced_front`, twin of `clouds/layer/front_upsample.rs`): the air in front changes
//! smoothly across the image, and the run costs a divisor squared less.

use crate::clouds::cloud_targets::CloudTargets;
use crate::clouds::frame_clouds::front_sun_map;
use crate::clouds::frame_pass::{CloudFramePass, MarchScene};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::pipeline::texel_groups;
use crate::gpu::timer::GpuTimer;
use crate::sky::model_pass::PassIo;
use crate::sky::sky_pass::{FrameRecorder, SkyPass};

/// What the second run reads besides the frame's model passes' own inputs.
#[derive(Debug)]
pub struct FrontRun<'a> {
    /// The frame's model passes' inputs and outputs, whose target and surface the run
    /// replaces.
    pub io: &'a PassIo<'a>,
    /// The frame's uniform, which the reduced run takes with the reduced image's size.
    pub uniform: FrameUniform,
    /// The frame, its clouds and its sun map, as the cloud steps take them.
    pub scene: &'a MarchScene<'a>,
    pub targets: &'a CloudTargets,
    /// The cloud steps' pipelines (the reduced run's rays).
    pub pass: &'a CloudFramePass,
    /// 1 for every pixel, else the divisor of the reduced run.
    pub divisor: u32,
}

/// Records `model`'s second run of `run` into `encoder`, timed in the plan's slot `step`,
/// with the frame's sun map as the run in front takes it (`frame_clouds.rs`'s
/// `front_sun_map`).
pub fn encode_front(
    model: &mut dyn SkyPass,
    gpu: &GpuContext,
    (encoder, timer): (&mut wgpu::CommandEncoder, Option<&GpuTimer>),
    run: &FrontRun<'_>,
    step: u32,
) -> Result<(), RenderError> {
    let (frame, settings) = (run.scene.frame, &run.scene.clouds.settings);
    let sun_map = front_sun_map(run.scene.sun_map, frame, settings);
    let targets = run.targets;
    let mut record = |encoder: &mut wgpu::CommandEncoder, io: &PassIo<'_>| {
        let mut recorder = FrameRecorder {
            gpu,
            io,
            encoder,
            timer,
        };
        model.encode_passes(&mut recorder, step);
    };
    if run.divisor <= 1 {
        let surface = targets.front_surface();
        record(
            encoder,
            &PassIo {
                sun_map: &sun_map,
                hdr: &targets.front,
                surface: &surface,
                has_surface: true,
                has_sea: false,
                ..*run.io
            },
        );
        return Ok(());
    }
    let Some(reduced) = targets.front_reduced(run.divisor) else {
        return Err(RenderError::Frame(format!(
            "the cloud targets hold no reduced run in front for resolution divisor {}",
            run.divisor
        )));
    };
    let mut uniform = run.uniform;
    let (width, height) = reduced.size();
    uniform.size_px = [width, height, 0, 0];
    gpu.write_uniform(&reduced.frame, &uniform);
    let (_, top_m) = settings.radii_m(frame.atmosphere.bottom_radius_m);
    gpu.write_uniform(&reduced.layer, &[top_m as f32, 0.0, 0.0, 0.0]);
    let rays = &run.pass.front_rays;
    let view = |t: &wgpu::Texture| t.create_view(&Default::default());
    let (entries, transmittance) = (view(&reduced.entries), view(&reduced.transmittance));
    let bind_group = rays.bind_group(
        gpu,
        &[
            run.io.atmosphere.as_entire_binding(),
            reduced.frame.as_entire_binding(),
            reduced.layer.as_entire_binding(),
            wgpu::BindingResource::TextureView(&entries),
            wgpu::BindingResource::TextureView(&transmittance),
        ],
    );
    rays.dispatch(
        encoder,
        "cloud front reduced rays",
        &bind_group,
        texel_groups(&reduced.entries),
        None,
    );
    let surface = reduced.surface();
    record(
        encoder,
        &PassIo {
            frame: &reduced.frame,
            sun_map: &sun_map,
            hdr: &reduced.radiance,
            surface: &surface,
            has_surface: true,
            has_sea: false,
            ..*run.io
        },
    );
    Ok(())
}
