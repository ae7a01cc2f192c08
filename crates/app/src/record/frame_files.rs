//! The bytes of a recorded frame's files, each saying what made it: the frame's index
//! and time, its fingerprint and (EXR: with the camera, sun, model and atmosphere) the
//! path's TOML.

use render_wgpu::Frame;

use crate::record::exr_order::sort_header_attributes;
use crate::record::fingerprint::FrameInputs;
use crate::record::naming::FileKind;
use crate::record::verify::FINGERPRINT_KEY;
use crate::render::image_files::{exr_bytes, header_attributes, png_bytes};

/// The metadata of frame `inputs.index` at `time_s` in a `kind` file.
fn metadata(inputs: &FrameInputs, time_s: f64, kind: FileKind) -> Vec<(&'static str, String)> {
    vec![
        ("Software", "atmos record".into()),
        ("atmos:frame", inputs.index.to_string()),
        ("atmos:time_s", time_s.to_string()),
        ("atmos:fps", inputs.fps.to_string()),
        (FINGERPRINT_KEY, inputs.fingerprint(kind)),
    ]
}

/// A tone-mapped frame (8-bit sRGB, RGBA, row-major) as PNG bytes: the metadata in tEXt
/// chunks, the path's TOML in a compressed iTXt chunk (`atmos:camera_path`).
pub fn png_file(
    frame: &Frame,
    pixels: &[[u8; 4]],
    inputs: &FrameInputs,
    time_s: f64,
) -> anyhow::Result<Vec<u8>> {
    png_bytes(
        frame,
        pixels,
        &metadata(inputs, time_s, FileKind::Png),
        &[("atmos:camera_path", inputs.path_toml.to_string())],
    )
}

/// A frame's HDR radiance as EXR bytes: the metadata, the frame's camera, sun, model and
/// atmosphere, and the path's TOML (`atmos:camera_path`) in header attributes, sorted
/// by name so that the same frame always gives the same bytes.
pub fn exr_file(
    frame: &Frame,
    radiance: &[[f32; 4]],
    inputs: &FrameInputs,
    time_s: f64,
) -> anyhow::Result<Vec<u8>> {
    let mut attributes: Vec<(&str, String)> = header_attributes(frame, inputs.path_toml)
        .into_iter()
        .map(|(name, value)| match name {
            "atmos:scene" => ("atmos:camera_path", value),
            _ => (name, value),
        })
        .collect();
    attributes.extend(metadata(inputs, time_s, FileKind::Exr));
    let mut bytes = exr_bytes(frame, &attributes, radiance)?;
    sort_header_attributes(&mut bytes)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use atmosphere_core::models::id::ModelId;

    use super::*;
    use crate::record::verify::{Verdict, verify};
    use crate::render::scene::Scene;

    fn scene() -> Scene {
        Scene {
            model: Some(ModelId::Nishita),
            altitude_m: Some(10.0),
            sun_zenith_deg: Some(80.0),
            width: Some(4),
            height: Some(3),
            ..Scene::default()
        }
    }

    fn frame() -> Frame {
        scene().frame().unwrap()
    }

    const INPUTS: FrameInputs = FrameInputs {
        path_toml: "version = 1\n[[keyframe]]\ntime_s = 0.0\n",
        index: 2,
        fps: 30.0,
        width: 4,
        height: 3,
    };

    fn verdict(dir: &Path, bytes: &[u8], kind: FileKind, inputs: &FrameInputs) -> Verdict {
        let path = dir.join(format!("f.{}", kind.extension()));
        std::fs::write(&path, bytes).unwrap();
        verify(&path, kind, 4, 3, &inputs.fingerprint(kind))
    }

    /// Many tiles, written in parallel, still land in one order.
    #[test]
    fn the_same_frame_gives_the_same_exr_bytes() {
        let scene = Scene {
            width: Some(300),
            height: Some(200),
            ..scene()
        };
        let frame = scene.frame().unwrap();
        let radiance: Vec<[f32; 4]> = (0..300 * 200)
            .map(|i| [i as f32 * 1e-3, (i % 7) as f32, (i % 300) as f32, 1.0])
            .collect();
        let inputs = FrameInputs {
            width: 300,
            height: 200,
            ..INPUTS
        };
        let first = exr_file(&frame, &radiance, &inputs, 0.0).unwrap();
        for _ in 0..4 {
            let again = exr_file(&frame, &radiance, &inputs, 0.0).unwrap();
            assert!(again == first, "the same frame gave other EXR bytes");
        }
    }

    #[test]
    fn whole_files_of_these_inputs_are_complete_and_others_redone() {
        let dir = tempfile::tempdir().unwrap();
        let frame = frame();
        let png = png_file(&frame, &[[10, 20, 30, 255]; 12], &INPUTS, 1.0 / 15.0).unwrap();
        let exr = exr_file(&frame, &[[0.1, 0.2, 0.3, 1.0]; 12], &INPUTS, 1.0 / 15.0).unwrap();
        for _ in 0..4 {
            let again = exr_file(&frame, &[[0.1, 0.2, 0.3, 1.0]; 12], &INPUTS, 1.0 / 15.0);
            assert!(again.unwrap() == exr, "the same frame gave other EXR bytes");
        }
        let other = FrameInputs { index: 3, ..INPUTS };
        for (bytes, kind) in [(png, FileKind::Png), (exr, FileKind::Exr)] {
            assert_eq!(
                verdict(dir.path(), &bytes, kind, &INPUTS),
                Verdict::Complete
            );
            let foreign = verdict(dir.path(), &bytes, kind, &other);
            assert_eq!(
                foreign,
                Verdict::Redo("made by another path or other flags".into())
            );
            for cut in [bytes.len() - 1, bytes.len() / 2, 8, 0] {
                let truncated = verdict(dir.path(), &bytes[..cut], kind, &INPUTS);
                assert!(
                    matches!(&truncated, Verdict::Redo(why) if why.starts_with("not a whole")),
                    "{kind:?} cut at {cut}: {truncated:?}"
                );
            }
        }
        let missing = verify(&dir.path().join("none.png"), FileKind::Png, 4, 3, "x");
        assert_eq!(missing, Verdict::Missing);
    }
}
