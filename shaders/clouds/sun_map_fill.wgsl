// Entry pass: the cloud layer's sun map (render-wgpu's `clouds/sun_map_pass.rs`; CPU
// twin: atmosphere-core's `clouds/layer/sun_map.rs`, `CloudSunMap::new`, compared texel
// by texel in `tests/tests/gpu_cloud_sun_map.rs`). Texel (i, j) of level k: the optical
// depth from the point at radius R_base + k thickness / levels in the direction of the
// grid's cell (i, j) to the shell's boundary along the sun, by a midpoint march of the
// light's extinction (`noise.y` octaves of detail noise): Dobashi, Yamamoto and Nishita
// 2002 section 5.4's attenuation texture, rendered from the sun.

#import clouds/layer_medium.wgsl
#import clouds/sun_map_read.wgsl

@group(0) @binding(4) var sun_map_out: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let m = sun_map_params;
    let n = m.counts.x;
    if id.x >= n || id.y >= n || id.z >= m.counts.y {
        return;
    }
    let base = m.radii.x;
    let half = 0.5 * f32(n);
    let x = (f32(id.x) + 0.5 - half) * m.east_cell.w / base;
    let y = (f32(id.y) + 0.5 - half) * m.east_cell.w / base;
    let d = normalize(m.up.xyz + x * m.east_cell.xyz + y * m.north.xyz);
    let radius = base + (m.radii.y - base) * f32(id.z) / f32(m.counts.y);
    let p = d * radius;
    let s = m.sun.xyz;
    let steps = m.counts.z;
    let ds = layer_boundary(p, s) / f32(steps);
    var tau = 0.0;
    for (var k = 0u; k < steps; k++) {
        tau += layer_extinction(p + s * ((f32(k) + 0.5) * ds), layer.noise.y) * ds;
    }
    textureStore(sun_map_out, vec2<u32>(id.x, id.z * n + id.y), vec4<f32>(tau, 0.0, 0.0, 0.0));
}
