//! The command line of `atmos` (clap derive).

use std::path::PathBuf;

use atmosphere_core::models::id::{ModelId, UnknownModel};
use atmosphere_core::models::sky_model::ModelSettings;
use atmosphere_core::sun_position::UtcDateTime;
use clap::{Args, Parser, Subcommand};

use crate::earth_data_flag::EarthDataFlag;
use crate::location_flags::LocationFlags;
use crate::probe_args::{ProbeArgs, parse_probe_model};
use crate::wavelength_flag::Wavelength;

/// Physically based atmospheric scattering.
#[derive(Debug, Parser)]
#[command(name = "atmos", version)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// The interactive viewer window (also `atmos` with no arguments).
    View(ViewArgs),
    /// Radiance and transmittance of given view rays for a given model, CSV in and out.
    Probe(ProbeArgs),
    /// Stiff and extreme cases through every model: a table of pass/fail and worst values.
    Stability(StabilityArgs),
    /// Error against run time of every model on a fixed set of views: README.md and
    /// error_vs_time.png.
    Report(ReportArgs),
    /// One frame of a scene, headless: EXR (linear HDR radiance) or PNG (tone-mapped).
    Render(Box<RenderArgs>),
    /// GPU table build and frame times of every model on this adapter (ground, sunset and
    /// orbit views), per pass, as Markdown tables.
    Bench(BenchArgs),
    /// Every GPU model in six views (noon, sunset, twilight, 10 km, 100 km, orbit) in one
    /// labelled PNG.
    ContactSheet(ContactSheetArgs),
    /// A camera path's frames, headless, to numbered PNG or EXR files; resumable and
    /// shardable (docs/recording.md).
    Record(RecordArgs),
    /// Phase functions of particles (water drops by Lorenz-Mie) as CSV, with Q_ext, Q_sca
    /// and g per wavelength (docs/particles.md).
    Phase(PhaseArgs),
}

/// The flags of `atmos view`.
#[derive(Clone, Debug, Default, Args)]
pub struct ViewArgs {
    /// Render this many frames, then close (for tests and docs); the settings of earlier
    /// runs are neither read nor saved.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: Option<u32>,
    /// With --frames: save the last displayed image to this PNG.
    #[arg(long, value_name = "FILE.png", requires = "frames")]
    pub screenshot: Option<PathBuf>,
    /// Load this camera path (docs/camera-paths.md) into the "Camera path" section and
    /// play it.
    #[arg(long, value_name = "PATH.toml")]
    pub path: Option<PathBuf>,
    /// Show this beams scene (docs/beams.md) instead of the planet.
    #[arg(long, value_name = "FILE.toml", conflicts_with = "path")]
    pub beams_scene: Option<PathBuf>,
    /// The beam method for --beams-scene: march, planes2000 or qtable2002 [default: march].
    #[arg(long, value_name = "METHOD", requires = "beams_scene")]
    pub beams_method: Option<String>,
    /// A setting of the beam method for --beams-scene, KEY=VALUE (repeat the flag; keys
    /// in docs/beams/).
    #[arg(long, value_name = "KEY=VALUE", requires = "beams_scene")]
    pub beams_set: Vec<String>,
    /// Where and how to start, over the saved (or default) settings.
    #[command(flatten)]
    pub start: StartView,
    /// Where the terrain's maps come from.
    #[command(flatten)]
    pub earth_data: EarthDataFlag,
}

/// The flags of `atmos view` that set the starting view (`viewer/start_view.rs`).
#[derive(Clone, Debug, Default, Args)]
pub struct StartView {
    /// Scattering model.
    #[arg(long, value_parser = gpu_model)]
    pub model: Option<ModelId>,
    /// Where the camera stands.
    #[command(flatten)]
    pub location: LocationFlags,
    /// Camera altitude above sea level, m, up to 1e10 (kept at least 1 m above the terrain).
    #[arg(long, value_name = "M")]
    pub altitude_m: Option<f64>,
    /// View heading, degrees from north towards east.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub heading_deg: Option<f64>,
    /// View pitch, degrees above the horizon (negative: down).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub pitch_deg: Option<f64>,
    /// The sun from this UTC date and time, YYYY-MM-DDTHH:MM[:SS].
    #[arg(long, value_name = "DATE", value_parser = parse_utc)]
    pub utc: Option<UtcDateTime>,
    /// Vertical exaggeration of the terrain (1 to 100).
    #[arg(long, value_name = "K")]
    pub exaggeration: Option<f64>,
    /// Draw the smooth sphere instead of the Earth's terrain.
    #[arg(long)]
    pub no_terrain: bool,
    /// Turn the cloud layer on (the panel's "Clouds" section holds its settings).
    #[arg(long)]
    pub clouds: bool,
}

