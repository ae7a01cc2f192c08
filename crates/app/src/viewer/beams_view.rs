//! A beams scene rendered for the viewer, without a window: the scene planned and
//! prepared for its method (atmosphere-core's `beams/plan.rs`, then the method's shadow
//! maps, planes and tables on the CPU) only when the scene, the camera, the size, the
//! method or its settings changed; its pass's pipelines made once per method
//! ([`BeamPasses`]); the image rendered only when re-prepared and tone-mapped only when
//! it or the exposure changed. The image and its exposure are those of
//! `atmos render --scene` (`render/beams.rs`) for the same scene and camera.

use std::time::Instant;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::scene::BeamScene;
use render_wgpu::GpuContext;
use render_wgpu::shafts::beams::gpu_methods::{BeamPasses, PackedBeams, PreparedBeams};
use render_wgpu::shafts::beams::image::BeamImage;
use render_wgpu::shafts::beams::qtable_pass::QtablePlanes;

use crate::render::beams::exposure_ev100;

/// What one frame was made of, for the panel's statistics.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BeamsStats {
    /// The planner's decision per light (`lights[0] drawn, lights[1] skipped (...)`).
    pub plan: String,
    /// The method's steps on the GPU and what they draw.
    pub steps: String,
    /// Wall time of the last preparation on the CPU (plan, shadow maps, planes, tables), ms.
    pub prepare_ms: f64,
    /// GPU time of the last render, ms, where the device has timestamps.
    pub gpu_ms: Option<f64>,
    /// The exposure of the image shown.
    pub ev100: f64,
}

/// A displayed frame: sRGB pixels (alpha 255) row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamsPixels {
    pub size: (u32, u32),
    pub pixels: Vec<[u8; 4]>,
}

/// What a preparation was made from.
#[derive(Clone, Debug, PartialEq)]
struct Key {
    scene: BeamScene,
    method: BeamMethodId,
    settings: BeamSettings,
}

/// The viewer's beams renderer; see the module documentation.
#[derive(Debug, Default)]
pub struct BeamsView {
    passes: BeamPasses,
    prepared: Option<(Key, PreparedBeams)>,
    /// The last preparation that failed and its error, not retried until its key changes.
    failed: Option<(Key, String)>,
    image: Option<(BeamImage, Vec<[f32; 4]>)>,
    /// The exposure asked for when the pixels shown were tone-mapped.
    shown_exposure: Option<Option<f64>>,
    pub stats: BeamsStats,
}

impl BeamsView {
    /// The frame of `scene` (its camera and size as given) by `method` with `settings`
    /// at `exposure` (metered as `atmos render` meters where `None`); `None` where the
    /// pixels shown are still right.
    pub fn render(
        &mut self,
        gpu: &GpuContext,
        scene: &BeamScene,
        method: BeamMethodId,
        settings: &BeamSettings,
        exposure: Option<f64>,
    ) -> anyhow::Result<Option<BeamsPixels>> {
        let key = Key {
            scene: scene.clone(),
            method,
            settings: settings.clone(),
        };
        if let Some((failed, error)) = &self.failed
            && *failed == key
        {
            anyhow::bail!("{error}");
        }
        if self.prepared.as_ref().is_none_or(|(k, _)| *k != key) {
            // A failed preparation leaves nothing stale behind to be shown as current.
            self.prepared = None;
            self.image = None;
            let start = Instant::now();
            let prepared = match PreparedBeams::new(method, scene, settings) {
                Ok(prepared) => prepared,
                Err(e) => {
                    let error = e.to_string();
                    self.failed = Some((key, error.clone()));
                    anyhow::bail!("{error}");
                }
            };
            self.failed = None;
            self.stats.prepare_ms = start.elapsed().as_secs_f64() * 1e3;
            self.stats.plan = prepared.plan.to_string();
            self.stats.steps = steps(&prepared.packed);
            self.prepared = Some((key, prepared));
        }
        if self.image.is_none() {
            self.shown_exposure = None;
            if let Some((key, prepared)) = &self.prepared {
                let rendered = self
                    .passes
                    .render(gpu, &prepared.packed)
                    .and_then(|(image, ms)| Ok((image.read_radiance(gpu)?, image, ms)));
                match rendered {
                    Ok((radiance, image, gpu_ms)) => {
                        self.stats.gpu_ms = gpu_ms;
                        self.image = Some((image, radiance));
                    }
                    Err(e) => {
                        let error = e.to_string();
                        self.failed = Some((key.clone(), error.clone()));
                        self.prepared = None;
                        anyhow::bail!("{error}");
                    }
                }
            }
        }
        if self.shown_exposure == Some(exposure) {
            return Ok(None);
        }
        let Some((image, radiance)) = &self.image else {
            return Ok(None);
        };
        let ev100 = exposure_ev100(exposure, radiance)?;
        let pixels = image.tone_mapped(gpu, ev100)?;
        self.stats.ev100 = ev100;
        self.shown_exposure = Some(exposure);
        Ok(Some(BeamsPixels {
            size: (image.radiance.width(), image.radiance.height()),
            pixels,
        }))
    }
}

/// The passes of a packed method and what they draw.
fn steps(packed: &PackedBeams) -> String {
    match packed {
        PackedBeams::March(scene) => {
            let [w, h, steps, lights] = scene.uniform.size_steps_lights;
            format!("march: {w}x{h} rays, {steps} steps, {lights} lights drawn")
        }
        PackedBeams::Planes2000(planes) => {
            let [count, n, lights, _] = planes.planes.planes_lattice_lights;
            format!(
                "ray end, then {count} planes x {lights} lights drawn, lattices of {n}x{n} points"
            )
        }
        PackedBeams::Qtable2002(qtable) => {
            let [nu, nv, ..] = qtable.uniform.nodes;
            let drawn = match qtable.planes {
                QtablePlanes::Raster(_) => "drawn one by one",
                QtablePlanes::PerPixel(_) => "walked per pixel",
            };
            format!(
                "ray end, then {} planes ({} of them sub-planes) {drawn}, q table {nu}x{nv}",
                qtable.plane_count(),
                qtable.subplane_count()
            )
        }
    }
}
