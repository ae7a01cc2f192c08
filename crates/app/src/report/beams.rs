//! The beams section of `atmos report` (docs/beams.md, "In atmos report"): every beam
//! method and setting against the reference on the shipped scenes. Per scene, the
//! scene's camera at a few pixels (its aspect kept) gives the rays; each method's
//! luminance there is compared with the reference's (relative RMS and largest
//! |L - L_ref| / max(L_ref, 1 % of the brightest L_ref)), its CPU frame time is its
//! preparation plus its time per ray times the pixels of a 1280 x 720 frame, and its
//! GPU frame time is measured at 1280 x 720 where the method is on the GPU. A setting
//! that names qtable2002's `resolution_divisor` (a reduced walk upsampled answers for
//! the frame's pixels) is prepared for the 1280 x 720 frame and asked the same rays.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::Context;
use atmosphere_core::beams::camera::Camera;
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::qtable2002::upsample::RESOLUTION_DIVISOR;
use atmosphere_core::beams::methods::registry::prepare;
use atmosphere_core::beams::ray::SceneRay;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::shafts::beams::gpu_methods::{GPU_BEAM_METHODS, PreparedBeams};

use crate::report::plot::{Point, Series, TimeAxis, mean_points};

/// The shipped scenes (`assets/scenes/beams/`).
pub const BEAM_SCENES: [&str; 4] = [
    "sphere_spotlight.toml",
    "teapot_spotlight.toml",
    "stage_five_spots.toml",
    "stained_glass_room.toml",
];

/// The settings the report measures: the march at two step counts, the papers'
/// defaults and a cheaper setting of each, the q-table with fewer sub-planes, and the
/// q-table with its samples weighted by g and counted per ray (not the paper's), walked
/// at every pixel and at a quarter of the resolution.
pub const BEAM_VARIANTS: [&str; 10] = [
    "march steps=32",
    "march steps=128",
    "planes2000",
    "planes2000 planes=50",
    "qtable2002",
    "qtable2002 epsilon=0.1",
    "qtable2002 epsilon=1",
    "qtable2002 resolution_divisor=4",
    "qtable2002 resolution_divisor=1 weighted_samples=true subplanes_per_ray=true epsilon=0.005",
    "qtable2002 resolution_divisor=4 weighted_samples=true subplanes_per_ray=true epsilon=0.005 upsample_tolerance=0.3",
];

/// The label of the reference's row of each scene (its errors zero by definition).
pub const REFERENCE_LABEL: &str = "reference";

/// Rays across each scene's camera in the report.
pub const RAYS_ACROSS: u32 = 24;

/// The folder of the shipped scenes.
pub fn shipped_folder() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/beams")
}

/// The frame the times are for.
pub const FRAME: (u32, u32) = (1280, 720);

/// The CPU axis of the beams plot.
pub const BEAMS_CPU_AXIS: TimeAxis = TimeAxis {
    caption: "Beams: luminance error against frame time (CPU, one thread)",
    description: "time of a 1280 x 720 frame on one CPU thread, s (mean over the scenes)",
    unit: "s",
};

/// The GPU axis of the beams plot.
pub const BEAMS_GPU_AXIS: TimeAxis = TimeAxis {
    caption: "Beams: luminance error against frame time (GPU)",
    description: "time of a 1280 x 720 GPU frame, ms (mean over the scenes)",
    unit: "ms",
};

/// One setting on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct BeamRow {
    pub scene: String,
    pub label: String,
    pub method: BeamMethodId,
    /// Relative RMS and largest relative error of luminance.
    pub rms: f64,
    pub max: f64,
    /// Dobashi et al. 2002's "average error in intensities" (section 4.3), here of
    /// luminance: the mean |L - L_ref| over the mean L_ref.
    pub mean_error: f64,
    pub cpu_frame_s: f64,
    /// GPU time of a 1280 x 720 frame, ms, where measured.
    pub gpu_ms: Option<f64>,
}

