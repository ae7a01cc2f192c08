//! The Rust twin of `SphereParams` in `shaders/clouds/spheres/params.wgsl` (the naga test
//! checks the layout): the camera, the light on the clouds, the shells and the textures'
//! sizes, in f32.

use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::clouds::layer_uniform::LayerCamera;
use crate::gpu::error::RenderError;

/// WGSL `SphereParams`, 176 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct SphereUniform {
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
    /// Ground and base radii, the layer's thickness, one shell's thickness, m.
    pub radii_m: [f32; 4],
    /// The droplets' albedo, 0, 0, 0.
    pub medium: [f32; 4],
    /// The number of spheres, the light's octaves, the image's width and height.
    pub counts: [u32; 4],
    /// The cloud textures' width and height, the attenuation textures' width and height.
    pub grids: [u32; 4],
}

fn vec4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn rgb(what: &str, values: &[f64]) -> Result<[f32; 4], RenderError> {
    match values {
        [r, g, b] => Ok([*r as f32, *g as f32, *b as f32, 0.0]),
        _ => Err(RenderError::Frame(format!(
            "cloud sphere {what}: {} wavelengths; the GPU renders 3 (680, 550, 440 nm)",
            values.len()
        ))),
    }
}

impl SphereUniform {
    /// The parameters of `camera` looking at `spheres` lit by `light` (three
    /// wavelengths, its sun the spheres' attenuation textures' own).
    pub fn new(
        camera: &LayerCamera,
        light: &CloudLight,
        spheres: &CloudSpheres,
    ) -> Result<SphereUniform, RenderError> {
        if camera.width == 0 || camera.height == 0 {
            return Err(RenderError::Frame(format!(
                "cloud sphere image {} x {} has no pixels",
                camera.width, camera.height
            )));
        }
        let sun = spheres.attenuation().sun_direction();
        if light.sun_direction.dot(sun) < 1.0 - 1e-9 {
            return Err(RenderError::Frame(format!(
                "cloud spheres: attenuation textures made for the sun at {sun}, the light's \
                 sun is at {}",
                light.sun_direction
            )));
        }
        let shells = spheres.shells();
        Ok(SphereUniform {
            camera_m: vec4(camera.position_m, (camera.fov_deg.to_radians() / 2.0).tan()),
            forward: vec4(camera.forward, 0.0),
            right: vec4(camera.right, 0.0),
            up: vec4(camera.up, 0.0),
            sun_direction: vec4(sun, 0.0),
            sun_irradiance: rgb("sun irradiance", &light.sun_irradiance)?,
            sky_irradiance: rgb("sky irradiance", &light.sky_irradiance)?,
            radii_m: [
                shells.ground_radius_m as f32,
                shells.base_radius_m as f32,
                shells.thickness_m as f32,
                shells.shell_thickness_m() as f32,
            ],
            medium: [spheres.albedo() as f32, 0.0, 0.0, 0.0],
            counts: [shells.count, spheres.octaves(), camera.width, camera.height],
            grids: [
                spheres.clouds().width() as u32,
                spheres.clouds().height() as u32,
                spheres.attenuation().width() as u32,
                spheres.attenuation().height() as u32,
            ],
        })
    }
}
