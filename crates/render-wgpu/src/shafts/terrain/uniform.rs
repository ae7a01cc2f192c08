//! WGSL `ShadowMapParams` (`shaders/shafts/terrain/shadow_map.wgsl`).

use atmosphere_core::shafts::ShadowMap;
use bytemuck::{Pod, Zeroable};

/// The shadow map's grid and bounds, 64 bytes; all zero (with `size[1] = 0`) for a frame
/// without shafts.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadowMapUniform {
    /// The grid's east axis; w: the cell's side, m.
    pub east_cell: [f32; 4],
    /// The grid's north axis; w: the penumbra band, m.
    pub north_band: [f32; 4],
    /// The grid's centre direction; w: the highest top S, m.
    pub up_top: [f32; 4],
    /// Cells per side, 1 when the frame has shafts, most and fewest samples per view
    /// segment.
    pub size: [u32; 4],
}

impl ShadowMapUniform {
    /// The parameters of `map`, marched in at most `samples.0` and at least `samples.1`
    /// samples per view segment.
    pub fn new(map: &ShadowMap, samples: (u32, u32)) -> ShadowMapUniform {
        let g = &map.grid;
        let v = |d: glam::DVec3, w: f32| [d.x as f32, d.y as f32, d.z as f32, w];
        ShadowMapUniform {
            east_cell: v(g.east, g.cell_m as f32),
            north_band: v(g.north, map.band_m),
            up_top: v(g.up, map.max_top_m),
            size: [g.size as u32, 1, samples.0, samples.1],
        }
    }
}
