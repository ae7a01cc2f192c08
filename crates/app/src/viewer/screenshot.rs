//! Screenshots of the viewer: the displayed image as PNG and the HDR radiance as EXR
//! (with the viewer's settings in the header), written atomically by the writers of
//! `atmos render`.

use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

use render_wgpu::{Frame, Renderer};

use crate::render::image_files::{write_exr, write_png};
use crate::viewer::settings::ViewerSettings;

/// A name for a screenshot taken now: `atmos-<seconds since 1970>.<extension>`, in the
/// current directory.
pub fn timestamped_path(extension: &str) -> PathBuf {
    let seconds = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    PathBuf::from(format!("atmos-{seconds}.{extension}"))
}

/// Writes the renderer's last display image (of `frame`) to `path` as PNG.
pub fn save_png(renderer: &Renderer, frame: &Frame, path: &Path) -> anyhow::Result<()> {
    write_png(path, frame, &renderer.read_ldr()?)
}

/// Writes the renderer's last frame to a timestamped PNG and EXR pair; returns the paths.
pub fn save_pair(
    renderer: &Renderer,
    frame: &Frame,
    settings: &ViewerSettings,
) -> anyhow::Result<(PathBuf, PathBuf)> {
    let (png, exr) = (timestamped_path("png"), timestamped_path("exr"));
    save_png(renderer, frame, &png)?;
    let settings_toml = toml::to_string(settings)?;
    write_exr(&exr, frame, &settings_toml, &renderer.read_hdr()?)?;
    Ok((png, exr))
}
