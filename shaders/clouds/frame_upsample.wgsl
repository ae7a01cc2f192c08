// Entry pass: a frame's reduced cloud march brought to full size
// (`frame_upsample_pixel.wgsl`) into the cloud image and the cloud's entry, for the
// model's second run and the composite (render-wgpu's `clouds/frame_pass.rs`); the
// listed pixels are left to `frame_march_list.wgsl`.

#import clouds/frame_upsample_pixel.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= layer.sizes.zw) {
        return;
    }
    var p: PixelCloud;
    if upsample_pixel(id.xy, &p) {
        store_pixel_cloud(id.xy, p);
    }
}
