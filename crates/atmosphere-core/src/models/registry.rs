//! The factory of the CPU models: [`prepare`] any [`ModelId`] for an atmosphere.

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::SkyModel;

/// Checks `settings` for model `id` without building anything: every key known and in
/// its range. [`prepare`] checks the same, then the CPU tables' memory budget (the GPU
/// checks its own tables against the device).
pub fn check_settings(id: ModelId, settings: &ModelSettings) -> Result<(), ModelError> {
    use crate::models::{bruneton, dobashi, hillaire, nishita, oneil, riley};
    settings.validate()?;
    let options = &settings.options;
    match id {
        ModelId::Reference => crate::reference::ReferenceSettings::from_options(options).map(drop),
        ModelId::Riley => riley::RileySettings::from_options(options).map(drop),
        ModelId::Bruneton => bruneton::BrunetonSettings::from_options(options).map(drop),
        ModelId::Hillaire => hillaire::HillaireSettings::from_options(options).map(drop),
        ModelId::Dobashi => dobashi::DobashiSettings::from_options(options).map(drop),
        ModelId::Nishita => nishita::NishitaSettings::from_options(options).map(drop),
        ModelId::Oneil => oneil::OneilSettings::from_options(options).map(drop),
    }
}

/// Prepares the model `id` for an atmosphere.
pub fn prepare(
    id: ModelId,
    atmosphere: &Atmosphere,
    settings: &ModelSettings,
) -> Result<Box<dyn SkyModel>, ModelError> {
    atmosphere.validate()?;
    settings.validate()?;
    match id {
        ModelId::Reference => Ok(Box::new(crate::reference::Reference::prepare(
            atmosphere, settings,
        )?)),
        ModelId::Bruneton => Ok(Box::new(crate::models::bruneton::Bruneton::prepare(
            atmosphere, settings,
        )?)),
        ModelId::Hillaire => Ok(Box::new(crate::models::hillaire::Hillaire::prepare(
            atmosphere,
            settings,
            crate::models::hillaire::HillaireSettings::from_options(&settings.options)?,
        )?)),
        ModelId::Nishita => Ok(Box::new(crate::models::nishita::Nishita::prepare(
            atmosphere,
            settings,
            crate::models::nishita::NishitaSettings::from_options(&settings.options)?,
        )?)),
        ModelId::Oneil => Ok(Box::new(crate::models::oneil::Oneil::prepare(
            atmosphere,
            settings,
            crate::models::oneil::OneilSettings::from_options(&settings.options)?,
        )?)),
        ModelId::Riley => Ok(Box::new(crate::models::riley::Riley::prepare(
            atmosphere,
            settings,
            crate::models::riley::RileySettings::from_options(&settings.options)?,
        ))),
        ModelId::Dobashi => Ok(Box::new(crate::models::dobashi::Dobashi::prepare(
            atmosphere,
            settings,
            crate::models::dobashi::DobashiSettings::from_options(&settings.options)?,
        )?)),
    }
}
