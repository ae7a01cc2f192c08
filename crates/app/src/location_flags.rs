//! The place flags that `atmos view` and `atmos render` share: the camera's latitude and
//! longitude, given together. Each command checks the values itself (`viewer/start_view.rs`,
//! `render/scene.rs`).

use clap::Args;

/// `--latitude-deg` and `--longitude-deg` (for `atmos render`, the scene's
/// `latitude_deg` and `longitude_deg`).
#[derive(Clone, Debug, Default, PartialEq, Args)]
pub struct LocationFlags {
    /// Camera latitude, degrees north.
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        requires = "longitude_deg"
    )]
    pub latitude_deg: Option<f64>,
    /// Camera longitude, degrees east.
    #[arg(
        long,
        value_name = "DEG",
        allow_negative_numbers = true,
        requires = "latitude_deg"
    )]
    pub longitude_deg: Option<f64>,
}