/// Measures `variants` on `scenes` (files in `folder`), `width` rays across each
/// camera; GPU times on `gpu` when given.
pub fn measure(
    folder: &Path,
    scenes: &[&str],
    variants: &[&str],
    width: u32,
    gpu: Option<&GpuContext>,
) -> anyhow::Result<Vec<BeamRow>> {
    let color = SpectrumToColor::new(&RGB_WAVELENGTHS_NM)?;
    let mut rows = Vec::new();
    for name in scenes {
        let path = folder.join(name);
        let full = BeamScene::load(&path).with_context(|| path.display().to_string())?;
        let mut at_frame = full.clone();
        (at_frame.camera.width_px, at_frame.camera.height_px) = FRAME;
        let mut scene = full.clone();
        let aspect = f64::from(full.camera.height_px) / f64::from(full.camera.width_px);
        scene.camera.width_px = width;
        scene.camera.height_px = ((f64::from(width) * aspect).round() as u32).max(1);
        let report_rays: Vec<SceneRay> = (0..scene.camera.height_px)
            .flat_map(|y| (0..scene.camera.width_px).map(move |x| (x, y)))
            .map(|(x, y)| scene.camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5))
            .collect();
        let frame_rays = frame_pixel_rays(&scene.camera, &at_frame.camera);
        // A setting's luminance on the report's rays, or prepared for the frame and
        // asked on its pixels (`on_frame`), and its CPU frame time.
        let luminance = |id: BeamMethodId,
                         options: &[String],
                         on_frame: bool|
         -> anyhow::Result<(Vec<f64>, f64)> {
            let settings = BeamSettings {
                wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
                options: ModelOptions::parse(options)?,
            };
            let (prepared_for, rays) = if on_frame {
                (&at_frame, &frame_rays)
            } else {
                (&scene, &report_rays)
            };
            let start = Instant::now();
            let method = prepare(id, prepared_for, &settings)?;
            let prepared_s = start.elapsed().as_secs_f64();
            let start = Instant::now();
            let mut out = Vec::with_capacity(rays.len());
            for ray in rays {
                out.push(color.luminance_cd_m2(&method.radiance(ray)?));
            }
            let per_ray = start.elapsed().as_secs_f64() / out.len() as f64;
            Ok((out, prepared_s + per_ray * f64::from(FRAME.0 * FRAME.1)))
        };
        // The reference on the frame's pixels, for the settings asked there.
        let mut frame_truth: Option<Vec<f64>> = None;
        eprintln!("report: beams on {name}, the reference");
        let (truth, reference_frame_s) = luminance(BeamMethodId::Reference, &[], false)?;
        // The reference's own row: its CPU frame time, the brute force the methods'
        // times compare with (Dobashi et al. 2002 section 4.3 compare with ray tracing).
        rows.push(BeamRow {
            scene: name.to_string(),
            label: REFERENCE_LABEL.to_string(),
            method: BeamMethodId::Reference,
            rms: 0.0,
            max: 0.0,
            mean_error: 0.0,
            cpu_frame_s: reference_frame_s,
            gpu_ms: None,
        });
        for (k, variant) in variants.iter().enumerate() {
            eprintln!(
                "report: beams on {name}, {}/{} {variant}",
                k + 1,
                variants.len()
            );
            let mut words = variant.split_whitespace();
            let method: BeamMethodId = words.next().unwrap_or_default().parse()?;
            let options: Vec<String> = words.map(str::to_string).collect();
            let (values, cpu_frame_s) = luminance(method, &options, frame_sized(&options))?;
            let truth = if frame_sized(&options) {
                if frame_truth.is_none() {
                    eprintln!("report: beams on {name}, the reference on the frame's pixels");
                    frame_truth = Some(luminance(BeamMethodId::Reference, &[], true)?.0);
                }
                frame_truth.as_deref().unwrap_or_default()
            } else {
                &truth
            };
            let floor = 0.01 * truth.iter().copied().fold(0.0, f64::max);
            let errors: Vec<f64> = values
                .iter()
                .zip(truth)
                .map(|(l, t)| (l - t).abs() / t.max(floor))
                .collect();
            let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
            let mean_error = values
                .iter()
                .zip(truth)
                .map(|(l, t)| (l - t).abs())
                .sum::<f64>()
                / truth.iter().sum::<f64>().max(f64::MIN_POSITIVE);
            let gpu_ms = match gpu {
                Some(gpu) if GPU_BEAM_METHODS.contains(&method) => {
                    gpu_frame_ms(gpu, &full, method, &options)?
                }
                _ => None,
            };
            rows.push(BeamRow {
                scene: name.to_string(),
                label: variant.to_string(),
                method,
                rms,
                max: errors.iter().copied().fold(0.0, f64::max),
                mean_error,
                cpu_frame_s,
                gpu_ms,
            });
        }
    }
    Ok(rows)
}

