// Library: the terrain's shadow in the air, read from its shadow map (render-wgpu's
// `shafts/terrain/`). CPU twin: atmosphere-core's `shafts/shadow_map.rs`
// (`ShadowMap::sun_visible`) and `shafts/gnomonic_grid.rs` (`GnomonicGrid::locate`).
// Over each cell of a gnomonic grid tangent to the planet under the view, the map holds
// S, the altitude of the top of the terrain's shadow volume for the frame's sun (Max
// 1988's horizon recurrence, docs/shafts.md); a point at altitude a sees the sun for
// a >= S, not at all below S - band, linearly between. The map is a cascade of levels on
// one centre and axes, each with cells twice as wide as the one inside it, stacked in
// the texture finest first; a point takes the finest level over it.

// WGSL `ShadowMapParams` (Rust `ShadowMapUniform`).
struct ShadowMapParams {
    // The grid's axes (planet-fixed, unit); w: the finest level's cell (m), the tangent
    // of the sun's elevation over the centre, and the highest S (m).
    east_cell: vec4<f32>,
    north_slope: vec4<f32>,
    up_top: vec4<f32>,
    // x: cells per side of a level; y: levels (0 when the frame has no shafts); z, w:
    // most and fewest samples per view segment.
    size: vec4<u32>,
}

// The width of the outermost level, m.
fn shadow_map_width(m: ShadowMapParams) -> f32 {
    return m.east_cell.w * f32(m.size.x) * exp2(f32(max(m.size.y, 1u) - 1u));
}

// `ShadowMap::sun_visible` at the planet-centred `position` (m) of altitude `altitude`
// (m) over the sphere of radius `radius`; 1 outside every level.
fn shadow_map_visible(tops: texture_2d<f32>, m: ShadowMapParams, radius: f32, position: vec3<f32>, altitude: f32) -> f32 {
    let along_up = dot(position, m.up_top.xyz);
    let n = m.size.x;
    let last = f32(n - 1u);
    if along_up <= 0.0 || altitude >= m.up_top.w {
        return 1.0;
    }
    let centre = 0.5 * f32(n) - 0.5;
    let x = dot(position, m.east_cell.xyz);
    let y = dot(position, m.north_slope.xyz);
    var cell = m.east_cell.w;
    for (var level = 0u; level < m.size.y; level++) {
        let scale = radius / along_up / cell;
        let column = x * scale + centre;
        let row = y * scale + centre;
        if column >= 0.0 && row >= 0.0 && column <= last && row <= last {
            let i = min(u32(column), n - 2u);
            let j = min(u32(row), n - 2u);
            let a = column - f32(i);
            let b = row - f32(j);
            let j0 = level * n + j;
            let s00 = textureLoad(tops, vec2<u32>(i, j0), 0).x;
            let s10 = textureLoad(tops, vec2<u32>(i + 1u, j0), 0).x;
            let s01 = textureLoad(tops, vec2<u32>(i, j0 + 1u), 0).x;
            let s11 = textureLoad(tops, vec2<u32>(i + 1u, j0 + 1u), 0).x;
            let low = s00 + a * (s10 - s00);
            let high = s01 + a * (s11 - s01);
            let top = low + b * (high - low);
            let band = clamp(cell * m.north_slope.w, 1.0, cell);
            return clamp((altitude - top) / band + 1.0, 0.0, 1.0);
        }
        cell *= 2.0;
    }
    return 1.0;
}
