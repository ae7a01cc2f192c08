// Entry pass: a frame's cloud spheres shaded at a reduced resolution (render-wgpu's
// `clouds/spheres/frame_spheres.rs`): reduced pixel (i, j) of w x h =
// ceil(W / divisor) x ceil(H / divisor) shades the full image's ray through the
// fractional pixel ((i + 0.5) W / w - 0.5, (j + 0.5) H / h - 0.5), ended on the surface
// of the full pixel nearest to it, and keeps the ray's span of the layer for
// `frame_upsample.wgsl`. CPU twin: atmosphere-core's `clouds/spheres/reduced.rs`.

#import clouds/spheres/frame_inputs.wgsl

// (t0, t1) of the ray's span of the layer; (0, 0) where it has none.
@group(0) @binding(29) var reduced_segments: texture_storage_2d<rg32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = spheres.counts.zw;
    let divisor = u32(frame_spheres.z);
    let reduced = (size + vec2<u32>(divisor - 1u)) / divisor;
    if any(id.xy >= reduced) {
        return;
    }
    let pixel = (vec2<f32>(id.xy) + 0.5) * vec2<f32>(size) / vec2<f32>(reduced) - 0.5;
    let nearest = vec2<u32>(clamp(floor(pixel + 0.5), vec2<f32>(0.0), vec2<f32>(size - 1u)));
    let o = spheres.camera_m.xyz;
    let d = pixel_ray_at(pixel);
    let end = surface_end(nearest);
    let along = spheres_along(o, d, end);
    let t = sphere_span(o, d, end);
    var segment = vec2<f32>(0.0);
    if t.x < t.y {
        segment = t;
    }
    textureStore(sphere_image, id.xy, along.cloud);
    textureStore(reduced_segments, id.xy, vec4<f32>(segment, 0.0, 0.0));
}
