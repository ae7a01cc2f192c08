//! The viewer's rain, cirrus and droplet deck on the renderer: the volumes of the
//! panel's settings, made (phase tables from the table cache or built, the light from
//! the frame's model on the CPU) when the settings, the model, the atmosphere or the sun
//! change, and kept while the camera moves: the shaft stays where it was placed. The sun
//! counts as changed once it has moved by [`SUN_TOLERANCE_DEG`], so a running sun clock
//! or a sun that follows the camera's place does not make the volumes again every frame.
//!
//! A table takes seconds to minutes to build, so the volumes are made on a worker
//! thread: the settings are checked at once (a bad value is named before anything is
//! built), the frames meanwhile draw the volumes made before (or none), and the new ones
//! are swapped in on the first frame after they are ready. A change while a build runs
//! supersedes it: its result is dropped when it arrives.

use std::sync::mpsc::{Receiver, TryRecvError, channel};

use anyhow::{Context, anyhow};
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use glam::DVec3;
use render_wgpu::{Frame, Renderer};

use crate::viewer::optics_settings::OpticsSettings;

/// How far the sun may move, in degrees, before the volumes are made again: half the
/// sun's apparent diameter (0.53 degrees), well inside the bows' and halos' widths.
pub const SUN_TOLERANCE_DEG: f64 = 0.25;

/// What the renderer's volumes were made for.
#[derive(Clone, Debug, PartialEq)]
struct MadeFor {
    settings: OpticsSettings,
    model: ModelId,
    atmosphere: Atmosphere,
    model_settings: ModelSettings,
    sun_direction: DVec3,
}

impl MadeFor {
    /// Whether volumes made for `self` still serve `wanted`: everything equal but the
    /// sun, which may have moved by up to [`SUN_TOLERANCE_DEG`].
    fn serves(&self, wanted: &MadeFor) -> bool {
        let moved_deg = self
            .sun_direction
            .normalize()
            .dot(wanted.sun_direction.normalize())
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        self.settings == wanted.settings
            && self.model == wanted.model
            && self.atmosphere == wanted.atmosphere
            && self.model_settings == wanted.model_settings
            && moved_deg <= SUN_TOLERANCE_DEG
    }
}

/// A build on the worker thread, by what it is for.
#[derive(Debug)]
struct Pending {
    made_for: MadeFor,
    result: Receiver<anyhow::Result<Vec<LitVolume>>>,
}

/// The volumes given to the renderer, by what they were made for, and the build under
/// way.
#[derive(Debug, Default)]
pub struct OpticsState {
    made_for: Option<MadeFor>,
    pending: Option<Pending>,
    /// The last build that failed, and its error, so that it is not started again
    /// every frame.
    failed: Option<(MadeFor, String)>,
}

impl OpticsState {
    /// Gives `renderer` the volumes of `settings` for `frame` (none when all are off):
    /// starts their build on a worker thread when they are not made for these yet,
    /// and swaps them in once it has finished. Returns whether the renderer's volumes
    /// were replaced. An error names the setting at fault, and the renderer then holds
    /// none.
    pub fn apply(
        &mut self,
        renderer: &mut Renderer,
        frame: &Frame,
        settings: &OpticsSettings,
    ) -> anyhow::Result<bool> {
        renderer.set_volumes_divisor(settings.resolution_divisor)?;
        let wanted = MadeFor {
            // The divisor is the renderer's, not the volumes': changing it builds nothing.
            settings: OpticsSettings {
                resolution_divisor: 1,
                ..settings.clone()
            },
            model: frame.model,
            atmosphere: frame.atmosphere.clone(),
            model_settings: frame.settings.clone(),
            sun_direction: frame.sun_direction,
        };
        if !settings.any() {
            self.pending = None;
            let replaced = self.made_for.take().is_some();
            renderer.set_volumes(Vec::new())?;
            return Ok(replaced);
        }
        if self
            .made_for
            .as_ref()
            .is_some_and(|made| made.serves(&wanted))
        {
            self.pending = None;
            return Ok(false);
        }
        if let Some((failed, error)) = &self.failed
            && failed.serves(&wanted)
        {
            return Err(anyhow!("{error}"));
        }
        if !self
            .pending
            .as_ref()
            .is_some_and(|p| p.made_for.serves(&wanted))
        {
            if let Err(e) = settings.flags().volumes(frame) {
                self.pending = None;
                self.made_for = None;
                renderer.set_volumes(Vec::new())?;
                return Err(e);
            }
            self.pending = Some(spawn_build(wanted, settings, frame)?);
        }
        self.poll(renderer)
    }

    /// Whether a build is under way (its volumes not yet given to the renderer).
    pub fn building(&self) -> bool {
        self.pending.is_some()
    }

    /// Swaps in the pending build's volumes if it has finished.
    fn poll(&mut self, renderer: &mut Renderer) -> anyhow::Result<bool> {
        let Some(pending) = &self.pending else {
            return Ok(false);
        };
        let result = match pending.result.try_recv() {
            Ok(result) => result,
            Err(TryRecvError::Empty) => return Ok(false),
            Err(TryRecvError::Disconnected) => Err(anyhow!("the optics tables' worker stopped")),
        };
        let Some(pending) = self.pending.take() else {
            return Ok(false);
        };
        self.made_for = None;
        match result {
            Ok(volumes) => {
                renderer.set_volumes(volumes)?;
                self.made_for = Some(pending.made_for);
                self.failed = None;
                Ok(true)
            }
            Err(e) => {
                renderer.set_volumes(Vec::new())?;
                self.failed = Some((pending.made_for, format!("{e:#}")));
                Err(e)
            }
        }
    }
}

/// Starts building the volumes of `settings` for `frame` on a worker thread.
fn spawn_build(
    made_for: MadeFor,
    settings: &OpticsSettings,
    frame: &Frame,
) -> anyhow::Result<Pending> {
    let (sender, result) = channel();
    let (flags, frame) = (settings.flags(), frame.clone());
    std::thread::Builder::new()
        .name("optics tables".into())
        .spawn(move || {
            // A superseded build's receiver is gone: its result is dropped.
            let _ = sender.send(flags.lit_volumes(&frame));
        })
        .context("cannot start the optics tables' worker thread")?;
    Ok(Pending { made_for, result })
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmosphere_core::atmosphere::presets;

    fn made_for(sun_elevation_deg: f64) -> MadeFor {
        let e = sun_elevation_deg.to_radians();
        MadeFor {
            settings: OpticsSettings::default(),
            model: ModelId::Hillaire,
            atmosphere: presets::earth(),
            model_settings: ModelSettings::default(),
            sun_direction: DVec3::new(e.cos(), 0.0, e.sin()),
        }
    }

    #[test]
    fn a_sun_that_creeps_keeps_the_volumes_and_one_that_moves_remakes_them() {
        let made = made_for(30.0);
        assert!(made.serves(&made_for(30.0)));
        assert!(made.serves(&made_for(30.2)));
        assert!(!made.serves(&made_for(30.3)));
        assert!(!made.serves(&made_for(10.0)));
    }

    #[test]
    fn any_other_change_remakes_the_volumes() {
        let made = made_for(30.0);
        let mut other_model = made_for(30.0);
        other_model.model = ModelId::Nishita;
        assert!(!made.serves(&other_model));
        let mut other_atmosphere = made_for(30.0);
        other_atmosphere.atmosphere = presets::hazy();
        assert!(!made.serves(&other_atmosphere));
    }
}
