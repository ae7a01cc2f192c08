//! The cloud layer's sun map on the GPU (`shaders/clouds/sun_map_fill.wgsl`) against its
//! CPU twin (atmosphere-core's `clouds/layer/sun_map.rs`), texel by texel: the optical
//! depth towards the sun of every texel within 1 % of itself plus 0.01 (the GPU's f32
//! positions about the planet's centre carry 0.5 m of rounding, and the detail noise's
//! cells are 2 km), and the transmittance exp(-tau) within 0.005.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::CloudLight;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::geo::equirectangular::lat_lon;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;
use render_wgpu::clouds::layer_inputs::LayerInputs;
use render_wgpu::clouds::layer_uniform::{LayerCamera, LayerUniform};
use render_wgpu::clouds::sun_map_pass::SunMapPass;
use render_wgpu::clouds::sun_map_texture::{SunMapTexture, SunMapUniform};
use render_wgpu::gpu::readback::read_texture;

const BOTTOM_M: f64 = 6_360_000.0;

/// Cells of cloud with a period of 100 km near (0 N, 0 E).
fn cover() -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = lat_lon(p);
        0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos()
    })
    .unwrap()
}

fn sun(elevation_deg: f64) -> DVec3 {
    let e = elevation_deg.to_radians();
    DVec3::new(e.sin(), e.cos() * 0.6, e.cos() * 0.8)
}

#[test]
fn the_gpu_fills_the_sun_map_as_the_cpu_does() {
    let Some(gpu) = support::gpu_or_skip("cloud sun map") else {
        return;
    };
    let cover = cover();
    let inputs = LayerInputs::new(&gpu, &cover, &support::clouds::orders()).unwrap();
    let pass = SunMapPass::new(&gpu).unwrap();
    let mut texture = SunMapTexture::new(&gpu);
    let settings = LayerSettings {
        extinction_per_m: 0.002,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    let layer = CloudLayer::new(settings, BOTTOM_M, cover, phase).unwrap();
    let resolution = SunMapResolution {
        cells: 48,
        levels: 3,
        steps: 24,
    };
    let camera_m = DVec3::X * (BOTTOM_M + 500.0);
    let mut grid = CloudSunMap::grid_for(layer.shell(), camera_m, &resolution).unwrap();
    grid.cell_m = 2_000.0;
    for elevation in [30.0, 8.0] {
        let s = sun(elevation);
        let cpu = CloudSunMap::new(&layer, grid, s, &resolution).unwrap();
        let params = SunMapUniform::new(&grid, s, layer.shell().top_radius_m, &resolution);
        texture.set(&gpu, Some(&params), (1, 1)).unwrap();
        let camera = LayerCamera {
            position_m: camera_m,
            forward: DVec3::Y,
            right: DVec3::Z,
            up: DVec3::X,
            fov_deg: 60.0,
            width: 1,
            height: 1,
        };
        let light = CloudLight {
            sun_direction: s,
            sun_irradiance: vec![1.0; 3],
            sky_irradiance: vec![0.0; 3],
            up: DVec3::X,
        };
        let uniform =
            LayerUniform::new(&camera, &light, &settings, BOTTOM_M, inputs.cover_size).unwrap();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        pass.encode(&gpu, &mut encoder, &uniform, &inputs.cover, &texture, None);
        gpu.queue.submit([encoder.finish()]);
        let bytes = read_texture(&gpu, texture.texture(), 4).unwrap();
        let depths: &[f32] = bytemuck::cast_slice(&bytes);
        assert_eq!(depths.len(), cpu.depths.len());
        let (mut worst, mut worst_t, mut clouded): (f64, f64, usize) = (0.0, 0.0, 0);
        for (g, c) in depths.iter().zip(&cpu.depths) {
            let (g, c) = (f64::from(*g), f64::from(*c));
            worst = worst.max((g - c).abs() / (0.01 * c + 0.01));
            worst_t = worst_t.max(((-g).exp() - (-c).exp()).abs());
            clouded += usize::from(c > 1.0);
        }
        println!(
            "sun {elevation} deg up: worst optical depth {worst:.3} of the tolerance, \
             transmittance {worst_t:.5}; {clouded} of {} texels with tau > 1",
            depths.len()
        );
        assert!(worst <= 1.0 && worst_t <= 0.005, "{worst} {worst_t}");
        assert!(clouded > depths.len() / 10 && clouded < depths.len() * 9 / 10);
    }
}
