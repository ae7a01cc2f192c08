//! How long the Bruneton 2008 tables take to build at the paper's sizes (S 32 x 128 x
//! 32 x 8, E 64 x 16, T 256 x 64) with every order until one adds less than the
//! threshold, at 680/550/440 nm, on all cores. Prints the time and share of each order.
//!
//! Run: `cargo bench -p atmosphere-core --bench bruneton`.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::{Bruneton, BrunetonSettings};
use atmosphere_core::models::sky_model::ModelSettings;

fn main() {
    let earth = Atmosphere::preset("earth").expect("earth preset");
    let settings = BrunetonSettings::default();
    println!(
        "bruneton, earth, 680/550/440 nm, S {:?}, {} threads, threshold {}",
        settings.scattering_size,
        rayon::current_num_threads(),
        settings.order_threshold
    );
    let model = Bruneton::prepare_with(&earth, &ModelSettings::default(), &settings)
        .expect("the tables build");
    println!("| order | seconds | share of the table's radiance |");
    println!("|---|---|---|");
    for o in model.orders() {
        println!("| {} | {:.3} | {:.5} |", o.order, o.seconds, o.share);
    }
    println!(
        "total build (transmittance, densities, all orders): {:.3} s",
        model.build_seconds()
    );
}
