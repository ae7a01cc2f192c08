// Entry pass: a frame's cloud layer marched at a reduced resolution (render-wgpu's
// `clouds/frame_pass.rs`): reduced pixel (i, j) of w x h = ceil(W / divisor) x
// ceil(H / divisor) marches the full image's ray through the fractional pixel
// ((i + 0.5) W / w - 0.5, (j + 0.5) H / h - 0.5), ended on the surface of the full pixel
// nearest to it, and keeps the segment it marched for `frame_upsample.wgsl`. CPU twin:
// atmosphere-core's `clouds/layer/upsample.rs` (`marched_coordinate`, `nearest_pixel`).

#import clouds/frame_rays.wgsl

// (t0, t1) of the marched segment; (0, 0) where the ray meets no cloud.
@group(0) @binding(7) var reduced_segments: texture_storage_2d<rg32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = layer.sizes.zw;
    let reduced = (size + vec2<u32>(layer.noise.z - 1u)) / layer.noise.z;
    if any(id.xy >= reduced) {
        return;
    }
    let pixel = (vec2<f32>(id.xy) + 0.5) * vec2<f32>(size) / vec2<f32>(reduced) - 0.5;
    let nearest = vec2<u32>(clamp(floor(pixel + 0.5), vec2<f32>(0.0), vec2<f32>(size - 1u)));
    let d = frame_direction(pixel);
    let t = frame_segment(d, nearest);
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var segment = vec2<f32>(0.0);
    if t.x < t.y {
        result = march_layer(layer.camera_m.xyz, d, t.x, t.y);
        segment = t;
    }
    textureStore(cloud_image, id.xy, result);
    textureStore(reduced_segments, id.xy, vec4<f32>(segment, 0.0, 0.0));
}
