//! What a tabulated phase function costs the cloud path tracer against an exact sampler:
//! paths through a slab (optical depth 4, albedo 0.99, sun at mu0 = 0.7) with
//! Henyey-Greenstein g = 0.5, sampled exactly, and with the same function tabulated every
//! 2 degrees and every 0.1 degree (a Mie table's step), sampled by the weighted
//! inverse-CDF sampler. Rounds interleave the three and the medians are reported, as a
//! ratio to the exact sampler, so that a busy machine's load largely cancels.
//!
//! Run: `cargo bench -p atmosphere-core --bench clouds`.

use std::time::Instant;

use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::slab::Slab;
use atmosphere_core::clouds::slab_transport::slab_fractions;
use atmosphere_core::optics::phase::PhaseFunction;

const PATHS: u64 = 20_000;
const ROUNDS: usize = 5;

fn tabulated(g: f64, step_deg: f64) -> PhaseFunction {
    let n = (180.0 / step_deg).round() as usize;
    let angles_deg: Vec<f64> = (0..=n).map(|i| step_deg * i as f64).collect();
    let hg = PhaseFunction::HenyeyGreenstein { g };
    let values = angles_deg
        .iter()
        .map(|a| hg.eval(a.to_radians().cos()))
        .collect();
    PhaseFunction::Tabulated { angles_deg, values }
}

fn microseconds_per_path(slab: &Slab, seed: u64) -> f64 {
    let start = Instant::now();
    slab_fractions(slab, 0.7, PATHS, seed).expect("a valid slab");
    start.elapsed().as_secs_f64() * 1e6 / PATHS as f64
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    let cases = [
        (
            "Henyey-Greenstein, exact sampler",
            PhaseFunction::HenyeyGreenstein { g: 0.5 },
        ),
        ("tabulated every 2 deg", tabulated(0.5, 2.0)),
        ("tabulated every 0.1 deg", tabulated(0.5, 0.1)),
    ];
    let slabs: Vec<Slab> = cases
        .iter()
        .map(|(_, phase)| {
            Slab::new(
                1000.0,
                0.004,
                0.99,
                CloudPhase::new(phase.clone()).expect("valid"),
            )
            .expect("a valid slab")
        })
        .collect();
    let mut times = vec![Vec::new(); cases.len()];
    for round in 0..ROUNDS {
        for (k, slab) in slabs.iter().enumerate() {
            times[k].push(microseconds_per_path(slab, round as u64 + 1));
        }
    }
    let medians: Vec<f64> = times.into_iter().map(median).collect();
    println!("cloud path tracer, {PATHS} paths x {ROUNDS} interleaved rounds, medians");
    for ((name, _), us) in cases.iter().zip(&medians) {
        println!("{name}: {us:.2} us a path, {:.2} x exact", us / medians[0]);
    }
}