/// The pixels of `frame` (the same view, another size) nearest the rays through the
/// pixel centres of `camera`, each moved within its share of the frame by a fixed
/// scramble of its row and column: a reduced walk upsampled is as exact as its walk on
/// the pixels that fall on a reduced pixel's ray, and a grid of rays would meet the
/// reduced pixels at one place only.
fn frame_pixel_rays(camera: &Camera, frame: &Camera) -> Vec<SceneRay> {
    let (w, h) = (f64::from(camera.width_px), f64::from(camera.height_px));
    let (fw, fh) = (f64::from(frame.width_px), f64::from(frame.height_px));
    // Frame pixels per ray of `camera` across (same vertical view, other aspect) and down.
    let across = (w / h) / (fw / fh) * fw / w;
    let down = fh / h;
    let scramble = |k: u32| f64::from(k % 16) / 16.0 - 0.5;
    (0..camera.height_px)
        .flat_map(|y| (0..camera.width_px).map(move |x| (x, y)))
        .map(|(x, y)| {
            let fx = 0.5 * fw + (f64::from(x) + 0.5 - 0.5 * w + scramble(7 * x + 13 * y)) * across;
            let fy = (f64::from(y) + 0.5 + scramble(11 * x + 5 * y)) * down;
            let px = fx.floor().clamp(0.0, fw - 1.0);
            let py = fy.floor().clamp(0.0, fh - 1.0);
            frame.ray(px + 0.5, py + 0.5)
        })
        .collect()
}

/// Whether a setting is prepared for the 1280 x 720 frame: where it names a
/// `resolution_divisor` (a reduced walk upsampled answers for the frame's pixels; the
/// divisor 1 is the walk prepared alike, to compare with).
fn frame_sized(options: &[String]) -> bool {
    options.iter().any(|o| {
        o.split_once('=')
            .is_some_and(|(k, _)| k.trim() == RESOLUTION_DIVISOR.key)
    })
}

/// The second of two 1280 x 720 frames of `method` on `scene`, ms (the first compiles
/// and uploads); `None` without timestamps.
fn gpu_frame_ms(
    gpu: &GpuContext,
    scene: &BeamScene,
    method: BeamMethodId,
    options: &[String],
) -> anyhow::Result<Option<f64>> {
    let mut scene = scene.clone();
    (scene.camera.width_px, scene.camera.height_px) = FRAME;
    let settings = BeamSettings {
        wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
        options: ModelOptions::parse(options)?,
    };
    let renderer = PreparedBeams::new(method, &scene, &settings)?.renderer(gpu)?;
    renderer.render(gpu)?;
    Ok(renderer.render(gpu)?.1)
}

