// Library: the cloud over the model's pixel where no air lies in front of the cloud
// (the camera inside the layer): atmosphere-core's `clouds/layer/composite.rs` with
// L_front = 0 and T_front = 1 (Riley et al. 2004, section 5),
//     L = L_cloud + T_cloud L_full,
// written to the HDR target; pixels without cloud (T_cloud = 1) keep L_full exactly, as
// in `frame_composite.wgsl`.

#import common/f16_max.wgsl

// The model's pixels (L_full) and the frame's HDR target.
@group(0) @binding(11) var full_image: texture_2d<f32>;
@group(0) @binding(12) var hdr: texture_storage_2d<rgba16float, write>;

// Writes pixel `px` of the HDR target: `cloud` (rgb radiance, a transmittance) over it.
fn store_over_full(px: vec2<u32>, cloud: vec4<f32>) {
    var out = textureLoad(full_image, px, 0).rgb;
    if cloud.a < 1.0 {
        out = cloud.rgb + cloud.a * max(out, vec3<f32>(0.0));
    }
    textureStore(hdr, px, vec4<f32>(min(out, vec3<f32>(F16_MAX)), 1.0));
}
