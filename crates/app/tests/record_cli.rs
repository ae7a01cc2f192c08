//! `atmos record` end to end on a tiny path (32x18, five frames): shards, resume,
//! redone frames, EXR metadata, the shard from Slurm's environment, and bad flags.

mod common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};
use exr::meta::attribute::AttributeValue;
use exr::prelude::{ReadChannels, ReadLayers};

/// Five frames at 4 fps, the camera climbing and turning while the sun sets.
const PATH: &str = r#"version = 1
fps = 4.0
width = 32
height = 18

[[keyframe]]
time_s = 0.0
latitude_deg = 46.0
longitude_deg = 7.5
altitude_m = 500.0
heading_deg = 250.0
pitch_deg = 5.0
sun_elevation_deg = 8.0
sun_azimuth_deg = 255.0
model = "nishita"
terrain = false

[[keyframe]]
time_s = 1.0
altitude_m = 3000.0
heading_deg = 270.0
sun_elevation_deg = 2.0
"#;

/// The same path seen from a little higher: its frames are foreign to `PATH`'s.
fn other_path() -> String {
    PATH.replace("altitude_m = 500.0", "altitude_m = 600.0")
}

fn write_path(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    fs::write(&path, text).unwrap();
    path
}

/// Runs `atmos record` with `args` and `env`.
fn record(args: &[&str], env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_atmos"))
        .arg("record")
        .args(args)
        .envs(env.iter().copied())
        .output()
        .expect("the atmos binary runs")
}

/// Asserts the run succeeded; returns its summary line (the last of the command's).
fn summary(output: &Output) -> String {
    let err = stderr(output);
    assert!(output.status.success(), "{err}");
    err.lines()
        .rev()
        .find(|l| l.starts_with("record: "))
        .unwrap_or_else(|| panic!("no summary in {err}"))
        .to_string()
}

/// The files of `dir`, sorted by name, with their bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (
                e.file_name().to_string_lossy().into_owned(),
                fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn shards_resume_and_redone_frames_equal_a_full_run() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_path(dir.path(), "path.toml", PATH);
    let full = dir.path().join("full");
    let output = record(&[s(&path), "--out", s(&full), "--format", "both"], &[]);
    if skipped_without_adapter(&output) {
        return;
    }
    let line = summary(&output);
    assert!(
        line.starts_with("record: 5 rendered (0 redone") && line.contains("0 skipped"),
        "{line}"
    );
    let names: Vec<String> = files(&full).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names.len(), 10, "{names:?}");
    assert_eq!(names[0], "frame_000000.exr");
    assert_eq!(names[9], "frame_000004.png");

    // A second run finds every frame complete and renders nothing.
    let line = summary(&record(
        &[s(&path), "--out", s(&full), "--format", "both"],
        &[],
    ));
    assert!(
        line.starts_with("record: 0 rendered (0 redone") && line.contains("5 skipped as complete"),
        "{line}"
    );

    // Shards 0/2 and 1/2 together are the full run, byte for byte.
    let sharded = dir.path().join("sharded");
    for shard in ["0/2", "1/2"] {
        let args = [
            s(&path),
            "--out",
            s(&sharded),
            "--format",
            "both",
            "--shard",
            shard,
        ];
        let line = summary(&record(&args, &[]));
        assert!(line.contains(&format!("(shard {shard})")), "{line}");
    }
    assert!(
        files(&sharded) == files(&full),
        "shards differ from the full run"
    );

    // A run stopped after two frames, resumed, equals the uninterrupted run; a truncated
    // frame and a frame of another path are redone.
    let resumed = dir.path().join("resumed");
    let args = [s(&path), "--out", s(&resumed), "--format", "both"];
    summary(&record(&[&args[..], &["--frames", "0..2"]].concat(), &[]));
    let other = write_path(dir.path(), "other.toml", &other_path());
    let args_other = [
        s(&other),
        "--out",
        s(&resumed),
        "--format",
        "both",
        "--frames",
        "3",
    ];
    summary(&record(&args_other, &[]));
    let truncated = resumed.join("frame_000001.png");
    let bytes = fs::read(&truncated).unwrap();
    fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let line = summary(&record(&args, &[]));
    assert!(
        line.starts_with("record: 4 rendered (2 redone") && line.contains("1 skipped as complete"),
        "{line}"
    );
    assert!(files(&resumed) == files(&full), "the resumed run differs");

    // The shard from a Slurm array task's environment.
    let slurm = dir.path().join("slurm");
    let env = [
        ("SLURM_ARRAY_TASK_ID", "1"),
        ("SLURM_ARRAY_TASK_COUNT", "2"),
    ];
    let line = summary(&record(&[s(&path), "--out", s(&slurm)], &env));
    assert!(line.contains("frames 2..5 of 0..5 (shard 1/2)"), "{line}");
    let slurm_names: Vec<String> = files(&slurm).into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        slurm_names,
        ["frame_000002.png", "frame_000003.png", "frame_000004.png"]
    );
    assert_eq!(
        files(&slurm)[0].1,
        fs::read(full.join("frame_000002.png")).unwrap()
    );

    check_exr_metadata(&full.join("frame_000002.exr"));
}

