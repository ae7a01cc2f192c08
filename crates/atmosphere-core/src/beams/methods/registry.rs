//! Prepares the beam method of an id for a scene.

use crate::beams::error::BeamError;
use crate::beams::methods::id::BeamMethodId;
use crate::beams::methods::march::March;
use crate::beams::methods::method::{BeamMethod, BeamSettings};
use crate::beams::methods::planes2000::Planes2000;
use crate::beams::methods::qtable2002::Qtable2002;
use crate::beams::methods::reference::Reference;
use crate::beams::scene::BeamScene;
use crate::models::error::ModelError;
use crate::models::settings::WAVELENGTH_COUNT;

/// The method `id` prepared for `scene` with `settings`; an error names a bad setting.
pub fn prepare(
    id: BeamMethodId,
    scene: &BeamScene,
    settings: &BeamSettings,
) -> Result<Box<dyn BeamMethod>, BeamError> {
    check_wavelengths(&settings.wavelengths_nm)?;
    Ok(match id {
        BeamMethodId::Reference => Box::new(Reference::new(scene, settings)?),
        BeamMethodId::March => Box::new(March::new(scene, settings)?),
        BeamMethodId::Planes2000 => Box::new(Planes2000::new(scene, settings)?),
        BeamMethodId::Qtable2002 => Box::new(Qtable2002::new(scene, settings)?),
    })
}

fn check_wavelengths(wavelengths_nm: &[f64]) -> Result<(), ModelError> {
    if !WAVELENGTH_COUNT.contains(&wavelengths_nm.len()) {
        return Err(ModelError::Settings(format!(
            "{} wavelengths is outside {}..={}",
            wavelengths_nm.len(),
            WAVELENGTH_COUNT.start(),
            WAVELENGTH_COUNT.end()
        )));
    }
    match wavelengths_nm
        .iter()
        .find(|w| !(w.is_finite() && (360.0..=830.0).contains(*w)))
    {
        Some(w) => Err(ModelError::Settings(format!(
            "wavelength {w} nm is outside the visible range 360..830 nm"
        ))),
        None => Ok(()),
    }
}
