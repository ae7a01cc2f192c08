// Library: the cloud layer's sun map read at a point (render-wgpu's
// `clouds/sun_map_texture.rs`; the per-pixel pass `sun_map_pixels.wgsl` and, with
// `sun_light = map`, the layer's march `layer_march.wgsl` read it). CPU
// twin: atmosphere-core's `clouds/layer/sun_map.rs` (`CloudSunMap::optical_depth`):
// Dobashi, Yamamoto and Nishita 2002 section 5.4's attenuation textures, the optical
// depth towards the sun through the layer at `levels` spheres of the shell over a
// gnomonic grid on the sphere of the layer's base. A point below the base is carried
// along the sun to the base sphere and read on level 0; a point inside the shell is read
// at its own direction, bilinearly in the grid and linearly in radius between levels; a
// point above the top or off the grid sees no cloud.

#import clouds/sun_map_params.wgsl

// Level k's optical depths in rows k n to k n + n - 1 (n cells per side); the
// parameters at 33 (`sun_map_params.wgsl`).
@group(0) @binding(35) var sun_map: texture_2d<f32>;

// `x` clamped to [0, hi] (0 for NaN) and truncated: a software rasteriser runs the loads
// of lanes that take no part, so every index stays inside the texture whatever `x` is.
fn sun_map_index(x: f32, hi: u32) -> u32 {
    return u32(min(select(0.0, x, x > 0.0), f32(hi)));
}

// Level `k`'s optical depth at fractional cell coordinates inside the grid (bilinear).
fn sun_map_level(k: u32, column: f32, row: f32) -> f32 {
    let n = sun_map_params.counts.x;
    let size = textureDimensions(sun_map);
    let i = sun_map_index(column, size.x - 2u);
    let j = sun_map_index(row, size.x - 2u);
    let a = column - f32(i);
    let b = row - f32(j);
    let y = min(k * n + j, size.y - 2u);
    let s00 = textureLoad(sun_map, vec2<u32>(i, y), 0).x;
    let s10 = textureLoad(sun_map, vec2<u32>(i + 1u, y), 0).x;
    let s01 = textureLoad(sun_map, vec2<u32>(i, y + 1u), 0).x;
    let s11 = textureLoad(sun_map, vec2<u32>(i + 1u, y + 1u), 0).x;
    let low = s00 + a * (s10 - s00);
    let high = s01 + a * (s11 - s01);
    return low + b * (high - low);
}

// The sun's transmittance through the cloud from the planet-centred `p` (m); 1 when
// the frame has no map.
fn cloud_sun_transmittance(p: vec3<f32>) -> f32 {
    return exp(-cloud_sun_optical_depth(p));
}

// The optical depth towards the sun through the cloud from the planet-centred `p` (m);
// 0 when the frame has no map.
fn cloud_sun_optical_depth(p: vec3<f32>) -> f32 {
    let m = sun_map_params;
    if m.counts.w == 0u {
        return 0.0;
    }
    let base = m.radii.x;
    let top = m.radii.y;
    let r = length(p);
    if r >= top {
        return 0.0;
    }
    var q = p;
    var x = 0.0;
    if r <= base {
        // The distance to the base sphere along the sun, without cancellation.
        let b = dot(p, m.sun.xyz);
        let c = (base - r) * (base + r);
        let root = sqrt(max(b * b + c, 0.0));
        var t = -b + root;
        if b > 0.0 {
            t = c / (b + root);
        }
        q = p + m.sun.xyz * t;
    } else {
        x = (r - base) / (top - base) * f32(m.counts.y);
    }
    let along_up = dot(q, m.up.xyz);
    if along_up <= 0.0 {
        return 0.0;
    }
    let n = m.counts.x;
    let last = f32(n - 1u);
    let scale = base / along_up / m.east_cell.w;
    let centre = 0.5 * f32(n) - 0.5;
    let column = dot(q, m.east_cell.xyz) * scale + centre;
    let row = dot(q, m.north.xyz) * scale + centre;
    if column < 0.0 || row < 0.0 || column > last || row > last {
        return 0.0;
    }
    let k = sun_map_index(x, max(m.counts.y, 1u) - 1u);
    let f = x - f32(k);
    let low = sun_map_level(k, column, row);
    var high = 0.0;
    if k + 1u < m.counts.y {
        high = sun_map_level(k + 1u, column, row);
    }
    return low + f * (high - low);
}
