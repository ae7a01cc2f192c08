//! The Rust twin of `LayerParams` in `shaders/clouds/layer_params.wgsl` (the naga test
//! checks the layout): the camera, the light where the layer is, and the layer's
//! settings, in f32.

use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::gpu::error::RenderError;

/// A pinhole camera for the layer's image: pixel (x, y) of a W x H image looks along
/// forward + (2 (x + 0.5) / W - 1) t a right - (2 (y + 0.5) / H - 1) t up, normalised,
/// with t = tan(fov / 2) and a = W / H.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerCamera {
    /// Relative to the planet's centre, m.
    pub position_m: DVec3,
    /// Unit, orthogonal.
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    /// Vertical field of view, degrees.
    pub fov_deg: f64,
    pub width: u32,
    pub height: u32,
}

impl LayerCamera {
    /// The unit direction of pixel (x, y), as the shader forms it.
    pub fn pixel_direction(&self, x: u32, y: u32) -> DVec3 {
        self.direction_at(f64::from(x), f64::from(y))
    }

    /// The unit direction through the fractional pixel coordinate (x, y) (pixel x's
    /// centre at x): what a reduced-resolution march's ray looks along.
    pub fn direction_at(&self, x: f64, y: f64) -> DVec3 {
        let t = (self.fov_deg.to_radians() / 2.0).tan();
        let aspect = f64::from(self.width) / f64::from(self.height);
        let sx = (2.0 * (x + 0.5) / f64::from(self.width) - 1.0) * t * aspect;
        let sy = (2.0 * (y + 0.5) / f64::from(self.height) - 1.0) * t;
        (self.forward + self.right * sx - self.up * sy).normalize()
    }
}

/// WGSL `LayerParams`, 208 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct LayerUniform {
    /// xyz: the camera, m; w: tan of half the vertical field of view.
    pub camera_m: [f32; 4],
    pub forward: [f32; 4],
    pub right: [f32; 4],
    pub up: [f32; 4],
    pub sun_direction: [f32; 4],
    /// The sun's irradiance through the atmosphere, W m^-2 nm^-1, at 680, 550, 440 nm.
    pub sun_irradiance: [f32; 4],
    /// The sky's horizontal irradiance, W m^-2 nm^-1.
    pub sky_irradiance: [f32; 4],
    /// Ground, base and top radii and the thickness, m.
    pub radii_m: [f32; 4],
    /// extinction_per_m, albedo, coverage_scale, backscatter_xi.
    pub medium: [f32; 4],
    /// detail_scale_m, detail_strength, min_transmittance, 0.
    pub detail: [f32; 4],
    /// steps, shadow_steps, method (0 riley, 1 octaves, 2 eddington), octaves.
    pub counts: [u32; 4],
    /// The cover grid's width and height, the image's width and height.
    pub sizes: [u32; 4],
    /// Octaves of detail noise of the view march and of the shadow march, the
    /// resolution divisor, the sun's light (0: a shadow march per sample, 1: the sun
    /// map).
    pub noise: [u32; 4],
}

fn vec4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn rgb(what: &str, values: &[f64]) -> Result<[f32; 4], RenderError> {
    match values {
        [r, g, b] => Ok([*r as f32, *g as f32, *b as f32, 0.0]),
        _ => Err(RenderError::Frame(format!(
            "cloud {what}: {} wavelengths; the GPU renders 3 (680, 550, 440 nm)",
            values.len()
        ))),
    }
}

impl LayerUniform {
    /// The parameters of `camera` looking at the layer of `settings` (checked) on a
    /// planet of `bottom_radius_m`, lit by `light` (three wavelengths), over a cover grid
    /// of `cover_size` texels.
    pub fn new(
        camera: &LayerCamera,
        light: &CloudLight,
        settings: &LayerSettings,
        bottom_radius_m: f64,
        cover_size: (usize, usize),
    ) -> Result<LayerUniform, RenderError> {
        settings
            .check()
            .map_err(|e| RenderError::Frame(e.to_string()))?;
        if camera.width == 0 || camera.height == 0 {
            return Err(RenderError::Frame(format!(
                "cloud image {} x {} has no pixels",
                camera.width, camera.height
            )));
        }
        let (base, top) = settings.radii_m(bottom_radius_m);
        Ok(LayerUniform {
            camera_m: vec4(camera.position_m, (camera.fov_deg.to_radians() / 2.0).tan()),
            forward: vec4(camera.forward, 0.0),
            right: vec4(camera.right, 0.0),
            up: vec4(camera.up, 0.0),
            sun_direction: vec4(light.sun_direction, 0.0),
            sun_irradiance: rgb("sun irradiance", &light.sun_irradiance)?,
            sky_irradiance: rgb("sky irradiance", &light.sky_irradiance)?,
            radii_m: [
                bottom_radius_m as f32,
                base as f32,
                top as f32,
                settings.thickness_m as f32,
            ],
            medium: [
                settings.extinction_per_m as f32,
                settings.albedo as f32,
                settings.coverage_scale as f32,
                settings.backscatter_xi as f32,
            ],
            detail: [
                settings.detail_scale_m as f32,
                settings.detail_strength as f32,
                settings.min_transmittance as f32,
                0.0,
            ],
            counts: [
                settings.steps,
                settings.shadow_steps,
                match settings.method {
                    LayerMethod::Riley => 0,
                    LayerMethod::Octaves => 1,
                    LayerMethod::Eddington => 2,
                    LayerMethod::FourStream => 3,
                },
                settings.octaves,
            ],
            sizes: [
                cover_size.0 as u32,
                cover_size.1 as u32,
                camera.width,
                camera.height,
            ],
            noise: [
                settings.detail_octaves,
                settings.shadow_octaves,
                settings.resolution_divisor,
                match settings.sun_light {
                    SunLight::March => 0,
                    SunLight::Map => 1,
                },
            ],
        })
    }
}
