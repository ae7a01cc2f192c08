//! The viewer's cloud layer settings (the panel's "Clouds" section), kept between runs
//! with the others, and their reading as `atmos render`'s cloud flags, which check them
//! (docs/clouds.md, "Clouds in frames").

use atmosphere_core::clouds::layer::presets::MarchQuality;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::spheres::handover::CloudForm;
use serde::{Deserialize, Serialize};

use crate::render::cloud_flags::CloudFlags;

/// The panel's cloud settings; fields missing from older stored settings take their
/// defaults (clouds off).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CloudSettings {
    pub on: bool,
    /// `generated` or an equirectangular image, `FILE.png[:r|g|b|a]`.
    pub cover: String,
    /// Base altitude above the ground, m, in [0, 20000].
    pub base_m: f64,
    /// Thickness, m, in [10, 15000].
    pub thickness_m: f64,
    /// Extinction where the cloud is densest, m^-1, in [0, 1].
    pub density_per_m: f64,
    /// `riley` or `octaves`.
    pub method: String,
    /// The march's quality, `interactive` or `offline`.
    pub quality: String,
    /// The form the cloud takes: `auto` (by altitude), `layer` or `spheres`.
    pub form: String,
    /// The cloud's shadow in the air below its base (every model's cloud shafts).
    pub shafts: bool,
}

impl Default for CloudSettings {
    fn default() -> CloudSettings {
        let layer = LayerSettings::default();
        CloudSettings {
            on: false,
            cover: "generated".into(),
            base_m: layer.base_m,
            thickness_m: layer.thickness_m,
            density_per_m: layer.extinction_per_m,
            method: layer.method.to_string(),
            quality: MarchQuality::Interactive.to_string(),
            form: CloudForm::default().to_string(),
            shafts: true,
        }
    }
}

impl CloudSettings {
    /// The same settings as `atmos render`'s flags.
    pub fn flags(&self) -> CloudFlags {
        CloudFlags {
            on: Some(self.on),
            cover: Some(self.cover.clone()),
            base_m: Some(self.base_m),
            thickness_m: Some(self.thickness_m),
            density_per_m: Some(self.density_per_m),
            method: Some(self.method.clone()),
            quality: Some(self.quality.clone()),
            sun_light: None,
            form: Some(self.form.clone()),
            sphere_divisor: None,
            shafts: Some(self.shafts),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_the_layers_and_bad_values_are_named() {
        let mut clouds = CloudSettings::default();
        assert_eq!(clouds.flags().settings().unwrap(), None);
        clouds.on = true;
        assert_eq!(
            clouds.flags().settings().unwrap(),
            Some(MarchQuality::Interactive.apply(LayerSettings::default()))
        );
        clouds.thickness_m = 1.0;
        let e = clouds.flags().settings().unwrap_err().to_string();
        assert!(e.contains("--cloud-thickness-m 1"), "{e}");
        let stored: CloudSettings = toml::from_str("on = true").unwrap();
        assert_eq!(stored.base_m, LayerSettings::default().base_m);
        assert_eq!(stored.flags().form().unwrap(), CloudForm::Auto);
        clouds.form = "slabs".into();
        let e = clouds.flags().form().unwrap_err().to_string();
        assert!(e.contains("--cloud-form") && e.contains("\"slabs\""), "{e}");
    }
}
