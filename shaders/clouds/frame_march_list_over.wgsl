// Entry pass: the listed pixels of a frame (`frame_list.wgsl`) marched and composited
// over the model's pixels (`frame_over_full.wgsl`), as `frame_march_list.wgsl` marches
// them, after `frame_upsample_over.wgsl` (render-wgpu's `clouds/frame_pass.rs`).

#import clouds/frame_list.wgsl
#import clouds/frame_over_full.wgsl

@compute @workgroup_size(256)
fn main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        store_over_full(px, march_pixel(px).cloud);
    }
}
