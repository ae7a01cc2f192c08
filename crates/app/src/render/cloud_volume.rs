//! `atmos render --volume FILE.toml`: a voxel cloud's scene (docs/clouds.md, "A local
//! volume by half-angle slicing") rendered by half-angle slicing on the GPU (or its CPU
//! twin with `--volume-cpu`), by the ray march on the CPU or by the path tracer on the
//! CPU (their ground truth, with progress; `--forward-peak-deg` trades its exactness
//! for far less noise), over a black background, written atomically
//! as a PNG (tone-mapped as a planet frame is) or an EXR (linear sRGB in cd/m^2).

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::clouds::reference::forward_peak::MAX_FORWARD_PEAK_DEG;
use atmosphere_core::clouds::volume::cloud::single_scattering_phase;
use atmosphere_core::clouds::volume::march_image::march_image;
use atmosphere_core::clouds::volume::path_traced::{
    MAX_PATHS_PER_PIXEL, PathTracing, path_traced_image,
};
use atmosphere_core::clouds::volume::scene::{VolumeScene, WAVELENGTHS_NM};
use atmosphere_core::clouds::volume::settings::{MAX_SLICES, MIN_SLICES, VolumeMethod};
use atmosphere_core::clouds::volume::slicing::slicing_image;
use render_wgpu::GpuContext;
use render_wgpu::clouds::volume::slicing_pass::slicing_image_gpu;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::post::tone_map::ToneMap;

use crate::files::write_atomically;
use crate::progress::Progress;
use crate::render::beams::exposure_ev100;
use crate::render::cloud_flags::droplet_orders;
use crate::render::image_files::{exr_of_size, png_of_size};
use crate::render::scene::{EXPOSURE_EV100, Output};

/// Paths per pixel and wavelength of `--method path` without `--paths`.
const DEFAULT_PATHS: u64 = 256;
/// The path tracer's random sequence.
const PATH_SEED: u64 = 1;

/// What an EXR of a volume holds.
const EXR_UNITS: &str = "linear sRGB (IEC 61966-2-1, D65) in cd/m^2, from spectral radiance at 680, 550, 440 nm (CIE 1931), over black";

/// The flags `atmos render --volume` reads.
#[derive(Debug)]
pub struct VolumeFlags<'a> {
    pub method: Option<&'a str>,
    /// Slicing on the CPU (its twin) instead of the GPU.
    pub cpu: bool,
    pub slices: Option<u32>,
    /// Paths per pixel and wavelength of the path tracer.
    pub paths: Option<u64>,
    /// The path tracer's forward cone taken as no scattering, degrees.
    pub forward_peak_deg: Option<f64>,
    pub exposure: Option<f64>,
}

