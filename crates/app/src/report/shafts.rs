//! The light-shafts section of `atmos report` (docs/shafts.md, "In atmos report"):
//! every model with shafts and its settings against the reference on the scenes with
//! terrain (the default view over the Alps at sunset and its sunrise twin). Each scene's
//! camera gives a grid of rays placed over the Earth's relief and ended on it, as
//! `atmos probe --terrain` places them; the reference answers with the exact march
//! through the relief at every quadrature node, the models with the frame's shadow map.
//! Single scattering only: it is the light the terrain's shadow takes out, and orders two
//! and up are unshadowed in the models and the reference alike. Each model is also
//! measured without shafts on the same rays, which shows what its shafts buy.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Context;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::Renderer;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

use crate::bench::shafts::ShaftTimes;
use crate::bench::variant::Variant;
use crate::probe_terrain::{Shadows, TerrainPlace, evaluate_timed};
use crate::progress::Progress;
use crate::render::scene::Scene;
use crate::report::plot::{Point, Series, TimeAxis, mean_points};
use crate::report::views::ReportView;

/// The shipped scenes with terrain (`assets/scenes/`).
pub const SHAFT_SCENES: [&str; 2] = ["default.toml", "alps_sunrise.toml"];

/// The models with shafts at the settings the main report measures.
pub const SHAFT_VARIANTS: [&str; 7] = [
    "hillaire",
    "nishita samples=16",
    "nishita",
    "oneil",
    "oneil samples=16",
    "bruneton",
    "dobashi",
];

/// The frame the times are for.
pub const FRAME: (u32, u32) = (1280, 720);

/// Frame pairs (with and without shafts) timed on the GPU per scene and setting.
const GPU_FRAMES: usize = 3;

/// The CPU axis of the shafts plot.
pub const SHAFTS_CPU_AXIS: TimeAxis = TimeAxis {
    caption: "Light shafts: single-scattering error against frame time (CPU, one thread)",
    description: "time of a 1280 x 720 frame on one CPU thread, s (mean over the scenes)",
    unit: "s",
};

/// The GPU axis of the shafts plot.
pub const SHAFTS_GPU_AXIS: TimeAxis = TimeAxis {
    caption: "Light shafts: single-scattering error against frame time (GPU)",
    description: "GPU time of the model's pass with shafts at 1280 x 720, ms (mean over the scenes)",
    unit: "ms",
};

/// The folder of the shipped scenes.
pub fn shipped_folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes")
}

/// A scene's camera as the report's pinhole (in the sun's frame) and its place.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaftView {
    pub scene: String,
    pub camera: ReportView,
    pub place: TerrainPlace,
}

impl ShaftView {
    /// The view of the scene at `path`, `columns x rows` rays across its field of view.
    pub fn load(path: &Path, columns: usize, rows: usize) -> anyhow::Result<ShaftView> {
        let scene = Scene::load(path)?.resolved()?;
        let name = path.display();
        let (Some(latitude_deg), Some(longitude_deg)) = (scene.latitude_deg, scene.longitude_deg)
        else {
            anyhow::bail!("{name}: a shafts scene needs latitude_deg and longitude_deg");
        };
        if scene.terrain != Some(true) {
            anyhow::bail!("{name}: a shafts scene needs `terrain = true`");
        }
        let field = |v: Option<f64>| v.unwrap_or_default();
        let sun_azimuth_deg = field(scene.sun_azimuth_deg);
        let place = TerrainPlace::new(latitude_deg, longitude_deg, sun_azimuth_deg)
            .with_context(|| name.to_string())?;
        // Frames take a vertical field of view; the report's pinhole a horizontal one.
        let aspect = f64::from(field_u32(scene.width)) / f64::from(field_u32(scene.height));
        let half_vertical = 0.5 * field(scene.fov_deg).to_radians();
        let fov_deg = 2.0 * (half_vertical.tan() * aspect).atan().to_degrees();
        let camera = ReportView {
            id: "shafts",
            title: "shafts",
            atmosphere: "earth",
            altitude_m: field(scene.altitude_m),
            sun_zenith_deg: field(scene.sun_zenith_deg),
            look_elevation_deg: 90.0 - field(scene.view_zenith_deg),
            look_azimuth_deg: field(scene.view_azimuth_deg) - sun_azimuth_deg,
            fov_deg,
            columns,
            rows,
        };
        let file = path.file_name().map(|f| f.to_string_lossy().into_owned());
        Ok(ShaftView {
            scene: file.unwrap_or_else(|| name.to_string()),
            camera,
            place,
        })
    }
}

