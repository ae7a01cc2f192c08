//! The three views of `atmos bench`: the ground, sunset and orbit views.

use render_wgpu::frame::LocalView;

/// A named camera and sun, with the vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchView {
    pub name: &'static str,
    pub view: LocalView,
    pub fov_deg: f64,
}

/// Ground in the afternoon looking at the horizon; sunset from the ground looking at
/// the sun; the limb and the planet from 400 km (the horizon dips 19.8 degrees there).
pub const BENCH_VIEWS: &[BenchView] = &[
    BenchView {
        name: "ground",
        view: LocalView {
            altitude_m: 2.0,
            view_zenith_deg: 75.0,
            view_azimuth_deg: 0.0,
            sun_zenith_deg: 45.0,
            sun_azimuth_deg: 120.0,
        },
        fov_deg: 60.0,
    },
    BenchView {
        name: "sunset",
        view: LocalView {
            altitude_m: 2.0,
            view_zenith_deg: 80.0,
            view_azimuth_deg: 0.0,
            sun_zenith_deg: 89.5,
            sun_azimuth_deg: 0.0,
        },
        fov_deg: 60.0,
    },
    BenchView {
        name: "orbit",
        view: LocalView {
            altitude_m: 400_000.0,
            view_zenith_deg: 105.0,
            view_azimuth_deg: 0.0,
            sun_zenith_deg: 60.0,
            sun_azimuth_deg: 30.0,
        },
        fov_deg: 60.0,
    },
];
