//! A deck of cloud droplets seen from above, composited into a `Renderer` frame
//! (`precipitation/`, `shaders/precipitation/`) against its CPU twin, atmosphere-core's
//! `hydrometeors/render.rs`: a 64 x 36 frame 3 km up looking at the antisolar point,
//! 45 degrees down, over the glory and out to the cloudbow, for two models, over the
//! model's own GPU pixels (the frame rendered without the deck).
//!
//! Tolerance: each pixel within 0.5 % of itself plus 0.1 % of the frame's brightest
//! value, as for the rain shaft and the cirrus (`gpu_volumes_parity.rs`): the march and
//! the atmosphere's columns in front of the deck in f32, and the f16 image written.
//!
//! Needs a GPU adapter (lavapipe will do); see `support`.

mod support;

use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::hydrometeors::render::composite;
use atmosphere_core::hydrometeors::scene::{DeckSettings, VolumeOptics, lit_volume};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::frame::surface_buffer::SurfaceTexel;
use render_wgpu::frame::{Frame, look_orientation};

const RELATIVE: f64 = 0.005;
const OF_BRIGHTEST: f64 = 0.001;
/// Wavelengths of the deck's table (few, to keep the test short).
const WAVELENGTHS: usize = 8;

/// 3 km above (0 N, 0 E), looking 45 degrees down towards the antisolar point, the sun
/// 45 degrees up behind the camera; 90 degrees high (the cloudbow, 39 degrees from the
/// antisolar point, at the top and bottom).
fn frame(model: ModelId) -> Frame {
    let atmosphere = atmosphere_core::atmosphere::Atmosphere::preset("earth").unwrap();
    let up = DVec3::X;
    let e = 45f64.to_radians();
    Frame {
        camera_position_m: up * (atmosphere.bottom_radius_m + 3_000.0),
        orientation: look_orientation(DVec3::new(-e.sin(), e.cos(), 0.0), up).unwrap(),
        vertical_fov_deg: 90.0,
        sun_direction: DVec3::new(e.sin(), -e.cos(), 0.0),
        atmosphere,
        model,
        settings: Default::default(),
        exposure_ev100: 14.0,
        width: 64,
        height: 36,
        terrain: None,
    }
}

#[test]
fn a_droplet_deck_seen_from_above_matches_the_cpu_composite() {
    let Some(mut renderer) = support::renderer_or_skip("glory parity") else {
        return;
    };
    for model_id in [ModelId::Nishita, ModelId::Hillaire] {
        let frame = frame(model_id);
        let surface = vec![SurfaceTexel::default(); (frame.width * frame.height) as usize];
        renderer.set_volumes(Vec::new()).unwrap();
        renderer.render_with_surface(&frame, &surface).unwrap();
        let without = renderer.read_hdr().unwrap();
        let model = prepare(frame.model, &frame.atmosphere, &frame.settings).unwrap();
        let deck = DeckSettings::default()
            .volume(frame.atmosphere.bottom_radius_m)
            .unwrap();
        let lit = vec![
            lit_volume(
                model.as_ref(),
                deck,
                (frame.camera_position_m, frame.sun_direction),
                VolumeOptics::new(WAVELENGTHS, frame.atmosphere.sun.angular_radius_rad),
                RGB_WAVELENGTHS_NM,
                &TableCache::off(),
            )
            .unwrap(),
        ];
        renderer.set_volumes(lit.clone()).unwrap();
        let plan = renderer.render_with_surface(&frame, &surface).unwrap();
        assert!(plan.steps.iter().any(|s| s.name == "volumes"));
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
                    "{model_id} pixel {i} channel {k}: GPU {gpu}, CPU {}",
                    c[k]
                );
                if (c[k] - f64::from(without[i][k])).abs() > 0.01 * c[k].abs() {
                    changed += 1;
                }
            }
        }
        // The deck fills the frame: most values change, so the test compares something.
        assert!(changed > cpu.len(), "{model_id}: {changed} values changed");
        eprintln!("{model_id}: worst error {worst:.3} of the tolerance");
    }
}
