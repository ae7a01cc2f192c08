//! The shipped optics scenes (`assets/scenes/optics/`) load as frames with their
//! volumes: the rainbow's rain shaft with the sun behind the camera, the halo's random
//! columns and the sundogs' falling plates with the sun 20 degrees up, both sundogs in
//! view; the small drops' shaft, and the glory's deck below the camera with the
//! antisolar point at the view's centre and the cloudbow inside the frame.

use std::path::{Path, PathBuf};

use atmos::render::scene::Scene;
use atmos::render::volume_flags::VolumeFlags;
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

#[test]
fn the_droplet_scenes_hold_their_volumes_and_views() {
    let small = Scene::load(&scene("rainbow_small_drops.toml")).unwrap();
    small.frame().unwrap();
    let shaft = small.volumes.rain_settings().unwrap();
    assert_eq!(shaft.small_drop_radius_um, Some(150.0));

    let glory = Scene::load(&scene("glory.toml")).unwrap();
    let frame = glory.frame().unwrap();
    let deck = glory.volumes.deck_settings().unwrap();
    let altitude = frame.camera_position_m.length() - frame.atmosphere.bottom_radius_m;
    assert!(altitude > deck.base_m + deck.thickness_m, "{altitude}");
    // The antisolar point at the view's centre, the cloudbow (about 39 degrees from it)
    // within half the vertical field of view.
    let off = (-frame.sun_direction)
        .dot(frame.axes()[2])
        .acos()
        .to_degrees();
    assert!(off < 0.1, "{off}");
    assert!(0.5 * frame.vertical_fov_deg > 40.0);

    // The small drops' radius needs the shaft, and is refused by name outside its range.
    let alone = VolumeFlags {
        rain_small_drop_radius_um: Some(150.0),
        ..VolumeFlags::default()
    };
    let e = alone.lit_volumes(&frame).unwrap_err().to_string();
    assert!(e.contains("--rain-small-drop-radius-um"), "{e}");
}
