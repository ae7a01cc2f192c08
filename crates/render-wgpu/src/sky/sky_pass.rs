//! The sky model of a frame as the renderer sees it ([`SkyPass`]): it plans its steps into
//! the frame's plan, then encodes the steps it planned, in order, each timed in the slot of
//! its index in the frame's plan. [`Planned`] runs a [`ModelPass`].

use crate::frame::Frame;
use crate::frame::plan::{FramePlan, StepKind};
use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::gpu::timer::GpuTimer;
use crate::sky::model_pass::{ModelPass, PassIo, StandaloneInputs, StepContext, frame_atmosphere};
use crate::sky::steps::{PassStep, PlannedStep, SkyPlan};

/// A sky model behind one object-safe interface; see the module documentation.
pub trait SkyPass: std::fmt::Debug {
    /// Adds the model's steps for `frame` to `plan` ([`ModelPass::plan`]).
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError>;

    /// Records the steps the last [`SkyPass::plan`] added, in order, into `frame`.
    fn encode_planned(&mut self, frame: &mut FrameRecorder<'_>);

    /// Records again only the passes (no table builds) the last [`SkyPass::plan`] added,
    /// into `frame`, whose `io` may hold another target and surface (the cloud's entry:
    /// `crate::clouds::frame_pass`); timed together in the plan's slot `slot`.
    fn encode_passes(&mut self, frame: &mut FrameRecorder<'_>, slot: u32);

    /// [`ModelPass::set_progressive`].
    fn set_progressive(&mut self, on: bool);

    /// [`ModelPass::table_bytes`].
    fn table_bytes(&self) -> u64;
}

/// Where a frame's steps record their work: the GPU, what they read and write
/// ([`PassIo`]), the frame's command encoder, and the timer of the frame's steps, when
/// timed.
#[derive(Debug)]
pub struct FrameRecorder<'a> {
    pub gpu: &'a GpuContext,
    pub io: &'a PassIo<'a>,
    pub encoder: &'a mut wgpu::CommandEncoder,
    pub timer: Option<&'a GpuTimer>,
}

impl FrameRecorder<'_> {
    /// Where the step at `index` in the frame's plan records, timed in that slot.
    pub fn step(&mut self, index: u32) -> StepContext<'_> {
        StepContext {
            gpu: self.gpu,
            io: self.io,
            encoder: self.encoder,
            timestamps: self.timer.map(|t| t.compute_writes(index)),
        }
    }
}

/// A [`ModelPass`] and the steps it planned for the frame.
#[derive(Debug)]
pub struct Planned<M: ModelPass> {
    model: M,
    steps: Vec<PlannedStep<M::Step>>,
}

impl<M: ModelPass> Planned<M> {
    pub fn new(model: M) -> Planned<M> {
        Planned {
            model,
            steps: Vec::new(),
        }
    }
}

impl<M: ModelPass> SkyPass for Planned<M> {
    fn plan(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
        plan: &mut FramePlan,
    ) -> Result<(), RenderError> {
        self.steps.clear();
        self.model
            .plan(&mut SkyPlan::new(gpu, frame, plan, &mut self.steps))
    }

    fn encode_planned(&mut self, frame: &mut FrameRecorder<'_>) {
        for &PlannedStep { index, step } in &self.steps {
            self.model.encode(step, frame.step(index));
        }
    }

    fn encode_passes(&mut self, frame: &mut FrameRecorder<'_>, slot: u32) {
        let passes: Vec<M::Step> = self
            .steps
            .iter()
            .map(|s| s.step)
            .filter(|s| s.kind() == StepKind::Pass)
            .collect();
        let last = passes.len().saturating_sub(1);
        for (i, step) in passes.into_iter().enumerate() {
            // The first pass writes the slot's start, the last its end.
            let timestamps = frame.timer.map(|t| {
                let mut writes = t.compute_writes(slot);
                if i > 0 {
                    writes.beginning_of_pass_write_index = None;
                }
                if i < last {
                    writes.end_of_pass_write_index = None;
                }
                writes
            });
            self.model.encode(
                step,
                StepContext {
                    gpu: frame.gpu,
                    io: frame.io,
                    encoder: frame.encoder,
                    timestamps,
                },
            );
        }
    }

    fn set_progressive(&mut self, on: bool) {
        self.model.set_progressive(on);
    }

    fn table_bytes(&self) -> u64 {
        self.model.table_bytes()
    }
}

/// Plans `frame` with `model` and builds the tables its plan lists, without rendering
/// (to have them ready before a first frame, or to read them back); returns that plan,
/// less the passes.
pub fn build_tables<M: ModelPass>(
    model: &mut M,
    gpu: &GpuContext,
    frame: &Frame,
) -> Result<FramePlan, RenderError> {
    frame.validate()?;
    let mut plan = FramePlan::default();
    let mut steps = Vec::new();
    model.plan(&mut SkyPlan::new(gpu, frame, &mut plan, &mut steps))?;
    plan.steps.retain(|s| s.kind == StepKind::TableBuild);
    let atmosphere = frame_atmosphere(frame)?;
    let inputs = StandaloneInputs::new(gpu, &atmosphere, frame);
    let io = inputs.io();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let mut recorder = FrameRecorder {
        gpu,
        io: &io,
        encoder: &mut encoder,
        timer: None,
    };
    for PlannedStep { index, step } in steps {
        if step.kind() == StepKind::TableBuild {
            model.encode(step, recorder.step(index));
        }
    }
    gpu.queue.submit([encoder.finish()]);
    Ok(plan)
}
