//! `atmos render`: one frame of a scene, headless, to an EXR (linear HDR) or a PNG
//! (tone-mapped) file.

pub mod beams;
pub mod cloud_flags;
pub mod cloud_volume;
pub mod image_files;
pub mod scene;
pub mod sun_disk_clip;
pub mod volume_flags;

use std::time::Instant;

use anyhow::Context;
use render_wgpu::Renderer;

use crate::cli::RenderArgs;
use crate::files::check_writable;
use cloud_flags::CloudInputs;
use scene::{Output, Scene};
use sun_disk_clip::sun_disk_clip_warning;

/// Renders the scene of `args` and writes it; prints the adapter, the plan and the
/// times on stderr.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let output = Output::from_path(&args.out)?;
    check_writable(&args.out)?;
    if let Some(path) = &args.volume {
        let flags = cloud_volume::VolumeFlags {
            method: args.volume_method.as_deref(),
            cpu: args.volume_cpu,
            slices: args.slices,
            paths: args.paths,
            forward_peak_deg: args.forward_peak_deg,
            exposure: args.fields.exposure,
        };
        return cloud_volume::run(path, &flags, &args.out);
    }
    let mut flags = args.fields.clone().at(&args.location);
    if let Some(path) = &args.scene
        && beams::is_beams_scene(path)?
    {
        return beams::run(path, &flags, args.model.as_deref(), &args.out);
    }
    if let Some(model) = &args.model {
        flags.model = Some(model.parse().map_err(|_| {
            anyhow::anyhow!("--model {model} is a beam method: give a beams scene with --scene")
        })?);
    }
    let scene = match &args.scene {
        Some(path) => Scene::load(path)?
            .overridden_by(flags)
            .resolved()
            .with_context(|| format!("scene {}", path.display()))?,
        None => flags.resolved()?,
    };
    let frame = scene.frame()?;
    let earth_data = args.earth_data.source()?;
    let clouds = CloudInputs::load(&scene.clouds)?;
    let divisor = scene.volumes.divisor()?;
    let volumes = scene.volumes.lit_volumes(&frame)?;
    if let Some(warning) = sun_disk_clip_warning(&frame.atmosphere) {
        eprintln!("warning: {warning}");
    }
    let mut renderer = Renderer::headless()?;
    renderer.set_earth_data(earth_data);
    if let Some(clouds) = &clouds {
        clouds.set_up(&mut renderer, &frame)?;
    }
    renderer.set_volumes(volumes)?;
    renderer.set_volumes_divisor(divisor)?;
    let start = Instant::now();
    let plan = renderer.render(&frame)?;
    let elapsed = start.elapsed();
    match &output {
        Output::Exr(path) => {
            let scene_toml = toml::to_string(&scene).context("cannot write the scene as TOML")?;
            image_files::write_exr(path, &frame, &scene_toml, &renderer.read_hdr()?)?;
        }
        Output::Png(path) => image_files::write_png(path, &frame, &renderer.read_ldr()?)?,
    }
    eprintln!(
        "{}x{} {} frame on {} in {elapsed:.1?} (GPU: {plan}); wrote {}",
        frame.width,
        frame.height,
        frame.model,
        renderer.gpu().adapter_summary(),
        args.out.display()
    );
    Ok(())
}
