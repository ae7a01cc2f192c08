//! `--video FILE`: the recorded PNG frames assembled into one video by ffmpeg, once every
//! frame of the path is whole in the folder. Shards of a farm finish in any order: the
//! run that completes the set (or any later run with `--video`) makes the video.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use anyhow::{Context, bail};

use crate::files::check_writable;
use crate::record::naming::{FileKind, FrameFormat};

/// The containers `--video` writes, by extension, with the encoder ffmpeg is asked for.
const CONTAINERS: [(&str, &[&str]); 4] = [
    (
        "mp4",
        &["-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18"],
    ),
    (
        "mov",
        &["-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18"],
    ),
    (
        "mkv",
        &["-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "18"],
    ),
    (
        "webm",
        &[
            "-c:v",
            "libvpx-vp9",
            "-pix_fmt",
            "yuv420p",
            "-crf",
            "30",
            "-b:v",
            "0",
        ],
    ),
];

/// The encoder flags for `video`'s extension, or why there are none.
fn encoder(video: &Path) -> anyhow::Result<&'static [&'static str]> {
    let extension = video
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let known: Vec<&str> = CONTAINERS.iter().map(|(e, _)| *e).collect();
    CONTAINERS
        .iter()
        .find(|(e, _)| Some(*e) == extension.as_deref())
        .map(|(_, flags)| *flags)
        .with_context(|| {
            format!(
                "--video {}: the file must end in .{}",
                video.display(),
                known.join(", .")
            )
        })
}

/// Checks, before any frame is rendered, that a video can be made: ffmpeg answers,
/// the frames are recorded as PNG, the extension is one ffmpeg is asked to write and
/// the file can be written.
pub fn check(video: &Path, format: FrameFormat) -> anyhow::Result<()> {
    encoder(video)?;
    if !format.kinds().contains(&FileKind::Png) {
        bail!("--video is made from the PNG frames: use --format png or both");
    }
    let answered = Command::new("ffmpeg")
        .arg("-version")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !answered {
        bail!(
            "--video needs ffmpeg on the PATH (Debian: apt-get install ffmpeg); without it, \
             record the frames and assemble them later (docs/recording.md)"
        );
    }
    check_writable(video).with_context(|| format!("--video {}", video.display()))
}

/// The file ffmpeg writes before it is renamed to `video`: beside it, with the same
/// extension, so that ffmpeg picks the same container.
fn partial_path(video: &Path) -> PathBuf {
    let stem = video.file_stem().unwrap_or_default().to_string_lossy();
    let extension = video.extension().unwrap_or_default().to_string_lossy();
    video.with_file_name(format!("{stem}.partial.{extension}"))
}

/// Makes `video` from the PNG frames `frame_000000.png` ... of `dir` at `fps` (odd
/// sides padded to even, as the encoders need), through a partial file renamed into
/// place.
pub fn assemble(dir: &Path, fps: f64, video: &Path) -> anyhow::Result<()> {
    let partial = partial_path(video);
    let output = Command::new("ffmpeg")
        .args(["-nostdin", "-y", "-loglevel", "error"])
        .args(["-framerate", &fps.to_string(), "-start_number", "0"])
        .arg("-i")
        .arg(dir.join("frame_%06d.png"))
        .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
        .args(encoder(video)?)
        .arg(&partial)
        .stdin(Stdio::null())
        .output()
        .context("--video: cannot run ffmpeg")?;
    if !output.status.success() {
        let _ = std::fs::remove_file(&partial);
        bail!(
            "--video {}: ffmpeg failed: {}",
            video.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    std::fs::rename(&partial, video).with_context(|| format!("--video {}", video.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn containers_are_chosen_by_extension_and_others_named() {
        assert!(encoder(Path::new("a.MP4")).unwrap().contains(&"libx264"));
        assert!(
            encoder(Path::new("a.webm"))
                .unwrap()
                .contains(&"libvpx-vp9")
        );
        let e = encoder(Path::new("a.gif")).unwrap_err().to_string();
        assert!(e.contains(".mp4, .mov, .mkv, .webm"), "{e}");
        assert_eq!(
            partial_path(Path::new("out/ascent.mp4")),
            Path::new("out/ascent.partial.mp4")
        );
    }

    #[test]
    fn exr_only_recordings_make_no_video() {
        let e = check(Path::new("v.mp4"), FrameFormat::Exr).unwrap_err();
        assert!(e.to_string().contains("--format png or both"), "{e}");
    }
}