/// A UTC date and time `YYYY-MM-DDTHH:MM[:SS]`, each field checked.
fn parse_utc(text: &str) -> Result<UtcDateTime, String> {
    let bad = || format!("'{text}' is not YYYY-MM-DDTHH:MM[:SS]");
    let (date, time) = text.split_once(['T', ' ']).ok_or_else(bad)?;
    let date: Vec<&str> = date.split('-').collect();
    let time: Vec<&str> = time.trim_end_matches('Z').split(':').collect();
    if date.len() != 3 || !(2..=3).contains(&time.len()) {
        return Err(bad());
    }
    let int = |s: &str| s.parse::<u32>().map_err(|_| bad());
    let second = match time.get(2) {
        Some(s) => s.parse::<f64>().map_err(|_| bad())?,
        None => 0.0,
    };
    let year = date[0].parse::<i32>().map_err(|_| bad())?;
    UtcDateTime::new(
        year,
        int(date[1])?,
        int(date[2])?,
        int(time[0])?,
        int(time[1])?,
        second,
    )
    .map_err(|e| e.to_string())
}

/// The flags of `atmos contact-sheet`.
#[derive(Debug, Args)]
pub struct ContactSheetArgs {
    /// Only these models, one row each (repeat the flag); every model on the GPU when
    /// absent.
    #[arg(long, value_enum)]
    pub model: Vec<ModelId>,
    /// Atmosphere: a preset (earth, clear, hazy, mars) or a TOML file.
    #[arg(long, value_name = "PRESET|FILE.toml", default_value = "earth")]
    pub atmosphere: String,
    /// Size of each image as WIDTHxHEIGHT.
    #[arg(long, value_name = "WIDTHxHEIGHT", default_value = "320x180", value_parser = parse_tile)]
    pub tile: (u32, u32),
    /// The image to write (atomically): FILE.png or FILE.jpg.
    #[arg(
        long,
        value_name = "FILE.png|FILE.jpg",
        default_value = "docs/images/contact_sheet.png"
    )]
    pub out: PathBuf,
}

/// The flags of `atmos bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Only these models (repeat the flag); every model on the GPU when neither this nor
    /// --variant is given. The baseline, nishita with 16 samples, is always measured.
    #[arg(long, value_enum)]
    pub model: Vec<ModelId>,
    /// Also this model with these settings, e.g. "bruneton orders=2" or "hillaire
    /// ms_samples=4 sky_view_samples=10" (repeat the flag; keys in docs/models/).
    #[arg(long, value_name = "MODEL KEY=VALUE ...")]
    pub variant: Vec<String>,
    /// Atmosphere: a preset (earth, clear, hazy, mars) or a TOML file.
    #[arg(long, value_name = "PRESET|FILE.toml", default_value = "earth")]
    pub atmosphere: String,
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Frames measured per view (after one warm-up frame); the median is reported.
    #[arg(long, default_value_t = 5)]
    pub frames: usize,
    /// A beams scene (docs/beams.md): also time beam methods on the GPU rendering its
    /// camera at --width x --height, each frame interleaved with a baseline frame; the
    /// planet models are then measured only when --model or --variant asks.
    #[arg(long, value_name = "FILE.toml")]
    pub beams_scene: Option<PathBuf>,
    /// A beam method on the GPU with its settings for --beams-scene, e.g. "march
    /// steps=32" (repeat the flag; keys in docs/beams/) [default: march].
    #[arg(long, value_name = "METHOD KEY=VALUE ...", requires = "beams_scene")]
    pub beams_variant: Vec<String>,
    /// A scene with rain or cirrus (docs/optics-rendering.md): time its frames at
    /// --width x --height with and without the volumes, interleaved, instead of the
    /// models' tables.
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["beams_scene", "flight"])]
    pub optics_scene: Option<PathBuf>,
    /// A scene with terrain, e.g. assets/scenes/default.toml: time its terrain pass
    /// against its model's sky pass in the same frames at --width x --height, instead of
    /// the models' tables (docs/terrain.md, "Cost of the refinement").
    #[arg(
        long,
        value_name = "FILE.toml",
        conflicts_with_all = ["beams_scene", "flight", "optics_scene"]
    )]
    pub terrain_scene: Option<PathBuf>,
    /// Also write the tables to this Markdown file (atomically).
    #[arg(long, value_name = "FILE.md")]
    pub out: Option<PathBuf>,
    /// Fly this camera path (docs/camera-paths.md, with terrain) as the viewer does, the
    /// terrain's chunk meshes built off the render thread, and report the median and the
    /// longest frame instead of the models' tables (docs/terrain.md, "No popping").
    #[arg(long, value_name = "PATH.toml", conflicts_with = "beams_scene")]
    pub flight: Option<PathBuf>,
    /// With --flight: frames per second of the path's time, 1 to 240 [default: the
    /// path's fps].
    #[arg(long, requires = "flight", value_parser = clap::value_parser!(u32).range(1..=240))]
    pub flight_fps: Option<u32>,
    /// Also time what the cloud layer at this march quality (interactive or offline;
    /// repeat the flag) adds to a hillaire flight view at 2.9 km, each frame interleaved
    /// with the frame without clouds (docs/clouds.md, "Cost").
    #[arg(long, value_name = "interactive|offline", conflicts_with = "flight")]
    pub clouds: Vec<String>,
    /// A scene with terrain (e.g. assets/scenes/default.toml): time its frames at --width
    /// x --height with and without light shafts, interleaved, instead of the models'
    /// tables: the sky pass's GPU time with shafts over without (docs/shafts.md, "Cost").
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["beams_scene", "flight", "optics_scene"])]
    pub shafts_scene: Option<PathBuf>,
}

