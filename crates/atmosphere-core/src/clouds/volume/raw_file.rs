//! The voxel grid's file: the densities alone, no header, x fastest, z slowest, either
//! one byte per voxel (`u8`: density = byte / 255) or four (`f32le`: the density as a
//! little-endian IEEE float in [0, 1]). Its dimensions come from the scene file that
//! names it (`scene.rs`). A file of the wrong length is refused with both lengths; the
//! read stops one byte past the expected length, so an endless file cannot hang it.

use std::fmt;
use std::fs::File;
use std::io::Read;
use std::path::Path;
use std::str::FromStr;

use super::grid::{VoxelGrid, check_dims};
use crate::clouds::error::CloudError;

/// How a voxel is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VoxelFormat {
    U8,
    F32Le,
}

impl VoxelFormat {
    pub fn bytes(self) -> usize {
        match self {
            VoxelFormat::U8 => 1,
            VoxelFormat::F32Le => 4,
        }
    }
}

impl fmt::Display for VoxelFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            VoxelFormat::U8 => "u8",
            VoxelFormat::F32Le => "f32le",
        })
    }
}

impl FromStr for VoxelFormat {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "u8" => Ok(VoxelFormat::U8),
            "f32le" => Ok(VoxelFormat::F32Le),
            other => Err(CloudError(format!(
                "voxel format {other:?} is not one of u8, f32le"
            ))),
        }
    }
}

/// The grid of `dims` in `format` read from `path`.
pub fn read_grid(
    path: &Path,
    dims: [usize; 3],
    format: VoxelFormat,
) -> Result<VoxelGrid, CloudError> {
    check_dims(dims)?;
    let name = path.display();
    let file = File::open(path).map_err(|e| CloudError(format!("cannot read {name}: {e}")))?;
    let expected = dims[0] * dims[1] * dims[2] * format.bytes();
    let mut bytes = Vec::with_capacity(expected);
    file.take(expected as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| CloudError(format!("cannot read {name}: {e}")))?;
    if bytes.len() != expected {
        let held = if bytes.len() > expected {
            format!("more than {expected}")
        } else {
            bytes.len().to_string()
        };
        return Err(CloudError(format!(
            "{name} holds {held} bytes; a {} x {} x {} grid of {format} needs {expected}",
            dims[0], dims[1], dims[2]
        )));
    }
    grid_from_bytes(&bytes, dims, format).map_err(|e| CloudError(format!("{name}: {e}")))
}

/// The grid of `dims` in `format` from `bytes` (exactly its length).
pub fn grid_from_bytes(
    bytes: &[u8],
    dims: [usize; 3],
    format: VoxelFormat,
) -> Result<VoxelGrid, CloudError> {
    let density = match format {
        VoxelFormat::U8 => bytes.iter().map(|&b| f32::from(b) / 255.0).collect(),
        VoxelFormat::F32Le => bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect(),
    };
    VoxelGrid::new(dims, density)
}

/// The bytes of `grid` as `u8` (each density rounded to the nearest 1 / 255).
pub fn grid_to_u8(grid: &VoxelGrid) -> Vec<u8> {
    grid.values()
        .iter()
        .map(|&d| (d * 255.0).round().clamp(0.0, 255.0) as u8)
        .collect()
}
