// Entry pass: the cloud layer in a renderer frame marched at full resolution
// (render-wgpu's `clouds/frame_pass.rs`): `clouds/layer_march.wgsl`'s march for each
// pixel of the frame's camera along its segment of the layer (`frame_rays.wgsl`), and
// the depth where the ray enters the cloud, on which the sky model's second run ends its
// rays (the aerial perspective in front of the cloud). CPU twin: atmosphere-core's
// `clouds/layer/composite.rs` (`radiance_with_clouds`, the march ended at the ray's
// `max_distance_m`).

#import clouds/frame_pixel_cloud.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= layer.sizes.zw) {
        return;
    }
    let d = frame_direction(vec2<f32>(id.xy));
    let t = frame_segment(d, id.xy);
    var p = CLEAR_PIXEL;
    if t.x < t.y {
        p = pixel_cloud(march_layer(layer.camera_m.xyz, d, t.x, t.y), d, t.x);
    }
    store_pixel_cloud(id.xy, p);
}
