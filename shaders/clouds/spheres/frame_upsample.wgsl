// Entry pass: a frame's reduced cloud spheres (`frame_reduced.wgsl`) brought to full size
// by the span each ray crossed (render-wgpu's `clouds/spheres/frame_spheres.rs`; CPU
// twin: atmosphere-core's `clouds/spheres/reduced.rs`, with the rule of
// `clouds/layer/segment_upsample.rs`). A pixel whose ray has no span of the layer is
// clear; otherwise it interpolates bilinearly between the reduced rays whose span is
// its own (`clouds/segment_taps.wgsl`); where they weigh too little (the planet's limb,
// the edge of terrain in front of the cloud) it is shaded itself.
// Then it is blended with the layer's march and written as `frame_image.wgsl` writes it.

#import clouds/spheres/frame_inputs.wgsl
#import clouds/segment_taps.wgsl

// The reduced spheres and the spans their rays crossed.
@group(0) @binding(9) var reduced_image: texture_2d<f32>;
@group(0) @binding(10) var reduced_segments: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = spheres.counts.zw;
    if any(id.xy >= size) {
        return;
    }
    let o = spheres.camera_m.xyz;
    let d = pixel_ray(id.xy);
    let end = surface_end(id.xy);
    let t = sphere_span(o, d, end);
    var cloud = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var first = -1.0;
    if t.x < t.y {
        let taps = same_span_taps(reduced_image, reduced_segments, id.xy, size, t,
            frame_spheres.w);
        if taps.weight >= MIN_SAME_WEIGHT {
            cloud = taps.sum / taps.weight;
            first = t.x;
        } else {
            let along = spheres_along(o, d, end);
            cloud = along.cloud;
            first = along.first_m;
        }
    }
    store_frame_pixel(id.xy, d, cloud, first);
}
