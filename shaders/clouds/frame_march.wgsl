// Entry pass: the cloud layer in a renderer frame marched at full resolution
// (render-wgpu's `clouds/frame_pass.rs`): `clouds/layer_march.wgsl`'s march for each
// pixel of the frame's camera along its segment of the layer (`frame_rays.wgsl`), and
// the depth where the ray enters the cloud, on which the sky model's second run ends its
// rays (the aerial perspective in front of the cloud). CPU twin: atmosphere-core's
// `clouds/layer/composite.rs` (`radiance_with_clouds`, the march ended at the ray's
// `max_distance_m`).

#import clouds/frame_rays.wgsl

// Where the sky model's second run ends its rays: xyz the outward vertical at the
// cloud's entry, w the entry distance, m; 0 where the pixel sees no cloud or the camera
// is inside one.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= layer.sizes.zw) {
        return;
    }
    let d = frame_direction(vec2<f32>(id.xy));
    let t = frame_segment(d, id.xy);
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var front = vec4<f32>(0.0);
    if t.x < t.y {
        let o = layer.camera_m.xyz;
        result = march_layer(o, d, t.x, t.y);
        if result.a < 1.0 {
            front = vec4<f32>(normalize(o + d * t.x), t.x);
        }
    }
    textureStore(cloud_image, id.xy, result);
    textureStore(cloud_front, id.xy, front);
}
