//! Tables that hold the sun as a disk where it meets the horizon (`sun_disk`) depend on
//! the disk's angular radius: the GPU's frame plan rebuilds single scattering and the
//! orders when it changes and renders what a fresh build renders; tables with the paper's
//! point sun rebuild nothing (Bruneton and Neyret 2008 treat the sun as a point). The
//! CPU twin's answer for the same change is `bruneton_sun_radius.rs`'s, and the GPU
//! tables' parity with it `gpu_bruneton_parity.rs`'s: this test builds as few tables as
//! it can (about a minute each on lavapipe).
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::Renderer;
use render_wgpu::frame::Frame;
use support::{BRUNETON_TABLES, gpu_or_skip, view};

/// Reduced table sizes (S 8 x 32 x 16 x 8), as in `gpu_bruneton_parity.rs`.
const REDUCED: [&str; 4] = ["r=8", "mu=32", "mu_s=16", "nu=8"];

/// A 48 x 27 frame from 2 m looking 5 deg above the horizon with the sun's centre on it,
/// where the disk's visible half decides the sun's light in the tables.
fn horizon_frame(sun_disk: bool) -> Frame {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let mut settings = ModelSettings::default();
    for item in REDUCED {
        let (k, v) = item.split_once('=').unwrap();
        settings.options.set(k, v);
    }
    settings.options.set("sun_disk", sun_disk.to_string());
    let mut v = view(2.0, 85.0, 90.0);
    v.sun_azimuth_deg = 10.0;
    Frame {
        camera_position_m: v.position_m(atmosphere.bottom_radius_m),
        orientation: v.orientation(),
        vertical_fov_deg: 90.0,
        sun_direction: v.sun_direction(),
        atmosphere,
        model: ModelId::Bruneton,
        settings,
        exposure_ev100: 14.0,
        width: 48,
        height: 27,
        terrain: None,
    }
}

#[test]
fn a_new_sun_radius_rebuilds_the_tables_of_a_disk_sun_and_of_no_point_sun() {
    let Some(gpu) = gpu_or_skip("bruneton sun radius") else {
        return;
    };
    let mut renderer = Renderer::new(gpu).unwrap();
    for sun_disk in [true, false] {
        let mut f = horizon_frame(sun_disk);
        renderer.render(&f).unwrap();
        // Four times the sun's angular radius: half the disk is still above the horizon,
        // but its centroid (and so the light's path) rises four times as high.
        f.atmosphere.sun.angular_radius_rad *= 4.0;
        let plan = renderer.render(&f).unwrap();
        if sun_disk {
            assert!(
                plan.runs("single_scattering") && plan.runs("scattering_orders"),
                "{plan}"
            );
            assert!(!plan.runs("transmittance"), "{plan}");
            let image = renderer.read_hdr().unwrap();
            let mut fresh = Renderer::headless().unwrap();
            fresh.render(&f).unwrap();
            assert_eq!(image, fresh.read_hdr().unwrap(), "the rebuilt disk's frame");
        } else {
            assert!(BRUNETON_TABLES.iter().all(|t| !plan.runs(t)), "{plan}");
        }
    }
}
