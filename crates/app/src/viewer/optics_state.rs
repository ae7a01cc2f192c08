//! The viewer's rain and cirrus on the renderer: the volumes of the panel's settings,
//! made (phase tables from the table cache, the light from the frame's model on the CPU)
//! when the settings, the model, the atmosphere or the sun change, and kept while the
//! camera moves: the shaft stays where it was placed.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use glam::DVec3;
use render_wgpu::{Frame, Renderer};

use crate::viewer::optics_settings::OpticsSettings;

/// What the renderer's volumes were made for.
#[derive(Clone, Debug, PartialEq)]
struct MadeFor {
    settings: OpticsSettings,
    model: ModelId,
    atmosphere: Atmosphere,
    model_settings: ModelSettings,
    sun_direction: DVec3,
}

/// The volumes given to the renderer, by what they were made for.
#[derive(Debug, Default)]
pub struct OpticsState {
    made_for: Option<MadeFor>,
}

impl OpticsState {
    /// Gives `renderer` the volumes of `settings` for `frame` (none when both are off);
    /// an error names the setting at fault, and the renderer then holds none.
    pub fn apply(
        &mut self,
        renderer: &mut Renderer,
        frame: &Frame,
        settings: &OpticsSettings,
    ) -> anyhow::Result<()> {
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
            return Ok(());
        }
        if self.made_for.as_ref() == Some(&wanted) {
            return Ok(());
        }
        self.made_for = None;
        renderer.set_volumes(Vec::new())?;
        let volumes = settings.flags().lit_volumes(frame)?;
        renderer.set_volumes(volumes)?;
        self.made_for = Some(wanted);
        Ok(())
    }
}
