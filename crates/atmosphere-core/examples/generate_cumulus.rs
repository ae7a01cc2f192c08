//! Writes the generated cumulus (`atmosphere_core::clouds::volume::cumulus`) as one byte
//! per voxel to the path given, by default `assets/scenes/clouds/cumulus.u8`.

use std::path::PathBuf;

use atmosphere_core::clouds::volume::cumulus::cumulus;
use atmosphere_core::clouds::volume::raw_file::grid_to_u8;

fn main() -> std::io::Result<()> {
    let path = std::env::args().nth(1).map_or_else(
        || PathBuf::from("assets/scenes/clouds/cumulus.u8"),
        PathBuf::from,
    );
    std::fs::write(&path, grid_to_u8(&cumulus()))?;
    println!("wrote {}", path.display());
    Ok(())
}
