//! The files of a recording: one per frame and image kind, named by the frame's index
//! (`frame_000123.png`), and `--format`, which kinds a run writes.

use std::path::{Path, PathBuf};

use clap::ValueEnum;

/// `--format`: the image files written for each frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum FrameFormat {
    /// Tone-mapped 8-bit sRGB PNG.
    #[default]
    Png,
    /// Linear HDR OpenEXR (linear sRGB in cd/m^2, f32).
    Exr,
    /// Both, from one render.
    Both,
}

impl FrameFormat {
    /// The kinds of file this format writes.
    pub fn kinds(self) -> &'static [FileKind] {
        match self {
            FrameFormat::Png => &[FileKind::Png],
            FrameFormat::Exr => &[FileKind::Exr],
            FrameFormat::Both => &[FileKind::Png, FileKind::Exr],
        }
    }
}

/// One kind of image file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    Png,
    Exr,
}

impl FileKind {
    /// The file name extension, also the kind's name in fingerprints.
    pub fn extension(self) -> &'static str {
        match self {
            FileKind::Png => "png",
            FileKind::Exr => "exr",
        }
    }
}

/// The file of frame `index` in `dir`: `frame_` and at least six digits.
pub fn frame_path(dir: &Path, index: u64, kind: FileKind) -> PathBuf {
    dir.join(format!("frame_{index:06}.{}", kind.extension()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_sort_in_frame_order_and_say_their_kind() {
        let dir = Path::new("out");
        assert_eq!(
            frame_path(dir, 123, FileKind::Png),
            Path::new("out/frame_000123.png")
        );
        assert_eq!(
            frame_path(dir, 1_234_567, FileKind::Exr),
            Path::new("out/frame_1234567.exr")
        );
        assert_eq!(FrameFormat::Both.kinds(), &[FileKind::Png, FileKind::Exr]);
    }
}
