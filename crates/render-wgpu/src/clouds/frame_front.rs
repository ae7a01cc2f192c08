//! The sky model's second run in a frame with clouds (`cloud_front`): its passes again,
//! each ray ended where it enters the cloud (L_front of atmosphere-core's
//! `clouds/layer/composite.rs`), for the composite. Every pixel's, on the full
//! image's entries; or, from above the layer with the spheres at a reduced resolution,
//! only the spheres' reduced rays', on their entries into the layer
//! (`spheres/reduced_targets.rs`), which the composite reads at each pixel
//! (`frame_composite.wgsl`'s `reduced_front`, twin of `clouds/layer/front_upsample.rs`):
//! there the entry is where the ray meets the sphere of the layer's top, smooth across
//! the image, and the run costs a divisor squared less.

use crate::clouds::frame_pass::CloudTargets;
use crate::clouds::sun_map_texture::SunMapTexture;
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
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
    pub frame: FrameUniform,
    pub targets: &'a CloudTargets,
    /// The sun map the run binds (`frame_clouds.rs`'s `front_sun_map`).
    pub sun_map: &'a SunMapTexture,
    /// 1 for every pixel, else the spheres' resolution divisor of the reduced run.
    pub divisor: u32,
}

/// Records `model`'s second run of `run` into `encoder`, timed in the plan's slot `step`.
pub fn encode_front(
    model: &mut dyn SkyPass,
    gpu: &GpuContext,
    (encoder, timer): (&mut wgpu::CommandEncoder, Option<&GpuTimer>),
    run: &FrontRun<'_>,
    step: u32,
) -> Result<(), RenderError> {
    let targets = run.targets;
    let mut record = |io: &PassIo<'_>| {
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
        record(&PassIo {
            sun_map: run.sun_map,
            hdr: &targets.front,
            surface: &surface,
            has_surface: true,
            has_sea: false,
            ..*run.io
        });
        return Ok(());
    }
    let Some(reduced) = targets
        .spheres_reduced
        .as_ref()
        .filter(|r| r.divisor == run.divisor)
    else {
        return Err(RenderError::Frame(format!(
            "the cloud targets hold no reduced images for resolution divisor {}",
            run.divisor
        )));
    };
    let mut uniform = run.frame;
    uniform.size_px = [reduced.front.width(), reduced.front.height(), 0, 0];
    gpu.write_uniform(&reduced.frame, &uniform);
    let surface = reduced.front_surface();
    record(&PassIo {
        frame: &reduced.frame,
        sun_map: run.sun_map,
        hdr: &reduced.front,
        surface: &surface,
        has_surface: true,
        has_sea: false,
        ..*run.io
    });
    Ok(())
}
