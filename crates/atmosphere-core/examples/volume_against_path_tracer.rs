//! Measures the ray march and half-angle slicing of a volume scene (by default the
//! shipped cumulus) against the cloud path tracer, all orders of scattering, on a
//! smaller copy of the scene's camera. The tracer runs at each of a list of forward
//! cones (`reference/forward_peak.rs`; 0 is the exact tracer): for each, its time,
//! noise, mean against the first's and RMS difference from the first beyond both
//! images' noise. Then, for each light (riley, octaves), the march at the scene's steps
//! and at 512 view and 64 shadow steps and slicing at 64 and 256 slices against each
//! traced image: the relative RMS radiance error beyond that image's noise, and its
//! mean radiance over the last traced image's. Markdown
//! tables (docs/clouds.md, "The path tracer on the volume"). The droplets' tables are
//! kept in the folder `ATMOS_CACHE_DIR` names, as `atmos` keeps them.
//!
//! `cargo run -p atmosphere-core --example volume_against_path_tracer [SCENE.toml
//! [WIDTH_PX [PATHS [CONES_DEG]]]]` (defaults: the cumulus, 16 pixels across, 256
//! paths per pixel and wavelength, cones `0,5`)

use std::path::PathBuf;
use std::time::Instant;

use atmosphere_core::clouds::layer::droplets::droplet_orders_cached;
use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::clouds::volume::cloud::single_scattering_phase;
use atmosphere_core::clouds::volume::march_image::march_image;
use atmosphere_core::clouds::volume::path_traced::{PathTracing, path_traced_image};
use atmosphere_core::clouds::volume::scene::{VolumeScene, WAVELENGTHS_NM};
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use atmosphere_core::clouds::volume::slicing::slicing_image;
use atmosphere_core::table_cache::TableCache;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().map_or_else(
        || PathBuf::from("assets/scenes/clouds/cumulus.toml"),
        PathBuf::from,
    );
    let width_px: u32 = args.next().map_or(Ok(16), |a| a.parse())?;
    let paths: u64 = args.next().map_or(Ok(256), |a| a.parse())?;
    let cones: Vec<f64> = args
        .next()
        .unwrap_or_else(|| "0,5".to_string())
        .split(',')
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let cache = std::env::var_os("ATMOS_CACHE_DIR").map_or_else(TableCache::off, TableCache::at);
    let orders = droplet_orders_cached(&WAVELENGTHS_NM, &cache)?;
    let scene = VolumeScene::load(&path, single_scattering_phase(&orders, 1)?)?;
    let (cloud, sun) = (&scene.cloud, &scene.sun);
    let mut camera = scene.camera;
    camera.height_px = (u64::from(camera.height_px) * u64::from(width_px)
        / u64::from(camera.width_px))
    .max(1) as u32;
    camera.width_px = width_px;
    println!(
        "{} at {}x{}, {paths} paths per pixel and wavelength\n",
        path.display(),
        camera.width_px,
        camera.height_px
    );
    println!(
        "| forward cone, deg | time, s | noise, % | mean / first's | RMS difference from the first beyond both noises, % |"
    );
    println!("|---|---|---|---|---|");
    let mut traced = Vec::new();
    for &forward_peak_deg in &cones {
        let start = Instant::now();
        let tracing = PathTracing {
            paths,
            seed: 1,
            forward_peak_deg,
        };
        let image = path_traced_image(cloud, &camera, sun, &orders, &tracing, &|| {})?;
        let seconds = start.elapsed().as_secs_f64();
        let first = traced.first().unwrap_or(&image);
        let difference = first.relative_rms_error(&image.image);
        let beyond = (difference.powi(2) - image.relative_noise().powi(2))
            .max(0.0)
            .sqrt();
        println!(
            "| {forward_peak_deg} | {seconds:.0} | {:.1} | {:.3} | {:.1} |",
            100.0 * image.relative_noise(),
            mean(&image.image.radiance) / mean(&first.image.radiance),
            100.0 * beyond
        );
        traced.push(image);
    }
    println!();
    let header: Vec<String> = cones
        .iter()
        .map(|c| format!("against {c} deg, %"))
        .collect();
    println!(
        "| light | method | {} | mean / {} deg's |",
        header.join(" | "),
        cones[cones.len() - 1]
    );
    println!("|---|---|{}---|", "---|".repeat(cones.len()));
    for light in [LayerMethod::Riley, LayerMethod::Octaves] {
        let base = VolumeSettings {
            light,
            ..scene.settings
        };
        let fine = VolumeSettings {
            steps: 512,
            shadow_steps: 64,
            ..base
        };
        let mut rows = vec![
            (
                format!("march {}/{}", base.steps, base.shadow_steps),
                march_image(cloud, &camera, sun, &orders, &base)?,
            ),
            (
                "march 512/64".to_string(),
                march_image(cloud, &camera, sun, &orders, &fine)?,
            ),
        ];
        for slices in [64, 256] {
            let s = VolumeSettings { slices, ..base };
            rows.push((
                format!("slicing {slices}"),
                slicing_image(cloud, &camera, sun, &orders, &s)?,
            ));
        }
        for (name, image) in rows {
            let errors: Vec<String> = traced
                .iter()
                .map(|t| format!("{:.1}", 100.0 * t.relative_rms_error(&image)))
                .collect();
            let last = &traced[traced.len() - 1].image.radiance;
            println!(
                "| {light} | {name} | {} | {:.3} |",
                errors.join(" | "),
                mean(&image.radiance) / mean(last)
            );
        }
    }
    Ok(())
}

fn mean(values: &[f64]) -> f64 {
    values.iter().sum::<f64>() / values.len().max(1) as f64
}
