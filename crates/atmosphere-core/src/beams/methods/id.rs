//! The one list of beam methods: [`BeamMethodId`] names a method on the command line,
//! in files and in the code.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A way to compute the light beams of a scene (docs/beams/ has one page per method).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BeamMethodId {
    /// Adaptive quadrature along the ray with exact shadow rays: the ground truth.
    Reference,
    /// A ray march with a shadow map per light: the common modern way, the baseline.
    March,
    /// Dobashi, Yamamoto and Nishita 2000: virtual planes with lattice meshes, projected
    /// light maps and shadow maps.
    Planes2000,
    /// Dobashi, Yamamoto and Nishita 2002: the pre-integrated q(u, v) table, the plane
    /// interval chosen from it, and sub-planes where f_l exceeds epsilon.
    Qtable2002,
}

impl BeamMethodId {
    /// Every method, the reference first.
    pub const ALL: [BeamMethodId; 4] = [
        BeamMethodId::Reference,
        BeamMethodId::March,
        BeamMethodId::Planes2000,
        BeamMethodId::Qtable2002,
    ];

    /// The id as written on the command line and in files.
    pub const fn as_str(self) -> &'static str {
        match self {
            BeamMethodId::Reference => "reference",
            BeamMethodId::March => "march",
            BeamMethodId::Planes2000 => "planes2000",
            BeamMethodId::Qtable2002 => "qtable2002",
        }
    }

    /// The ids of `methods`, comma-separated, for messages.
    pub fn list(methods: &[BeamMethodId]) -> String {
        let names: Vec<&str> = methods.iter().map(|m| m.as_str()).collect();
        names.join(", ")
    }
}

impl fmt::Display for BeamMethodId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A name that is no beam method's id.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("unknown beam method '{0}' (known: {known})", known = BeamMethodId::list(&BeamMethodId::ALL))]
pub struct UnknownBeamMethod(pub String);

impl FromStr for BeamMethodId {
    type Err = UnknownBeamMethod;

    fn from_str(s: &str) -> Result<BeamMethodId, UnknownBeamMethod> {
        BeamMethodId::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| UnknownBeamMethod(s.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_id_reads_back_from_its_name() {
        for id in BeamMethodId::ALL {
            assert_eq!(id.as_str().parse::<BeamMethodId>(), Ok(id));
            assert_eq!(id.to_string(), id.as_str());
        }
        let err = "nishita".parse::<BeamMethodId>().unwrap_err().to_string();
        assert!(
            err.starts_with("unknown beam method 'nishita' (known: reference"),
            "{err}"
        );
    }
}
