//! The viewer's flight controller: pure logic, no window, stepped with a time step.
//!
//! State: a planet-centred f64 position, a velocity and a unit `forward` vector. Heading
//! (from north towards east) and pitch (above the local horizon) are read from `forward`
//! against the local east-north-up frame; mouse-look turns `forward` about the local
//! vertical (heading) and the local horizontal right (pitch, kept within
//! `max_pitch_rad`). As the camera moves, `forward` is carried with the local frame (the
//! shortest rotation from the old vertical to the new one), so a level heading stays
//! level all the way round the planet and over the poles, where heading itself is
//! undefined.
//!
//! Keys: W/S forward and back, D/A right and left, E/Q up and down (along the local
//! vertical), shift multiplies the speed by `boost`. The wanted speed is
//! `rate_per_s * altitude` with the altitude above the terrain (not below `min_height_m`),
//! so a key held for one second crosses the same fraction of the altitude at 2 m and at
//! 2,000 km. The velocity approaches the wanted one exponentially with time constant
//! `time_constant_s`: `v += (v_wanted - v) (1 - exp(-dt / tau))`, exact for any step
//! while the wanted velocity holds. After each step the camera is kept at least
//! `min_height_m` above the terrain height function it is given (moved out along the
//! vertical, its downward velocity removed). The same inputs and steps give the same
//! states, bit for bit.

use glam::{DQuat, DVec3};

/// The controller's constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlightSettings {
    /// The reference radius the terrain heights are measured from, metres.
    pub radius_m: f64,
    /// Speed per metre of altitude, 1/s.
    pub rate_per_s: f64,
    /// Speed factor while shift is held.
    pub boost: f64,
    /// Time constant of the smoothing of the velocity, seconds.
    pub time_constant_s: f64,
    /// The lowest height above the terrain, metres (also the altitude used for the speed
    /// below it).
    pub min_height_m: f64,
    /// The largest pitch above or below the horizon, radians.
    pub max_pitch_rad: f64,
}

impl FlightSettings {
    /// Defaults for a planet of radius `radius_m`: 1 altitude per second, shift x5,
    /// 0.25 s smoothing, 1 m above the ground at least, pitch within 89 degrees.
    pub fn new(radius_m: f64) -> FlightSettings {
        FlightSettings {
            radius_m,
            rate_per_s: 1.0,
            boost: 5.0,
            time_constant_s: 0.25,
            min_height_m: 1.0,
            max_pitch_rad: 89f64.to_radians(),
        }
    }
}

/// What the user asks for during one step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FlightInput {
    /// W = +1, S = -1 (both: 0).
    pub forward: f64,
    /// D = +1, A = -1.
    pub right: f64,
    /// E = +1, Q = -1.
    pub up: f64,
    /// Shift held.
    pub boost: bool,
    /// Mouse-look: heading change (positive turns right, towards east from north).
    pub yaw_rad: f64,
    /// Mouse-look: pitch change (positive looks up).
    pub pitch_rad: f64,
}

/// The camera's state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlightState {
    /// Planet-centred, metres.
    pub position_m: DVec3,
    /// Metres per second.
    pub velocity_m_s: DVec3,
    /// Unit view direction.
    pub forward: DVec3,
}

/// The local east-north-up frame at a position. At the poles, where east is undefined,
/// east is taken towards longitude 90 deg.
pub fn local_frame(position_m: DVec3) -> (DVec3, DVec3, DVec3) {
    let up = position_m.normalize();
    let east = DVec3::Z.cross(up);
    let east = if east.length_squared() > 1e-20 {
        east.normalize()
    } else {
        DVec3::Y
    };
    (east, up.cross(east), up)
}

impl FlightState {
    /// A camera at `position_m` looking along heading and pitch (radians), at rest.
    pub fn new(position_m: DVec3, heading_rad: f64, pitch_rad: f64) -> FlightState {
        let (east, north, up) = local_frame(position_m);
        let horizontal = north * heading_rad.cos() + east * heading_rad.sin();
        FlightState {
            position_m,
            velocity_m_s: DVec3::ZERO,
            forward: (horizontal * pitch_rad.cos() + up * pitch_rad.sin()).normalize(),
        }
    }

    /// Heading from north towards east, radians in (-pi, pi].
    pub fn heading_rad(&self) -> f64 {
        let (east, north, _) = local_frame(self.position_m);
        self.forward.dot(east).atan2(self.forward.dot(north))
    }

    /// Pitch above the local horizon, radians.
    pub fn pitch_rad(&self) -> f64 {
        self.forward
            .dot(self.position_m.normalize())
            .clamp(-1.0, 1.0)
            .asin()
    }

    /// The unit vector to the camera's right, level with the horizon.
    pub fn right(&self) -> DVec3 {
        let up = self.position_m.normalize();
        let right = self.forward.cross(up);
        if right.length_squared() > 1e-20 {
            right.normalize()
        } else {
            local_frame(self.position_m).0
        }
    }