fn field_u32(v: Option<u32>) -> u32 {
    v.unwrap_or(1).max(1)
}

/// One setting on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct ShaftRow {
    pub scene: String,
    pub label: String,
    pub model: ModelId,
    /// Relative RMS and largest relative luminance error with the model's shafts.
    pub rms: f64,
    pub max: f64,
    /// Relative RMS error of the same model without shafts.
    pub rms_without: f64,
    /// The mean share of the reference's single scattering the exact shadow takes out.
    pub shadow_share: f64,
    /// Preparation (tables, the frame's shadow map) plus the time per ray times the
    /// pixels of a 1280 x 720 frame, s.
    pub cpu_frame_s: f64,
    /// GPU times of the model's pass with and without shafts, where measured.
    pub gpu: Option<ShaftTimes>,
}

/// Luminance per ray of `id` at `settings` with or without shadows, and the CPU frame
/// time the evaluation implies.
fn luminance(
    view: &ShaftView,
    earth: &Atmosphere,
    (id, settings): (ModelId, &ModelSettings),
    shadows: Shadows,
    color: &SpectrumToColor,
) -> anyhow::Result<(Vec<f64>, f64)> {
    let rays = view.camera.rays(earth);
    let ((_, answers), timing) = evaluate_timed(id, earth, settings, &rays, &view.place, shadows)?;
    let values = answers
        .into_iter()
        .map(|a| Ok(color.luminance_cd_m2(&a?.radiance)))
        .collect::<anyhow::Result<Vec<f64>>>()
        .with_context(|| format!("{id} on {}", view.scene))?;
    let per_ray = timing.rays_s / rays.len().max(1) as f64;
    let pixels = f64::from(FRAME.0 * FRAME.1);
    Ok((values, timing.prepare_s + per_ray * pixels))
}

/// |L - L_ref| / L_ref per ray; rays the reference sees no light on are left out.
fn relative_errors(values: &[f64], truth: &[f64]) -> Vec<f64> {
    values
        .iter()
        .zip(truth)
        .filter(|(_, t)| **t > 0.0)
        .map(|(l, t)| (l - t).abs() / t)
        .collect()
}

fn rms(errors: &[f64]) -> f64 {
    (errors.iter().map(|e| e * e).sum::<f64>() / errors.len().max(1) as f64).sqrt()
}

