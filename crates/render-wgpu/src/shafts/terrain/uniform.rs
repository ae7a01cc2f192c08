//! WGSL `ShadowMapParams` (`shaders/shafts/terrain/shadow_map.wgsl`).

use atmosphere_core::shafts::ShadowMap;
use bytemuck::{Pod, Zeroable};

/// The shadow map's grid (the finest level's; the levels share its centre and axes) and
/// bounds, 64 bytes; all zero but the sample counts (with `size[1] = 0`) for a frame
/// without terrain shafts (the cloud's shadow in the air takes those counts too).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadowMapUniform {
    /// The grid's east axis; w: the finest level's cell, m (each level out doubles it).
    pub east_cell: [f32; 4],
    /// The grid's north axis; w: the tangent of the sun's elevation over the centre (a
    /// level's penumbra band is its cell times it, between 1 m and the cell).
    pub north_slope: [f32; 4],
    /// The grid's centre direction; w: the highest top S, m.
    pub up_top: [f32; 4],
    /// Cells per side of each level, the levels (0 when the frame has no shafts), most
    /// and fewest samples per view segment.
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
            north_slope: v(g.north, map.sun_slope.clamp(-1e30, 1e30) as f32),
            up_top: v(g.up, map.max_top_m),
            size: [
                g.size as u32,
                map.levels().count() as u32,
                samples.0,
                samples.1,
            ],
        }
    }
}
