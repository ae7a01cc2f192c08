// Entry pass: the cloud spheres' radiance and transmittance for every pixel (render-wgpu's
// `clouds/spheres/sphere_pass.rs`; CPU twin: atmosphere-core's
// `clouds/spheres/composite.rs`, `spheres_only`, compared pixel by pixel in
// `tests/tests/gpu_cloud_spheres_parity.rs`). Pixel (x, y) of a W x H image looks along
// forward + (2 (x + 0.5) / W - 1) tan(fov / 2) aspect right
//         - (2 (y + 0.5) / H - 1) tan(fov / 2) up, normalised.

#import clouds/spheres/pixel_ray.wgsl

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= spheres.counts.zw) {
        return;
    }
    let along = spheres_along(spheres.camera_m.xyz, pixel_ray(id.xy), 3.0e38);
    textureStore(sphere_image, id.xy, along.cloud);
}
