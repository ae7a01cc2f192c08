// Entry pass: the listed pixels of a frame (`frame_list.wgsl`) marched, each invocation
// taking every (groups x 256)-th entry, dispatched indirectly with the workgroup count
// the upsample wrote (render-wgpu's `clouds/frame_pass.rs`); with `OVER_MODEL`,
// composited over the model's pixels as `frame_upsample.wgsl` does then.

#import clouds/frame_list.wgsl
#import clouds/frame_over_full.wgsl

// Whether the pass writes the HDR target (the pipeline's variant).
override OVER_MODEL: bool = false;

@compute @workgroup_size(256)
fn main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        let p = march_pixel(px);
        if OVER_MODEL {
            store_over_full(px, p.cloud);
        } else {
            store_pixel_cloud(px, p);
        }
    }
}
