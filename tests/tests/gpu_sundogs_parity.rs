//! A cirrus layer of falling plates (a phase table over the sky's elevation and azimuth,
//! `hydrometeors/channel_phase.rs`) composited by the GPU pass (`precipitation/`,
//! `shaders/precipitation/volumes_composite.wgsl`) against its CPU twin,
//! atmosphere-core's `hydrometeors/render.rs`, on a 64 x 36 frame looking at the sun 20
//! degrees up, with both sundogs in view.
//!
//! Tolerance: each pixel within 0.5 % of itself plus 0.1 % of the frame's brightest
//! value, as for the volumes by scattering angle (`gpu_volumes_parity.rs`): the march in
//! f32, the f16 image, and the sky angles by atan2 in f32.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::hydrometeors::render::composite;
use atmosphere_core::hydrometeors::scene::{CirrusSettings, VolumeOptics, lit_volume};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::frame::{Frame, look_orientation};

const RELATIVE: f64 = 0.005;
const OF_BRIGHTEST: f64 = 0.001;
const SUN_ELEVATION_DEG: f64 = 20.0;

/// 2 m above (0 N, 0 E), looking at the sun 20 degrees up towards -Y.
fn frame() -> Frame {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let e = SUN_ELEVATION_DEG.to_radians();
    let towards_sun = DVec3::new(e.sin(), -e.cos(), 0.0);
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + 2.0),
        orientation: look_orientation(towards_sun, up).unwrap(),
        vertical_fov_deg: 60.0,
        sun_direction: towards_sun,
        atmosphere,
        model: ModelId::Nishita,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

#[test]
fn falling_plates_match_the_cpu_composite() {
    let Some(mut renderer) = support::renderer_or_skip("sundogs parity") else {
        return;
    };
    let frame = frame();
    let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
    let cirrus = CirrusSettings {
        crystal_radius_um: 50.0,
        crystal_length_um: 20.0,
        rays: 20_000,
        plates_tilt_deg: Some(1.0),
        ..CirrusSettings::default()
    }
    .volume(frame.atmosphere.bottom_radius_m, SUN_ELEVATION_DEG)
    .unwrap();
    let lit = vec![
        lit_volume(
            model.as_ref(),
            cirrus,
            (frame.camera_position_m, frame.sun_direction),
            VolumeOptics::new(3, frame.atmosphere.sun.angular_radius_rad),
            RGB_WAVELENGTHS_NM,
            &TableCache::off(),
        )
        .unwrap(),
    ];
    assert!(lit[0].phase.sky.is_some());
    renderer.set_volumes(Vec::new()).unwrap();
    renderer.render(&frame).unwrap();
    let without = renderer.read_hdr().unwrap();
    renderer.set_volumes(lit.clone()).unwrap();
    renderer.render(&frame).unwrap();
    let with = renderer.read_hdr().unwrap();
    let spectra = Spectra::new(&frame.atmosphere, &RGB_WAVELENGTHS_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let mut cpu = Vec::new();
    for row in 0..frame.height {
        for column in 0..frame.width {
            let i = (row * frame.width + column) as usize;
            let ray = frame.pixel_ray(column, row);
            let full = std::array::from_fn(|c| f64::from(without[i][c]));
            cpu.push(composite(
                &frame.atmosphere,
                &extinction,
                &lit,
                ray.origin_m,
                ray.direction,
                f64::INFINITY,
                full,
            ));
        }
    }
    let brightest = cpu.iter().flatten().fold(0.0f64, |m, v| m.max(*v));
    let (mut changed, mut worst) = (0, 0.0f64);
    for (i, (c, g)) in cpu.iter().zip(&with).enumerate() {
        for k in 0..3 {
            let gpu = f64::from(g[k]);
            let error = (gpu - c[k]).abs() / (RELATIVE * c[k].abs() + OF_BRIGHTEST * brightest);
            worst = worst.max(error);
            assert!(
                error <= 1.0,
                "pixel {i} channel {k}: GPU {gpu}, CPU {}",
                c[k]
            );
            if (c[k] - f64::from(without[i][k])).abs() > 0.01 * c[k].abs() {
                changed += 1;
            }
        }
    }
    // The layer changes most of the frame: the test compares something.
    assert!(changed > cpu.len(), "{changed} values changed");
    eprintln!("sundogs: worst error {worst:.3} of the tolerance");
}