/// The EXR's header says what made it, read back with the exr crate.
fn check_exr_metadata(exr_path: &Path) {
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(exr_path)
        .unwrap();
    let layer = &image.layer_data;
    assert_eq!((layer.size.x(), layer.size.y()), (32, 18));
    let text = |name: &str| match layer
        .attributes
        .other
        .get(&exr::meta::attribute::Text::from(name))
    {
        Some(AttributeValue::Text(t)) => t.to_string(),
        other => panic!("{name}: {other:?}"),
    };
    assert_eq!(text("atmos:frame"), "2");
    assert_eq!(text("atmos:time_s"), "0.5");
    assert_eq!(text("atmos:fps"), "4");
    assert_eq!(text("atmos:model"), "nishita");
    assert_eq!(text("atmos:fingerprint").len(), 16);
    let path_toml = text("atmos:camera_path");
    assert!(path_toml.contains("version = 1"), "{path_toml}");
    assert!(path_toml.contains("nishita"), "{path_toml}");
    assert!(text("atmos:camera").contains("position_m"));
    // OpenEXR's standard attributes of the place: the path's 46 N 7.5 E, half-way up.
    let a = &layer.attributes;
    assert!(
        (a.latitude.unwrap() - 46.0).abs() < 1e-3,
        "{:?}",
        a.latitude
    );
    assert!(
        (a.longitude.unwrap() - 7.5).abs() < 1e-3,
        "{:?}",
        a.longitude
    );
    assert!(
        (500.0..3000.0).contains(&a.altitude.unwrap()),
        "{:?}",
        a.altitude
    );
}

#[test]
fn bad_flags_and_folders_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_path(dir.path(), "path.toml", PATH);
    let out = dir.path().join("out");
    let run = |extra: &[&str], expected: &str| {
        let args = [&["record", s(&path), "--out", s(&out)], extra].concat();
        atmos_fails_with(&args, expected);
    };
    run(
        &["--shard", "2/2"],
        "--shard 2/2: shard 2 of 2 does not exist; shards count from 0 to 1",
    );
    run(&["--shard", "1"], "--shard 1: expected I/N");
    run(&["--frames", "5..2"], "--frames 5..2 selects no frame");
    run(
        &["--frames", "0..9"],
        "--frames 0..9 runs past the path's 5 frames (indices 0 to 4)",
    );
    run(
        &["--fps", "0"],
        "--fps 0 must lie in (0, 1000] frames per second",
    );
    run(&["--width", "0"], "--width 0 must be 1 to 8192 px");
    run(
        &["--format", "gif"],
        "invalid value 'gif' for '--format <FORMAT>'",
    );
    run(
        &["--shard-count", "2"],
        "--shard-count 2 needs JOB_COMPLETION_INDEX",
    );
    assert!(!out.exists(), "a refused run made its folder");
    let file = write_path(dir.path(), "file", "x");
    atmos_fails_with(
        &["record", s(&path), "--out", s(&file)],
        "it is a file, not a folder",
    );
    let bad = write_path(
        dir.path(),
        "bad.toml",
        "version = 1\n[[keyframe]]\ntime_s = \"x\"\n",
    );
    let output = atmos(&["record", s(&bad), "--out", s(&out)]);
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("bad.toml:3:"),
        "{}",
        stderr(&output)
    );
}

#[test]
fn the_shard_of_a_kubernetes_job_needs_its_count() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_path(dir.path(), "path.toml", PATH);
    let out = dir.path().join("out");
    let output = record(
        &[s(&path), "--out", s(&out)],
        &[("JOB_COMPLETION_INDEX", "0")],
    );
    assert!(!output.status.success());
    assert!(
        stderr(&output).contains("JOB_COMPLETION_INDEX=0 needs the number of shards: --shard-count N or ATMOS_SHARD_COUNT=N"),
        "{}",
        stderr(&output)
    );
}

