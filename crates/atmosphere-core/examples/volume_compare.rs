//! Compares half-angle slicing with the ray march on a volume scene (by default the
//! shipped cumulus): for each light (riley, octaves) the march at the scene's steps and
//! at 512 view and 64 shadow steps, and slicing at 32 to 512 slices, each with its time
//! and its mean absolute radiance error against both marches, as a Markdown table
//! (docs/clouds.md, "A local volume by half-angle slicing"). The droplets' tables are
//! kept in the folder `ATMOS_CACHE_DIR` names, as `atmos` keeps them.
//!
//! `cargo run -p atmosphere-core --example volume_compare [SCENE.toml]`

use std::path::PathBuf;
use std::time::Instant;

use atmosphere_core::clouds::layer::droplets::droplet_orders_cached;
use atmosphere_core::clouds::layer::settings::LayerMethod;
use atmosphere_core::clouds::volume::cloud::single_scattering_phase;
use atmosphere_core::clouds::volume::image::VolumeImage;
use atmosphere_core::clouds::volume::march_image::march_image;
use atmosphere_core::clouds::volume::scene::{VolumeScene, WAVELENGTHS_NM};
use atmosphere_core::clouds::volume::settings::VolumeSettings;
use atmosphere_core::clouds::volume::slicing::slicing_image;
use atmosphere_core::table_cache::TableCache;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).map_or_else(
        || PathBuf::from("assets/scenes/clouds/cumulus.toml"),
        PathBuf::from,
    );
    let cache = std::env::var_os("ATMOS_CACHE_DIR").map_or_else(TableCache::off, TableCache::at);
    let orders = droplet_orders_cached(&WAVELENGTHS_NM, &cache)?;
    let scene = VolumeScene::load(&path, single_scattering_phase(&orders, 1)?)?;
    let (cloud, camera, sun) = (&scene.cloud, &scene.camera, &scene.sun);
    let timed = |f: &dyn Fn() -> Result<VolumeImage, Box<dyn std::error::Error>>| {
        let start = Instant::now();
        f().map(|image| (image, start.elapsed().as_secs_f64()))
    };
    println!(
        "{} ({}x{}), light buffer {} px",
        path.display(),
        camera.width_px,
        camera.height_px,
        scene.settings.light_buffer_px
    );
    println!(
        "| light | method | error vs march {}/{} | error vs march 512/64 | time, s |",
        scene.settings.steps, scene.settings.shadow_steps
    );
    println!("|---|---|---|---|---|");
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
        let (march, march_s) = timed(&|| Ok(march_image(cloud, camera, sun, &orders, &base)?))?;
        let (reference, fine_s) = timed(&|| Ok(march_image(cloud, camera, sun, &orders, &fine)?))?;
        let row = |name: String, image: &VolumeImage, seconds: f64| {
            println!(
                "| {light} | {name} | {:.4} | {:.4} | {seconds:.2} |",
                image.relative_error(&march),
                image.relative_error(&reference)
            );
        };
        row(
            format!("march {}/{}", base.steps, base.shadow_steps),
            &march,
            march_s,
        );
        row("march 512/64".into(), &reference, fine_s);
        for slices in [32, 64, 128, 256, 512] {
            let s = VolumeSettings { slices, ..base };
            let (image, seconds) = timed(&|| Ok(slicing_image(cloud, camera, sun, &orders, &s)?))?;
            row(format!("slicing {slices}"), &image, seconds);
        }
    }
    Ok(())
}
