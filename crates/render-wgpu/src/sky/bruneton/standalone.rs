//! Building the tables outside a `Renderer` frame: in one submission for the tests of the
//! tables, or one dispatch at a time for profiling the build.

use crate::frame::Frame;
use crate::frame::plan::{FramePlan, StepKind};
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::sky::bruneton::built::Built;
use crate::sky::bruneton::orders::{clear_orders, order_dispatches};
use crate::sky::bruneton::pass::BrunetonPass;
use crate::sky::bruneton::step::BrunetonStep;
use crate::sky::model_pass::{ModelPass, StandaloneInputs, StepContext};
use crate::sky::steps::{PassStep, PlannedStep, SkyPlan};

/// Waits for the GPU to finish its work.
fn wait(gpu: &GpuContext) -> Result<(), RenderError> {
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(GpuError::from)?;
    Ok(())
}

/// Records what `record` records in one submission, waits for the GPU, and returns the
/// wall-clock time in ms.
fn timed(
    gpu: &GpuContext,
    record: impl FnOnce(&mut wgpu::CommandEncoder),
) -> Result<f64, RenderError> {
    let start = std::time::Instant::now();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    record(&mut encoder);
    gpu.queue.submit([encoder.finish()]);
    wait(gpu)?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

impl BrunetonPass {
    /// Plans `frame` and builds the tables its plan lists, without rendering; returns
    /// the plan (for tests of the tables).
    pub fn build_tables(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
    ) -> Result<FramePlan, RenderError> {
        let plan = crate::sky::sky_pass::build_tables(self, gpu, frame)?;
        wait(gpu)?;
        Ok(plan)
    }

    /// Builds every table of `frame` (as if never built) one dispatch at a time, waiting
    /// for the GPU after each, and returns each step's wall-clock time in ms: the table
    /// steps by name, and the loop over orders per dispatch (`scattering_orders
    /// order 3 scattering`). For profiling the build: a CPU adapter such as lavapipe
    /// times its dispatches unreliably with timestamp queries.
    pub fn profile_build(
        &mut self,
        gpu: &GpuContext,
        frame: &Frame,
    ) -> Result<Vec<(String, f64)>, RenderError> {
        self.tables.built = Built::default();
        let mut plan = FramePlan::default();
        let mut steps = Vec::new();
        self.plan(&mut SkyPlan::new(gpu, frame, &mut plan, &mut steps))?;
        let inputs = StandaloneInputs::new(gpu, &self.frame.atmosphere_uniform, frame);
        let io = inputs.io();
        let mut times = Vec::new();
        wait(gpu)?;
        let table_builds = steps
            .into_iter()
            .map(|PlannedStep { step, .. }| step)
            .filter(|step| step.kind() == StepKind::TableBuild);
        for step in table_builds {
            if step != BrunetonStep::ScatteringOrders {
                let ms = timed(gpu, |encoder| {
                    let cx = StepContext {
                        gpu,
                        io: &io,
                        encoder,
                        timestamps: None,
                    };
                    self.encode(step, cx);
                })?;
                times.push((step.name().to_string(), ms));
                continue;
            }
            let (tables, planned) = (&self.tables, &self.frame);
            timed(gpu, |encoder| clear_orders(tables, encoder))?;
            for d in order_dispatches(gpu, &io, tables, &self.pipelines) {
                let ms = timed(gpu, |encoder| {
                    d.record(&mut encoder.begin_compute_pass(&Default::default()));
                })?;
                let name = format!("{} order {} {}", step.name(), d.share.order, d.name);
                times.push((name, ms));
            }
            self.tables.built.orders = Some((planned.atmosphere.clone(), planned.mie));
        }
        Ok(times)
    }
}
