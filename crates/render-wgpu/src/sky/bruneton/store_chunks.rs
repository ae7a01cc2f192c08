//! The store's bindings: one buffer bound as up to [`STORE_BINDINGS`] consecutive ranges
//! (chunks) of equal size, each within the device's largest storage buffer binding and
//! starting at a multiple of its storage offset alignment, so that the tables being built
//! may exceed one binding (`store_read` and `store_write` of
//! `sky/bruneton/bindings.wgsl` route a texel's index to its chunk).

use std::num::NonZeroU64;

use crate::sky::bruneton::store::TEXEL_BYTES;

/// Storage buffer bindings of the store in every bruneton shader (`store0` to `store3`).
pub const STORE_BINDINGS: usize = 4;

/// How the store is split over its bindings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StoreChunks {
    /// Texels of every chunk but the last.
    pub chunk_texels: u32,
    /// Chunks the store needs.
    pub count: u32,
    /// Texels of the whole store.
    pub texels: u64,
}

impl StoreChunks {
    /// The chunks of a store of `texels`, each at most `binding_bytes` and a multiple of
    /// `alignment` bytes; `Err` with the chunk size when the store needs more than
    /// [`STORE_BINDINGS`] of them, or when no texel fits one binding.
    pub fn new(texels: u64, binding_bytes: u64, alignment: u64) -> Result<StoreChunks, u64> {
        let step = alignment.max(TEXEL_BYTES);
        let chunk_bytes = (binding_bytes / step * step).min(u64::from(u32::MAX) * TEXEL_BYTES);
        let chunk_texels = chunk_bytes / TEXEL_BYTES;
        if chunk_texels == 0 {
            return Err(chunk_bytes);
        }
        let count = texels.div_ceil(chunk_texels).max(1);
        if count > STORE_BINDINGS as u64 {
            return Err(chunk_bytes);
        }
        Ok(StoreChunks {
            chunk_texels: chunk_texels as u32,
            count: count as u32,
            texels,
        })
    }

    /// The byte range (offset, size) bound at each of the [`STORE_BINDINGS`] bindings:
    /// the chunks in order, the last repeated in the bindings past it.
    pub fn ranges(&self) -> [(u64, NonZeroU64); STORE_BINDINGS] {
        let chunk = u64::from(self.chunk_texels);
        std::array::from_fn(|k| {
            let k = (k as u64).min(u64::from(self.count) - 1);
            let start = k * chunk;
            let end = ((k + 1) * chunk).min(self.texels);
            let size = NonZeroU64::new((end - start) * TEXEL_BYTES).unwrap_or(NonZeroU64::MIN);
            (start * TEXEL_BYTES, size)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_cover_the_store_in_order_and_aligned() {
        // 1000 texels with bindings of 5000 bytes aligned to 256: chunks of 4864 bytes
        // (304 texels), four of them, the last 88 texels.
        let c = StoreChunks::new(1000, 5000, 256).unwrap();
        assert_eq!((c.chunk_texels, c.count), (304, 4));
        let ranges = c.ranges();
        let mut end = 0;
        for (offset, size) in ranges {
            assert_eq!(offset, end);
            assert_eq!(offset % 256, 0);
            assert!(size.get() <= 5000);
            end = offset + size.get();
        }
        assert_eq!(end, 1000 * TEXEL_BYTES);
        assert_eq!(ranges[3].1.get(), 88 * TEXEL_BYTES);
    }

    #[test]
    fn a_store_in_one_binding_repeats_it() {
        let c = StoreChunks::new(100, 1 << 20, 256).unwrap();
        assert_eq!(c.count, 1);
        let whole = (0, NonZeroU64::new(1600).unwrap());
        assert_eq!(c.ranges(), [whole; STORE_BINDINGS]);
    }

    #[test]
    fn too_many_chunks_or_none_fitting_are_errors() {
        // Five chunks of 256 bytes would be needed for 80 texels.
        assert_eq!(StoreChunks::new(80, 300, 256), Err(256));
        assert_eq!(StoreChunks::new(10, 200, 256), Err(0));
    }
}
