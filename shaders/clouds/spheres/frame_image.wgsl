// Entry pass: the cloud spheres in a renderer frame (render-wgpu's
// `clouds/spheres/frame_spheres.rs`): each pixel's spheres ended on the frame's surface
// (terrain in front of the cloud hides it), blended with the layer's march by the
// spheres' weight of the hand-over (atmosphere-core's `clouds/spheres/handover.rs`),
// and where the ray enters the cloud, on which the sky model's second run ends its rays
// (as `clouds/frame_march.wgsl` writes it). The composite with the model is the layer's
// (`clouds/frame_composite.wgsl`). CPU twin: `spheres_only` ended at the surface, mixed
// with the layer's march, through `layer/composite.rs`'s `composite`.

#import clouds/spheres/pixel_ray.wgsl

// Where the sky model's second run ends its rays: xyz the outward vertical at the
// cloud's entry, w the entry distance, m; 0 where the pixel sees no cloud.
@group(0) @binding(5) var cloud_front: texture_storage_2d<rgba32float, write>;
// The frame's surface: xyz the normal, w the distance along the pixel's ray, m (0: none).
@group(0) @binding(6) var frame_surface: texture_2d<f32>;
// x: 1 when the frame has a surface (binding 6 holds it), else 0; y: the spheres'
// weight w in [0, 1], the layer's march (binding 8) taking 1 - w.
@group(0) @binding(7) var<uniform> frame_spheres: vec4<f32>;
// The layer's march of this frame (rgb radiance, a transmittance), read where w < 1.
@group(0) @binding(8) var layer_image: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= spheres.counts.zw) {
        return;
    }
    let o = spheres.camera_m.xyz;
    let d = pixel_ray(id.xy);
    var end = 3.0e38;
    if frame_spheres.x == 1.0 {
        let surface_m = textureLoad(frame_surface, id.xy, 0).w;
        if surface_m > 0.0 {
            end = surface_m;
        }
    }
    let along = spheres_along(o, d, end);
    let w = frame_spheres.y;
    var cloud = along.cloud;
    if w < 1.0 {
        cloud = mix(textureLoad(layer_image, id.xy, 0), cloud, w);
    }
    var front = vec4<f32>(0.0);
    if cloud.a < 1.0 && along.first_m > 0.0 {
        front = vec4<f32>(normalize(o + d * along.first_m), along.first_m);
    }
    textureStore(sphere_image, id.xy, cloud);
    textureStore(cloud_front, id.xy, front);
}
