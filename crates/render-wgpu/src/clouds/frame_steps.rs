//! The cloud steps of a renderer frame after the model's pixel passes, in order: the
//! model's second run in front of the cloud (`frame_front.rs`) first where it is reduced,
//! since it then needs nothing the cloud writes and the spheres' upsample may composite
//! over it; the layer's march and the spheres (`frame_pass.rs`); the second run where it
//! takes every pixel, ended on the entries the cloud wrote; and the composite, unless an
//! upsample did it (`frame_clouds.rs`'s `CloudSteps`).

use crate::clouds::cloud_targets::CloudTargets;
use crate::clouds::frame_clouds::CloudSteps;
use crate::clouds::frame_front::{FrontRun, encode_front};
use crate::clouds::frame_pass::{CloudFramePass, MarchScene};
use crate::frame::uniform::FrameUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::timer::GpuTimer;
use crate::sky::model_pass::PassIo;
use crate::sky::sky_pass::SkyPass;

/// What the cloud steps after the model's passes read and write.
#[derive(Debug)]
pub struct AfterModel<'a> {
    pub pass: &'a CloudFramePass,
    pub scene: &'a MarchScene<'a>,
    pub targets: &'a CloudTargets,
    /// The model passes' inputs and outputs, and the frame's uniform (the second run's).
    pub io: &'a PassIo<'a>,
    pub uniform: FrameUniform,
    /// The planned steps and the plan's slots of the second run and the composite
    /// (`frame_clouds.rs`'s `plan_after_model`).
    pub steps: (CloudSteps, Option<u32>, Option<u32>),
}

/// Records the cloud steps of `after` with `model`'s second run, each timed by `timer`
/// in its plan's slot.
pub fn encode_after_model(
    model: &mut dyn SkyPass,
    gpu: &GpuContext,
    (encoder, timer): (&mut wgpu::CommandEncoder, Option<&GpuTimer>),
    after: &AfterModel<'_>,
) -> Result<(), RenderError> {
    let (steps, front, composite) = after.steps;
    let run = FrontRun {
        io: after.io,
        uniform: after.uniform,
        scene: after.scene,
        targets: after.targets,
        pass: after.pass,
        divisor: steps.front_divisor,
    };
    let front_first = steps.front_divisor > 1;
    if let (Some(step), true) = (front, front_first) {
        encode_front(model, gpu, (encoder, timer), &run, step)?;
    }
    let targets = after.targets;
    (after.pass).encode_clouds(gpu, encoder, after.scene, targets, (&steps, timer))?;
    if let (Some(step), false) = (front, front_first) {
        encode_front(model, gpu, (encoder, timer), &run, step)?;
    }
    if let Some(slot) = composite {
        after.pass.encode_composite(
            gpu,
            encoder,
            after.scene.uniforms,
            (targets, &steps),
            after.scene.hdr,
            timer.map(|t| t.compute_writes(slot)),
        )?;
    }
    Ok(())
}
