// Entry pass: the cloud layer's radiance and transmittance for every pixel of an image
// (render-wgpu's `clouds/layer_pass.rs`; CPU twin: atmosphere-core's
// `clouds/layer/shell.rs` and `march.rs`, compared pixel by pixel in
// `tests/tests/gpu_cloud_layer_parity.rs`). Pixel (x, y) looks along
// forward + (2 (x + 0.5) / W - 1) tan(fov / 2) aspect right
//         - (2 (y + 0.5) / H - 1) tan(fov / 2) up, normalised.

#import clouds/layer_march.wgsl

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
    let t = layer_segment(o, d);
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if t.x < t.y {
        result = march_layer(o, d, t.x, t.y);
    }
    textureStore(cloud_image, id.xy, result);
}
