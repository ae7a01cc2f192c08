// Entry pass: the listed pixels of a frame (`frame_list.wgsl`) marched, each invocation
// taking every (groups x 256)-th entry, dispatched indirectly with the workgroup count
// the upsample wrote (render-wgpu's `clouds/frame_pass.rs`).

#import clouds/frame_list.wgsl

@compute @workgroup_size(256)
fn main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        store_pixel_cloud(px, march_pixel(px));
    }
}
