// Library: the unit direction through pixel (x, y) of the spheres' W x H image,
// forward + (2 (x + 0.5) / W - 1) tan(fov / 2) aspect right
//         - (2 (y + 0.5) / H - 1) tan(fov / 2) up, normalised (render-wgpu's
// `LayerCamera::pixel_direction`, the frame's camera), at a fractional pixel too (pixel
// x's centre at x).

#import clouds/spheres/shade.wgsl

fn pixel_ray_at(pixel: vec2<f32>) -> vec3<f32> {
    let size = spheres.counts.zw;
    let tan_half = spheres.camera_m.w;
    let aspect = f32(size.x) / f32(size.y);
    let sx = (2.0 * (pixel.x + 0.5) / f32(size.x) - 1.0) * tan_half * aspect;
    let sy = (2.0 * (pixel.y + 0.5) / f32(size.y) - 1.0) * tan_half;
    return normalize(spheres.forward.xyz + sx * spheres.right.xyz - sy * spheres.up.xyz);
}

fn pixel_ray(pixel: vec2<u32>) -> vec3<f32> {
    return pixel_ray_at(vec2<f32>(pixel));
}