/// The section's Markdown: one table row per scene and setting.
pub fn markdown(rows: &[BeamRow], width: u32) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "## Light beams\n\nEach beam method and setting against the reference on the shipped \
         scenes (`assets/scenes/beams/`), {width} rays across each camera: relative RMS and \
         largest |L - L_ref| / max(L_ref, 1 % of the brightest L_ref) of luminance; the \
         mean |L - L_ref| over the mean L_ref (Dobashi et al. 2002's average error); CPU time \
         of a 1280 x 720 frame on one thread (preparation plus time per ray); GPU time of a \
         1280 x 720 frame (ms, `-` off the GPU or without timestamps). A setting that names `resolution_divisor` is prepared for the \
         1280 x 720 frame and asked at as many of its pixels, one in each block of the \
         grid moved within it by a fixed scramble (`resolution_divisor=1`: every pixel \
         walked, asked alike); those pixels come nearer the lights than the grid's \
         centres, and the rays beside a light, the brightest, weigh most in the mean \
         error (docs/beams/qtable2002.md). Plots: \
         `beams_error_vs_time.png`, `beams_error_vs_gpu_time.png`.\n"
    );
    let _ = writeln!(
        out,
        "| scene | setting | RMS error % | max error % | mean error % | CPU frame s | GPU frame ms |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    for r in rows {
        let gpu = r
            .gpu_ms
            .map_or_else(|| "-".to_string(), |ms| format!("{ms:.1}"));
        let _ = writeln!(
            out,
            "| {} | {} | {:.2} | {:.2} | {:.2} | {:.1} | {gpu} |",
            r.scene,
            r.label,
            100.0 * r.rms,
            100.0 * r.max,
            100.0 * r.mean_error,
            r.cpu_frame_s
        );
    }
    out.push_str(&cost_notes(rows));
    out
}

/// The notes under the table: what the cost of Dobashi et al. 2002 section 4.3 compares
/// with, and each GPU setting's frame as a share of its scene's reference CPU frame.
fn cost_notes(rows: &[BeamRow]) -> String {
    let mut out = String::from(
        "\nNotes. The `reference` rows are the ground truth's own CPU frame (its errors zero \
         by definition). Dobashi et al. 2002 section 4.3 compare their method's frame on \
         the GPU (0.08 s) with their ground truth's, ray tracing on the CPU (29 s): 1/360. \
         The like-for-like here is a setting's GPU frame over its scene's reference CPU \
         frame; the GPU frame against the march at the step count of equal error, \
         measured in one interleaved `atmos bench` run, is in docs/beams/qtable2002.md.\n",
    );
    let shares: Vec<String> = rows
        .iter()
        .filter_map(|r| {
            let reference = rows
                .iter()
                .find(|t| t.scene == r.scene && t.label == REFERENCE_LABEL)?;
            let ratio = reference.cpu_frame_s * 1e3 / r.gpu_ms?;
            Some(format!("| {} | {} | 1/{ratio:.0} |", r.scene, r.label))
        })
        .collect();
    if !shares.is_empty() {
        out.push_str("\n| scene | setting | GPU frame / reference CPU frame |\n|---|---|---|\n");
        for line in shares {
            let _ = writeln!(out, "{line}");
        }
    }
    out
}

