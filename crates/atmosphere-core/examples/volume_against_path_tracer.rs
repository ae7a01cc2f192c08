//! Measures the ray march and half-angle slicing of a volume scene (by default the
//! shipped cumulus) against the cloud path tracer, all orders of scattering, on a
//! smaller copy of the scene's camera: for each light (riley, octaves) the march at the
//! scene's steps and at 512 view and 64 shadow steps, and slicing at 64 and 256 slices,
//! the relative RMS radiance error beyond the path tracer's own noise, as a Markdown
//! table (docs/clouds.md, "A local volume by half-angle slicing"). The droplets' tables
//! are kept in the folder `ATMOS_CACHE_DIR` names, as `atmos` keeps them.
//!
//! `cargo run -p atmosphere-core --example volume_against_path_tracer [SCENE.toml
//! [WIDTH_PX [PATHS [FORWARD_PEAK_DEG]]]]` (defaults: the cumulus, 16 pixels across, 256
//! paths per pixel and wavelength, the exact tracer)

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
    let forward_peak_deg: f64 = args.next().map_or(Ok(0.0), |a| a.parse())?;
    let cache = std::env::var_os("ATMOS_CACHE_DIR").map_or_else(TableCache::off, TableCache::at);
    let orders = droplet_orders_cached(&WAVELENGTHS_NM, &cache)?;
    let scene = VolumeScene::load(&path, single_scattering_phase(&orders, 1)?)?;
    let (cloud, sun) = (&scene.cloud, &scene.sun);
    let mut camera = scene.camera;
    camera.height_px = (u64::from(camera.height_px) * u64::from(width_px)
        / u64::from(camera.width_px))
    .max(1) as u32;
    camera.width_px = width_px;
    let start = Instant::now();
    let tracing = PathTracing {
        paths,
        seed: 1,
        forward_peak_deg,
    };
    let reference = path_traced_image(cloud, &camera, sun, &orders, &tracing, &|| {})?;
    println!(
        "{} at {}x{}: path tracer {paths} paths per pixel and wavelength, forward peak \
         {forward_peak_deg} deg, in {:.0} s, relative noise {:.2} %",
        path.display(),
        camera.width_px,
        camera.height_px,
        start.elapsed().as_secs_f64(),
        100.0 * reference.relative_noise()
    );
    println!("| light | method | RMS error beyond the noise, % |");
    println!("|---|---|---|");
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
            println!(
                "| {light} | {name} | {:.1} |",
                100.0 * reference.relative_rms_error(&image)
            );
        }
    }
    Ok(())
}
