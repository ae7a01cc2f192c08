//! The reference's orders two and up on rays of the sky from 2 m, without guiding, with
//! directions guided towards sunlit air, and with the later events drawn towards the
//! light as well, at a fixed number of paths: the estimate, its standard
//! error relative to the whole radiance, and the time.
//!
//! `cargo run --release -p atmosphere-core --example twilight_guiding -- SUN_ZENITH_DEG
//! PATHS [ORDERS|all] [SEED]` (defaults 102, 32768, all orders, seed 7); 440 nm. Runs
//! with different seeds are independent, so their spread checks the standard errors.

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::numerics::sampling::Sampler;
use atmosphere_core::optics::column::Fineness;
use atmosphere_core::reference::{Guiding, MAX_PATHS, Reference, ViewPath, single_scattering};

/// (elevation, azimuth from the sun) of the rays, degrees.
const LOOKS: [(f64, f64); 6] = [
    (50.0, 0.0),
    (30.0, 0.0),
    (10.0, 0.0),
    (2.0, 0.0),
    (20.0, 60.0),
    (-10.0, 0.0),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let sun_zenith: f64 = args.get(1).map_or(Ok(102.0), |s| s.parse())?;
    let paths: usize = args.get(2).map_or(Ok(32768), |s| s.parse())?;
    let max_orders: Option<u32> = args
        .get(3)
        .filter(|s| *s != "all")
        .map(|s| s.parse())
        .transpose()?;
    let seed: u64 = args.get(4).map_or(Ok(7), |s| s.parse())?;
    let a = Atmosphere::preset("earth")?;
    let mut settings = ModelSettings {
        wavelengths_nm: vec![440.0],
        target_relative_error: 1e-6,
        max_orders,
        ..ModelSettings::default()
    };
    settings.options.set(MAX_PATHS.key, paths);
    let reference = Reference::prepare(&a, &settings)?;
    let spectra = Spectra::new(&a, &[440.0]);
    println!("elevation,azimuth,L1,guiding,L2+,rel_std_error,seconds");
    for (elevation, azimuth) in LOOKS {
        let ray = ViewRay::from_angles(
            a.bottom_radius_m,
            2.0,
            90.0 - elevation,
            sun_zenith,
            azimuth,
            None,
        )?;
        let path = ViewPath::new(&a, &ray, Fineness::VIEW)?;
        let single = single_scattering(&a, &spectra, &path, ray.sun_direction, None)[0];
        for guiding in [Guiding::Off, Guiding::Directions, Guiding::TowardsLitAir] {
            let mut sampler = Sampler::new(seed);
            let start = Instant::now();
            let e = reference.multiple_scattering(
                &path,
                ray.sun_direction,
                0,
                single,
                guiding,
                &mut sampler,
            )?;
            println!(
                "{elevation},{azimuth},{single:.4e},{guiding:?},{:.4e},{:.4},{:.2}",
                e.mean,
                e.std_error / (single + e.mean),
                start.elapsed().as_secs_f64()
            );
        }
    }
    Ok(())
}
