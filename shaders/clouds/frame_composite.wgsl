// Entry pass: a frame's cloud composited with its sky model (render-wgpu's
// `clouds/frame_pass.rs`), each pixel as `composite_pixel.wgsl` composites it, the cloud
// from the layer's march (`clouds/frame_march.wgsl`) or the spheres
// (`clouds/spheres/frame_image.wgsl`). From above the layer with the spheres at a
// reduced resolution their upsample composites instead, and this pass does not run.

#import clouds/composite_pixel.wgsl

// rgb: the cloud's radiance; a: its transmittance.
@group(0) @binding(4) var cloud_image: texture_2d<f32>;
// w: the cloud's entry distance, m (0: the camera is inside it, or no cloud).
@group(0) @binding(5) var cloud_front: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let cloud = textureLoad(cloud_image, id.xy, 0);
    store_composite(id.xy, cloud, textureLoad(cloud_front, id.xy, 0).w);
}
