// Entry passes: a frame's cloud composited with its sky model (render-wgpu's
// `clouds/frame_pass.rs`), each pixel as `composite_pixel.wgsl` composites it, the cloud
// from the layer's march (`clouds/frame_march.wgsl`) or the spheres
// (`clouds/spheres/frame_image.wgsl`). With the model's run in front reduced
// (`FROM_TAPS`, the pipeline's variant) `main` reads each pixel's air in front from its
// bilinear taps and lists the pixels that need more (`common/pixel_list.wgsl`) for
// `listed` to composite by the whole rule, by an indirect dispatch over the list alone:
// on a software rasteriser a group of invocations pays for a branch any of them takes,
// and a loop compiled into a pass costs even where none runs it. From above the layer with the spheres at a reduced
// resolution their upsample composites instead, and these passes do not run.

#import clouds/composite_pixel.wgsl
#import common/pixel_list.wgsl

// rgb: the cloud's radiance; a: its transmittance.
@group(0) @binding(4) var cloud_image: texture_2d<f32>;
// w: the cloud's entry distance, m (0: the camera is inside it, or no cloud).
@group(0) @binding(5) var cloud_front: texture_2d<f32>;
// The pixels `from_taps` leaves to `listed`, and its dispatch.
@group(0) @binding(10) var<storage, read_write> march_list: MarchList;
@group(0) @binding(11) var<storage, read_write> list_dispatch: ListDispatch;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let cloud = textureLoad(cloud_image, id.xy, 0);
    store_composite(id.xy, cloud, textureLoad(cloud_front, id.xy, 0).w);
}

@compute @workgroup_size(8, 8)
fn from_taps(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let cloud = textureLoad(cloud_image, id.xy, 0);
    if !store_composite_from_taps(id.xy, cloud, textureLoad(cloud_front, id.xy, 0).w) {
        list_pixel(id.xy);
    }
}

@compute @workgroup_size(256)
fn listed(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        let cloud = textureLoad(cloud_image, px, 0);
        store_composite(px, cloud, textureLoad(cloud_front, px, 0).w);
    }
}
