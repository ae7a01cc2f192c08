//! What made a frame file, as one number stored in it: a hash of the path's TOML, the
//! frame's index, the frame rate, the image size and the file's kind. A file whose
//! fingerprint differs was made by another path or other flags, and is redone.

use crate::record::naming::FileKind;

/// FNV-1a, 64 bits (Fowler, Noll and Vo): stable across builds and platforms, unlike
/// the standard library's hasher.
#[derive(Debug)]
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Fnv1a {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    /// Adds `bytes`, preceded by their length so that fields cannot run into each other.
    fn field(&mut self, bytes: &[u8]) {
        for &b in (bytes.len() as u64).to_le_bytes().iter().chain(bytes) {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
}

/// The inputs of a frame file that its fingerprint covers.
#[derive(Clone, Copy, Debug)]
pub struct FrameInputs<'a> {
    pub path_toml: &'a str,
    pub index: u64,
    pub fps: f64,
    pub width: u32,
    pub height: u32,
}

impl FrameInputs<'_> {
    /// The fingerprint of the `kind` file of these inputs, as 16 hexadecimal digits.
    pub fn fingerprint(&self, kind: FileKind) -> String {
        let mut hash = Fnv1a::new();
        hash.field(b"atmos record 1");
        hash.field(self.path_toml.as_bytes());
        hash.field(&self.index.to_le_bytes());
        hash.field(&self.fps.to_bits().to_le_bytes());
        hash.field(&self.width.to_le_bytes());
        hash.field(&self.height.to_le_bytes());
        hash.field(kind.extension().as_bytes());
        format!("{:016x}", hash.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_input_changes_the_fingerprint() {
        let base = FrameInputs {
            path_toml: "version = 1\n",
            index: 3,
            fps: 30.0,
            width: 32,
            height: 18,
        };
        let print = base.fingerprint(FileKind::Png);
        assert_eq!(print.len(), 16);
        assert_eq!(print, base.fingerprint(FileKind::Png));
        let others = [
            base.fingerprint(FileKind::Exr),
            FrameInputs {
                path_toml: "version = 2\n",
                ..base
            }
            .fingerprint(FileKind::Png),
            FrameInputs { index: 4, ..base }.fingerprint(FileKind::Png),
            FrameInputs { fps: 24.0, ..base }.fingerprint(FileKind::Png),
            FrameInputs { width: 33, ..base }.fingerprint(FileKind::Png),
            FrameInputs { height: 19, ..base }.fingerprint(FileKind::Png),
        ];
        for other in others {
            assert_ne!(other, print);
        }
    }
}
