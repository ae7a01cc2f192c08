// Entry pass: the cloud layer's radiance and transmittance for every pixel of an image
// of w x h = ceil(W / divisor) x ceil(H / divisor) pixels, W x H the full image
// (render-wgpu's `clouds/layer_pass.rs`; CPU twin: atmosphere-core's
// `clouds/layer/shell.rs`, `march.rs` and `upsample.rs`, compared pixel by pixel in
// `tests/tests/gpu_cloud_layer_parity.rs`). Pixel (i, j) looks through the full image's
// fractional pixel (x, y) = ((i + 0.5) W / w - 0.5, (j + 0.5) H / h - 0.5), along
// forward + (2 (x + 0.5) / W - 1) tan(fov / 2) aspect right
//         - (2 (y + 0.5) / H - 1) tan(fov / 2) up, normalised.

#import clouds/layer_march.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = layer.sizes.zw;
    let reduced = (size + vec2<u32>(layer.noise.z - 1u)) / layer.noise.z;
    if any(id.xy >= reduced) {
        return;
    }
    let pixel = (vec2<f32>(id.xy) + 0.5) * vec2<f32>(size) / vec2<f32>(reduced) - 0.5;
    let tan_half = layer.camera_m.w;
    let aspect = f32(size.x) / f32(size.y);
    let sx = (2.0 * (pixel.x + 0.5) / f32(size.x) - 1.0) * tan_half * aspect;
    let sy = (2.0 * (pixel.y + 0.5) / f32(size.y) - 1.0) * tan_half;
    let d = normalize(layer.forward.xyz + sx * layer.right.xyz - sy * layer.up.xyz);
    let o = layer.camera_m.xyz;
    let t = layer_segment(o, d);
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    if t.x < t.y {
        result = march_layer(o, d, t.x, t.y);
    }
    textureStore(cloud_image, id.xy, result);
}
