// Entry pass: the cloud spheres in a renderer frame (render-wgpu's
// `clouds/spheres/frame_spheres.rs`), every pixel shaded: each pixel's spheres ended on
// the frame's surface (terrain in front of the cloud hides it), blended with the layer's
// march by the spheres' weight of the hand-over (atmosphere-core's
// `clouds/spheres/handover.rs`), and where the ray enters the cloud, on which the sky
// model's second run ends its rays (as `clouds/frame_march.wgsl` writes it). The
// composite with the model is the layer's (`clouds/frame_composite.wgsl`). CPU twin:
// `spheres_only` ended at the surface, mixed with the layer's march, through
// `layer/composite.rs`'s `composite`. At a resolution divisor above 1,
// `frame_reduced.wgsl` and `frame_upsample.wgsl` take its place.

#import clouds/spheres/frame_inputs.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= spheres.counts.zw) {
        return;
    }
    let d = pixel_ray(id.xy);
    let along = spheres_along(spheres.camera_m.xyz, d, surface_end(id.xy));
    store_frame_pixel(id.xy, d, along.cloud, along.first_m);
}
