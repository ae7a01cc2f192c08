//! Error and CPU time per ray of the beam methods on the sphere under a spotlight
//! (Dobashi et al. 2002 Fig. 4, `assets/scenes/beams/sphere_spotlight.toml`): a grid of
//! 30 x 45 of its camera's 300 x 450 pixel centres, each method against the reference
//! (mean |L_550 - L_ref| over the mean L_ref, the paper's "average error in
//! intensities"), and the median time per ray on one thread over interleaved rounds, as
//! a ratio to the 128-step march, so that a busy machine's load largely cancels.
//! Preparation (tables, shadow maps) is timed apart.
//!
//! Run: `cargo bench -p atmosphere-core --bench beams`.

use std::path::Path;
use std::time::Instant;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::{BeamMethod, BeamSettings};
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;

const ROUNDS: usize = 5;

fn prepared(scene: &BeamScene, id: BeamMethodId, options: &[&str]) -> (Box<dyn BeamMethod>, f64) {
    let settings = BeamSettings {
        options: ModelOptions::parse(options).expect("valid options"),
        ..BeamSettings::default()
    };
    let start = Instant::now();
    let method = prepare(id, scene, &settings).expect("a valid method");
    (method, start.elapsed().as_secs_f64())
}

fn l_550(method: &dyn BeamMethod, rays: &[SceneRay]) -> (Vec<f64>, f64) {
    let start = Instant::now();
    let values = rays
        .iter()
        .map(|r| method.radiance(r).expect("a camera ray")[1])
        .collect();
    (
        values,
        start.elapsed().as_secs_f64() * 1e6 / rays.len() as f64,
    )
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/beams/sphere_spotlight.toml");
    let scene = BeamScene::load(&path).expect("the shipped scene");
    let rays: Vec<SceneRay> = (0..45)
        .flat_map(|j| (0..30).map(move |i| (i, j)))
        .map(|(i, j)| {
            scene
                .camera
                .ray(10.0 * i as f64 + 5.0, 10.0 * j as f64 + 5.0)
        })
        .collect();
    let (reference, _) = prepared(&scene, BeamMethodId::Reference, &[]);
    let (truth, _) = l_550(reference.as_ref(), &rays);
    let total: f64 = truth.iter().sum();
    let cases: [(BeamMethodId, &[&str]); 7] = [
        (BeamMethodId::March, &["steps=128"]),
        (BeamMethodId::March, &["steps=2048"]),
        (BeamMethodId::Planes2000, &[]),
        (BeamMethodId::Qtable2002, &["epsilon=1"]),
        (BeamMethodId::Qtable2002, &[]),
        (BeamMethodId::Qtable2002, &["epsilon=0.002"]),
        (BeamMethodId::Qtable2002, &["epsilon=0"]),
    ];
    let methods: Vec<(Box<dyn BeamMethod>, f64)> = cases
        .iter()
        .map(|(id, options)| prepared(&scene, *id, options))
        .collect();
    let mut times = vec![Vec::new(); cases.len()];
    let mut errors = vec![0.0; cases.len()];
    for _ in 0..ROUNDS {
        for (k, (method, _)) in methods.iter().enumerate() {
            let (values, us) = l_550(method.as_ref(), &rays);
            times[k].push(us);
            let diff: f64 = values.iter().zip(&truth).map(|(a, b)| (a - b).abs()).sum();
            errors[k] = diff / total;
        }
    }
    let medians: Vec<f64> = times.into_iter().map(median).collect();
    println!(
        "sphere_spotlight.toml, {} rays x {ROUNDS} interleaved rounds, one thread, medians",
        rays.len()
    );
    for (k, (id, options)) in cases.iter().enumerate() {
        println!(
            "{id} {}: error {:.2} %, {:.2} us a ray ({:.2} x march 128), prepared in {:.3} s",
            if options.is_empty() {
                "(defaults)".to_string()
            } else {
                options.join(" ")
            },
            100.0 * errors[k],
            medians[k],
            medians[k] / medians[0],
            methods[k].1
        );
    }
}
