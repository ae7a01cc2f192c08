// Entry pass: the cloud layer in a renderer frame (render-wgpu's `clouds/frame_pass.rs`):
// `clouds/layer_image.wgsl`'s march for each pixel of the frame's camera, ended where
// the pixel's ray meets the frame's surface (terrain drawn in front of the cloud hides
// it; terrain inside the layer ends the march), and the depth where the ray enters the
// cloud, on which the sky model's second run ends its rays (the aerial perspective in
// front of the cloud). CPU twin: atmosphere-core's `clouds/layer/composite.rs`
// (`radiance_with_clouds`, the march ended at the ray's `max_distance_m`).

#import clouds/layer_march.wgsl

struct FrameCloudParams {
    // x: 1 when the frame has a surface (binding 4 holds it), 0 when it has none.
    flags: vec4<u32>,
}

// The frame's surface: xyz the normal, w the distance along the pixel's ray, m (0: none).
@group(0) @binding(4) var frame_surface: texture_2d<f32>;
// Where the sky model's second run ends its rays: xyz the outward vertical at the
// cloud's entry, w the entry distance, m; 0 where the pixel sees no cloud or the camera
// is inside one.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;
@group(0) @binding(6) var<uniform> frame_clouds: FrameCloudParams;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = layer.sizes.zw;
    if any(id.xy >= size) {
        return;
    }
    let tan_half = layer.camera_m.w;
    let aspect = f32(size.x) / f32(size.y);
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(size.x) - 1.0) * tan_half * aspect;
    let sy = (2.0 * (f32(id.y) + 0.5) / f32(size.y) - 1.0) * tan_half;
    let d = normalize(layer.forward.xyz + sx * layer.right.xyz - sy * layer.up.xyz);
    let o = layer.camera_m.xyz;
    var t = layer_segment(o, d);
    if frame_clouds.flags.x == 1u {
        let surface_m = textureLoad(frame_surface, id.xy, 0).w;
        if surface_m > 0.0 {
            t.y = min(t.y, surface_m);
        }
    }
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var front = vec4<f32>(0.0);
    if t.x < t.y {
        result = march_layer(o, d, t.x, t.y);
        if result.a < 1.0 {
            front = vec4<f32>(normalize(o + d * t.x), t.x);
        }
    }
    textureStore(cloud_image, id.xy, result);
    textureStore(cloud_front, id.xy, front);
}
