//! The camera of a beams scene in the viewer: a simple fly camera in the scene's frame
//! (not the planet's flight controller, whose frame is the planet's centre and whose
//! speed follows the altitude). W/S, A/D and Q/E move it along its view, its right and
//! the scene frame's up at a fixed speed (five times with shift); dragging turns it about the
//! scene's up (yaw) and its right (pitch), never past 85 degrees from the horizon.

use atmosphere_core::beams::camera::Camera;
use glam::{DQuat, DVec3};

use crate::viewer::flight::FlightInput;

/// The speed of the fly camera, m/s (the shipped scenes are tens of metres across).
pub const FLY_SPEED_M_S: f64 = 3.0;
/// The factor shift gives the speed.
const BOOST: f64 = 5.0;
/// The largest angle of the view from the scene's horizon, degrees.
const MAX_PITCH_DEG: f64 = 85.0;

/// The camera's position and view in the scene's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub position_m: DVec3,
    /// Unit view direction.
    pub forward: DVec3,
    /// The scene frame's up: +y, glTF's (docs/beams.md, "Units").
    pub up: DVec3,
    /// Whether it has left the scene's camera (until then it is that camera exactly).
    pub moved: bool,
}

impl FlyCamera {
    /// At the scene camera `camera`, looking where it looks.
    pub fn new(camera: &Camera) -> FlyCamera {
        FlyCamera {
            position_m: camera.position_m,
            forward: camera.forward,
            up: DVec3::Y,
            moved: false,
        }
    }

    /// The view's right, unit.
    fn right(&self) -> DVec3 {
        self.forward.cross(self.up).normalize()
    }

    /// The view turned by `yaw_rad` about the scene's up (positive to the right) and
    /// raised by `pitch_rad`, its elevation kept within [`MAX_PITCH_DEG`].
    fn turned(mut self, yaw_rad: f64, pitch_rad: f64) -> FlyCamera {
        let sine = self.forward.dot(self.up).clamp(-1.0, 1.0);
        let horizontal = (self.forward - self.up * sine)
            .try_normalize()
            .unwrap_or_else(|| self.up.any_orthonormal_vector());
        let horizontal = DQuat::from_axis_angle(self.up, -yaw_rad) * horizontal;
        let limit = MAX_PITCH_DEG.to_radians();
        let elevation = (sine.asin() + pitch_rad).clamp(-limit, limit);
        self.forward = (horizontal * elevation.cos() + self.up * elevation.sin()).normalize();
        self
    }

    /// One step of `dt` seconds under `input`; whether the camera moved. A camera that
    /// looks more steeply than [`MAX_PITCH_DEG`] is brought within it first.
    pub fn step(&mut self, input: &FlightInput, dt: f64) -> bool {
        let still = FlightInput {
            boost: input.boost,
            ..FlightInput::default()
        };
        if *input == still {
            return false;
        }
        let before = *self;
        *self = self.turned(input.yaw_rad, input.pitch_rad);
        let speed = FLY_SPEED_M_S * if input.boost { BOOST } else { 1.0 };
        let motion = self.forward * input.forward + self.right() * input.right + self.up * input.up;
        self.position_m += motion * (speed * dt);
        self.moved |= *self != before;
        *self != before
    }

    /// `base` (its field of view) seen from here, `width` x `height` pixels.
    pub fn camera(&self, base: &Camera, width: u32, height: u32) -> Camera {
        if !self.moved {
            return Camera {
                width_px: width,
                height_px: height,
                ..base.clone()
            };
        }
        let right = self.right();
        Camera {
            position_m: self.position_m,
            forward: self.forward,
            right,
            up: right.cross(self.forward),
            vertical_fov_deg: base.vertical_fov_deg,
            width_px: width,
            height_px: height,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_camera() -> Camera {
        Camera {
            position_m: DVec3::new(0.0, 4.0, 28.0),
            forward: DVec3::NEG_Z,
            right: DVec3::X,
            up: DVec3::Y,
            vertical_fov_deg: 50.0,
            width_px: 300,
            height_px: 450,
        }
    }

    #[test]
    fn without_input_the_camera_is_the_scenes() {
        let base = scene_camera();
        let mut fly = FlyCamera::new(&base);
        assert!(!fly.step(&FlightInput::default(), 0.1));
        let camera = fly.camera(&base, 300, 450);
        assert_eq!(camera, base);
        let moved = FlyCamera { moved: true, ..fly };
        let camera = moved.camera(&base, 64, 36);
        assert!((camera.forward - base.forward).length() < 1e-12);
        assert!((camera.right - base.right).length() < 1e-12);
        assert!((camera.up - base.up).length() < 1e-12);
        assert_eq!((camera.width_px, camera.height_px), (64, 36));
    }

    #[test]
    fn keys_move_along_the_view_the_right_and_up_at_the_speed() {
        let mut fly = FlyCamera::new(&scene_camera());
        let input = FlightInput {
            forward: 1.0,
            right: 1.0,
            up: -1.0,
            ..FlightInput::default()
        };
        assert!(fly.step(&input, 2.0));
        assert!(fly.moved);
        let mut down = FlyCamera::new(&Camera {
            forward: DVec3::NEG_Y,
            right: DVec3::X,
            up: DVec3::NEG_Z,
            ..scene_camera()
        });
        assert!(down.step(&input, 1.0));
        let camera = down.camera(&scene_camera(), 64, 36);
        assert!(camera.position_m.is_finite() && camera.right.is_finite());
        let elevation = camera.forward.dot(DVec3::Y).asin().to_degrees();
        assert!((elevation + MAX_PITCH_DEG).abs() < 1e-9, "{elevation}");
        let d = 2.0 * FLY_SPEED_M_S;
        let expected = DVec3::new(d, 4.0 - d, 28.0 - d);
        assert!((fly.position_m - expected).length() < 1e-12);
    }

    #[test]
    fn dragging_right_turns_right_and_pitch_stops_short_of_the_zenith() {
        let mut fly = FlyCamera::new(&scene_camera());
        let turn = FlightInput {
            yaw_rad: 0.5 * std::f64::consts::PI,
            ..FlightInput::default()
        };
        fly.step(&turn, 0.0);
        assert!((fly.forward - DVec3::X).length() < 1e-12, "{}", fly.forward);
        let up = FlightInput {
            pitch_rad: 3.0,
            ..FlightInput::default()
        };
        fly.step(&up, 0.0);
        let elevation = fly.forward.dot(DVec3::Y).asin().to_degrees();
        assert!((elevation - MAX_PITCH_DEG).abs() < 1e-9, "{elevation}");
        assert!((fly.forward.length() - 1.0).abs() < 1e-12);
    }
}
