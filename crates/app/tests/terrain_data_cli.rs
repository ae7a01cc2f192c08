//! The Earth's maps end to end: built into the binary, so a copy of it draws the terrain
//! from any folder with the source tree out of sight; `--earth-data DIR` and
//! `ATMOS_EARTH_DATA` take them from a folder instead, and a missing folder or map is
//! named with every path looked for. Renders are tiny (32 x 18) and run on any adapter
//! (lavapipe will do); without one they fail, unless `ATMOS_SKIP_GPU_TESTS=1`, when
//! they record that they skipped (counted in the suite's summary line).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{atmos, skipped_without_adapter, stderr};

/// Over the Alps from 8 km, looking down the valleys to the south-west (terrain in the
/// lower rows).
const TERRAIN_SCENE: &[&str] = &[
    "render",
    "--model=nishita",
    "--set=samples=16",
    "--latitude-deg=46.0",
    "--longitude-deg=7.8",
    "--terrain=true",
    "--altitude-m=8000",
    "--sun-zenith-deg=45",
    "--view-zenith-deg=100",
    "--view-azimuth-deg=225",
    "--fov-deg=60",
    "--width=32",
    "--height=18",
];

/// `atmos` with `TERRAIN_SCENE`, `extra` and `--out out`, without ATMOS_EARTH_DATA
/// unless `env` sets it.
fn render_command(bin: &Path, extra: &[&str], out: &Path, env: Option<&Path>) -> Command {
    let mut command = Command::new(bin);
    command
        .args(TERRAIN_SCENE)
        .args(extra)
        .arg("--out")
        .arg(out);
    match env {
        Some(dir) => command.env("ATMOS_EARTH_DATA", dir),
        None => command.env_remove("ATMOS_EARTH_DATA"),
    };
    command
}

/// Runs a render; `None` when it skipped for want of an adapter, else the image after
/// asserting success.
fn rendered(command: &mut Command, out: &Path) -> Option<image::RgbImage> {
    let output = command.output().unwrap();
    if skipped_without_adapter(&output) {
        return None;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    Some(image::open(out).unwrap().to_rgb8())
}

/// The workspace, which a copied binary must not need.
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .unwrap()
}

