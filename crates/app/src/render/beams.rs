//! `atmos render --scene FILE.toml` where the file is a beams scene (docs/beams.md):
//! its camera's image rendered on the GPU by a beam method and written atomically as a
//! PNG (tone-mapped as a planet frame is) or an EXR (linear sRGB in cd/m^2). A scene file is a beams scene when it has
//! a `[medium]` table or `[[lights]]`, which no planet scene has.

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::text_file::{TOML_LIMITS, read_text};
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::frame::MAX_SIDE_PX;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::post::luminance::{log_average_luminance, luminance_weights};
use render_wgpu::shafts::beams::gpu_methods::{GPU_BEAM_METHODS, PreparedBeams};

use crate::exposure_meter::metered_ev100;
use crate::files::write_atomically;
use crate::render::image_files::{exr_of_size, png_of_size};
use crate::render::scene::{EXPOSURE_EV100, Output, Scene};

/// What an EXR of a beams scene holds.
const EXR_UNITS: &str = "linear sRGB (IEC 61966-2-1, D65) in cd/m^2, from spectral radiance at 680, 550, 440 nm (CIE 1931)";

/// Whether the TOML file at `path` is a beams scene (it has `medium` or `lights`).
pub fn is_beams_scene(path: &Path) -> anyhow::Result<bool> {
    let text = read_text(path, TOML_LIMITS).context("--scene")?;
    // A file that is no TOML table is left to the planet scene's reader to name.
    Ok(text
        .parse::<toml::Table>()
        .is_ok_and(|t| t.contains_key("medium") || t.contains_key("lights")))
}

/// The beam method `model` (default `march`) given by `flag`, refused unless it is on
/// the GPU.
pub fn gpu_method(flag: &str, model: Option<&str>) -> anyhow::Result<BeamMethodId> {
    let Some(text) = model else {
        return Ok(BeamMethodId::March);
    };
    let id: BeamMethodId = text.parse().map_err(|_| {
        anyhow::anyhow!(
            "{flag} {text}: a beams scene takes a beam method ({})",
            BeamMethodId::list(&BeamMethodId::ALL)
        )
    })?;
    if !GPU_BEAM_METHODS.contains(&id) {
        bail!(
            "{flag} {id}: not on the GPU (beam methods on the GPU: {}; `atmos probe \
             --scene` computes the {id} on the CPU)",
            BeamMethodId::list(&GPU_BEAM_METHODS)
        );
    }
    Ok(id)
}

/// `exposure`, or where none is given the EV100 the log-average luminance of
/// `radiance` (at 680, 550 and 440 nm) asks for, as `atmos record` meters a frame.
pub fn exposure_ev100(exposure: Option<f64>, radiance: &[[f32; 4]]) -> anyhow::Result<f64> {
    Ok(match exposure {
        Some(ev) => ev,
        None => metered_ev100(log_average_luminance(
            luminance_weights(RGB_WAVELENGTHS_NM)?,
            radiance,
        )),
    })
}

/// The planet flags given with a beams scene, which has no use for them.
fn planet_flags(f: &Scene) -> Vec<&'static str> {
    [
        ("--altitude-m", f.altitude_m.is_some()),
        ("--sun-zenith-deg", f.sun_zenith_deg.is_some()),
        ("--sun-azimuth-deg", f.sun_azimuth_deg.is_some()),
        ("--view-zenith-deg", f.view_zenith_deg.is_some()),
        ("--view-azimuth-deg", f.view_azimuth_deg.is_some()),
        ("--fov-deg", f.fov_deg.is_some()),
        ("--atmosphere", f.atmosphere.is_some()),
        ("--latitude-deg", f.latitude_deg.is_some()),
        ("--longitude-deg", f.longitude_deg.is_some()),
        ("--terrain", f.terrain.is_some()),
        ("--exaggeration", f.exaggeration.is_some()),
    ]
    .into_iter()
    .filter_map(|(flag, given)| given.then_some(flag))
    .collect()
}

/// Renders the beams scene at `path` with the flags `f` (`--width`, `--height`,
/// `--exposure`, `--set`) and method `model` to `out`; prints the adapter and the
/// times on stderr.
pub fn run(path: &Path, f: &Scene, model: Option<&str>, out: &Path) -> anyhow::Result<()> {
    let id = gpu_method("--model", model)?;
    let unused = planet_flags(f);
    if !unused.is_empty() {
        bail!(
            "{} do not apply to a beams scene (its camera, lights and medium are in {})",
            unused.join(", "),
            path.display()
        );
    }
    let output = Output::from_path(out)?;
    if let Some(ev) = f.exposure
        && !(ev.is_finite() && (EXPOSURE_EV100[0]..=EXPOSURE_EV100[1]).contains(&ev))
    {
        bail!(
            "--exposure {ev} is outside [{}, {}]",
            EXPOSURE_EV100[0],
            EXPOSURE_EV100[1]
        );
    }
    let mut scene = BeamScene::load(path)?;
    for (flag, given, side) in [
        ("--width", f.width, &mut scene.camera.width_px),
        ("--height", f.height, &mut scene.camera.height_px),
    ] {
        if let Some(px) = given {
            if !(1..=MAX_SIDE_PX).contains(&px) {
                bail!("{flag} {px} must be 1 to {MAX_SIDE_PX} px");
            }
            *side = px;
        }
    }
    let settings = BeamSettings {
        wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
        options: ModelOptions::parse(&f.set)?,
    };
    // Refused before the device is opened: the loops depend on the settings alone.
    let prepared = PreparedBeams::new(id, &scene, &settings)?;
    eprintln!("plan: {}", prepared.plan);
    let gpu = GpuContext::headless()?;
    let renderer = prepared.renderer(&gpu)?;
    let start = Instant::now();
    let (image, gpu_ms) = renderer.render(&gpu)?;
    let radiance = image.read_radiance(&gpu)?;
    let elapsed = start.elapsed();
    let ev100 = exposure_ev100(f.exposure, &radiance)?;
    let size = (scene.camera.width_px, scene.camera.height_px);
    let mut text = vec![
        ("atmos:beam_method", id.to_string()),
        ("atmos:beam_settings", f.set.join(", ")),
        ("atmos:beams_scene", path.display().to_string()),
        ("atmos:exposure_ev100", ev100.to_string()),
    ];
    match &output {
        Output::Png(png) => {
            let pixels = image.tone_mapped(&gpu, ev100)?;
            write_atomically(png, &png_of_size(size, &pixels, &text, &[])?)?;
        }
        Output::Exr(exr) => {
            text.push(("atmos:units", EXR_UNITS.into()));
            write_atomically(exr, &exr_of_size(size, None, &text, &radiance)?)?;
        }
    }
    let gpu_time = gpu_ms.map_or("no timestamps".into(), |ms| format!("{id} {ms:.1} ms"));
    eprintln!(
        "{}x{} beams {id} frame on {} in {elapsed:.1?} (GPU: {gpu_time}; EV100 {ev100:.1}); wrote {}",
        size.0,
        size.1,
        gpu.adapter_summary(),
        out.display()
    );
    Ok(())
}
