//! `--earth-data DIR` and `ATMOS_EARTH_DATA`: a folder of Earth maps that `atmos render`
//! and `atmos view` draw the terrain from instead of the built-in ones.

use std::path::PathBuf;

use anyhow::Context;
use clap::Args;
use render_wgpu::terrain::EarthData;

/// The environment variable naming a folder of Earth maps.
pub const EARTH_DATA_ENV: &str = "ATMOS_EARTH_DATA";

/// The flag of the commands that draw the terrain.
#[derive(Clone, Debug, Default, Args)]
pub struct EarthDataFlag {
    /// A folder holding the Earth's maps height.png and colour.jpg (docs/terrain.md) to
    /// draw the terrain from, over ATMOS_EARTH_DATA [default: the built-in maps].
    #[arg(long, value_name = "DIR")]
    pub earth_data: Option<PathBuf>,
}

impl EarthDataFlag {
    /// The flag's folder, else `ATMOS_EARTH_DATA`'s (when set and not empty), else the
    /// built-in maps; a folder lacking a map is an error naming the flag or variable,
    /// the folder and each path looked for.
    pub fn source(&self) -> anyhow::Result<EarthData> {
        if let Some(dir) = &self.earth_data {
            return EarthData::folder(dir)
                .with_context(|| format!("--earth-data {}", dir.display()));
        }
        match std::env::var_os(EARTH_DATA_ENV) {
            Some(dir) if !dir.is_empty() => EarthData::folder(&dir)
                .with_context(|| format!("{EARTH_DATA_ENV}={}", dir.to_string_lossy())),
            _ => Ok(EarthData::BuiltIn),
        }
    }
}
