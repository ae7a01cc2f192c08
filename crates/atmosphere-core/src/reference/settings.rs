//! The reference's own settings: how many Monte Carlo paths it may draw per ray and
//! wavelength before it stops short of its target error (and reports the error reached),
//! whether paths through the umbra draw their later events towards the light, and
//! whether rays ending on the ground in the umbra share the ground's light.

use crate::models::error::ModelError;
use crate::models::options::{ModelOptions, Setting};

/// Fewest paths before the standard error is trusted.
pub const MIN_PATHS: usize = 256;

/// Paths per ray and wavelength at most: from the fewest the error is trusted with to
/// 2^26 (about a minute per ray and wavelength in deep twilight on one core).
pub const MAX_PATHS: Setting<usize> = Setting {
    model: "reference",
    key: "max_paths",
    range: MIN_PATHS..=1 << 26,
};

/// The key of [`ReferenceSettings::towards_light`].
pub const TOWARDS_LIGHT: &str = "towards_light";

/// The key of [`ReferenceSettings::shared_ground`].
pub const SHARED_GROUND: &str = "shared_ground";

/// The reference's settings read from `key=value` options.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferenceSettings {
    pub max_paths: usize,
    /// Paths guided through the umbra draw their later events towards the light as well
    /// as their directions (`towards_light.rs`); off: by delta tracking.
    pub towards_light: bool,
    /// Rays that end on the ground in the umbra take the light the ground reflects from
    /// nodes of mu_s shared by every such ray (`ground_light.rs`); off: each ray draws
    /// it with its own paths.
    pub shared_ground: bool,
}

impl Default for ReferenceSettings {
    /// 2^17 paths: daylight rays reach 0.25 % well before it; twilight rays stop there.
    fn default() -> Self {
        ReferenceSettings {
            max_paths: 1 << 17,
            towards_light: false,
            shared_ground: false,
        }
    }
}

impl ReferenceSettings {
    /// The settings in `options`; an unknown key or a value outside its range is an error
    /// naming it.
    pub fn from_options(options: &ModelOptions) -> Result<ReferenceSettings, ModelError> {
        options.read_settings(
            "reference",
            |_| Ok(()),
            |reader, defaults: ReferenceSettings| {
                Ok(ReferenceSettings {
                    max_paths: reader.count(&MAX_PATHS, defaults.max_paths)?,
                    towards_light: reader.flag(TOWARDS_LIGHT, defaults.towards_light)?,
                    shared_ground: reader.flag(SHARED_GROUND, defaults.shared_ground)?,
                })
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_path_cap_is_read_within_its_range() {
        let read =
            |items: &[&str]| ReferenceSettings::from_options(&ModelOptions::parse(items).unwrap());
        assert_eq!(read(&[]).unwrap().max_paths, 1 << 17);
        assert_eq!(read(&["max_paths=1048576"]).unwrap().max_paths, 1 << 20);
        for bad in ["max_paths=0", "max_paths=255", "max_paths=1000000000"] {
            let e = read(&[bad]).unwrap_err().to_string();
            assert!(e.contains("outside 256..=67108864"), "{e}");
        }
        let e = read(&["paths=3"]).unwrap_err().to_string();
        assert!(
            e.contains("its settings: max_paths, towards_light, shared_ground"),
            "{e}"
        );
        assert!(read(&["towards_light=true"]).unwrap().towards_light);
        assert!(!read(&[]).unwrap().towards_light);
        assert!(read(&["shared_ground=true"]).unwrap().shared_ground);
        assert!(!read(&[]).unwrap().shared_ground);
        let e = read(&["towards_light=2"]).unwrap_err().to_string();
        assert!(e.contains("towards_light"), "{e}");
    }
}
