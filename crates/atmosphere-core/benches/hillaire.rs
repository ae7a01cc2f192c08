//! How long the Hillaire 2020 model takes at the paper's sizes, at 680/550/440 nm on all
//! cores: the global tables (transmittance 256 x 64, Psi_ms 32 x 32, the ground's sky
//! irradiance), one view's tables (sky view 192 x 108, aerial-perspective volume), and
//! rays of one view once its tables exist (sky, near surfaces, far surfaces) and from
//! orbit (marched per pixel), on one thread.
//!
//! Run: `cargo bench -p atmosphere-core --bench hillaire`.

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

fn main() {
    let earth = Atmosphere::preset("earth").expect("earth preset");
    println!(
        "hillaire, earth, 680/550/440 nm, {} threads",
        rayon::current_num_threads()
    );
    let start = Instant::now();
    let model = Hillaire::prepare(
        &earth,
        &ModelSettings::default(),
        HillaireSettings::default(),
    )
    .expect("the tables build");
    println!(
        "global tables (transmittance, Psi_ms, ground irradiance): {:.3} s",
        start.elapsed().as_secs_f64()
    );
    let r = earth.bottom_radius_m + 1_000.0;
    let (r, mu_s) = model.view_key(r, 0.5);
    let start = Instant::now();
    model.with_sky_view(r, mu_s, |_| ());
    println!(
        "sky-view LUT of one view: {:.3} s",
        start.elapsed().as_secs_f64()
    );
    let start = Instant::now();
    model.with_aerial_perspective(r, mu_s, |_| ());
    println!(
        "aerial-perspective volume of one view: {:.3} s",
        start.elapsed().as_secs_f64()
    );
    let grid = |altitude_m: f64, distance_m: Option<f64>| -> Vec<ViewRay> {
        let mut rays = Vec::new();
        for k in 0..64 {
            for m in 0..64 {
                let view = 0.5 + 179.0 * k as f64 / 63.0;
                let azimuth = 180.0 * m as f64 / 63.0;
                rays.push(
                    ViewRay::from_angles(
                        earth.bottom_radius_m,
                        altitude_m,
                        view,
                        60.0,
                        azimuth,
                        distance_m,
                    )
                    .expect("valid rays"),
                );
            }
        }
        rays
    };
    for (name, rays) in [
        ("1 km, 4096 rays to sky or ground", grid(1_000.0, None)),
        (
            "1 km, 4096 rays to objects at 10 km",
            grid(1_000.0, Some(10_000.0)),
        ),
        ("orbit (400 km), 4096 rays", grid(400_000.0, None)),
    ] {
        // The first ray builds the view's tables; time the rest.
        model.radiance(&rays[0]).expect("valid ray");
        let start = Instant::now();
        for ray in &rays {
            model.radiance(ray).expect("valid ray");
        }
        println!(
            "{name}: {:.2} us per ray (one thread, tables built)",
            start.elapsed().as_secs_f64() * 1e6 / rays.len() as f64
        );
    }
}
