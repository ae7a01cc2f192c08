//! How fast the reference is, and how precise: 1,000 view rays at 680/550/440 nm with
//! single scattering only and with all orders, on all cores. Prints a table.
//!
//! Run: `cargo bench -p atmosphere-core --bench reference` (add `-- --rays N` for another
//! count).

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use rayon::prelude::*;

/// A fixed, varied set of rays: altitudes from the ground to space, every view and sun
/// zenith (the sun to 10 degrees below the horizon), every azimuth; a golden-ratio
/// sequence so that any count covers the space evenly.
fn benchmark_rays(count: usize, bottom_radius_m: f64) -> Vec<ViewRay> {
    const ALTITUDES_M: [f64; 6] = [0.0, 1.0, 2_000.0, 10_000.0, 40_000.0, 200_000.0];
    let phi = [
        0.618_033_988_749_895,
        0.754_877_666_246_693,
        0.569_840_290_998_053,
    ];
    (0..count)
        .map(|i| {
            let f = |k: usize| (0.5 + phi[k] * i as f64).fract();
            let altitude = ALTITUDES_M[i % ALTITUDES_M.len()];
            ViewRay::from_angles(
                bottom_radius_m,
                altitude,
                180.0 * f(0),
                100.0 * f(1),
                180.0 * f(2),
                None,
            )
            .expect("benchmark rays are valid")
        })
        .collect()
}

fn main() {
    let mut count = 1000;
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--rays") {
        count = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .expect("--rays N");
    }
    let earth = Atmosphere::preset("earth").expect("earth preset");
    let rays = benchmark_rays(count, earth.bottom_radius_m);
    println!(
        "reference, earth, {count} rays at 680/550/440 nm, {} threads",
        rayon::current_num_threads()
    );
    println!(
        "| orders | rays | radiance > 0 | prepare s | time for all rays, s | rays per s | max rel. std. error | mean rel. std. error | 2 std. errors < 0.5 % |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for orders in [Some(1), None] {
        let settings = ModelSettings {
            max_orders: orders,
            ..ModelSettings::default()
        };
        let start = Instant::now();
        let model = prepare(ModelId::Reference, &earth, &settings).expect("reference prepares");
        let prepared = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let results: Vec<_> = rays
            .par_iter()
            .map(|ray| model.radiance(ray).expect("valid ray"))
            .collect();
        let elapsed = start.elapsed().as_secs_f64();
        for (label, twilight) in [
            ("sun above the horizon", false),
            ("sun 0-10 deg below", true),
        ] {
            let relative: Vec<f64> = results
                .iter()
                .zip(&rays)
                .filter(|(_, ray)| (ray.sun_direction.z < 0.0) == twilight)
                .flat_map(|(r, _)| {
                    r.radiance
                        .iter()
                        .zip(&r.radiance_std_error)
                        .filter(|(l, _)| **l > 1e-9)
                        .map(|(l, e)| e / l)
                        .collect::<Vec<_>>()
                })
                .collect();
            let max = relative.iter().cloned().fold(0.0, f64::max);
            let mean = relative.iter().sum::<f64>() / relative.len().max(1) as f64;
            let within = relative.iter().filter(|e| 2.0 * **e < 0.005).count() as f64
                / relative.len().max(1) as f64;
            println!(
                "| {} | {label} | {} | {prepared:.2} | {elapsed:.2} | {:.1} | {:.3}% | {:.3}% | {:.1}% |",
                orders.map_or("all".to_string(), |o| o.to_string()),
                relative.len() / 3,
                count as f64 / elapsed,
                100.0 * max,
                100.0 * mean,
                100.0 * within
            );
        }
    }
}
