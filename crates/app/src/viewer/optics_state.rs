//! The viewer's rain and cirrus on the renderer: the volumes of the panel's settings,
//! made (phase tables from the table cache, the light from the frame's model on the CPU)
//! when the settings, the model, the atmosphere or the sun change, and kept while the
//! camera moves: the shaft stays where it was placed. The sun counts as changed once it
//! has moved by [`SUN_TOLERANCE_DEG`], so a running sun clock or a sun that follows the
//! camera's place does not make the volumes again every frame.

use atmosphere_core::atmosphere::Atmosphere;
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

/// The volumes given to the renderer, by what they were made for.
#[derive(Debug, Default)]
pub struct OpticsState {
    made_for: Option<MadeFor>,
}

impl OpticsState {
    /// Gives `renderer` the volumes of `settings` for `frame` (none when both are off);
    /// returns whether they were made again. An error names the setting at fault, and
    /// the renderer then holds none.
    pub fn apply(
        &mut self,
        renderer: &mut Renderer,
        frame: &Frame,
        settings: &OpticsSettings,
    ) -> anyhow::Result<bool> {
        let wanted = MadeFor {
            settings: settings.clone(),
            model: frame.model,
            atmosphere: frame.atmosphere.clone(),
            model_settings: frame.settings.clone(),
            sun_direction: frame.sun_direction,
        };
        if !settings.any() {
            self.made_for = None;
            renderer.set_volumes(Vec::new())?;
            return Ok(false);
        }
        if self
            .made_for
            .as_ref()
            .is_some_and(|made| made.serves(&wanted))
        {
            return Ok(false);
        }
        self.made_for = None;
        renderer.set_volumes(Vec::new())?;
        let volumes = settings.flags().lit_volumes(frame)?;
        renderer.set_volumes(volumes)?;
        self.made_for = Some(wanted);
        Ok(true)
    }
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
