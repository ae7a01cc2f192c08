//! The voxel cloud's files: the shipped cumulus is the generator's output and its scene
//! loads; a grid of the wrong length, a NaN, a side of 0, too many voxels, an unknown
//! format or key, and a bad setting are refused by name.

use std::path::{Path, PathBuf};

use atmosphere_core::clouds::error::CloudError;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::volume::cumulus::{CUMULUS_DIMS, cumulus};
use atmosphere_core::clouds::volume::grid::{MAX_SIDE, VoxelGrid};
use atmosphere_core::clouds::volume::raw_file::{
    VoxelFormat, grid_from_bytes, grid_to_u8, read_grid,
};
use atmosphere_core::clouds::volume::scene::VolumeScene;
use atmosphere_core::optics::phase::PhaseFunction;

fn phase() -> CloudPhase {
    CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap()
}

fn shipped(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes/clouds")
        .join(name)
}

#[test]
fn the_shipped_cumulus_is_the_generators_and_its_scene_loads() {
    let bytes = std::fs::read(shipped("cumulus.u8")).unwrap();
    let generated = cumulus();
    assert_eq!(
        bytes,
        grid_to_u8(&generated),
        "regenerate with `cargo run -p atmosphere-core --example generate_cumulus`"
    );
    // A cloud, not a block: a flat base, a crown narrower than the base, nothing on the faces.
    let [nx, ny, nz] = CUMULUS_DIMS;
    let layer = |k: usize| {
        (0..nx * ny)
            .filter(|&c| generated.at(c % nx, c / nx, k) > 0.5)
            .count()
    };
    let filled: Vec<usize> = (0..nz).map(layer).collect();
    let base = filled.iter().position(|&n| n > 0).unwrap();
    let top = filled.iter().rposition(|&n| n > 0).unwrap();
    assert!(filled[base + 1] > nx * ny / 10, "a flat base: {filled:?}");
    assert!(
        filled[top - 4] < filled[base + 4] / 4,
        "a crown: {filled:?}"
    );
    assert!(top - base > nz / 2, "a tower: {filled:?}");
    let faces = (0..nx * ny).all(|c| {
        generated.at(c % nx, c / nx, 0) == 0.0 && generated.at(c % nx, c / nx, nz - 1) == 0.0
    });
    assert!(faces);
    let scene = VolumeScene::load(&shipped("cumulus.toml"), phase()).unwrap();
    assert_eq!(scene.cloud.grid().dims(), CUMULUS_DIMS);
    assert_eq!(
        scene.cloud.grid(),
        &read_grid(&shipped("cumulus.u8"), CUMULUS_DIMS, VoxelFormat::U8).unwrap()
    );
}

#[test]
fn bad_grids_are_refused_by_name() {
    let err = |r: Result<VoxelGrid, CloudError>| r.unwrap_err().to_string();
    let e = err(grid_from_bytes(&[0; 7], [2, 2, 2], VoxelFormat::U8));
    assert!(e.contains("needs 8 values, got 7"), "{e}");
    let mut f32s: Vec<u8> = [0.5f32, f32::NAN]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let e = err(grid_from_bytes(&f32s, [2, 1, 1], VoxelFormat::F32Le));
    assert!(e.contains("voxel (1, 0, 0) has density NaN"), "{e}");
    f32s.truncate(4);
    f32s.extend(1.5f32.to_le_bytes());
    let e = err(grid_from_bytes(&f32s, [1, 1, 2], VoxelFormat::F32Le));
    assert!(
        e.contains("voxel (0, 0, 1) has density 1.5 outside [0, 1]"),
        "{e}"
    );
    let e = err(VoxelGrid::new([4, 0, 4], vec![]));
    assert!(e.contains("dims y = 0 must lie in [1, 1024]"), "{e}");
    let e = err(VoxelGrid::new([MAX_SIDE + 1, 1, 1], vec![]));
    assert!(e.contains("dims x = 1025"), "{e}");
    let e = err(VoxelGrid::new([1024, 1024, 64], vec![]));
    assert!(e.contains("67108864 voxels is more than 33554432"), "{e}");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("grid.u8");
    std::fs::write(&path, [0u8; 30]).unwrap();
    let e = err(read_grid(&path, [3, 3, 3], VoxelFormat::U8));
    assert!(
        e.contains("holds more than 27 bytes; a 3 x 3 x 3 grid of u8 needs 27"),
        "{e}"
    );
    let e = err(read_grid(&path, [2, 2, 2], VoxelFormat::F32Le));
    assert!(
        e.contains("holds 30 bytes; a 2 x 2 x 2 grid of f32le needs 32"),
        "{e}"
    );
    let e = err(read_grid(
        &dir.path().join("none.u8"),
        [1, 1, 1],
        VoxelFormat::U8,
    ));
    assert!(e.contains("cannot read") && e.contains("none.u8"), "{e}");
    let e = "u16".parse::<VoxelFormat>().unwrap_err().to_string();
    assert!(e.contains("\"u16\" is not one of u8, f32le"), "{e}");
}