/// `--video`: refused before any frame for a file type ffmpeg is not asked for, for
/// EXR-only frames and where ffmpeg is missing; with ffmpeg, the run that completes the
/// frames (here the second shard) makes the video, of every frame at the path's size.
#[test]
fn a_video_is_made_once_every_frame_is_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_path(dir.path(), "path.toml", PATH);
    let out = dir.path().join("out");
    let video = dir.path().join("path.mp4");
    let run = |extra: &[&str]| {
        let args = [&[s(&path), "--out", s(&out), "--video", s(&video)], extra].concat();
        record(&args, &[])
    };
    let gif = dir.path().join("path.gif");
    atmos_fails_with(
        &["record", s(&path), "--out", s(&out), "--video", s(&gif)],
        "the file must end in .mp4, .mov, .mkv, .webm",
    );
    let output = run(&["--format", "exr"]);
    assert!(
        stderr(&output).contains("--format png or both"),
        "{}",
        stderr(&output)
    );
    let ffmpeg = Command::new("ffmpeg")
        .arg("-version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !ffmpeg {
        let output = run(&[]);
        assert!(!output.status.success());
        assert!(
            stderr(&output).contains("--video needs ffmpeg on the PATH"),
            "{}",
            stderr(&output)
        );
        assert!(
            !out.exists(),
            "frames were rendered for a video that cannot be made"
        );
        return;
    }
    let first = run(&["--shard", "0/2"]);
    if skipped_without_adapter(&first) {
        return;
    }
    summary(&first);
    assert!(
        stderr(&first)
            .contains("video: not made yet, 3 of 5 frames are not whole (the first is 2)"),
        "{}",
        stderr(&first)
    );
    assert!(!video.exists());
    let second = run(&["--shard", "1/2"]);
    summary(&second);
    assert!(
        stderr(&second).contains("video: wrote"),
        "{}",
        stderr(&second)
    );
    let probe = Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=width,height,nb_read_frames",
            "-of",
            "csv=p=0",
        ])
        .arg(&video)
        .output()
        .expect("ffprobe comes with ffmpeg");
    assert_eq!(String::from_utf8_lossy(&probe.stdout).trim(), "32,18,5");
}

/// `kill -9` in the middle of a run loses at most the frame in progress: the run resumed
/// keeps every frame written before the kill and ends equal to an uninterrupted run.
#[test]
fn a_run_killed_mid_way_resumes_to_the_uninterrupted_frames() {
    let dir = tempfile::tempdir().unwrap();
    let path = write_path(dir.path(), "path.toml", PATH);
    let (full, killed) = (dir.path().join("full"), dir.path().join("killed"));
    // 21 frames, so that the kill falls mid-way.
    let args = |out: &Path| [s(&path), "--out", s(out), "--fps", "20"].map(String::from);
    let output = record(&args(&full).each_ref().map(String::as_str), &[]);
    if skipped_without_adapter(&output) {
        return;
    }
    summary(&output);
    let mut child = Command::new(env!("CARGO_BIN_EXE_atmos"))
        .arg("record")
        .args(args(&killed))
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the atmos binary runs");
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(120);
    while !killed.join("frame_000003.png").exists() && std::time::Instant::now() < deadline {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    // Frames are renamed into place whole: every PNG there is complete.
    let kept = files(&killed)
        .iter()
        .filter(|(name, _)| name.ends_with(".png"))
        .count();
    assert!((4..21).contains(&kept), "{kept} frames when killed");
    let line = summary(&record(&args(&killed).each_ref().map(String::as_str), &[]));
    assert!(
        line.contains(&format!("{} rendered (0 redone", 21 - kept))
            && line.contains(&format!("{kept} skipped as complete")),
        "{line}"
    );
    assert!(files(&killed) == files(&full), "the resumed run differs");
}

/// `auto_exposure = true` meters each frame on its own: a path's badly chosen `exposure`
/// (the sky blown out to white) no longer matters, every frame comes out mid-grey, and a
/// frame rendered alone equals the same frame of a longer run.
#[test]
fn auto_exposure_meters_each_frame() {
    let dir = tempfile::tempdir().unwrap();
    let blown = PATH.replace("terrain = false", "terrain = false\nexposure = 2.0");
    let metered = blown.replace("exposure = 2.0", "exposure = 2.0\nauto_exposure = true");
    let mean_level = |text: &str, name: &str| -> Option<f64> {
        let path = write_path(dir.path(), &format!("{name}.toml"), text);
        let out = dir.path().join(name);
        let output = record(&[s(&path), "--out", s(&out), "--frames", "2"], &[]);
        if skipped_without_adapter(&output) {
            return None;
        }
        summary(&output);
        let image = image::open(out.join("frame_000002.png")).unwrap().to_rgb8();
        let sum: u64 = image.pixels().flat_map(|p| p.0).map(u64::from).sum();
        Some(sum as f64 / (3 * image.width() * image.height()) as f64)
    };
    let Some(fixed) = mean_level(&blown, "fixed") else {
        return;
    };
    let auto = mean_level(&metered, "auto").unwrap();
    assert!(
        fixed > 240.0,
        "EV100 2 should blow the sky out: mean level {fixed}"
    );
    assert!(
        (60.0..200.0).contains(&auto),
        "metered frame's mean level {auto}"
    );
    // Metered alone or in a run of frames, frame 2 is the same, byte for byte.
    let path = dir.path().join("auto.toml");
    let run = dir.path().join("auto_run");
    summary(&record(
        &[s(&path), "--out", s(&run), "--frames", "0..4"],
        &[],
    ));
    let alone = fs::read(dir.path().join("auto/frame_000002.png")).unwrap();
    assert!(fs::read(run.join("frame_000002.png")).unwrap() == alone);
}
