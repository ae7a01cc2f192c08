//! The flags of `atmos probe`: the model or beam method, the atmosphere or beams scene,
//! the rays' CSV and, with `--terrain` or `--clouds`, their place over the Earth's
//! relief or under its cloud cover.

use std::path::PathBuf;

use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use clap::Args;

use crate::render::cloud_flags::CloudFlags;
use crate::wavelength_flag::Wavelength;

/// The flags of `atmos probe`.
#[derive(Debug, Args)]
pub struct ProbeArgs {
    /// Scattering model: a sky model, or with --scene a beam method (reference, march,
    /// planes2000, qtable2002).
    #[arg(long, value_name = "MODEL", value_parser = parse_probe_model)]
    pub model: String,
    /// A beams scene (TOML; docs/beams.md): rays in its frame, radiance of its lights
    /// through its medium; the input columns are then origin_x_m, origin_y_m,
    /// origin_z_m, dir_x, dir_y, dir_z and optionally distance_m.
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// Atmosphere: a preset (earth, clear, hazy, mars) or a TOML file.
    #[arg(
        long,
        value_name = "PRESET|FILE.toml",
        default_value = "earth",
        conflicts_with = "scene"
    )]
    pub atmosphere: String,
    /// Wavelengths in nm, comma-separated.
    #[arg(
        long,
        value_name = "NM,...",
        value_delimiter = ',',
        default_value = "680,550,440"
    )]
    pub wavelengths: Vec<Wavelength>,
    /// Highest scattering order (1 = single scattering) [default: all orders].
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..), conflicts_with = "scene")]
    pub orders: Option<u32>,
    /// Relative standard error of the radiance that stochastic models aim for.
    #[arg(long, value_name = "REL", default_value_t = ModelSettings::default().target_relative_error)]
    pub target_error: f64,
    /// Seed of the random sequence of stochastic models.
    #[arg(long, default_value_t = ModelSettings::default().seed)]
    pub seed: u64,
    /// A model setting as key=value (repeat the flag), e.g. `--set samples=16` for
    /// nishita; docs/models/<model>.md lists each model's keys and defaults.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// CSV of view rays: altitude_m, view_zenith_deg, sun_zenith_deg,
    /// view_sun_azimuth_deg and optionally distance_m, with a header.
    #[arg(long, value_name = "FILE.csv")]
    pub input: PathBuf,
    /// Where to write the CSV of results (atomically) [default: stdout].
    #[arg(long, value_name = "FILE.csv")]
    pub output: Option<PathBuf>,
    /// Place the rays over the Earth's relief at --latitude-deg, --longitude-deg, the sun
    /// at --sun-azimuth-deg and each view at that azimuth plus view_sun_azimuth_deg, so
    /// that the terrain's shadow in the air reaches them (light shafts: reference,
    /// hillaire, nishita, oneil, bruneton; docs/shafts.md).
    #[arg(long, requires_all = ["latitude_deg", "longitude_deg", "sun_azimuth_deg"], conflicts_with = "scene")]
    pub terrain: bool,
    /// With --terrain or --clouds: the rays' latitude, degrees north, in [-90, 90].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub latitude_deg: Option<f64>,
    /// With --terrain or --clouds: the rays' longitude, degrees east, in [-180, 180].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub longitude_deg: Option<f64>,
    /// With --terrain or --clouds: the sun's azimuth, degrees from north towards east,
    /// in [-360, 360].
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub sun_azimuth_deg: Option<f64>,
    /// The planet's cloud layer (`--clouds` and the `--cloud-*` flags of `atmos
    /// render`): the rays placed at --latitude-deg, --longitude-deg with the sun at
    /// --sun-azimuth-deg over the cover, answered by the model with the layer's march,
    /// or with `--model reference` by the cloud path tracer (hillaire's air around the
    /// cloud); adds the columns T_cloud and, for the path tracer, paths
    /// (docs/clouds.md).
    #[command(flatten)]
    pub clouds: CloudFlags,
}

/// A sky model's or a beam method's name, checked against both lists (which one it must
/// be depends on --scene).
pub fn parse_probe_model(text: &str) -> Result<String, String> {
    use atmosphere_core::beams::methods::id::BeamMethodId;
    if text.parse::<ModelId>().is_ok() || text.parse::<BeamMethodId>().is_ok() {
        Ok(text.to_string())
    } else {
        Err(format!(
            "unknown model '{text}' (sky models: {}; beam methods, with --scene: {})",
            ModelId::list(&ModelId::ALL),
            BeamMethodId::list(&BeamMethodId::ALL)
        ))
    }
}
