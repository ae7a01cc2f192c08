//! What every model keeps of its preparation, whatever its tables: which model it is,
//! the atmosphere's coefficients at its wavelengths, and whether it does Mie work. The
//! [`crate::models::sky_model::SkyModel`] trait answers `id`, `spectra` and the
//! wavelengths from it.

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::settings::ModelSettings;
use crate::models::table_update::TableUpdate;

/// A model's id, spectra and Mie switch, refreshed together when its atmosphere changes.
#[derive(Clone, Debug)]
pub struct ModelBase {
    pub id: ModelId,
    /// The atmosphere's coefficients at the settings' wavelengths.
    pub spectra: Spectra,
    /// [`ModelSettings::prune`], kept to recompute `with_mie` on an update.
    pub prune: bool,
    /// False when pruning at zero aerosol: the model skips its Mie terms and tables.
    /// `spectra.needs_mie(prune)`, kept because the models read it for every ray.
    pub with_mie: bool,
}

impl ModelBase {
    /// Samples `atmosphere` at the settings' wavelengths, without checking either.
    pub fn new(id: ModelId, atmosphere: &Atmosphere, settings: &ModelSettings) -> ModelBase {
        let spectra = Spectra::new(atmosphere, &settings.wavelengths_nm);
        ModelBase {
            id,
            with_mie: spectra.needs_mie(settings.prune),
            prune: settings.prune,
            spectra,
        }
    }

    /// What most models prepare from: checks `atmosphere` and `settings`, then samples.
    pub fn checked(
        id: ModelId,
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
    ) -> Result<ModelBase, ModelError> {
        atmosphere.validate()?;
        settings.validate()?;
        Ok(ModelBase::new(id, atmosphere, settings))
    }

    /// Samples a changed atmosphere at the same wavelengths, with the same pruning.
    fn refresh(&mut self, atmosphere: &Atmosphere) {
        self.spectra = Spectra::new(atmosphere, &self.spectra.wavelengths_nm);
        self.with_mie = self.spectra.needs_mie(self.prune);
    }

    /// The start of `SkyModel::update` for a model that keeps the atmosphere it was
    /// prepared for in `kept`: checks `atmosphere`, finds what changed, then adopts it
    /// (refreshing the spectra and `kept`). The model rebuilds its tables from the update.
    pub fn adopt(
        &mut self,
        kept: &mut Atmosphere,
        atmosphere: &Atmosphere,
    ) -> Result<TableUpdate, ModelError> {
        let update = TableUpdate::new(kept, atmosphere)?;
        self.refresh(atmosphere);
        *kept = atmosphere.clone();
        Ok(update)
    }
}
