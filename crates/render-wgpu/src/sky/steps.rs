//! A model's steps, typed: each model names its table builds and passes in an enum
//! ([`PassStep`]), plans them into a [`SkyPlan`], and encodes exactly the steps it
//! planned. The plan records each step twice: by name in the frame's
//! [`FramePlan`] (what the viewer shows and tests query) and as the typed step, with its
//! index in the frame's plan (its timer slot), in the list the model encodes.

use crate::frame::Frame;
use crate::frame::plan::{FramePlan, INPUTS_UNCHANGED, StepKind};
use crate::gpu::context::GpuContext;

/// One table build or pass of a model.
pub trait PassStep: Copy + std::fmt::Debug + Eq + 'static {
    /// The step's name in the frame's plan, like its shader or CPU twin (`g_l`, `nishita`).
    fn name(self) -> &'static str;
    /// Whether it builds a table or renders.
    fn kind(self) -> StepKind;
}

/// A step a frame runs, and its index in the frame's plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlannedStep<S> {
    pub index: u32,
    pub step: S,
}

/// The steps one model plans for a frame, and what it plans them with; see the module
/// documentation.
#[derive(Debug)]
pub struct SkyPlan<'a, S> {
    /// The GPU, for the tables a plan remakes and the uniforms it uploads.
    pub gpu: &'a GpuContext,
    /// The frame planned.
    pub frame: &'a Frame,
    record: &'a mut FramePlan,
    steps: &'a mut Vec<PlannedStep<S>>,
}

impl<'a, S: PassStep> SkyPlan<'a, S> {
    /// A plan of `frame` on `gpu`, adding to `record` (the frame's plan) and to `steps`.
    pub fn new(
        gpu: &'a GpuContext,
        frame: &'a Frame,
        record: &'a mut FramePlan,
        steps: &'a mut Vec<PlannedStep<S>>,
    ) -> Self {
        SkyPlan {
            gpu,
            frame,
            record,
            steps,
        }
    }

    /// Adds a step that runs.
    pub fn run(&mut self, step: S) {
        let index = self.record.steps.len() as u32;
        self.record.run(step.name(), step.kind());
        self.steps.push(PlannedStep { index, step });
    }

    /// Adds a table build when `stale`, else records it as skipped because its inputs did
    /// not change.
    pub fn build_if(&mut self, step: S, stale: bool) {
        if stale {
            self.run(step);
        } else {
            self.skip(step, INPUTS_UNCHANGED);
        }
    }

    /// Records a step left out and why.
    pub fn skip(&mut self, step: S, why: &'static str) {
        self.record.skip(step.name(), why);
    }

    /// Whether the frame's rays may end on a surface ([`FramePlan::surface`]).
    pub fn surface(&self) -> bool {
        self.record.surface
    }

    /// Whether the frame's sun map shades the air ([`FramePlan::cloud_shafts`]).
    pub fn cloud_shafts(&self) -> bool {
        self.record.cloud_shafts
    }

    /// What a progressive table build is doing this frame ([`FramePlan::building`]).
    pub fn set_building(&mut self, building: Option<String>) {
        self.record.building = building;
    }
}
