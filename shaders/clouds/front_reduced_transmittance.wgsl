// Entry pass: the transmittance T_front of the spheres' reduced rays from the camera to
// where each enters the layer (render-wgpu's `clouds/frame_pass.rs`), which the
// composite's `reduced_front` divides the model's reduced run by (CPU twin:
// atmosphere-core's `clouds/layer/front_upsample.rs`). The frame uniform at 1 is the
// reduced run's, whose size is the reduced image's, so that pixel (i, j) is the reduced
// ray (i, j); 1 where the ray does not enter the layer.

#import clouds/front_transmittance.wgsl

// w: where each reduced ray enters the layer, m (0: it does not).
@group(0) @binding(2) var reduced_entries: texture_2d<f32>;
@group(0) @binding(3) var reduced_transmittance: texture_storage_2d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let entry_m = textureLoad(reduced_entries, id.xy, 0).w;
    var t = vec3<f32>(1.0);
    if entry_m > 0.0 {
        t = front_transmittance(pixel_direction(id.xy), entry_m);
    }
    textureStore(reduced_transmittance, id.xy, vec4<f32>(t, 1.0));
}