/// The flags of `atmos record` (docs/recording.md).
#[derive(Debug, Args)]
pub struct RecordArgs {
    /// The camera path file (TOML).
    #[arg(value_name = "PATH.toml")]
    pub path: PathBuf,
    /// The folder the frames go to (created if missing): frame_000000.png, ...
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Frames per second, in (0, 1000] [default: the path's, else 30].
    #[arg(long, value_name = "N")]
    pub fps: Option<f64>,
    /// Image width, px, 1 to 8192 [default: the path's, else 1280].
    #[arg(long, value_name = "PX")]
    pub width: Option<u32>,
    /// Image height, px, 1 to 8192 [default: the path's, else 720].
    #[arg(long, value_name = "PX")]
    pub height: Option<u32>,
    /// The files of each frame: png (tone-mapped), exr (linear HDR) or both.
    #[arg(long, value_enum, default_value_t)]
    pub format: crate::record::naming::FrameFormat,
    /// Only these frames, by index from 0: A..B (A to B-1), A..=B, A.., ..B or A
    /// [default: all].
    #[arg(long, value_name = "A..B")]
    pub frames: Option<String>,
    /// Render shard I of N (from 0) of the selected frames [default: from
    /// SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX, else all].
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// The number of shards of a Kubernetes indexed Job (JOB_COMPLETION_INDEX)
    /// [default: ATMOS_SHARD_COUNT].
    #[arg(long, value_name = "N")]
    pub shard_count: Option<u64>,
    /// Also a video of the whole path from the PNG frames, by ffmpeg (.mp4, .mov, .mkv
    /// or .webm), once every frame is recorded.
    #[arg(long, value_name = "FILE")]
    pub video: Option<PathBuf>,
    /// Where the terrain's maps come from.
    #[command(flatten)]
    pub earth_data: EarthDataFlag,
}

/// The flags of `atmos render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A scene file (TOML) with the fields of the flags below (model, altitude_m,
    /// sun_zenith_deg, ..., set); flags given as well override its fields.
    /// A beams scene (docs/beams.md: a file with `[medium]` and `[[lights]]`) is
    /// rendered from its own camera; of the flags below it takes --model (a beam
    /// method on the GPU: march), --width, --height, --exposure and --set.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// A voxel cloud's scene (docs/clouds.md, "A local volume by half-angle slicing"),
    /// rendered from its own camera by --method; of the flags below it takes
    /// --exposure.
    #[arg(long, value_name = "FILE.toml", conflicts_with_all = ["scene", "model"])]
    pub volume: Option<PathBuf>,
    /// With --volume: slicing (Riley et al. 2004's half-angle slicing, on the GPU), march
    /// (a ray march per pixel, on the CPU) or path (the cloud path tracer, all orders of
    /// scattering, on the CPU: the other two's ground truth) [default: slicing].
    #[arg(long = "method", value_name = "METHOD", requires = "volume")]
    pub volume_method: Option<String>,
    /// With --volume and slicing: run the CPU twin instead of the GPU passes.
    #[arg(long, requires = "volume")]
    pub volume_cpu: bool,
    /// With --volume: slices through the volume, 2 to 4096 [default: the scene's].
    #[arg(long, value_name = "N", requires = "volume")]
    pub slices: Option<u32>,
    /// With --volume and path: paths per pixel and wavelength, 1 to 1048576 [default:
    /// 256].
    #[arg(long, value_name = "N", requires = "volume")]
    pub paths: Option<u64>,
    /// With --volume and path: scattering within this many degrees of the forward
    /// direction taken as none (delta-M), 0 to 20 [default: 0, exact].
    #[arg(long, value_name = "DEG", requires = "volume")]
    pub forward_peak_deg: Option<f64>,
    /// Scattering model (every sky model but the reference is on the GPU), or with a
    /// beams scene a beam method [default: march].
    #[arg(long, value_name = "MODEL", value_parser = parse_probe_model)]
    pub model: Option<String>,
    #[command(flatten)]
    pub fields: crate::render::scene::Scene,
    /// The flags of the scene's `latitude_deg` and `longitude_deg`.
    #[command(flatten)]
    pub location: LocationFlags,
    /// Where the terrain's maps come from.
    #[command(flatten)]
    pub earth_data: EarthDataFlag,
    /// Output image: FILE.exr (linear HDR radiance) or FILE.png (tone-mapped), written
    /// atomically.
    #[arg(long, value_name = "FILE.exr|FILE.png")]
    pub out: PathBuf,
}

