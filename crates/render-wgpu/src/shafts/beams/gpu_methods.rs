//! The beam methods on the GPU, by their one id ([`BeamMethodId`]): each prepared on the
//! CPU (its shadow maps, planes and tables) and packed without a device, then rendered
//! by its pass.

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::march::March;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::planes2000::Planes2000;
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
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

/// A beams scene prepared and packed for one method's pass.
#[derive(Clone, Debug, PartialEq)]
pub enum PreparedBeams {
    March(GpuScene),
    Planes2000(GpuPlanes),
    Qtable2002(GpuQtable),
}

impl PreparedBeams {
    /// `scene` prepared for method `id` with `settings` (three wavelengths); an error
    /// naming the method where it is not on the GPU.
    pub fn new(
        id: BeamMethodId,
        scene: &BeamScene,
        settings: &BeamSettings,
    ) -> Result<PreparedBeams, RenderError> {
        let prepared = match id {
            BeamMethodId::March => {
                PreparedBeams::March(GpuScene::new(&March::new(scene, settings)?))
            }
            BeamMethodId::Planes2000 => {
                PreparedBeams::Planes2000(GpuPlanes::new(&Planes2000::new(scene, settings)?))
            }
            BeamMethodId::Qtable2002 => {
                PreparedBeams::Qtable2002(GpuQtable::new(&Qtable2002::new(scene, settings)?))
            }
            BeamMethodId::Reference => {
                return Err(RenderError::Unsupported(format!(
                    "beam method {id} (beam methods on the GPU: {})",
                    BeamMethodId::list(&GPU_BEAM_METHODS)
                )));
            }
        };
        prepared.check_trips()?;
        Ok(prepared)
    }

    /// The packed scene, which every method has.
    pub fn scene(&self) -> &GpuScene {
        match self {
            PreparedBeams::March(scene) => scene,
            PreparedBeams::Planes2000(planes) => &planes.scene,
            PreparedBeams::Qtable2002(qtable) => &qtable.scene,
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
            PreparedBeams::March(scene) => BeamRenderer::March(MarchPass::new(gpu)?, scene),
            PreparedBeams::Planes2000(planes) => {
                BeamRenderer::Planes2000(PlanesPass::new(gpu)?, planes)
            }
            PreparedBeams::Qtable2002(qtable) => {
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