/// Renders the volume scene at `path` with `flags` to `out`; prints the method, its
/// settings and its time on stderr.
pub fn run(path: &Path, flags: &VolumeFlags, out: &Path) -> anyhow::Result<()> {
    let output = Output::from_path(out)?;
    let method: VolumeMethod = flags
        .method
        .unwrap_or("slicing")
        .parse()
        .context("--method")?;
    if let Some(ev) = flags.exposure
        && !(ev.is_finite() && (EXPOSURE_EV100[0]..=EXPOSURE_EV100[1]).contains(&ev))
    {
        bail!(
            "--exposure {ev} is outside [{}, {}]",
            EXPOSURE_EV100[0],
            EXPOSURE_EV100[1]
        );
    }
    if let Some(n) = flags.slices
        && !(MIN_SLICES..=MAX_SLICES).contains(&n)
    {
        bail!("--slices {n} must lie in [{MIN_SLICES}, {MAX_SLICES}]");
    }
    let tracing = PathTracing {
        paths: flags.paths.unwrap_or(DEFAULT_PATHS),
        seed: PATH_SEED,
        forward_peak_deg: flags.forward_peak_deg.unwrap_or(0.0),
    };
    if let Some(n) = flags.paths
        && !(1..=MAX_PATHS_PER_PIXEL).contains(&n)
    {
        bail!("--paths {n} must lie in [1, {MAX_PATHS_PER_PIXEL}]");
    }
    if let Some(deg) = flags.forward_peak_deg
        && !(0.0..=MAX_FORWARD_PEAK_DEG).contains(&deg)
    {
        bail!("--forward-peak-deg {deg} must lie in [0, {MAX_FORWARD_PEAK_DEG}]");
    }
    if method != VolumeMethod::PathTraced {
        if flags.paths.is_some() {
            bail!("--paths is a setting of --method path, not of {method}");
        }
        if flags.forward_peak_deg.is_some() {
            bail!("--forward-peak-deg is a setting of --method path, not of {method}");
        }
    }
    if WAVELENGTHS_NM != RGB_WAVELENGTHS_NM {
        bail!(
            "volume scenes' wavelengths {WAVELENGTHS_NM:?} differ from the images' {RGB_WAVELENGTHS_NM:?}"
        );
    }
    let orders = droplet_orders()?;
    let phase = single_scattering_phase(&orders, 1)?;
    let mut scene =
        VolumeScene::load(path, phase).with_context(|| format!("--volume {}", path.display()))?;
    if let Some(slices) = flags.slices {
        scene.settings.slices = slices;
    }
    let s = &scene.settings;
    // The device is opened before the clock starts: the time is the method's.
    let gpu = match method {
        VolumeMethod::Slicing if !flags.cpu => Some(GpuContext::headless()?),
        _ => None,
    };
    let start = Instant::now();
    let image = match method {
        VolumeMethod::Slicing => match &gpu {
            Some(gpu) => {
                slicing_image_gpu(gpu, &scene.cloud, &scene.camera, &scene.sun, &orders, s)?
            }
            None => slicing_image(&scene.cloud, &scene.camera, &scene.sun, &orders, s)?,
        },
        VolumeMethod::March => march_image(&scene.cloud, &scene.camera, &scene.sun, &orders, s)?,
        VolumeMethod::PathTraced => {
            let progress = Progress::new(
                "path tracing the volume",
                "rows",
                u64::from(scene.camera.height_px),
            );
            let (cloud, camera, sun) = (&scene.cloud, &scene.camera, &scene.sun);
            let row_done = || progress.inc();
            let traced = path_traced_image(cloud, camera, sun, &orders, &tracing, &row_done)?;
            progress.finish();
            eprintln!(
                "path tracer: {} paths per pixel and wavelength, forward peak {} deg, relative noise {:.2} %",
                tracing.paths,
                tracing.forward_peak_deg,
                100.0 * traced.relative_noise()
            );
            traced.image
        }
    };
    let elapsed = start.elapsed();
    let device = if gpu.is_some() { "GPU" } else { "CPU" };
    let radiance: Vec<[f32; 4]> = image
        .transmittance
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let l = image.pixel(k);
            [l[0] as f32, l[1] as f32, l[2] as f32, t as f32]
        })
        .collect();
    let ev100 = exposure_ev100(flags.exposure, &radiance)?;
    let steps = match method {
        VolumeMethod::Slicing => {
            format!("{} slices, light buffer {} px", s.slices, s.light_buffer_px)
        }
        VolumeMethod::March => format!("{} steps, {} shadow steps", s.steps, s.shadow_steps),
        VolumeMethod::PathTraced => format!(
            "{} paths per pixel, all orders, forward peak {} deg",
            tracing.paths, tracing.forward_peak_deg
        ),
    };
    // The path tracer takes no light approximation: the march's and slicing's do.
    let described = match method {
        VolumeMethod::PathTraced => format!("{method} ({steps})"),
        _ => format!("{method} ({}, {steps})", s.light),
    };
    let size = (scene.camera.width_px, scene.camera.height_px);
    let mut text = vec![
        ("atmos:volume_scene", path.display().to_string()),
        ("atmos:volume_method", described.clone()),
        ("atmos:exposure_ev100", ev100.to_string()),
    ];
    match &output {
        Output::Png(png) => {
            let tone = ToneMap::new(RGB_WAVELENGTHS_NM, ev100)?;
            let pixels: Vec<[u8; 4]> = radiance
                .iter()
                .map(|p| tone.pixel([p[0], p[1], p[2]].map(f64::from)))
                .collect();
            write_atomically(png, &png_of_size(size, &pixels, &text, &[])?)?;
        }
        Output::Exr(exr) => {
            text.push(("atmos:units", EXR_UNITS.into()));
            write_atomically(exr, &exr_of_size(size, None, &text, &radiance)?)?;
        }
    }
    eprintln!(
        "{}x{} volume by {described} on the {device} in {elapsed:.2?} (EV100 {ev100:.1}); wrote {}",
        size.0,
        size.1,
        out.display()
    );
    Ok(())
}