/// The flags of `atmos report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Directory of README.md, errors.csv, the plots and the reference caches
    /// reference.csv and reference_single.csv.
    #[arg(long, value_name = "DIR", default_value = crate::report::variants::DEFAULT_OUT)]
    pub out: PathBuf,
    /// Rays per view as COLUMNSxROWS.
    #[arg(long, value_name = "COLUMNSxROWS", default_value = "16x9", value_parser = parse_grid)]
    pub rays: (usize, usize),
    /// Only these models (repeat the flag); all when absent.
    #[arg(long, value_parser = report_model)]
    pub model: Vec<ModelId>,
    /// Only these settings, as `model key=value ...` (repeat the flag), in place of the
    /// report's list; e.g. `--variant "bruneton nu=16 mu_s=64"`.
    #[arg(long, value_name = "SETTING")]
    pub variant: Vec<String>,
    /// Relative standard error the reference aims for per ray and wavelength.
    #[arg(long, value_name = "REL", default_value_t = ModelSettings::default().target_relative_error)]
    pub reference_error: f64,
    /// The reference's most Monte Carlo paths per ray and wavelength on the views with
    /// the sun below the horizon, where the default stops at 1-5 % standard error
    /// (256..=67108864; a change recomputes those views alone).
    #[arg(long, value_name = "N", default_value_t = atmosphere_core::reference::ReferenceSettings::default().max_paths)]
    pub twilight_max_paths: usize,
    /// Compute the reference of every view again, even where reference.csv has it.
    #[arg(long)]
    pub recompute_reference: bool,
    /// Compute the reference of this view again (its id, e.g. nautical; repeat the flag),
    /// keeping the others from reference.csv: for a change of the reference's method,
    /// which no fingerprint sees.
    #[arg(long, value_name = "ID")]
    pub recompute_view: Vec<String>,
    /// Stop once the reference caches are up to date, before measuring any model.
    #[arg(long)]
    pub reference_only: bool,
    /// Leave out the GPU frame times (for a machine without an adapter); the report says
    /// so.
    #[arg(long)]
    pub no_gpu: bool,
    /// Only this section (repeat the flag); every section when absent. `--model` and
    /// `--variant` narrow the skies and leave out the others.
    #[arg(long, value_enum)]
    pub section: Vec<ReportSection>,
}