/// The shipped scene with one line replaced, loaded beside a copy of its grid.
fn load_edited(from: &str, to: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(shipped("cumulus.u8"), dir.path().join("cumulus.u8")).unwrap();
    let text = std::fs::read_to_string(shipped("cumulus.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text.replacen(from, to, 1)).unwrap();
    VolumeScene::load(&path, phase()).unwrap_err().to_string()
}

#[test]
fn bad_scenes_are_refused_by_name() {
    let cases = [
        ("dims = [96, 96, 64]", "dims = [96, 96, 63]", "needs 580608"),
        ("dims = [96, 96, 64]", "dims = [96, 0, 64]", "dims y = 0"),
        (
            "format = \"u8\"",
            "format = \"f16\"",
            "\"f16\" is not one of u8, f32le",
        ),
        (
            "voxel_m = 20.0",
            "voxel_m = nan",
            "volume voxel_m = NaN must lie in [0.001, 10000]",
        ),
        (
            "voxel_m = 20.0",
            "voxel_m = 0.0",
            "volume voxel_m = 0 must lie",
        ),
        (
            "extinction_per_m = 0.05",
            "extinction_per_m = 2.0",
            "volume extinction_per_m = 2 must lie in [0, 1]",
        ),
        ("albedo = 1.0", "albedo = -0.1", "volume albedo = -0.1"),
        (
            "albedo = 1.0",
            "albedo = 1.0\ndensity = 2",
            "unknown field `density`",
        ),
        (
            "elevation_deg = 40.0",
            "elevation_deg = 95.0",
            "volume sun elevation_deg = 95",
        ),
        (
            "[1.474, 1.8504, 1.91198]",
            "[1.474, 1.8504]",
            "holds 2 values",
        ),
        (
            "[1.474, 1.8504, 1.91198]",
            "[1.474, inf, 1.9]",
            "irradiance_w_m2_nm = inf",
        ),
        (
            "look_at_m = [0.0, 0.0, 1200.0]",
            "look_at_m = [-3300.0, -1400.0, 800.0]",
            "must differ from position_m",
        ),
        (
            "vertical_fov_deg = 35.0",
            "vertical_fov_deg = 170.0",
            "vertical_fov_deg = 170 must lie in [1, 120]",
        ),
        (
            "width_px = 320",
            "width_px = 0",
            "width_px = 0 must lie in [1, 8192]",
        ),
        (
            "slices = 256",
            "slices = 1",
            "volume slices = 1 must lie in [2, 4096]",
        ),
        (
            "light_buffer_px = 256",
            "light_buffer_px = 5000",
            "light_buffer_px = 5000",
        ),
        (
            "shadow_steps = 32",
            "shadow_steps = 65",
            "volume shadow_steps = 65 must lie in [1, 64]",
        ),
        (
            "light = \"riley\"",
            "light = \"sunny\"",
            "\"sunny\" is not one of riley, octaves",
        ),
        (
            "light = \"riley\"",
            "light = \"eddington\"",
            "volume light = eddington",
        ),
        (
            "backscatter_xi = 0.05",
            "backscatter_xi = 2.0",
            "backscatter_xi = 2",
        ),
        (
            "grid = \"cumulus.u8\"",
            "grid = \"missing.u8\"",
            "missing.u8",
        ),
    ];
    for (from, to, expected) in cases {
        let e = load_edited(from, to);
        assert!(e.contains(expected), "{to}: {e}");
    }
}
