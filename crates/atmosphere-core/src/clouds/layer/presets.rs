//! The march's quality presets: how many view and shadow steps, whether the sun's
//! light comes from a shadow march or the frame's sun map, how many octaves of detail
//! noise the eye and the sun's shadow rays read, and where the march stops. They
//! leave the cloud itself (where it lies, how dense, its light's method) as it is. What
//! each costs and how far it lies from the finest is measured in `docs/clouds.md`
//! ("Cost").

use std::fmt;
use std::str::FromStr;

use super::settings::{LayerSettings, MAX_DETAIL_OCTAVES, MAX_SHADOW_STEPS, MAX_STEPS, SunLight};
use crate::clouds::error::CloudError;

/// A quality of the cloud layer's march.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarchQuality {
    /// For flight: few view steps through one octave of detail, a two-step shadow
    /// march through the cover and profile alone (the noise's mean; the frame's sun map
    /// instead costs no less, docs/clouds.md "The sun light from the sun map"), a stop
    /// once 2 % of the light behind is left, one ray per 3 x 3 pixels (per 6 x 6 for the
    /// cloud's shadow in the air).
    Interactive,
    /// For recordings: more steps than the defaults and the full noise everywhere.
    Offline,
    /// The most steps and octaves the settings allow: what the others are measured
    /// against.
    Finest,
}

/// The view steps, sun light, shadow steps, view octaves, shadow octaves, stopping
/// transmittance and resolution divisors (the layer's, its shadow in the air's) of a
/// quality.
struct March {
    steps: u32,
    sun_light: SunLight,
    shadow_steps: u32,
    detail_octaves: u32,
    shadow_octaves: u32,
    min_transmittance: f64,
    resolution_divisor: u32,
    air_shadow_divisor: u32,
}

impl MarchQuality {
    fn march(self) -> March {
        match self {
            MarchQuality::Interactive => March {
                steps: 20,
                sun_light: SunLight::March,
                shadow_steps: 2,
                detail_octaves: 1,
                shadow_octaves: 0,
                min_transmittance: 0.02,
                resolution_divisor: 3,
                air_shadow_divisor: 6,
            },
            MarchQuality::Offline => March {
                steps: 128,
                sun_light: SunLight::March,
                shadow_steps: 16,
                detail_octaves: MAX_DETAIL_OCTAVES,
                shadow_octaves: MAX_DETAIL_OCTAVES,
                min_transmittance: 1e-4,
                resolution_divisor: 1,
                air_shadow_divisor: 1,
            },
            MarchQuality::Finest => March {
                steps: MAX_STEPS,
                sun_light: SunLight::March,
                shadow_steps: MAX_SHADOW_STEPS,
                detail_octaves: MAX_DETAIL_OCTAVES,
                shadow_octaves: MAX_DETAIL_OCTAVES,
                min_transmittance: 1e-6,
                resolution_divisor: 1,
                air_shadow_divisor: 1,
            },
        }
    }

    /// `settings` with this quality's march.
    pub fn apply(self, settings: LayerSettings) -> LayerSettings {
        let m = self.march();
        LayerSettings {
            steps: m.steps,
            sun_light: m.sun_light,
            shadow_steps: m.shadow_steps,
            detail_octaves: m.detail_octaves,
            shadow_octaves: m.shadow_octaves,
            min_transmittance: m.min_transmittance,
            resolution_divisor: m.resolution_divisor,
            air_shadow_divisor: m.air_shadow_divisor,
            ..settings
        }
    }
}

impl MarchQuality {
    /// The divisor of the cloud spheres' resolution in frames at this quality
    /// (`SphereSettings::resolution_divisor`): the layer's march's, so that one quality
    /// reduces both forms alike (for flight one ray per 3 x 3 pixels; for recordings and
    /// measurements every pixel).
    pub fn sphere_resolution_divisor(self) -> u32 {
        self.march().resolution_divisor
    }
}

impl fmt::Display for MarchQuality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            MarchQuality::Interactive => "interactive",
            MarchQuality::Offline => "offline",
            MarchQuality::Finest => "finest",
        })
    }
}

/// A user's choice: `interactive` or `offline` (the finest march is for measurements,
/// minutes a frame, and not offered).
impl FromStr for MarchQuality {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "interactive" => Ok(MarchQuality::Interactive),
            "offline" => Ok(MarchQuality::Offline),
            other => Err(CloudError(format!(
                "cloud quality {other:?} is not one of interactive, offline"
            ))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_offered_qualities_read_back_and_others_are_named() {
        for q in [MarchQuality::Interactive, MarchQuality::Offline] {
            assert_eq!(q.to_string().parse::<MarchQuality>().unwrap(), q);
            assert!(q.apply(LayerSettings::default()).check().is_ok());
        }
        let e = "finest".parse::<MarchQuality>().unwrap_err().to_string();
        assert!(
            e.contains("\"finest\"") && e.contains("interactive, offline"),
            "{e}"
        );
    }
}