/// A section of `atmos report`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ReportSection {
    /// The sky models on the report's views: README.md, errors.csv and its plots.
    Skies,
    /// The light beams of the shipped beams scenes: beams.md and its plots.
    Beams,
    /// The terrain's light shafts on the scenes with terrain: shafts.md and its plots.
    Shafts,
    /// The cloud methods against the cloud path tracer on four views: clouds.md, its
    /// reference cache clouds_reference.csv and its plots.
    Clouds,
    /// The rain shaft, cirrus layer and droplet deck against the volumes' path tracer
    /// on three views: optics.md, its reference cache optics_reference.csv and its
    /// plots.
    Optics,
}

impl ReportArgs {
    /// Whether the report writes `section`. `--model` and `--variant` narrow the skies
    /// and leave the other sections out, except the clouds or the optics when
    /// `--section` names them (its `--variant`s are then that section's rows).
    pub fn writes(&self, section: ReportSection) -> bool {
        let asked = self.section.is_empty() || self.section.contains(&section);
        let skies_only = !(self.model.is_empty() && self.variant.is_empty());
        let named_rows = matches!(section, ReportSection::Clouds | ReportSection::Optics)
            && self.section.contains(&section)
            && self.model.is_empty();
        asked && (section == ReportSection::Skies || !skies_only || named_rows)
    }
}

/// "16x9" -> (16, 9), each at least 1.
fn parse_grid(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("'{text}' is not COLUMNSxROWS, e.g. 16x9");
    let (c, r) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let c: usize = c.trim().parse().map_err(|_| bad())?;
    let r: usize = r.trim().parse().map_err(|_| bad())?;
    if c == 0 || r == 0 {
        return Err(format!("'{text}': at least one column and one row"));
    }
    Ok((c, r))
}

/// A model the GPU renders (`atmos view --model`).
fn gpu_model(text: &str) -> Result<ModelId, String> {
    let id: ModelId = text.parse().map_err(|e: UnknownModel| e.to_string())?;
    render_wgpu::Renderer::check_model(id).map_err(|e| e.to_string())?;
    Ok(id)
}

/// A model the report has settings for (`atmos report --model`).
fn report_model(text: &str) -> Result<ModelId, String> {
    let id: ModelId = text.parse().map_err(|e: UnknownModel| e.to_string())?;
    let known = crate::report::variants::report_models();
    if known.contains(&id) {
        Ok(id)
    } else {
        Err(format!(
            "the report has no settings for {id} (it has: {})",
            ModelId::list(&known)
        ))
    }
}

/// "320x180" -> (320, 180), each side 1 to the GPU's largest texture side.
fn parse_tile(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = parse_grid(text)?;
    let max = render_wgpu::frame::MAX_SIDE_PX as usize;
    if w > max || h > max {
        return Err(format!("'{text}': each side at most {max} px"));
    }
    Ok((w as u32, h as u32))
}

/// The flags of `atmos stability`.
#[derive(Debug, Args)]
pub struct StabilityArgs {
    /// Models to check (repeat the flag); all models when absent.
    #[arg(long, value_enum)]
    pub model: Vec<ModelId>,
}

