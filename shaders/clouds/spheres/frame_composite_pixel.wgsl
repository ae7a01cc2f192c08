// Library: a full pixel of a frame's cloud spheres composited with the sky model at once
// (`clouds/composite_pixel.wgsl`), where the composite needs nothing the spheres write:
// from above the layer with the model's run in front reduced (render-wgpu's
// `clouds/spheres/frame_spheres.rs`). One full-size pass then does the spheres' upsample
// and the composite, which on a software rasteriser costs tens of milliseconds a pass
// (docs/clouds.md, "The whole frame from orbit").

#import clouds/spheres/frame_inputs.wgsl
#import clouds/composite_pixel.wgsl

// Writes full pixel `px` of the HDR target: the spheres' `spheres_cloud`, first crossed
// at `first_m`, blended with the layer's march and composited with the model's runs.
fn store_composited_pixel(px: vec2<u32>, spheres_cloud: vec4<f32>, first_m: f32) {
    let cloud = frame_cloud(px, spheres_cloud);
    store_composite(px, cloud, entry_distance(cloud, first_m));
}

// `store_composited_pixel` with the air in front from its bilinear taps alone
// (`store_composite_from_taps`); false, with nothing written, where that cannot be.
fn store_composited_from_taps(px: vec2<u32>, spheres_cloud: vec4<f32>, first_m: f32) -> bool {
    let cloud = frame_cloud(px, spheres_cloud);
    return store_composite_from_taps(px, cloud, entry_distance(cloud, first_m));
}
