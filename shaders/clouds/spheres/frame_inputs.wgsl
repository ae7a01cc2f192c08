// Library: what the cloud spheres' passes of a renderer frame read and write besides
// the spheres' own bindings (render-wgpu's `clouds/spheres/frame_spheres.rs`): the
// frame's surface, the hand-over's weight and the layer's march it blends with, where
// each ray enters the cloud; and the ray's span of the layer that the reduced passes
// compare (`frame_reduced.wgsl`, `frame_upsample.wgsl`; CPU twin: atmosphere-core's
// `clouds/spheres/reduced.rs`).

#import clouds/spheres/pixel_ray.wgsl

// Where the sky model's second run ends its rays: xyz the outward vertical at the
// cloud's entry, w the entry distance, m; 0 where the pixel sees no cloud.
@group(0) @binding(25) var cloud_front: texture_storage_2d<rgba32float, write>;
// The frame's surface: xyz the normal, w the distance along the pixel's ray, m (0: none).
@group(0) @binding(26) var frame_surface: texture_2d<f32>;
// x: 1 when the frame has a surface (binding 26 holds it), else 0; y: the spheres'
// weight w in [0, 1], the layer's march (binding 28) taking 1 - w; z: the resolution
// divisor; w: the layer's densest extinction, m^-1.
@group(0) @binding(27) var<uniform> frame_spheres: vec4<f32>;
// The layer's march of this frame (rgb radiance, a transmittance), read where w < 1.
@group(0) @binding(28) var layer_image: texture_2d<f32>;

// Where the ray of full pixel `px` ends: on the frame's surface, else far away.
fn surface_end(px: vec2<u32>) -> f32 {
    if frame_spheres.x == 1.0 {
        let surface_m = textureLoad(frame_surface, px, 0).w;
        if surface_m > 0.0 {
            return surface_m;
        }
    }
    return 3.0e38;
}

// The stretch (t0, t1) of the ray from o along the unit d inside the layer's top sphere,
// t0 clamped to o, ended at `end_m` and on the ground; t0 >= t1 where it is empty
// (`reduced.rs`'s `span`).
fn sphere_span(o: vec3<f32>, d: vec3<f32>, end_m: f32) -> vec2<f32> {
    let r = length(o);
    let mu = clamp(dot(o, d) / r, -1.0, 1.0);
    let top = sphere_roots(r, mu, spheres.radii_m.y + spheres.radii_m.z);
    if top.x > top.y {
        return vec2<f32>(1.0, 0.0);
    }
    var t1 = min(top.y, end_m);
    let ground = sphere_roots(r, mu, spheres.radii_m.x);
    if ground.x <= ground.y && ground.x >= 0.0 && mu < 0.0 {
        t1 = min(t1, ground.x);
    }
    return vec2<f32>(max(top.x, 0.0), t1);
}

// The cloud of full pixel `px`: the spheres' `spheres_cloud` blended with the layer's
// march by the hand-over's weight.
fn frame_cloud(px: vec2<u32>, spheres_cloud: vec4<f32>) -> vec4<f32> {
    let w = frame_spheres.y;
    if w < 1.0 {
        return mix(textureLoad(layer_image, px, 0), spheres_cloud, w);
    }
    return spheres_cloud;
}

// Where the ray enters `cloud` (the spheres' first crossing `first_m`), m; 0 where it
// sees none or the camera is inside the layer (`first_m` not positive).
fn entry_distance(cloud: vec4<f32>, first_m: f32) -> f32 {
    return select(0.0, first_m, cloud.a < 1.0 && first_m > 0.0);
}

// Writes full pixel `px`, whose ray runs along `d`: the spheres' `cloud` blended with the
// layer's march (`frame_cloud`), and where the ray enters the cloud (`entry_distance`).
fn store_frame_pixel(px: vec2<u32>, d: vec3<f32>, spheres_cloud: vec4<f32>, first_m: f32) {
    let cloud = frame_cloud(px, spheres_cloud);
    let entry_m = entry_distance(cloud, first_m);
    var front = vec4<f32>(0.0);
    if entry_m > 0.0 {
        front = vec4<f32>(normalize(spheres.camera_m.xyz + d * entry_m), entry_m);
    }
    textureStore(sphere_image, px, cloud);
    textureStore(cloud_front, px, front);
}
