//! The pipelines of one cloud spheres shader, one per light (`SPHERE_LIGHT` in
//! `shaders/clouds/spheres/shade.wgsl`): the octaves, delta-Eddington's slab or the
//! four-stream slab, after the layer's method (`slab_light.rs`). Each pipeline holds one
//! light's code, as the layer's march variants do (`march_variants.rs`: on a software
//! rasteriser a shader with every light made each sample dearer); a variant is compiled
//! the first time a frame asks for it.

use std::sync::OnceLock;

use atmosphere_core::clouds::layer::settings::LayerMethod;

use crate::gpu::context::GpuContext;
use crate::gpu::error::GpuError;
use crate::gpu::pipeline::ComputePipeline;

/// One entry point of one spheres shader, compiled lazily per light.
#[derive(Debug)]
pub struct SphereVariants {
    shader: &'static str,
    entry: &'static str,
    label: &'static str,
    entries: Vec<wgpu::BindGroupLayoutEntry>,
    built: [OnceLock<ComputePipeline>; 3],
}

/// The light code and pipeline slot of the layer's `method`: the slab methods light the
/// spheres by their slab, the others by the octaves.
fn light_of(method: LayerMethod) -> (u32, usize) {
    match method {
        LayerMethod::Riley | LayerMethod::Octaves => (0, 0),
        LayerMethod::Eddington => (2, 1),
        LayerMethod::FourStream => (3, 2),
    }
}

impl SphereVariants {
    /// The variants of `shader`'s entry point `entry` with one bind group of `entries`;
    /// the octaves' is compiled now, so that a shader error shows at once.
    pub fn new(
        gpu: &GpuContext,
        shader_entry: (&'static str, &'static str),
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> Result<SphereVariants, GpuError> {
        let variants = SphereVariants::lazy(shader_entry, label, entries);
        variants.for_method(gpu, LayerMethod::Octaves)?;
        Ok(variants)
    }

    /// The same with none compiled yet: for an entry point of a shader whose other entry
    /// point is compiled at once, which only some frames take.
    pub fn lazy(
        (shader, entry): (&'static str, &'static str),
        label: &'static str,
        entries: &[wgpu::BindGroupLayoutEntry],
    ) -> SphereVariants {
        SphereVariants {
            shader,
            entry,
            label,
            entries: entries.to_vec(),
            built: Default::default(),
        }
    }

    /// The pipeline lighting the spheres as the layer's `method` does.
    pub fn for_method(
        &self,
        gpu: &GpuContext,
        method: LayerMethod,
    ) -> Result<&ComputePipeline, GpuError> {
        let (light, slot) = light_of(method);
        if let Some(pipeline) = self.built[slot].get() {
            return Ok(pipeline);
        }
        let pipeline = ComputePipeline::with_constants(
            gpu,
            self.shader,
            self.entry,
            self.label,
            &self.entries,
            &[("SPHERE_LIGHT", f64::from(light))],
        )?;
        Ok(self.built[slot].get_or_init(|| pipeline))
    }
}