    /// Height above the terrain, metres, for a terrain height function (metres above the
    /// reference radius, of a unit direction).
    pub fn height_above_terrain_m(
        &self,
        settings: &FlightSettings,
        terrain_m: impl Fn(DVec3) -> f64,
    ) -> f64 {
        let up = self.position_m.normalize();
        self.position_m.length() - settings.radius_m - terrain_m(up)
    }

    /// The speed the keys ask for at this altitude, metres per second.
    pub fn wanted_speed_m_s(
        &self,
        settings: &FlightSettings,
        terrain_m: impl Fn(DVec3) -> f64,
        boost: bool,
    ) -> f64 {
        let altitude = self
            .height_above_terrain_m(settings, terrain_m)
            .max(settings.min_height_m);
        settings.rate_per_s * altitude * if boost { settings.boost } else { 1.0 }
    }

    /// Advances the state by `dt_s` seconds of `input` over the terrain `terrain_m`.
    pub fn step(
        &mut self,
        settings: &FlightSettings,
        input: &FlightInput,
        dt_s: f64,
        terrain_m: impl Fn(DVec3) -> f64,
    ) {
        self.look(settings, input.yaw_rad, input.pitch_rad);

        // The wanted velocity: the keys' direction (diagonals no faster) at the speed of
        // this altitude.
        let up = self.position_m.normalize();
        let keys = self.forward * input.forward + self.right() * input.right + up * input.up;
        let wanted = if keys.length_squared() > 0.0 {
            keys.normalize() * self.wanted_speed_m_s(settings, &terrain_m, input.boost)
        } else {
            DVec3::ZERO
        };
        let blend = 1.0 - (-dt_s / settings.time_constant_s).exp();
        self.velocity_m_s += (wanted - self.velocity_m_s) * blend;

        // Move, carrying the view direction and velocity with the local frame.
        let new_position = self.position_m + self.velocity_m_s * dt_s;
        let turn = DQuat::from_rotation_arc(up, new_position.normalize());
        self.forward = (turn * self.forward).normalize();
        self.velocity_m_s = turn * self.velocity_m_s;
        self.position_m = new_position;

        // Never below the terrain.
        let up = self.position_m.normalize();
        let lowest = settings.radius_m + terrain_m(up) + settings.min_height_m;
        if self.position_m.length() < lowest {
            self.position_m = up * lowest;
            let down = self.velocity_m_s.dot(up).min(0.0);
            self.velocity_m_s -= up * down;
        }
    }

