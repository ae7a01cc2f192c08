//! qtable2002's walk at reduced resolution, upsampled (`resolution_divisor`,
//! `upsample_tolerance`; `beams/methods/qtable2002/upsample.rs`), against the walk of
//! every pixel on the sphere under a spotlight (Dobashi et al. 2002 Fig. 4): close to it
//! everywhere, the edges of the beam, of the sphere's shadow and of the sphere itself
//! walked exactly, where a plain bilinear upsample smears them.

use std::path::PathBuf;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::qtable2002::Qtable2002;
use atmosphere_core::beams::methods::registry::prepare;
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
    BeamSettings {
        options: ModelOptions::parse(options).unwrap(),
        ..BeamSettings::default()
    }
}

/// Radiance at 550 nm of `id` with `options` through every pixel's centre, row by row.
fn image(scene: &BeamScene, id: BeamMethodId, options: &[&str]) -> Vec<f64> {
    let method = prepare(id, scene, &settings(options)).unwrap();
    let camera = &scene.camera;
    (0..HEIGHT)
        .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| {
            let ray = camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
            method.radiance(&ray).unwrap()[1]
        })
        .collect()
}

fn qtable_image(scene: &BeamScene, options: &[&str]) -> Vec<f64> {
    image(scene, BeamMethodId::Qtable2002, options)
}

/// The relative RMS of |L - L_ref| / max(L_ref, 1 % of the brightest), as the report's.
fn rms_error(truth: &[f64], other: &[f64]) -> f64 {
    let floor = 0.01 * truth.iter().copied().fold(0.0, f64::max);
    let sum: f64 = truth
        .iter()
        .zip(other)
        .map(|(t, o)| ((o - t) / t.max(floor)).powi(2))
        .sum();
    (sum / truth.len() as f64).sqrt()
}

#[test]
fn the_upsampled_walk_keeps_the_edges_a_bilinear_upsample_smears() {
    let scene = sphere_scene();
    let truth = image(&scene, BeamMethodId::Reference, &["tolerance=1e-4"]);
    let walked = qtable_image(&scene, &[]);
    let upsampled = qtable_image(&scene, &["resolution_divisor=2"]);
    let bilinear = qtable_image(&scene, &["resolution_divisor=2", "upsample_tolerance=1"]);
    let lit = walked.iter().filter(|&&l| l > 0.0).count();
    let interpolated = walked
        .iter()
        .zip(&upsampled)
        .filter(|(w, u)| w != u)
        .count();
    let [walk, up, plain] = [&walked, &upsampled, &bilinear].map(|i| rms_error(&truth, i));
    println!(
        "{lit} lit pixels, {interpolated} interpolated; RMS error: walk {walk:.4}, upsampled {up:.4}, bilinear {plain:.4}"
    );
    // At this small size (a reduced pixel is 2 of 48 across) a third of the beam's
    // glow is interpolated and the error stays near the walk's; a bilinear upsample
    // puts light across the edges of the beam and the shadow.
    assert!(interpolated > lit / 3, "{interpolated} of {lit}");
    assert!(up < 1.3 * walk, "upsampled {up}, walked {walk}");
    assert!(plain > 5.0 * walk, "bilinear {plain}, walked {walk}");
}

#[test]
fn a_reduced_walk_of_divisor_one_or_bad_settings_are_what_they_say() {
    let scene = sphere_scene();
    // Divisor 1 is the walk itself.
    assert_eq!(
        qtable_image(&scene, &["resolution_divisor=1", "upsample_tolerance=1"]),
        qtable_image(&scene, &[])
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
