// Entry pass: the rays of the sky model's reduced run in front of the cloud from above
// the layer (render-wgpu's `clouds/frame_front.rs`). The frame uniform at 1 is the
// run's, whose size is the reduced image's, so that pixel (i, j) is reduced ray (i, j)
// (`layer/upsample.rs`'s map). For each it writes where the ray enters the sphere of the
// layer's top (the run's surface: xyz the outward vertical there, w the distance, m; 0
// where the ray misses the sphere) and the atmosphere's transmittance to there, which the
// composite's `reduced_front` reads with the run (CPU twin: atmosphere-core's
// `clouds/layer/front_upsample.rs`, the entry `clouds/spheres/reduced.rs`'s `span`).

#import clouds/front_transmittance.wgsl
#import common/sphere_roots.wgsl

// x: the radius of the layer's top, m.
@group(0) @binding(2) var<uniform> front_layer: vec4<f32>;
@group(0) @binding(3) var front_entries: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var front_transmittance_out: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let o = frame.camera_m.xyz;
    let d = pixel_direction(id.xy);
    let r = length(o);
    let top = sphere_roots(r, clamp(dot(o, d) / r, -1.0, 1.0), front_layer.x);
    var entry = vec4<f32>(0.0);
    var t = vec3<f32>(1.0);
    if top.x <= top.y && top.x > 0.0 {
        entry = vec4<f32>(normalize(o + d * top.x), top.x);
        t = front_transmittance(d, top.x);
    }
    textureStore(front_entries, id.xy, entry);
    textureStore(front_transmittance_out, id.xy, vec4<f32>(t, 1.0));
}
