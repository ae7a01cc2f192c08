//! The shipped optics scenes (`assets/scenes/optics/`) load as frames with their
//! volumes: the rainbow's rain shaft with the sun behind the camera, the halo's random
//! columns and the sundogs' falling plates with the sun 20 degrees up, both sundogs in
//! view.

use std::path::{Path, PathBuf};

use atmos::render::scene::Scene;
use glam::DVec3;

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/optics")
        .join(name)
}

/// A unit direction at `elevation_deg` and `azimuth_deg` from the sun's azimuth.
fn around_sun(sun: DVec3, up: DVec3, elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let north = (sun - up * sun.dot(up)).normalize();
    let east = up.cross(north);
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    up * e.sin() + (north * a.cos() + east * a.sin()) * e.cos()
}

#[test]
fn the_optics_scenes_hold_their_volumes_and_views() {
    let rainbow = Scene::load(&scene("rainbow.toml")).unwrap();
    let frame = rainbow.frame().unwrap();
    assert!(rainbow.volumes.rain_settings().is_some());
    assert!(frame.sun_direction.dot(frame.axes()[2]) < 0.0, "sun ahead");

    let halo = Scene::load(&scene("halo.toml")).unwrap();
    halo.frame().unwrap();
    let columns = halo.volumes.cirrus_settings().unwrap();
    assert_eq!(columns.plates_tilt_deg, None);

    let sundogs = Scene::load(&scene("sundogs.toml")).unwrap();
    let frame = sundogs.frame().unwrap();
    let plates = sundogs.volumes.cirrus_settings().unwrap();
    assert_eq!(plates.plates_tilt_deg, Some(0.5));
    let up = frame.camera_position_m.normalize();
    let elevation = frame.sun_direction.dot(up).asin().to_degrees();
    assert!((elevation - 20.0).abs() < 1e-6, "{elevation}");
    // Both sundogs (24.7 degrees from the sun's azimuth) within half the vertical field
    // of view of the view's centre: inside the image.
    let forward = frame.axes()[2];
    for side in [-1.0, 1.0] {
        let sundog = around_sun(frame.sun_direction, up, 20.0, side * 24.7);
        let off = sundog.dot(forward).acos().to_degrees();
        assert!(off < 0.5 * frame.vertical_fov_deg, "{off}");
    }
}
