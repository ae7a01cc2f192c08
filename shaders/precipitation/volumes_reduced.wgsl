// Entry pass: the rain and ice volumes marched for one pixel in N x N (render-wgpu's
// `precipitation/volumes_pass.rs`, N = `volumes.reduction.x`): the composite's terms
// and the ray's spans at the frame's pixel (N i, N j), past the frame's last pixel too,
// for the composite pass to upsample. CPU twin: atmosphere-core's `hydrometeors/reduced.rs`.

#import precipitation/volumes_march.wgsl

// rgb: the terms' times_full; a: the nearest entry, m.
@group(0) @binding(7) var reduced_a: texture_storage_2d<rgba32float, write>;
// rgb: the terms' added light; a: the length inside the volumes, m.
@group(0) @binding(8) var reduced_b: texture_storage_2d<rgba32float, write>;

// Over the reduced pixels the composite's rectangle reads, from `volumes.reduction.yz`.
@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let r = id.xy + volumes.reduction.yz;
    if any(r >= textureDimensions(reduced_a)) {
        return;
    }
    let px = r * volumes.reduction.x;
    let d = pixel_direction(px);
    let max_t = max_distance(px);
    let terms = pixel_terms(d, max_t);
    let spans = pixel_spans(d, max_t);
    textureStore(reduced_a, r, vec4<f32>(terms.times_full, spans.x));
    textureStore(reduced_b, r, vec4<f32>(terms.added, spans.y));
}