/// Measures `variants` on `scenes` (files in `folder`), `columns x rows` rays each; GPU
/// times of each setting's pass with and without shafts on `renderer` when given.
pub fn measure(
    folder: &Path,
    scenes: &[&str],
    variants: &[&str],
    (columns, rows): (usize, usize),
    mut renderer: Option<&mut Renderer>,
) -> anyhow::Result<Vec<ShaftRow>> {
    let earth = Atmosphere::preset("earth")?;
    let color = SpectrumToColor::new(&RGB_WAVELENGTHS_NM)?;
    let single = |variant: &Variant| ModelSettings {
        wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
        max_orders: Some(1),
        ..variant.settings()
    };
    let parsed = variants
        .iter()
        .map(|text| Variant::parse(text))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let mut out = Vec::new();
    for name in scenes {
        let path = folder.join(name);
        let view = ShaftView::load(&path, columns, rows)?;
        let reference = (
            ModelId::Reference,
            &single(&Variant::new(ModelId::Reference, None, &[])),
        );
        let (truth, _) = luminance(&view, &earth, reference, Shadows::Terrain, &color)?;
        let (lit, _) = luminance(&view, &earth, reference, Shadows::Off, &color)?;
        let shares = relative_errors(&truth, &lit);
        let shadow_share = shares.iter().sum::<f64>() / shares.len().max(1) as f64;
        for (k, variant) in parsed.iter().enumerate() {
            eprintln!(
                "report: shafts on {name}, {}/{} {}",
                k + 1,
                parsed.len(),
                variant.label
            );
            let settings = single(variant);
            let model = (variant.model, &settings);
            let (with, cpu_frame_s) = luminance(&view, &earth, model, Shadows::Terrain, &color)?;
            let (without, _) = luminance(&view, &earth, model, Shadows::Off, &color)?;
            let errors = relative_errors(&with, &truth);
            let gpu = match renderer.as_deref_mut() {
                Some(renderer) => Some(gpu_times(renderer, &path, variant)?),
                None => None,
            };
            out.push(ShaftRow {
                scene: view.scene.clone(),
                label: variant.label.clone(),
                model: variant.model,
                rms: rms(&errors),
                max: errors.iter().copied().fold(0.0, f64::max),
                rms_without: rms(&relative_errors(&without, &truth)),
                shadow_share,
                cpu_frame_s,
                gpu,
            });
        }
    }
    Ok(out)
}

/// The model's pass with and without shafts on the scene at `path` at 1280 x 720 (all
/// orders, as a frame draws it), medians of interleaved pairs (`atmos bench
/// --shafts-scene`'s machinery).
fn gpu_times(
    renderer: &mut Renderer,
    path: &Path,
    variant: &Variant,
) -> anyhow::Result<ShaftTimes> {
    let overrides = Scene {
        model: Some(variant.model),
        width: Some(FRAME.0),
        height: Some(FRAME.1),
        set: variant
            .options
            .items()
            .map(|(key, value)| format!("{key}={value}"))
            .collect(),
        ..Scene::default()
    };
    let frames = crate::bench::shafts::frames_per_scene(GPU_FRAMES) as u64;
    let progress = Progress::new(
        &format!("report: shafts, {}", variant.label),
        "frames",
        frames,
    );
    let times = crate::bench::shafts::measure(renderer, path, (&overrides, GPU_FRAMES), &progress);
    progress.finish();
    times
}

/// The section's Markdown: one table row per scene and setting.
pub fn markdown(rows: &[ShaftRow], (columns, rows_per_view): (usize, usize)) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Light shafts\n\nEach model with light shafts, at each setting, against the \
         reference on the shipped scenes with terrain (`assets/scenes/`), {columns} x \
         {rows_per_view} rays across each camera, placed over the Earth's relief and ended \
         on it as `atmos probe --terrain` places them. Single scattering only (orders two \
         and up are unshadowed in every model and in the reference): the reference tests \
         the sun's visibility by the exact march through the relief at every quadrature \
         node, the models by the frame's shadow map (docs/shafts.md). Relative RMS and \
         largest |L - L_ref| / L_ref of luminance with the model's shafts, and its RMS \
         without them on the same rays; shadow: the mean share of the reference's light \
         the exact shadow takes out. CPU: a 1280 x 720 frame on one thread (tables, the \
         shadow map, then the time per ray). GPU: the model's pass with shafts and without \
         (all orders, as the frame draws it) at 1280 x 720, medians of {GPU_FRAMES} \
         interleaved pairs after a warm-up pair. Plots: `shafts_error_vs_time.png`, \
         `shafts_error_vs_gpu_time.png`.\n"
    );
    let _ = writeln!(
        out,
        "| scene | setting | shadow % | RMS error % | max error % | RMS without shafts % | CPU frame s | GPU pass with shafts ms | without ms | with / without |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|---|");
    let ms = |v: Option<f64>| v.map_or_else(|| "-".to_string(), |v| format!("{v:.1}"));
    for r in rows {
        let gpu = r.gpu.as_ref();
        let _ = writeln!(
            out,
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} |",
            r.scene,
            r.label,
            100.0 * r.shadow_share,
            100.0 * r.rms,
            100.0 * r.max,
            100.0 * r.rms_without,
            r.cpu_frame_s,
            ms(gpu.and_then(|g| g.pass_with_ms)),
            ms(gpu.and_then(|g| g.pass_without_ms)),
            gpu.and_then(ShaftTimes::pass_ratio)
                .map_or_else(|| "-".to_string(), |x| format!("{x:.2}")),
        );
    }
    out
}

