//! The pipelines of one entry point that marches the cloud layer, one per light method,
//! sun light and whether the shadow march reads detail noise:
//! `shaders/clouds/layer_march.wgsl` takes them as pipeline-overridable constants
//! (`LAYER_METHOD`, `SUN_FROM_MAP`, `SHADOW_DETAIL`) so that each pipeline holds the code
//! of one case. A software rasteriser (lavapipe) runs every branch some lane of a SIMD
//! group takes and allocates registers for all the code compiled in, so one shader with
//! every method in it made each sample dearer (docs/clouds.md, "What brought it within
//! the target"). A variant is compiled the first time a pass asks for it: most frames
//! use one.

use std::sync::OnceLock;

use crate::clouds::layer_uniform::LayerUniform;
use crate::gpu::context::GpuContext;
use crate::gpu::error::{GpuError, RenderError};
use crate::gpu::pipeline::ComputePipeline;

/// The methods (riley, octaves, eddington, four-stream) times the sun's lights (march,
/// map) times the shadow march with and without noise.
const VARIANTS: usize = 4 * 2 * 2;

/// Entry point `main` of one march shader, compiled lazily per case.
#[derive(Debug)]
pub struct MarchVariants {
    shader: &'static str,
    label: &'static str,
    entries: Vec<wgpu::BindGroupLayoutEntry>,
    /// Constants every variant of this entry point takes alike.
    fixed: Vec<(&'static str, f64)>,
    built: [OnceLock<ComputePipeline>; VARIANTS],
}

impl MarchVariants {
    /// The variants of `shader`'s `main` with one bind group of `entries`; none is
    /// compiled yet.
    pub fn new(
        shader: &'static str,
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> MarchVariants {
        MarchVariants {
            shader,
            label,
            entries: entries.to_vec(),
            fixed: Vec::new(),
            built: Default::default(),
        }
    }

    /// These variants with the pipeline-overridable constant `name` at `value` in each.
    pub fn with_constant(mut self, name: &'static str, value: f64) -> MarchVariants {
        self.fixed.push((name, value));
        self
    }

    /// The pipeline for the method (`counts[2]`), sun light (`noise[3]`) and shadow
    /// octaves (`noise[1]`) of `params`, compiled on first use; an error names a method
    /// or light outside its range.
    pub fn for_params(
        &self,
        gpu: &GpuContext,
        params: &LayerUniform,
    ) -> Result<&ComputePipeline, RenderError> {
        let (method, map) = (params.counts[2], params.noise[3]);
        if method > 3 || map > 1 {
            return Err(RenderError::Frame(format!(
                "{}: light method {method} (0..=3) or sun light {map} (0..=1) out of range",
                self.label
            )));
        }
        let detail = params.noise[1] > 0;
        let slot = &self.built[((method * 2 + map) * 2 + u32::from(detail)) as usize];
        if let Some(pipeline) = slot.get() {
            return Ok(pipeline);
        }
        let pipeline = self.compile(gpu, method, map == 1, detail)?;
        Ok(slot.get_or_init(|| pipeline))
    }

    fn compile(
        &self,
        gpu: &GpuContext,
        method: u32,
        from_map: bool,
        shadow_detail: bool,
    ) -> Result<ComputePipeline, GpuError> {
        ComputePipeline::with_constants(
            gpu,
            self.shader,
            "main",
            self.label,
            &self.entries,
            &[
                ("LAYER_METHOD", f64::from(method)),
                ("SUN_FROM_MAP", f64::from(u8::from(from_map))),
                ("SHADOW_DETAIL", f64::from(u8::from(shadow_detail))),
            ]
            .into_iter()
            .chain(self.fixed.iter().copied())
            .collect::<Vec<_>>(),
        )
    }
}
