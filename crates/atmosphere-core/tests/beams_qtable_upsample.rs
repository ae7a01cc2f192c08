//! qtable2002's walk at reduced resolution, upsampled (`resolution_divisor`,
//! `upsample_tolerance`; `beams/methods/qtable2002/upsample.rs`), against the walk of
//! every pixel on the sphere under a spotlight (Dobashi et al. 2002 Fig. 4): close to it
//! everywhere, the edges of the beam, of the sphere's shadow and of the sphere itself
//! walked exactly, where a plain bilinear upsample smears them.

use std::path::PathBuf;

use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;

const WIDTH: u32 = 48;
const HEIGHT: u32 = 72;

fn sphere_scene() -> BeamScene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml");
    let mut scene = BeamScene::load(&path).unwrap();
    (scene.camera.width_px, scene.camera.height_px) = (WIDTH, HEIGHT);
    scene
}

fn settings(options: &[&str]) -> BeamSettings {
    let mut all = vec!["table_u=64", "table_v=64", "shadow_map_px=256"];
    all.extend_from_slice(options);
    BeamSettings {
        options: ModelOptions::parse(&all).unwrap(),
        ..BeamSettings::default()
    }
}

/// Radiance at 550 nm through every pixel's centre, row by row.
fn image(scene: &BeamScene, options: &[&str]) -> Vec<f64> {
    let method = Qtable2002::new(scene, &settings(options)).unwrap();
    let camera = &scene.camera;
    (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
            method.radiance(&ray).unwrap()[1]
        })
        .collect()
}

/// Each pixel's |L - L_walk| / max(L_walk, 1 % of the brightest).
fn errors(walked: &[f64], other: &[f64]) -> Vec<f64> {
    let floor = 0.01 * walked.iter().copied().fold(0.0, f64::max);
    walked
        .iter()
        .zip(other)
        .map(|(w, o)| (o - w).abs() / w.max(floor))
        .collect()
}

#[test]
fn the_upsampled_walk_keeps_the_edges_a_bilinear_upsample_smears() {
    let scene = sphere_scene();
    let walked = image(&scene, &[]);
    let upsampled = errors(
        &walked,
        &image(&scene, &["resolution_divisor=4", "upsample_tolerance=0.05"]),
    );
    let bilinear = errors(
        &walked,
        &image(&scene, &["resolution_divisor=4", "upsample_tolerance=1"]),
    );
    let lit = walked.iter().filter(|&&l| l > 0.0).count();
    let interpolated = upsampled.iter().filter(|&&e| e > 1e-9).count();
    let walked_again = upsampled.iter().filter(|&&e| e == 0.0).count();
    let worst = |e: &[f64]| e.iter().copied().fold(0.0, f64::max);
    println!(
        "{lit} lit pixels: {interpolated} interpolated, {walked_again} walked; largest error {:.3} (bilinear {:.3})",
        worst(&upsampled),
        worst(&bilinear)
    );
    // Most of the beam's glow is interpolated, yet no pixel strays from its walk by more
    // than twice the tolerance; a bilinear upsample puts light across the edges.
    assert!(interpolated > lit / 2, "{interpolated} of {lit}");
    assert!(walked_again > 0);
    assert!(worst(&upsampled) < 0.1, "{}", worst(&upsampled));
    assert!(worst(&bilinear) > 0.3, "{}", worst(&bilinear));
}

#[test]
fn a_reduced_walk_of_divisor_one_or_bad_settings_are_what_they_say() {
    let scene = sphere_scene();
    // Divisor 1 is the walk itself.
    assert_eq!(
        image(&scene, &["resolution_divisor=1", "upsample_tolerance=1"]),
        image(&scene, &[])
    );
    for (bad, key) in [
        ("resolution_divisor=0", "resolution_divisor"),
        ("resolution_divisor=17", "resolution_divisor"),
        ("upsample_tolerance=1.5", "upsample_tolerance"),
    ] {
        let err = Qtable2002::new(&scene, &settings(&[bad])).unwrap_err();
        assert!(err.to_string().contains(key), "{bad}: {err}");
    }
}
