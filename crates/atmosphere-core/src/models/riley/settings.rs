//! The riley model's settings: what it integrates in closed form. Riley et al. 2004 use a
//! flat earth, each species dimmed by its own extinction only, and no ozone
//! ([`RileySettings::PAPER`]); the defaults put the same closed form on the sphere, with
//! every species' extinction and ozone's absorption, so that low suns, the horizon,
//! twilight and views from space stay within a factor of two of single scattering
//! (docs/models/riley.md).

use crate::models::error::ModelError;
use crate::models::options::{ModelOptions, Setting};

/// What the closed form integrates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RileySettings {
    /// `sphere`: columns of the view and the sun on the sphere (the Chapman function in
    /// closed form) and the planet's shadow; false: the paper's flat legs in the camera's
    /// tangent frame, no light with the sun below its horizon.
    pub sphere: bool,
    /// `shared_extinction`: each species' light dimmed by the extinction of all species;
    /// false: by its own only (the paper's Eq. 11-12 per species).
    pub shared_extinction: bool,
    /// `ozone`: ozone's absorption (one fitted exponential) on the view and the sun paths.
    pub ozone: bool,
    /// `pieces`: closed-form pieces per monotone lit part of the ray, over which the
    /// exponent of the integrand is taken linear in the scattering species' own optical
    /// depth (exact for one species on a flat earth, as in the paper).
    pub pieces: usize,
}

impl Default for RileySettings {
    fn default() -> Self {
        RileySettings {
            sphere: true,
            shared_extinction: true,
            ozone: true,
            pieces: 4,
        }
    }
}

/// `pieces`: one is the paper's single closed form per leg; 64 is past where more changes
/// nothing visible on the report's views.
pub const PIECES: Setting<usize> = Setting {
    model: "riley",
    key: "pieces",
    range: 1..=64,
};

impl RileySettings {
    /// Riley et al. 2004 as printed: flat, each species by itself, no ozone, one piece.
    pub const PAPER: RileySettings = RileySettings {
        sphere: false,
        shared_extinction: false,
        ozone: false,
        pieces: 1,
    };

    /// The settings from `key=value` options: `sphere`, `shared_extinction`, `ozone`
    /// (true or false), `pieces`; the defaults where absent.
    pub fn from_options(options: &ModelOptions) -> Result<RileySettings, ModelError> {
        options.read_settings("riley", RileySettings::validate, |o, d| {
            Ok(RileySettings {
                sphere: o.flag("sphere", d.sphere)?,
                shared_extinction: o.flag("shared_extinction", d.shared_extinction)?,
                ozone: o.flag("ozone", d.ozone)?,
                pieces: o.count(&PIECES, d.pieces)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        PIECES.check(self.pieces).map(drop)
    }

    /// The settings as `key=value` options (the inverse of [`RileySettings::from_options`]).
    pub fn to_options(&self) -> ModelOptions {
        let mut options = ModelOptions::default();
        options.set("sphere", self.sphere);
        options.set("shared_extinction", self.shared_extinction);
        options.set("ozone", self.ozone);
        options.set("pieces", self.pieces);
        options
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_round_trip_and_bad_values_are_named() {
        let paper = RileySettings::from_options(&RileySettings::PAPER.to_options()).unwrap();
        assert_eq!(paper, RileySettings::PAPER);
        let none = ModelOptions::default();
        assert_eq!(
            RileySettings::from_options(&none).unwrap(),
            RileySettings::default()
        );
        let bad = ModelOptions::parse(&["pieces=0"]).unwrap();
        let e = RileySettings::from_options(&bad).unwrap_err().to_string();
        assert!(e.contains("pieces=0") && e.contains("1..=64"), "{e}");
        let bad = ModelOptions::parse(&["sphere=yes"]).unwrap();
        let e = RileySettings::from_options(&bad).unwrap_err().to_string();
        assert!(
            e.contains("sphere=yes") && e.contains("true or false"),
            "{e}"
        );
    }
}
