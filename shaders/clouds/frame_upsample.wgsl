// Entry pass: a frame's reduced cloud march brought to full size
// (`frame_upsample_pixel.wgsl`; render-wgpu's `clouds/frame_pass.rs`): into the cloud
// image and the cloud's entry, for the model's second run and the composite, or, with
// `OVER_MODEL` (the camera inside the layer, where the composite needs nothing else),
// composited over the model's pixels at once (`frame_over_full.wgsl`): one full-size
// pass instead of the upsample's and the composite's. The listed pixels are left to
// `frame_march_list.wgsl`.

#import clouds/frame_upsample_pixel.wgsl
#import clouds/frame_over_full.wgsl

// Whether the pass writes the HDR target (the pipeline's variant).
override OVER_MODEL: bool = false;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= layer.sizes.zw) {
        return;
    }
    var p: PixelCloud;
    if upsample_pixel(id.xy, &p) {
        if OVER_MODEL {
            store_over_full(id.xy, p.cloud);
        } else {
            store_pixel_cloud(id.xy, p);
        }
    }
}