/// The flags of `atmos phase` (docs/particles.md).
#[derive(Debug, Args)]
pub struct PhaseArgs {
    /// The particle.
    #[arg(long, value_enum)]
    pub particle: crate::phase::flags::Particle,
    /// Radius in um, in (0, 10000]: of water drops (with --distribution, the effective
    /// radius <r^3> / <r^2>), or of ice crystals (axis to prism edge). Not for rain.
    #[arg(long, value_name = "UM", allow_negative_numbers = true,
          value_parser = crate::phase::flags::parse_radius_um)]
    pub radius_um: Option<f64>,
    /// Rain: the rain rate of the Marshall-Palmer drop sizes, mm/h, in [0.1, 300].
    #[arg(long, value_name = "MM_PER_H", allow_negative_numbers = true)]
    pub rain_rate_mm_h: Option<f64>,
    /// Ice: the crystal's length along its c-axis in um; length / (2 radius) in
    /// [0.01, 100].
    #[arg(long, value_name = "UM", allow_negative_numbers = true,
          value_parser = crate::phase::flags::parse_radius_um)]
    pub length_um: Option<f64>,
    /// Ice plates: horizontal (c-axis near the vertical, for sundogs) instead of random
    /// orientations; needs --sun-elevation-deg.
    #[arg(long)]
    pub horizontal: bool,
    /// Horizontal plates: the sun's elevation in degrees, in [0, 90].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_elevation_deg: Option<f64>,
    /// Horizontal plates: the standard deviation of each tilt component of the c-axis,
    /// degrees, in [0, 30].
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub tilt_deg: f64,
    /// Ice: rays traced per wavelength, in [1000, 1e8].
    #[arg(long, value_name = "N", default_value_t = 2_000_000)]
    pub rays: usize,
    /// Size distribution: lognormal:SIGMA (sigma of ln r, in [0.01, 1]) or
    /// modified-gamma:ALPHA,GAMMA (alpha in [0.5, 100], gamma in [0.1, 10]) [default: one
    /// radius].
    #[arg(long, value_name = "KIND:PARAMS", value_parser = crate::phase::flags::parse_distribution)]
    pub distribution: Option<crate::phase::flags::DistributionFlag>,
    /// Relative refractive index N or N+Ki (K >= 0 absorbs), at every wavelength
    /// [default: the particle's table].
    #[arg(long, value_name = "N+Ki", allow_hyphen_values = true,
          value_parser = crate::phase::flags::parse_refractive_index)]
    pub refractive_index: Option<num_complex::Complex64>,
    /// Vacuum wavelengths in nm, comma-separated (at most 64).
    #[arg(
        long,
        value_name = "NM,...",
        value_delimiter = ',',
        default_value = "680,550,440",
        allow_negative_numbers = true
    )]
    pub wavelengths: Vec<Wavelength>,
    /// Scattering angles START:END:STEP in degrees, within [0, 180].
    #[arg(long, value_name = "START:END:STEP", default_value = "0:180:0.1",
          value_parser = crate::phase::flags::parse_angles)]
    pub angles_deg: crate::phase::flags::AngleRange,
    /// Where to write the CSV (atomically) [default: stdout].
    #[arg(long, value_name = "FILE.csv")]
    pub output: Option<PathBuf>,
}

#[cfg(test)]
mod tests {
    use super::{Cli, Command, ReportSection, parse_utc};
    use clap::Parser;

    #[test]
    fn report_sections_are_all_by_default_and_skies_alone_for_a_model() {
        let sections = |args: &[&str]| {
            let cli = Cli::try_parse_from([&["atmos", "report"], args].concat()).unwrap();
            let Some(Command::Report(report)) = cli.command else {
                panic!("not the report");
            };
            [
                ReportSection::Skies,
                ReportSection::Beams,
                ReportSection::Shafts,
                ReportSection::Clouds,
                ReportSection::Optics,
            ]
            .map(|s| report.writes(s))
        };
        assert_eq!(sections(&[]), [true; 5]);
        assert_eq!(
            sections(&["--section", "shafts"]),
            [false, false, true, false, false]
        );
        assert_eq!(
            sections(&["--section", "skies", "--section", "beams"]),
            [true, true, false, false, false]
        );
        assert_eq!(
            sections(&["--model", "riley"]),
            [true, false, false, false, false]
        );
        assert_eq!(
            sections(&["--model", "riley", "--section", "shafts"]),
            [false; 5]
        );
        // --variant narrows the clouds or the optics section when it is named.
        assert_eq!(
            sections(&["--variant", "riley", "--section", "clouds"]),
            [false, false, false, true, false]
        );
        assert_eq!(
            sections(&["--variant", "sun=point", "--section", "optics"]),
            [false, false, false, false, true]
        );
        assert_eq!(
            sections(&["--variant", "riley"]),
            [true, false, false, false, false]
        );
        assert!(Cli::try_parse_from(["atmos", "report", "--section", "cloud"]).is_err());
    }

    #[test]
    fn utc_times_are_read_and_bad_ones_named() {
        let t = parse_utc("2024-10-15T16:05").unwrap();
        assert_eq!(
            (t.year, t.month, t.day, t.hour, t.minute),
            (2024, 10, 15, 16, 5)
        );
        assert_eq!(t.second, 0.0);
        let t = parse_utc("2024-10-15T16:05:30Z").unwrap();
        assert_eq!((t.minute, t.second), (5, 30.0));
        for bad in [
            "2024-10-15",
            "2024-10-15T16",
            "2024-13-01T00:00",
            "2024-10-15T25:00",
        ] {
            let e = parse_utc(bad).unwrap_err();
            assert!(!e.is_empty(), "{bad}");
        }
        assert!(
            parse_utc("2024-10-15")
                .unwrap_err()
                .contains("'2024-10-15'")
        );
    }
}
