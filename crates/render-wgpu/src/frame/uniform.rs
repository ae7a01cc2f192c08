//! The Rust twin of `FrameParams` in `shaders/common/frame_params.wgsl`: a [`Frame`]'s camera
//! and sun in f32, relative to the camera.
//!
//! Camera-relative scheme (docs/rendering.md): the GPU never forms a planet-centred
//! radius by subtracting large f32 numbers. The camera's radius enters only as
//! `q = r^2 - bottom^2`, computed here in f64 (exact to f32 rounding even 1 m above the
//! ground, where r itself carries 0.5 m of rounding), and per pixel the shaders use
//! `r mu = camera . direction`, whose f32 error (half a metre near the planet) moves
//! altitudes along the ray by less than a millimetre. Far out (up to 1e8 m and more)
//! the camera position in f32 is off by at most about 8 m, a 1e-7 relative error far
//! below a pixel's angle, and the shaders find where a ray enters the atmosphere from
//! its closest approach to the centre, which does not cancel.

use atmosphere_core::optics::sea_surface::{WATER_REFRACTIVE_INDEX, slope_variance};
use atmosphere_core::optics::sun_disk;
use bytemuck::{Pod, Zeroable};

use crate::frame::Frame;

/// WGSL `FrameParams`, 160 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameUniform {
    /// xyz: camera position relative to the planet's centre, m; w: its radius, m.
    pub camera_m: [f32; 4],
    /// x: r^2 - bottom^2 of the camera (f64, then rounded), m^2; y: 1 when the camera is
    /// above the top of the atmosphere, else 0; zw: 0.
    pub camera_height: [f32; 4],
    /// xyz: the camera's right axis times half the image width at unit distance.
    pub right: [f32; 4],
    /// xyz: the camera's up axis times half the image height at unit distance.
    pub up: [f32; 4],
    /// xyz: the camera's forward axis.
    pub forward: [f32; 4],
    /// xyz: unit vector towards the sun; w: the sun's angular radius, rad.
    pub sun_direction: [f32; 4],
    /// xyz: the sun disk's radiance at its centre at the three wavelengths,
    /// W m^-2 sr^-1 nm^-1; w: 0.
    pub sun_centre_radiance: [f32; 4],
    /// xyz: the limb-darkening exponent at the three wavelengths; w: 0.
    pub sun_limb_exponent: [f32; 4],
    /// Image width and height, px; zw: 0.
    pub size_px: [u32; 4],
    /// x: the sea's mean square slope for the terrain's wind (default wind without
    /// terrain); y: water's refractive index; zw: 0 (`common/sea_surface.wgsl`).
    pub sea: [f32; 4],
}

impl FrameUniform {
    /// The frame's camera and sun, with the sun disk at `wavelengths_nm`; the frame must
    /// be valid ([`Frame::validate`]).
    pub fn new(frame: &Frame, wavelengths_nm: [f64; 3]) -> FrameUniform {
        let a = &frame.atmosphere;
        let c = frame.camera_position_m;
        let r = c.length();
        let bottom = a.bottom_radius_m;
        let [right, up, forward] = frame.axes();
        let (half_w, half_h) = frame.half_extent();
        let v4 = |v: glam::DVec3, w: f64| [v.x as f32, v.y as f32, v.z as f32, w as f32];
        let per_channel = |f: &dyn Fn(f64) -> f64| {
            let [x, y, z] = wavelengths_nm.map(|l| f(l) as f32);
            [x, y, z, 0.0]
        };
        FrameUniform {
            camera_m: v4(c, r),
            camera_height: [
                ((r - bottom) * (r + bottom)) as f32,
                if r > a.top_radius_m { 1.0 } else { 0.0 },
                0.0,
                0.0,
            ],
            right: v4(right * half_w, 0.0),
            up: v4(up * half_h, 0.0),
            forward: v4(forward, 0.0),
            sun_direction: v4(frame.sun_direction.normalize(), a.sun.angular_radius_rad),
            sun_centre_radiance: per_channel(&|l| {
                let e = a.coefficients(l).solar_irradiance_w_m2_nm;
                sun_disk::centre_radiance(e, a.sun.angular_radius_rad, l)
            }),
            sun_limb_exponent: per_channel(&sun_disk::limb_darkening_exponent),
            size_px: [frame.width, frame.height, 0, 0],
            sea: [
                slope_variance(frame.terrain.unwrap_or_default().wind_m_s) as f32,
                WATER_REFRACTIVE_INDEX as f32,
                0.0,
                0.0,
            ],
        }
    }
}
