// Entry pass: a frame's reduced cloud march brought to full size
// (`frame_upsample_pixel.wgsl`) and composited over the model's pixels at once
// (`frame_over_full.wgsl`), where no air lies in front of the cloud (the camera inside
// the layer) and the composite needs nothing else: one full-size pass instead of the
// upsample's and the composite's (render-wgpu's `clouds/frame_pass.rs`). The listed
// pixels are left to `frame_march_list_over.wgsl`.

#import clouds/frame_upsample_pixel.wgsl
#import clouds/frame_over_full.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= layer.sizes.zw) {
        return;
    }
    var p: PixelCloud;
    if upsample_pixel(id.xy, &p) {
        store_over_full(id.xy, p.cloud);
    }
}
