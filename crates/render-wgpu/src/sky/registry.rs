//! The sky models the GPU renders and the factory that makes their passes.

use atmosphere_core::models::id::ModelId;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::sky::bruneton::pass::BrunetonPass;
use crate::sky::dobashi::DobashiPass;
use crate::sky::hillaire::HillairePass;
use crate::sky::nishita::NishitaPass;
use crate::sky::oneil::OneilPass;
use crate::sky::riley::RileyPass;
use crate::sky::sky_pass::{Planned, SkyPass};

/// The models the GPU renders: every model but the reference.
pub const GPU_MODELS: [ModelId; 6] = {
    let [reference, on_gpu @ ..] = ModelId::ALL;
    assert!(matches!(reference, ModelId::Reference));
    on_gpu
};

/// Whether model `id` can be rendered: an error naming it when it is not on the GPU (no
/// model silently stands in for another).
pub fn check_model(id: ModelId) -> Result<(), RenderError> {
    if GPU_MODELS.contains(&id) {
        Ok(())
    } else {
        Err(not_on_gpu(id))
    }
}

fn not_on_gpu(id: ModelId) -> RenderError {
    RenderError::NotOnGpu {
        model: id,
        on_gpu: ModelId::list(&GPU_MODELS),
    }
}

/// The GPU twin of model `id`, its pipelines compiled, no table built yet.
pub fn create(id: ModelId, gpu: &GpuContext) -> Result<Box<dyn SkyPass>, RenderError> {
    Ok(match id {
        ModelId::Bruneton => Box::new(Planned::new(BrunetonPass::new(gpu)?)),
        ModelId::Dobashi => Box::new(Planned::new(DobashiPass::new(gpu)?)),
        ModelId::Hillaire => Box::new(Planned::new(HillairePass::new(gpu)?)),
        ModelId::Nishita => Box::new(Planned::new(NishitaPass::new(gpu)?)),
        ModelId::Oneil => Box::new(Planned::new(OneilPass::new(gpu)?)),
        ModelId::Riley => Box::new(Planned::new(RileyPass::new(gpu)?)),
        ModelId::Reference => return Err(not_on_gpu(id)),
    })
}
