//! The planner's rule for the cloud layer's shadow in the air (crepuscular rays under a
//! deck; docs/clouds.md, "Cloud shadows in the air"): a pass after the sun map's fill
//! marches the cloud's part of the shadow below the layer's base for every model
//! (`air_shadow_pass.rs`), so the map is made for a frame without a surface too when some
//! pixel sees air below the base.
//! Conservative: a frame the rule prunes has no pixel whose ray dips below the base.

use crate::clouds::frame_clouds::FrameClouds;
use crate::frame::Frame;
use crate::frame::ground_in_view::ground_within;

/// The planner's name for the cloud's shadow in the air.
pub const CLOUD_SHAFTS: &str = "cloud_shafts";
/// Why it is left out when [`FrameClouds::shafts`] is off.
pub const CLOUD_SHAFTS_OFF: &str = "cloud shafts off";
/// Why it is left out when no pixel's ray comes down below the layer's base.
pub const NO_AIR_BELOW: &str = "no air below the cloud layer's base in view";
/// Why it is left out when the cloud steps are.
pub const NO_CLOUD_STEPS: &str = "the cloud steps are left out";

/// Why `frame` with `clouds` needs no cloud shadow in the air, if it does not: the
/// setting is off, or the camera is above the layer's base and no pixel's ray comes down
/// to it (the ground test of `frame/ground_in_view.rs` on a planet as large as the base
/// sphere, as the terrain shafts' rule does with their shadow's top), a pruning applied
/// when `clouds.prune`.
pub fn why_no_cloud_shafts(frame: &Frame, clouds: &FrameClouds) -> Option<&'static str> {
    if !clouds.shafts {
        return Some(CLOUD_SHAFTS_OFF);
    }
    if !clouds.prune {
        return None;
    }
    let (base_m, _) = clouds.settings.radii_m(frame.atmosphere.bottom_radius_m);
    if frame.camera_position_m.length() > base_m {
        let mut shell = frame.clone();
        shell.atmosphere.bottom_radius_m = base_m;
        if !ground_within(&shell, f64::INFINITY) {
            return Some(NO_AIR_BELOW);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use atmosphere_core::atmosphere::Atmosphere;
    use atmosphere_core::clouds::layer::march::CloudLight;
    use atmosphere_core::clouds::layer::settings::LayerSettings;
    use atmosphere_core::clouds::spheres::handover::CloudForm;
    use atmosphere_core::clouds::spheres::settings::SphereSettings;
    use atmosphere_core::models::id::ModelId;
    use glam::DVec3;

    use super::*;
    use crate::frame::look_orientation;

    /// A hillaire frame `altitude_m` up on the x axis, pitched `pitch_deg` above the
    /// horizon.
    fn frame(altitude_m: f64, pitch_deg: f64) -> Frame {
        let atmosphere = Atmosphere::preset("earth").unwrap();
        let p = pitch_deg.to_radians();
        Frame {
            camera_position_m: DVec3::X * (atmosphere.bottom_radius_m + altitude_m),
            orientation: look_orientation(DVec3::new(p.sin(), p.cos(), 0.0), DVec3::X).unwrap(),
            vertical_fov_deg: 40.0,
            sun_direction: DVec3::new(0.3, 1.0, 0.0).normalize(),
            atmosphere,
            model: ModelId::Hillaire,
            settings: Default::default(),
            exposure_ev100: 14.0,
            width: 64,
            height: 36,
            terrain: None,
        }
    }

    fn clouds(shafts: bool, prune: bool) -> FrameClouds {
        FrameClouds {
            settings: LayerSettings::default(),
            light: CloudLight {
                sun_direction: DVec3::Y,
                sun_irradiance: vec![1.0; 3],
                sky_irradiance: vec![0.1; 3],
                up: DVec3::X,
            },
            form: CloudForm::Layer,
            spheres: SphereSettings::default(),
            prune,
            shafts,
        }
    }

    #[test]
    fn the_air_below_the_base_needs_a_view_of_it_and_the_setting() {
        let (on, off) = (clouds(true, true), clouds(false, true));
        // Under the default layer's base (1.5 km) the camera is in that air.
        assert_eq!(why_no_cloud_shafts(&frame(500.0, 30.0), &on), None);
        assert_eq!(
            why_no_cloud_shafts(&frame(500.0, 30.0), &off),
            Some(CLOUD_SHAFTS_OFF)
        );
        // Every model takes it.
        for model in [ModelId::Nishita, ModelId::Bruneton, ModelId::Riley] {
            let other = Frame {
                model,
                ..frame(500.0, 30.0)
            };
            assert_eq!(why_no_cloud_shafts(&other, &on), None, "{model:?}");
        }
        // Inside the layer looking up, no ray comes down to the base; looking down,
        // rays do.
        assert_eq!(
            why_no_cloud_shafts(&frame(2_000.0, 40.0), &on),
            Some(NO_AIR_BELOW)
        );
        assert_eq!(why_no_cloud_shafts(&frame(2_000.0, -10.0), &on), None);
        // Without pruning only the setting counts.
        assert_eq!(
            why_no_cloud_shafts(&frame(2_000.0, 40.0), &clouds(true, false)),
            None
        );
    }
}
