// Entry pass: the reduced-resolution cloud image brought to full size by bilinear
// interpolation (render-wgpu's `clouds/layer_pass.rs`; CPU twin: atmosphere-core's
// `clouds/layer/upsample.rs`, which holds the maps). Full pixel (x, y) of W x H reads
// the w x h image at ((x + 0.5) w / W - 0.5, (y + 0.5) h / H - 0.5), clamped.

// The reduced image: rgb radiance, a transmittance.
@group(0) @binding(0) var reduced: texture_2d<f32>;
@group(0) @binding(1) var full: texture_storage_2d<rgba32float, write>;

// The two reduced texels and the weight of the second along an axis.
fn upsample_taps(x: u32, size: u32, reduced_size: u32) -> vec3<f32> {
    let u = clamp((f32(x) + 0.5) * f32(reduced_size) / f32(size) - 0.5, 0.0,
        f32(reduced_size - 1u));
    let i0 = floor(u);
    return vec3<f32>(i0, min(i0 + 1.0, f32(reduced_size - 1u)), u - i0);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(full);
    if any(id.xy >= size) {
        return;
    }
    let low = textureDimensions(reduced);
    let tx = upsample_taps(id.x, size.x, low.x);
    let ty = upsample_taps(id.y, size.y, low.y);
    let a = textureLoad(reduced, vec2<u32>(u32(tx.x), u32(ty.x)), 0);
    let b = textureLoad(reduced, vec2<u32>(u32(tx.y), u32(ty.x)), 0);
    let c = textureLoad(reduced, vec2<u32>(u32(tx.x), u32(ty.y)), 0);
    let d = textureLoad(reduced, vec2<u32>(u32(tx.y), u32(ty.y)), 0);
    let top = a + (b - a) * tx.z;
    let bottom = c + (d - c) * tx.z;
    textureStore(full, id.xy, top + (bottom - top) * ty.z);
}
