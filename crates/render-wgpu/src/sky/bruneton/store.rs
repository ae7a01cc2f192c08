//! The store: one storage buffer holding every table being built, each at its offset and
//! indexed as on the CPU, so that a table read back compares texel by texel.

use atmosphere_core::models::bruneton::parameterization::ScatteringSize;

/// Samples of the density table (`DensityTable::SAMPLES`).
pub const DENSITY_SAMPLES: u32 = 8192;
/// Workgroups of the partial sums (`SUM_GROUPS` of `sky/bruneton/orders.wgsl`).
pub const SUM_GROUPS: u32 = 256;
/// Bytes of one texel of the store (`vec4<f32>`, rgb = the three channels).
pub const TEXEL_BYTES: u64 = 16;

/// The tables of the store, in its order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StoreTable {
    Density,
    SingleRayleigh,
    SingleMie,
    Multiple,
    DeltaS,
    DeltaJ,
    DeltaE,
    Irradiance,
    Moments,
    Partials,
}

/// How many tables the store holds.
const TABLES: usize = StoreTable::Partials as usize + 1;

/// Offsets and lengths (texels) of the store's tables.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StoreLayout {
    offsets: [u32; TABLES],
    lengths: [u32; TABLES],
}

impl StoreLayout {
    /// The layout for S of size `s` and E of `irradiance` texels.
    pub fn new(s: ScatteringSize, irradiance: usize) -> StoreLayout {
        let n = s.texels() as u32;
        let e = irradiance as u32;
        let lengths = [
            DENSITY_SAMPLES,
            n,
            n,
            n,
            n,
            n,
            e,
            e,
            (7 * s.r * s.mu_s) as u32,
            SUM_GROUPS,
        ];
        let mut offsets = [0; TABLES];
        for k in 1..TABLES {
            offsets[k] = offsets[k - 1] + lengths[k - 1];
        }
        StoreLayout { offsets, lengths }
    }

    /// The store's size in texels.
    pub fn texels(&self) -> u64 {
        u64::from(self.offsets[TABLES - 1]) + u64::from(self.lengths[TABLES - 1])
    }

    /// The store's size in bytes.
    pub fn bytes(&self) -> u64 {
        self.texels() * TEXEL_BYTES
    }

    /// The first texel of `table`.
    pub fn offset(&self, table: StoreTable) -> u32 {
        self.offsets[table as usize]
    }

    /// The texels of `table`.
    pub fn length(&self, table: StoreTable) -> u32 {
        self.lengths[table as usize]
    }

    /// The bytes of `table`: offset and size.
    pub fn range(&self, table: StoreTable) -> (u64, u64) {
        (
            u64::from(self.offset(table)) * TEXEL_BYTES,
            u64::from(self.length(table)) * TEXEL_BYTES,
        )
    }
}
