//! The small frame and the rain shaft that the planner's and the pixel rectangle's unit
//! tests turn the camera round.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::hydrometeors::channel_phase::ChannelPhase;
use atmosphere_core::hydrometeors::render::{LitVolume, VolumeLight};
use atmosphere_core::hydrometeors::volumes::Volume;
use atmosphere_core::models::id::ModelId;
use glam::DVec3;

use crate::frame::{Frame, look_orientation};

/// A 64 x 36 frame 2 m above the ground at (R, 0, 0) looking along `forward` with a
/// vertical field of view of `fov_deg`, the sun overhead.
pub fn frame(forward: DVec3, fov_deg: f64) -> Frame {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    Frame {
        camera_position_m: DVec3::X * (atmosphere.bottom_radius_m + 2.0),
        orientation: look_orientation(forward, DVec3::X).unwrap(),
        vertical_fov_deg: fov_deg,
        sun_direction: DVec3::X,
        atmosphere,
        model: ModelId::Nishita,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

/// A rain shaft of radius 1 km and `height_m` standing `away_m` along +y from the
/// camera's foot on the ground sphere of radius `ground_m`, with a flat phase table.
pub fn shaft(ground_m: f64, away_m: f64, height_m: f64) -> LitVolume {
    let foot = (DVec3::X * ground_m + DVec3::Y * away_m).normalize() * ground_m;
    LitVolume {
        volume: Volume::rain_shaft(foot, ground_m, 1_000.0, height_m, 5.0).unwrap(),
        phase: ChannelPhase {
            bin_deg: 90.0,
            sky: None,
            values: vec![[0.1; 3]; 2],
        },
        peak_fraction: [0.0; 3],
        light: VolumeLight {
            sun_direction: DVec3::X,
            sun_irradiance: [1.0; 3],
            sky_radiance: [0.1; 3],
        },
        orders: None,
    }
}