/// One point per setting, its error and time the means over the scenes: (CPU, GPU).
pub fn points(rows: &[ShaftRow], variants: &[&str]) -> (Vec<Point>, Vec<Point>) {
    let (mut cpu, mut gpu) = (Vec::new(), Vec::new());
    for variant in variants {
        let own: Vec<&ShaftRow> = rows.iter().filter(|r| r.label == *variant).collect();
        let Some(first) = own.first() else {
            continue;
        };
        let scenes: Vec<(f64, f64, Option<f64>)> = own
            .iter()
            .map(|r| {
                (
                    r.cpu_frame_s,
                    r.rms,
                    r.gpu.as_ref().and_then(|g| g.pass_with_ms),
                )
            })
            .collect();
        let (point, gpu_point) = mean_points(variant, Series::Sky(first.model), &scenes);
        cpu.push(point);
        gpu.extend(gpu_point);
    }
    (cpu, gpu)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On the default view's rays, the reference's exact shadow takes light out, and
    /// hillaire with its shafts is nearer the reference than without them: what the
    /// section is for. A handful of rays keeps it quick.
    #[test]
    fn shafts_bring_hillaire_nearer_the_shadowed_reference() {
        let rows = measure(
            &shipped_folder(),
            &["default.toml"],
            &["hillaire"],
            (8, 5),
            None,
        )
        .unwrap();
        assert_eq!(rows.len(), 1);
        let row = &rows[0];
        println!("{row:?}");
        assert!(row.shadow_share > 0.005, "{row:?}");
        assert!(row.rms < row.rms_without, "{row:?}");
        assert!(row.max >= row.rms && row.cpu_frame_s > 0.0, "{row:?}");
        let text = markdown(&rows, (8, 5));
        assert!(text.contains("| default.toml | hillaire |"), "{text}");
        let (cpu, gpu) = points(&rows, &["hillaire"]);
        assert_eq!(cpu.len(), 1);
        assert!(gpu.is_empty());
    }

    #[test]
    fn the_sunrise_scene_becomes_a_view_looking_near_the_sun() {
        let view = ShaftView::load(&shipped_folder().join("alps_sunrise.toml"), 16, 9).unwrap();
        assert_eq!(view.scene, "alps_sunrise.toml");
        assert_eq!(view.camera.look_azimuth_deg, 10.0);
        assert!((view.camera.look_elevation_deg + 3.0).abs() < 1e-12);
        // 60 deg vertical at 16:9 is 91.5 deg across.
        assert!(
            (view.camera.fov_deg - 91.49).abs() < 0.01,
            "{}",
            view.camera.fov_deg
        );
        assert_eq!(view.place.sun_azimuth_deg, 100.0);
    }

    #[test]
    fn a_scene_without_terrain_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("flat.toml");
        std::fs::write(
            &path,
            "model = \"hillaire\"\naltitude_m = 100.0\nsun_zenith_deg = 80.0\nlatitude_deg = 46.0\nlongitude_deg = 7.8\n",
        )
        .unwrap();
        let text = format!("{:#}", ShaftView::load(&path, 4, 4).unwrap_err());
        assert!(
            text.contains("flat.toml") && text.contains("terrain = true"),
            "{text}"
        );
    }
}