/// Runs `command` with the workspace hidden behind an empty folder (a private mount
/// namespace: needs root or unprivileged namespaces); where the system allows no such
/// namespace it runs as it is and says so.
fn without_workspace(command: &Command, empty: &Path) -> Command {
    let allowed = Command::new("unshare")
        .args(["--mount", "true"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !allowed {
        println!("the workspace stays visible: this system allows no mount namespace");
        let mut plain = Command::new(command.get_program());
        plain.args(command.get_args());
        plain.current_dir(command.get_current_dir().unwrap());
        plain.env_remove("ATMOS_EARTH_DATA");
        return plain;
    }
    let mut hidden = Command::new("unshare");
    hidden
        .args([
            "--mount",
            "sh",
            "-c",
            r#"mount --bind "$0" "$1" && shift && exec "$@""#,
        ])
        .arg(empty)
        .arg(workspace())
        .arg(command.get_program())
        .args(command.get_args())
        .current_dir(command.get_current_dir().unwrap())
        .env_remove("ATMOS_EARTH_DATA");
    hidden
}

#[test]
fn a_copied_binary_draws_the_built_in_terrain_from_anywhere() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("bin/atmos");
    let work = dir.path().join("work");
    let empty = dir.path().join("empty");
    for folder in [bin.parent().unwrap(), &work, &empty] {
        std::fs::create_dir(folder).unwrap();
    }
    std::fs::copy(env!("CARGO_BIN_EXE_atmos"), &bin).unwrap();
    let mut copied = render_command(&bin, &[], Path::new("alps.png"), None);
    copied.current_dir(&work);
    let Some(from_copy) = rendered(
        &mut without_workspace(&copied, &empty),
        &work.join("alps.png"),
    ) else {
        return;
    };
    // The same pixels as the built binary's in the source tree: the maps of assets/earth.
    let out = dir.path().join("in_tree.png");
    let built = Path::new(env!("CARGO_BIN_EXE_atmos"));
    let in_tree = rendered(&mut render_command(built, &[], &out, None), &out).unwrap();
    assert_eq!(from_copy, in_tree);
}

/// A folder of 8 x 4 maps: flat land at sea level, all red.
fn red_flat_maps(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    image::ImageBuffer::<image::Luma<u16>, _>::from_pixel(8, 4, image::Luma([11_000]))
        .save(dir.join("height.png"))
        .unwrap();
    image::RgbImage::from_pixel(8, 4, image::Rgb([220, 20, 20]))
        .save_with_format(dir.join("colour.jpg"), image::ImageFormat::Jpeg)
        .unwrap();
}

/// The mean (red - blue) of the lower rows, where the terrain is.
fn ground_redness(image: &image::RgbImage) -> f64 {
    let pixels: Vec<_> = (12..18)
        .flat_map(|y| (0..32).map(move |x| (x, y)))
        .map(|(x, y)| image.get_pixel(x, y))
        .collect();
    pixels
        .iter()
        .map(|p| f64::from(p[0]) - f64::from(p[2]))
        .sum::<f64>()
        / pixels.len() as f64
}

#[test]
fn a_folder_of_maps_is_drawn_by_flag_and_by_environment() {
    let dir = tempfile::tempdir().unwrap();
    let maps = dir.path().join("maps");
    red_flat_maps(&maps);
    let built = Path::new(env!("CARGO_BIN_EXE_atmos"));
    let out = dir.path().join("built_in.png");
    let Some(built_in) = rendered(&mut render_command(built, &[], &out, None), &out) else {
        return;
    };
    let out = dir.path().join("flag.png");
    let flag = ["--earth-data", maps.to_str().unwrap()];
    // The flag wins over a variable naming no folder.
    let nowhere = dir.path().join("nowhere");
    let by_flag = rendered(
        &mut render_command(built, &flag, &out, Some(&nowhere)),
        &out,
    )
    .unwrap();
    let out = dir.path().join("env.png");
    let by_env = rendered(&mut render_command(built, &[], &out, Some(&maps)), &out).unwrap();
    assert_eq!(by_flag, by_env);
    let (red, usual) = (ground_redness(&by_flag), ground_redness(&built_in));
    assert!(red > usual + 20.0, "red maps {red}, built-in {usual}");
}

#[test]
fn a_missing_folder_or_map_is_named_with_every_path_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let nowhere = dir.path().join("nowhere");
    let tried = format!(
        "it needs {} and {}",
        nowhere.join("height.png").display(),
        nowhere.join("colour.jpg").display()
    );
    let out = dir.path().join("out.png");
    let built = Path::new(env!("CARGO_BIN_EXE_atmos"));
    let by_flag = ["--earth-data", nowhere.to_str().unwrap()];
    let cases = [
        (
            render_command(built, &by_flag, &out, None),
            format!("--earth-data {}", nowhere.display()),
        ),
        (
            render_command(built, &[], &out, Some(&nowhere)),
            format!("ATMOS_EARTH_DATA={}", nowhere.display()),
        ),
    ];
    for (mut command, named) in cases {
        let output = command.output().unwrap();
        let err = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{err}");
        let expected = format!(
            "error: {named}: terrain data folder {}: no such folder; {tried}",
            nowhere.display()
        );
        assert!(err.contains(&expected), "{err}");
        assert!(!err.contains("adapter"), "{err}");
    }
    // The viewer names it before it looks for a display.
    let output = atmos(&["view", "--earth-data", nowhere.to_str().unwrap()]);
    assert!(stderr(&output).contains(&tried), "{}", stderr(&output));

    let half = dir.path().join("half");
    red_flat_maps(&half);
    std::fs::remove_file(half.join("colour.jpg")).unwrap();
    let output = atmos(&["view", "--earth-data", half.to_str().unwrap()]);
    let expected = format!(
        "terrain data folder {}: colour.jpg is missing; it needs",
        half.display()
    );
    assert!(stderr(&output).contains(&expected), "{}", stderr(&output));
    assert!(!out.exists());
}

#[test]
fn a_map_that_does_not_decode_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let maps = dir.path().join("maps");
    red_flat_maps(&maps);
    std::fs::write(maps.join("height.png"), b"not a picture").unwrap();
    let out = dir.path().join("out.png");
    let built = Path::new(env!("CARGO_BIN_EXE_atmos"));
    let flag = ["--earth-data", maps.to_str().unwrap()];
    let output = render_command(built, &flag, &out, None).output().unwrap();
    if skipped_without_adapter(&output) {
        return;
    }
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    let expected = format!(
        "cannot read terrain map {}",
        maps.join("height.png").display()
    );
    assert!(err.contains(&expected), "{err}");
    assert!(!out.exists());
}

/// A colour map wider than the GPU's largest texture (8192 texels under WebGPU's default
/// limits) is named, not left to the GPU's validation.
#[test]
fn a_colour_map_too_wide_for_a_texture_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let maps = dir.path().join("maps");
    red_flat_maps(&maps);
    // PNG inside colour.jpg: the format is read from the contents.
    image::RgbImage::new(8194, 4097)
        .save_with_format(maps.join("colour.jpg"), image::ImageFormat::Png)
        .unwrap();
    let out = dir.path().join("out.png");
    let built = Path::new(env!("CARGO_BIN_EXE_atmos"));
    let flag = ["--earth-data", maps.to_str().unwrap()];
    let output = render_command(built, &flag, &out, None).output().unwrap();
    if skipped_without_adapter(&output) {
        return;
    }
    let err = stderr(&output);
    assert_eq!(output.status.code(), Some(1), "{err}");
    let expected = format!(
        "terrain map {} is 8194 x 4097, wider than this GPU's largest texture (8192 texels)",
        maps.join("colour.jpg").display()
    );
    assert!(err.contains(&expected), "{err}");
}