    /// Mouse-look: turns `forward` by `yaw_rad` about the vertical and by `pitch_rad`
    /// about the right axis, keeping the pitch within the limit.
    pub fn look(&mut self, settings: &FlightSettings, yaw_rad: f64, pitch_rad: f64) {
        let up = self.position_m.normalize();
        // Positive yaw turns right: clockwise seen from above, a negative rotation about up.
        self.forward = (DQuat::from_axis_angle(up, -yaw_rad) * self.forward).normalize();
        let pitch = self.pitch_rad();
        let target = (pitch + pitch_rad).clamp(-settings.max_pitch_rad, settings.max_pitch_rad);
        let right = self.right();
        self.forward = (DQuat::from_axis_angle(right, target - pitch) * self.forward).normalize();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: f64 = 6.36e6;

    fn flat(_: DVec3) -> f64 {
        0.0
    }

    /// Hills up to 3 km, a steep mountain of 8 km near longitude 0.
    fn rugged(d: DVec3) -> f64 {
        1500.0 * (1.0 + (40.0 * d.x).sin() * (30.0 * d.y).cos())
            + 8000.0 * (-(d - DVec3::X).length_squared() * 1e4).exp()
    }

    fn at_altitude(altitude_m: f64) -> FlightState {
        FlightState::new(
            DVec3::new(0.2, 0.9, 0.3).normalize() * (R + altitude_m),
            0.7,
            0.0,
        )
    }

    const W: FlightInput = FlightInput {
        forward: 1.0,
        right: 0.0,
        up: 0.0,
        boost: false,
        yaw_rad: 0.0,
        pitch_rad: 0.0,
    };

    /// One tap of W moves the camera the same fraction of its altitude at 2 m and at
    /// 2,000 km, and shift multiplies it.
    #[test]
    fn speed_scales_with_altitude() {
        let s = FlightSettings::new(R);
        let mut fractions = Vec::new();
        for altitude in [2.0, 2e6] {
            for boost in [false, true] {
                let mut state = at_altitude(altitude);
                let start = state.position_m;
                for _ in 0..6 {
                    state.step(&s, &FlightInput { boost, ..W }, 1.0 / 60.0, flat);
                }
                fractions.push((state.position_m - start).length() / altitude);
            }
        }
        assert!(
            (fractions[0] / fractions[2] - 1.0).abs() < 1e-3,
            "{fractions:?}"
        );
        assert!(
            (fractions[1] / fractions[3] - 1.0).abs() < 1e-3,
            "{fractions:?}"
        );
        assert!(
            (fractions[1] / fractions[0] - 5.0).abs() < 1e-2,
            "{fractions:?}"
        );
        let state = at_altitude(2e6);
        assert!((state.wanted_speed_m_s(&s, flat, false) - 2e6).abs() < 1e-6);
        // Below the minimum height the speed is the minimum height's.
        assert_eq!(at_altitude(0.2).wanted_speed_m_s(&s, flat, false), 1.0);
    }

    /// From rest the speed rises as 1 - exp(-t / tau) towards the wanted speed: 63 % after
    /// one time constant, above 99 % after five, never past it, whatever the step.
    #[test]
    fn acceleration_is_smooth() {
        let s = FlightSettings::new(R);
        for dt in [1.0 / 240.0, 1.0 / 60.0, 1.0 / 15.0] {
            let mut state = at_altitude(100.0);
            let mut t = 0.0;
            let mut previous = 0.0;
            while t < 5.0 * s.time_constant_s - 1e-9 {
                state.step(&s, &W, dt, flat);
                t += dt;
                let ratio = state.velocity_m_s.length() / state.wanted_speed_m_s(&s, flat, false);
                assert!(
                    ratio > previous && ratio < 1.0,
                    "dt {dt}: {ratio} after {previous}"
                );
                if (t - s.time_constant_s).abs() < dt / 2.0 {
                    let want = 1.0 - (-t / s.time_constant_s).exp();
                    assert!((ratio - want).abs() < 2e-3, "dt {dt}: {ratio} vs {want}");
                }
                previous = ratio;
            }
            assert!(previous > 0.99, "dt {dt}: {previous}");
        }
    }

    /// Diving at full boost into rugged terrain and a mountain, with small and large
    /// steps, the camera stays at least the minimum height above the ground.
    #[test]
    fn never_enters_the_terrain() {
        let s = FlightSettings::new(R);
        for dt in [1.0 / 60.0, 0.5] {
            // Start 5 km up, west of the mountain at longitude 0, heading east, diving.
            let start = DVec3::new(1.0, -0.02, 0.0).normalize();
            let mut state = FlightState::new(
                start * (R + rugged(start) + 5000.0),
                90f64.to_radians(),
                -0.5,
            );
            let dive = FlightInput {
                boost: true,
                up: -1.0,
                ..W
            };
            let mut lowest = f64::INFINITY;
            for _ in 0..400 {
                state.step(&s, &dive, dt, rugged);
                let h = state.height_above_terrain_m(&s, rugged);
                lowest = lowest.min(h);
                assert!(h >= s.min_height_m - 1e-6, "dt {dt}: {h} m");
            }
            assert!(lowest < 1.5, "dt {dt}: never came down ({lowest} m)");
        }
    }

    /// A fixed sequence of inputs and steps gives the same states bit for bit.
    #[test]
    fn fixed_steps_are_deterministic() {
        let s = FlightSettings::new(R);
        let run = || {
            let mut state = at_altitude(1500.0);
            let mut states = Vec::new();
            for k in 0..300 {
                let input = FlightInput {
                    forward: [1.0, 0.0, -1.0][k % 3],
                    right: if k % 7 < 3 { 1.0 } else { -1.0 },
                    up: if k < 150 { -1.0 } else { 0.5 },
                    boost: k % 11 == 0,
                    yaw_rad: 0.01 * (k as f64).sin(),
                    pitch_rad: -0.004,
                };
                state.step(&s, &input, 1.0 / 60.0, rugged);
                states.push(state);
            }
            states
        };
        let (a, b) = (run(), run());
        assert!(a.iter().zip(&b).all(|(x, y)| {
            x.position_m.to_array().map(f64::to_bits) == y.position_m.to_array().map(f64::to_bits)
                && x.forward.to_array().map(f64::to_bits) == y.forward.to_array().map(f64::to_bits)
        }));
        assert_ne!(a[0], a[299]);
    }

    /// Mouse-look turns the heading and pitch by the deltas; pitch stops at its limit.
    #[test]
    fn mouse_look() {
        let s = FlightSettings::new(R);
        let mut state = at_altitude(10.0);
        let heading = state.heading_rad();
        state.look(&s, 0.3, 0.2);
        assert!((state.heading_rad() - heading - 0.3).abs() < 1e-12);
        assert!((state.pitch_rad() - 0.2).abs() < 1e-12);
        state.look(&s, 0.0, 3.0);
        assert!((state.pitch_rad() - s.max_pitch_rad).abs() < 1e-9);
        assert!((state.heading_rad() - heading - 0.3).abs() < 1e-9);
    }

    /// Flying level due north over the pole: pitch stays level, and past the pole the
    /// heading is due south.
    #[test]
    fn level_flight_over_the_pole() {
        let s = FlightSettings::new(R);
        let start = DVec3::new(0.0, 0.05, 1.0).normalize();
        let mut state = FlightState::new(start * (R + 1e5), 0.0, 0.0);
        for _ in 0..400 {
            state.step(&s, &W, 1.0 / 60.0, flat);
            assert!(state.pitch_rad().abs() < 0.02, "{}", state.pitch_rad());
        }
        assert!(state.position_m.y < 0.0, "did not cross the pole");
        assert!((state.heading_rad().abs() - std::f64::consts::PI).abs() < 1e-6);
    }
}
