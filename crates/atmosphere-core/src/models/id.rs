//! The one list of scattering models: [`ModelId`] names a model on the command line, in
//! scene and settings files and in the code, so that no list of names can disagree with
//! another.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A scattering model (docs/models/ has one page per model).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ModelId {
    /// The spectral ground truth: quadrature of single scattering plus Monte Carlo
    /// multiple scattering.
    Reference,
    /// Bruneton and Neyret 2008, precomputed scattering with all orders.
    Bruneton,
    /// Dobashi, Yamamoto and Nishita 2002, sampling planes and spheres.
    Dobashi,
    /// Hillaire 2020, sky-view and aerial-perspective tables.
    Hillaire,
    /// Nishita et al. 1993, a ray march with an optical-depth table.
    Nishita,
    /// O'Neil 2004, a few samples with a 4-channel optical-depth table.
    Oneil,
    /// Riley, Ebert, Kraus et al. 2004, closed-form single scattering.
    Riley,
}

impl ModelId {
    /// Every model, the reference first.
    pub const ALL: [ModelId; 7] = [
        ModelId::Reference,
        ModelId::Bruneton,
        ModelId::Dobashi,
        ModelId::Hillaire,
        ModelId::Nishita,
        ModelId::Oneil,
        ModelId::Riley,
    ];

    /// The id as written on the command line and in files.
    pub const fn as_str(self) -> &'static str {
        match self {
            ModelId::Reference => "reference",
            ModelId::Bruneton => "bruneton",
            ModelId::Dobashi => "dobashi",
            ModelId::Hillaire => "hillaire",
            ModelId::Nishita => "nishita",
            ModelId::Oneil => "oneil",
            ModelId::Riley => "riley",
        }
    }

    /// The ids of `models`, comma-separated, for messages.
    pub fn list(models: &[ModelId]) -> String {
        models
            .iter()
            .map(|m| m.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl fmt::Display for ModelId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A name that is no model's id.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("unknown model '{0}' (known: {known})", known = ModelId::list(&ModelId::ALL))]
pub struct UnknownModel(pub String);

impl FromStr for ModelId {
    type Err = UnknownModel;

    fn from_str(s: &str) -> Result<ModelId, UnknownModel> {
        ModelId::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| UnknownModel(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_reads_back_from_its_name_and_from_toml() {
        for id in ModelId::ALL {
            assert_eq!(id.as_str().parse::<ModelId>(), Ok(id));
            assert_eq!(id.to_string(), id.as_str());
            #[derive(Deserialize)]
            struct Scene {
                model: ModelId,
            }
            let scene: Scene = toml::from_str(&format!("model = \"{id}\"")).unwrap();
            assert_eq!(scene.model, id);
        }
        let err = "nishita-16".parse::<ModelId>().unwrap_err();
        assert_eq!(
            err.to_string(),
            "unknown model 'nishita-16' (known: reference, bruneton, dobashi, hillaire, \
             nishita, oneil, riley)"
        );
    }
}
