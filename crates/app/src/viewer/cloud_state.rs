//! The viewer's clouds on the renderer: what the panel's cloud settings need made
//! (the cover grid when its source changes, the multiple-scattering tables once, the
//! frame's model on the CPU when the model or atmosphere changes, for the light on the
//! layer) and given to the renderer before each frame.

use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel};
use render_wgpu::clouds::frame_clouds::{FrameClouds, frame_light};
use render_wgpu::{Frame, Renderer};

use crate::render::cloud_flags::droplet_orders;
use crate::viewer::cloud_settings::CloudSettings;

/// What was made for the renderer's clouds, kept between frames.
#[derive(Default)]
pub struct CloudState {
    orders: Option<ScatteringOrders>,
    /// The cover source whose grid the renderer holds.
    cover: Option<String>,
    /// The frame's model on the CPU and what it was prepared for.
    model: Option<(
        ModelId,
        atmosphere_core::atmosphere::Atmosphere,
        ModelSettings,
        Box<dyn SkyModel>,
    )>,
}

impl std::fmt::Debug for CloudState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CloudState")
            .field("cover", &self.cover)
            .finish_non_exhaustive()
    }
}

impl CloudState {
    /// Gives `renderer` the clouds of `settings` for `frame`, or none when they are off;
    /// an error names the setting at fault.
    pub fn apply(
        &mut self,
        renderer: &mut Renderer,
        frame: &Frame,
        settings: &CloudSettings,
    ) -> anyhow::Result<()> {
        let flags = settings.flags();
        let Some(layer) = flags.settings()? else {
            renderer.set_clouds(None)?;
            return Ok(());
        };
        if self.cover.as_deref() != Some(settings.cover.as_str()) {
            if self.orders.is_none() {
                self.orders = Some(droplet_orders()?);
            }
            let orders = self.orders.as_ref().expect("made above");
            renderer.set_cloud_inputs(&flags.cover_grid()?, orders)?;
            self.cover = Some(settings.cover.clone());
        }
        let fresh = self
            .model
            .as_ref()
            .is_some_and(|(id, atmosphere, model_settings, _)| {
                *id == frame.model
                    && *atmosphere == frame.atmosphere
                    && *model_settings == frame.settings
            });
        if !fresh {
            let model = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
            self.model = Some((
                frame.model,
                frame.atmosphere.clone(),
                frame.settings.clone(),
                model,
            ));
        }
        let (_, _, _, model) = self.model.as_ref().expect("prepared above");
        let light = frame_light(model.as_ref(), frame, &layer)?;
        renderer.set_clouds(Some(FrameClouds {
            settings: layer,
            light,
            form: flags.form()?,
            spheres: flags.sphere_settings()?,
            prune: true,
            shafts: flags.shafts.unwrap_or(true),
        }))?;
        Ok(())
    }
}