/// One point per setting, its error and time the means over the scenes: (CPU, GPU).
pub fn points(rows: &[BeamRow], variants: &[&str]) -> (Vec<Point>, Vec<Point>) {
    let (mut cpu, mut gpu) = (Vec::new(), Vec::new());
    for variant in variants {
        let own: Vec<&BeamRow> = rows.iter().filter(|r| r.label == *variant).collect();
        let Some(first) = own.first() else {
            continue;
        };
        let scenes: Vec<(f64, f64, Option<f64>)> = own
            .iter()
            .map(|r| (r.cpu_frame_s, r.rms, r.gpu_ms))
            .collect();
        let (point, gpu_point) = mean_points(variant, Series::Beam(first.method), &scenes);
        cpu.push(point);
        gpu.extend(gpu_point);
    }
    (cpu, gpu)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_march_steps_come_closer_to_the_reference() {
        let variants = ["march steps=4", "march steps=128"];
        let rows = measure(
            &shipped_folder(),
            &["sphere_spotlight.toml"],
            &variants,
            6,
            None,
        )
        .unwrap();
        assert_eq!(rows.len(), 3);
        let (reference, rows) = (&rows[0], &rows[1..]);
        assert_eq!(reference.label, REFERENCE_LABEL);
        assert!(reference.cpu_frame_s > 0.0 && reference.rms == 0.0);
        assert!(
            rows.iter()
                .all(|r| r.rms.is_finite() && r.cpu_frame_s > 0.0)
        );
        assert!(rows[1].rms < rows[0].rms, "{rows:?}");
        assert!(rows[0].max >= rows[0].rms);
        assert!(rows[1].mean_error < rows[0].mean_error && rows[1].mean_error > 0.0);
        let text = markdown(rows, 6);
        assert!(
            text.contains("| sphere_spotlight.toml | march steps=128 |"),
            "{text}"
        );
        assert!(text.contains("Notes. The `reference` rows"), "{text}");
        let mut timed = vec![reference.clone(), rows[1].clone()];
        // A GPU frame of a 4000th of the reference's CPU frame.
        timed[1].gpu_ms = Some(reference.cpu_frame_s / 4.0);
        assert!(
            cost_notes(&timed).contains("| sphere_spotlight.toml | march steps=128 | 1/4000 |"),
            "{}",
            cost_notes(&timed)
        );
        let (cpu, gpu) = points(rows, &variants);
        assert_eq!(cpu.len(), 2);
        assert!(gpu.is_empty());
        let dir = tempfile::tempdir().unwrap();
        let plot = dir.path().join("beams_error_vs_time.png");
        crate::report::plot::draw(&plot, &BEAMS_CPU_AXIS, &cpu).unwrap();
        assert!(std::fs::metadata(&plot).unwrap().len() > 1000);
    }

    #[test]
    #[ignore = "slow: the reference and every setting on the four shipped scenes"]
    fn every_setting_is_measured_on_every_shipped_scene() {
        let rows = measure(&shipped_folder(), &BEAM_SCENES, &BEAM_VARIANTS, 12, None).unwrap();
        assert_eq!(rows.len(), BEAM_SCENES.len() * (1 + BEAM_VARIANTS.len()));
        assert!(rows.iter().all(|r| r.rms.is_finite()));
        println!("{}", markdown(&rows, 12));
    }

    /// A named divisor, 1 included, sizes the setting for the frame.
    #[test]
    fn frame_sized_settings_are_told_apart() {
        let options = |o: &str| vec![o.to_string()];
        assert!(frame_sized(&options("resolution_divisor=4")));
        assert!(frame_sized(&options("resolution_divisor=1")));
        assert!(!frame_sized(&options("epsilon=0.1")));
    }

    #[test]
    #[ignore = "slow: the reference and the reduced walks on the sphere scene"]
    fn the_reduced_walk_upsampled_against_the_walk_on_the_sphere_scene() {
        let variants = [
            "qtable2002",
            "qtable2002 resolution_divisor=1",
            "qtable2002 resolution_divisor=2",
            "qtable2002 resolution_divisor=4",
            "qtable2002 resolution_divisor=4 upsample_tolerance=0.02",
            "qtable2002 resolution_divisor=4 upsample_tolerance=0.1",
            "qtable2002 resolution_divisor=8",
        ];
        let scenes = ["sphere_spotlight.toml"];
        let rows = measure(&shipped_folder(), &scenes, &variants, RAYS_ACROSS, None).unwrap();
        println!("{}", markdown(&rows, RAYS_ACROSS));
    }

    #[test]
    #[ignore = "slow: the march at up to 8191 steps against the reference"]
    fn the_march_that_matches_the_q_tables_error_on_the_sphere_scene() {
        let variants = [
            "march steps=1024",
            "march steps=2048",
            "march steps=4096",
            "march steps=8191",
            "march steps=8191 shadow_map_px=2048",
            "qtable2002",
        ];
        let scenes = ["sphere_spotlight.toml"];
        let rows = measure(&shipped_folder(), &scenes, &variants, RAYS_ACROSS, None).unwrap();
        println!("{}", markdown(&rows, RAYS_ACROSS));
    }

    #[test]
    #[ignore = "slow: the reference, the walks and the march at up to 8191 steps"]
    fn the_rays_that_set_the_mean_error_on_the_sphere_scene() {
        // Every setting on the frame's pixels the reduced walks are asked at, and the
        // rays that carry most of |L - L_ref|, with their distance from the light.
        let variants = [
            "qtable2002 resolution_divisor=1",
            "qtable2002 resolution_divisor=1 epsilon=0",
            "qtable2002 resolution_divisor=1 weighted_samples=true epsilon=0",
            "qtable2002 resolution_divisor=1 subplanes_per_ray=true",
            "qtable2002 resolution_divisor=1 weighted_samples=true subplanes_per_ray=true",
            "qtable2002 resolution_divisor=1 weighted_samples=true subplanes_per_ray=true epsilon=0.005",
            "qtable2002 resolution_divisor=1 weighted_samples=true subplanes_per_ray=true epsilon=0.002",
            "qtable2002 resolution_divisor=4",
            "qtable2002 resolution_divisor=4 weighted_samples=true subplanes_per_ray=true",
            "qtable2002 resolution_divisor=4 weighted_samples=true subplanes_per_ray=true epsilon=0.005",
            "qtable2002 resolution_divisor=4 weighted_samples=true subplanes_per_ray=true epsilon=0.005 upsample_tolerance=0.3",
            "qtable2002 resolution_divisor=4 weighted_samples=true subplanes_per_ray=true epsilon=0.005 upsample_tolerance=0.2",
            "march steps=2048",
            "march steps=4096",
            "march steps=8191",
        ];
        let color = SpectrumToColor::new(&RGB_WAVELENGTHS_NM).unwrap();
        let full = BeamScene::load(&shipped_folder().join("sphere_spotlight.toml")).unwrap();
        let mut frame = full.clone();
        (frame.camera.width_px, frame.camera.height_px) = FRAME;
        let mut grid = full.clone();
        grid.camera.width_px = RAYS_ACROSS;
        grid.camera.height_px = RAYS_ACROSS * full.camera.height_px / full.camera.width_px;
        let rays = frame_pixel_rays(&grid.camera, &frame.camera);
        let light = full.lights[0].position_m().unwrap();
        let luminance = |variant: &str| {
            let mut words = variant.split_whitespace();
            let id: BeamMethodId = words.next().unwrap().parse().unwrap();
            let options: Vec<&str> = words.collect();
            let settings = BeamSettings {
                wavelengths_nm: RGB_WAVELENGTHS_NM.to_vec(),
                options: ModelOptions::parse(&options).unwrap(),
            };
            let method = prepare(id, &frame, &settings).unwrap();
            rays.iter()
                .map(|r| color.luminance_cd_m2(&method.radiance(r).unwrap()))
                .collect::<Vec<f64>>()
        };
        let truth = luminance("reference");
        let total: f64 = truth.iter().sum();
        let mut means = Vec::new();
        for variant in variants {
            let values = luminance(variant);
            let mut shares: Vec<(f64, usize)> = values
                .iter()
                .zip(&truth)
                .map(|(l, t)| (l - t).abs() / total)
                .zip(0..)
                .collect();
            let mean: f64 = shares.iter().map(|s| s.0).sum();
            means.push(mean);
            shares.sort_by(|a, b| b.0.total_cmp(&a.0));
            println!("{variant}: mean error {:.2} %", 100.0 * mean);
            for &(share, i) in &shares[..3] {
                let r = &rays[i];
                let to_light = light - r.origin_m;
                let miss = (to_light - r.direction * to_light.dot(r.direction)).length();
                println!(
                    "  {:.2} % of it from a ray {miss:.2} m from the light, {:+.1} % there",
                    100.0 * share,
                    100.0 * (values[i] / truth[i] - 1.0)
                );
            }
        }
        // The paper's 1.5 %: not met by the walk here, met with the weighted samples
        // counted per ray, walked and at a quarter of the resolution.
        assert!(means[0] > 0.015, "the walk: {}", means[0]);
        assert!(means[5] < 0.015 && means[10] < 0.015, "{means:?}");
    }
}
