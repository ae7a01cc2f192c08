//! The beam methods on the GPU, by their one id ([`BeamMethodId`]): the frame's plan
//! (atmosphere-core's `beams/plan.rs`: no work for a light that cannot reach the
//! visible air), then each method prepared on the CPU (its shadow maps, planes and
//! tables) for the lights drawn and packed without a device, then rendered by its pass.

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::march::March;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::planes2000::Planes2000;
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::plan::BeamPlan;
use atmosphere_core::beams::scene::BeamScene;

use crate::gpu::context::GpuContext;
use crate::gpu::error::RenderError;
use crate::shafts::beams::gpu_scene::GpuScene;
use crate::shafts::beams::image::BeamImage;
use crate::shafts::beams::limits::check_trips;
use crate::shafts::beams::march_pass::MarchPass;
use crate::shafts::beams::planes_pass::{GpuPlanes, PlanesPass};
use crate::shafts::beams::qtable_pass::{GpuQtable, QtablePass};

/// The beam methods the GPU renders.
pub const GPU_BEAM_METHODS: [BeamMethodId; 3] = [
    BeamMethodId::March,
    BeamMethodId::Planes2000,
    BeamMethodId::Qtable2002,
];

/// A beams scene packed for one method's pass.
#[derive(Clone, Debug, PartialEq)]
pub enum PackedBeams {
    March(GpuScene),
    Planes2000(GpuPlanes),
    Qtable2002(GpuQtable),
}

/// A beams scene planned, prepared and packed for one method's pass.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedBeams {
    /// Which lights the frame draws and why the others are skipped.
    pub plan: BeamPlan,
    pub packed: PackedBeams,
}

impl PreparedBeams {
    /// `scene` planned and prepared for method `id` with `settings` (three
    /// wavelengths); an error naming the method where it is not on the GPU.
    pub fn new(
        id: BeamMethodId,
        scene: &BeamScene,
        settings: &BeamSettings,
    ) -> Result<PreparedBeams, RenderError> {
        let plan = BeamPlan::new(scene, &settings.wavelengths_nm);
        let prepared = PreparedBeams {
            packed: PackedBeams::new(id, &plan.pruned(scene), settings)?,
            plan,
        };
        prepared.packed.check_trips()?;
        Ok(prepared)
    }

    /// The pass that renders it on `gpu`, made.
    pub fn renderer(self, gpu: &GpuContext) -> Result<BeamRenderer, RenderError> {
        self.packed.renderer(gpu)
    }
}

impl PackedBeams {
    /// `scene`, every light of it, prepared for method `id` with `settings`.
    pub fn new(
        id: BeamMethodId,
        scene: &BeamScene,
        settings: &BeamSettings,
    ) -> Result<PackedBeams, RenderError> {
        Ok(match id {
            BeamMethodId::March => PackedBeams::March(GpuScene::new(&March::new(scene, settings)?)),
            BeamMethodId::Planes2000 => {
                PackedBeams::Planes2000(GpuPlanes::new(&Planes2000::new(scene, settings)?))
            }
            BeamMethodId::Qtable2002 => {
                PackedBeams::Qtable2002(GpuQtable::new(&Qtable2002::new(scene, settings)?))
            }
            BeamMethodId::Reference => {
                return Err(RenderError::Unsupported(format!(
                    "beam method {id} (beam methods on the GPU: {})",
                    BeamMethodId::list(&GPU_BEAM_METHODS)
                )));
            }
        })
    }

    /// The packed scene, which every method has.
    pub fn scene(&self) -> &GpuScene {
        match self {
            PackedBeams::March(scene) => scene,
            PackedBeams::Planes2000(planes) => &planes.scene,
            PackedBeams::Qtable2002(qtable) => &qtable.scene,
        }
    }

    /// Nothing, or an error naming the loops that exceed what one invocation may run
    /// (no device needed).
    pub fn check_trips(&self) -> Result<(), RenderError> {
        check_trips(self.scene())
    }

    /// The pass that renders it on `gpu`, made.
    pub fn renderer(self, gpu: &GpuContext) -> Result<BeamRenderer, RenderError> {
        Ok(match self {
            PackedBeams::March(scene) => BeamRenderer::March(MarchPass::new(gpu)?, scene),
            PackedBeams::Planes2000(planes) => {
                BeamRenderer::Planes2000(PlanesPass::new(gpu)?, planes)
            }
            PackedBeams::Qtable2002(qtable) => {
                BeamRenderer::Qtable2002(QtablePass::new(gpu)?, qtable)
            }
        })
    }
}

/// A prepared scene with its pass.
#[derive(Debug)]
pub enum BeamRenderer {
    March(MarchPass, GpuScene),
    Planes2000(PlanesPass, GpuPlanes),
    Qtable2002(QtablePass, GpuQtable),
}

impl BeamRenderer {
    /// One frame; its GPU time in milliseconds where the device has timestamps.
    pub fn render(&self, gpu: &GpuContext) -> Result<(BeamImage, Option<f64>), RenderError> {
        match self {
            BeamRenderer::March(pass, scene) => pass.render(gpu, scene),
            BeamRenderer::Planes2000(pass, planes) => pass.render(gpu, planes),
            BeamRenderer::Qtable2002(pass, qtable) => pass.render(gpu, qtable),
        }
    }
}

/// The passes of the methods on the GPU, each made the first time its method renders:
/// an interactive view re-prepares its scene as it changes without remaking pipelines.
#[derive(Debug, Default)]
pub struct BeamPasses {
    march: Option<MarchPass>,
    planes: Option<PlanesPass>,
    qtable: Option<QtablePass>,
}

impl BeamPasses {
    /// One frame of `packed` by its method's pass (made now if it was not); its GPU
    /// time in milliseconds where the device has timestamps. The same image as
    /// [`BeamRenderer::render`] of the same packing.
    pub fn render(
        &mut self,
        gpu: &GpuContext,
        packed: &PackedBeams,
    ) -> Result<(BeamImage, Option<f64>), RenderError> {
        match packed {
            PackedBeams::March(scene) => {
                made(&mut self.march, || MarchPass::new(gpu))?.render(gpu, scene)
            }
            PackedBeams::Planes2000(planes) => {
                made(&mut self.planes, || PlanesPass::new(gpu))?.render(gpu, planes)
            }
            PackedBeams::Qtable2002(qtable) => {
                made(&mut self.qtable, || QtablePass::new(gpu))?.render(gpu, qtable)
            }
        }
    }
}

/// The pass in `slot`, made by `make` where there is none yet.
fn made<P, E>(slot: &mut Option<P>, make: impl FnOnce() -> Result<P, E>) -> Result<&P, E> {
    Ok(match slot {
        Some(pass) => pass,
        None => slot.insert(make()?),
    })
}
