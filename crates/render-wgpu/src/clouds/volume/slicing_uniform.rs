//! The Rust twin of `SlicingParams` in `shaders/clouds/volume/bindings.wgsl`: the eye's
//! projection, the light buffer's frame, the slices and the voxel cloud, relative to
//! the camera, in f32.

use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::clouds::volume::camera::{VolumeCamera, VolumeSun};
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::half_angle::HalfAngle;
use atmosphere_core::clouds::volume::light_buffer::LightBuffer;
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

/// Byte for byte `SlicingParams` (the WGSL's comments say what each field holds).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SlicingUniform {
    pub view_proj: [[f32; 4]; 4],
    pub light_u: [f32; 4],
    pub light_v: [f32; 4],
    pub light_size: [f32; 4],
    pub half: [f32; 4],
    pub light_dir: [f32; 4],
    pub sun: [f32; 4],
    pub irradiance: [f32; 4],
    pub box_origin: [f32; 4],
    pub dims: [u32; 4],
    pub misc: [f32; 4],
}

fn v4(v: DVec3, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

impl SlicingUniform {
    /// The parameters of `cloud` seen by `camera` under `sun` (three wavelengths), its
    /// `slices` and light buffer `light`, with the light's method of `settings`.
    pub fn new(
        cloud: &VoxelCloud,
        camera: &VolumeCamera,
        sun: &VolumeSun,
        slices: &HalfAngle,
        light: &LightBuffer,
        settings: &VolumeSettings,
    ) -> SlicingUniform {
        let c = camera.position_m;
        let aspect = f64::from(camera.width_px) / f64::from(camera.height_px);
        // Camera coordinates to clip space: x and y by the pinhole's field of view,
        // w the depth along the forward axis, z half of it (inside [0, w] in front of
        // the camera, clipped behind it); no depth test, every slice drawn.
        let f = 1.0 / (0.5 * camera.vertical_fov_deg.to_radians()).tan();
        let rows = [
            camera.right * (f / aspect),
            camera.up * f,
            camera.forward * 0.5,
            camera.forward,
        ];
        // Columns, as WGSL's mat4x4 holds them; positions are relative to the camera, so
        // the fourth column (the translation) is 0.
        let view_proj = std::array::from_fn(|c| {
            std::array::from_fn(|r| if c < 3 { rows[r][c] as f32 } else { 0.0 })
        });
        let dims = cloud.grid().dims();
        let side = light.side as f64;
        SlicingUniform {
            view_proj,
            light_u: v4(light.e_u, light.u0 - c.dot(light.e_u)),
            light_v: v4(light.e_v, light.v0 - c.dot(light.e_v)),
            light_size: [
                (light.du * side) as f32,
                (light.dv * side) as f32,
                side as f32,
                slices.light_step_m() as f32,
            ],
            half: v4(slices.half, slices.offset_m(0) - c.dot(slices.half)),
            light_dir: v4(slices.light, slices.spacing_m),
            sun: v4(sun.direction, cloud.albedo()),
            irradiance: [
                sun.irradiance[0] as f32,
                sun.irradiance[1] as f32,
                sun.irradiance[2] as f32,
                cloud.extinction_per_m() as f32,
            ],
            box_origin: v4(cloud.origin_m() - c, cloud.voxel_m()),
            dims: [
                dims[0] as u32,
                dims[1] as u32,
                dims[2] as u32,
                match settings.light {
                    LayerMethod::Riley => 0,
                    // `VolumeSettings::check` refuses the slab methods for a volume.
                    LayerMethod::Octaves | LayerMethod::Eddington | LayerMethod::FourStream => 1,
                },
            ],
            misc: [
                settings.backscatter_xi as f32,
                settings.octaves as f32,
                if slices.front_to_back { 1.0 } else { 0.0 },
                0.0,
            ],
        }
    }
}
