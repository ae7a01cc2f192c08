//! Whether a frame file on disk is complete: it decodes whole, at the expected size, and
//! carries the expected fingerprint (a PNG tEXt chunk or an EXR header attribute). Only
//! then does a resumed run skip it; anything else is rendered again.

use std::io::{Cursor, ErrorKind};
use std::path::Path;

use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{ReadChannels, ReadLayers};

use crate::record::naming::FileKind;

/// The name of the fingerprint in a frame's metadata.
pub const FINGERPRINT_KEY: &str = "atmos:fingerprint";

/// What a frame file on disk is worth.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// There is none.
    Missing,
    /// It is whole and was made by these inputs: skip it.
    Complete,
    /// It is there but truncated, unreadable, of another size or from other inputs.
    Redo(String),
}

/// The verdict on the `kind` file at `path` for a `width` x `height` frame whose
/// fingerprint is `fingerprint`.
pub fn verify(path: &Path, kind: FileKind, width: u32, height: u32, fingerprint: &str) -> Verdict {
    let bytes = match std::fs::read(path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == ErrorKind::NotFound => return Verdict::Missing,
        Err(e) => return Verdict::Redo(format!("unreadable: {e}")),
    };
    let found = match kind {
        FileKind::Png => png_size_and_fingerprint(&bytes),
        FileKind::Exr => exr_size_and_fingerprint(&bytes),
    };
    match found {
        Err(why) => Verdict::Redo(why),
        Ok((size, _)) if size != (width, height) => {
            Verdict::Redo(format!("{}x{} px, not {width}x{height}", size.0, size.1))
        }
        Ok((_, print)) if print.as_deref() != Some(fingerprint) => {
            Verdict::Redo("made by another path or other flags".into())
        }
        Ok(_) => Verdict::Complete,
    }
}

/// Decodes a whole PNG: its size and fingerprint.
fn png_size_and_fingerprint(bytes: &[u8]) -> Result<((u32, u32), Option<String>), String> {
    let broken = |e: png::DecodingError| format!("not a whole PNG: {e}");
    let mut reader = png::Decoder::new(Cursor::new(bytes))
        .read_info()
        .map_err(broken)?;
    let info = reader.info();
    let size = (info.width, info.height);
    let print = info
        .uncompressed_latin1_text
        .iter()
        .find(|chunk| chunk.keyword == FINGERPRINT_KEY)
        .map(|chunk| chunk.text.clone());
    let buffer_size = reader
        .output_buffer_size()
        .ok_or("not a whole PNG: its image is too large")?;
    let mut pixels = vec![0; buffer_size];
    reader.next_frame(&mut pixels).map_err(broken)?;
    reader.finish().map_err(broken)?;
    Ok((size, print))
}

/// Decodes a whole EXR, strictly: its size and fingerprint.
fn exr_size_and_fingerprint(bytes: &[u8]) -> Result<((u32, u32), Option<String>), String> {
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .pedantic()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| format!("not a whole EXR: {e}"))?;
    let layer = &image.layer_data;
    let (width, height) = (layer.size.x(), layer.size.y());
    let size = (
        u32::try_from(width).unwrap_or(u32::MAX),
        u32::try_from(height).unwrap_or(u32::MAX),
    );
    let print = layer
        .attributes
        .other
        .get(&Text::from(FINGERPRINT_KEY))
        .and_then(|value| match value {
            AttributeValue::Text(text) => Some(text.to_string()),
            _ => None,
        });
    Ok((size, print))
}
