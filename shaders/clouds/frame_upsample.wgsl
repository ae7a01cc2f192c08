// Entry pass: a frame's reduced cloud march brought to full size by the segment each
// ray marched (render-wgpu's `clouds/frame_pass.rs`; CPU twin: atmosphere-core's
// `clouds/layer/segment_upsample.rs`, which states the rule). A pixel whose ray meets
// no cloud before the surface is clear; otherwise it interpolates bilinearly between the
// reduced rays that marched the same segment of the layer (`segment_taps.wgsl`); where
// they weigh too little (the edge of a mountain in front of or inside the cloud) it
// lists the pixel (`frame_list.wgsl`) for `frame_march_list.wgsl` to march.

#import clouds/frame_list.wgsl
#import clouds/segment_taps.wgsl

// The reduced march (`frame_march_reduced.wgsl`) and the segments it marched.
@group(0) @binding(7) var reduced_image: texture_2d<f32>;
@group(0) @binding(8) var reduced_segments: texture_2d<f32>;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = layer.sizes.zw;
    if any(id.xy >= size) {
        return;
    }
    let d = frame_direction(vec2<f32>(id.xy));
    let t = frame_segment(d, id.xy);
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    var front = vec4<f32>(0.0);
    if t.x < t.y {
        let taps = same_span_taps(reduced_image, reduced_segments, id.xy, size, t,
            layer.medium.x);
        if taps.weight < MIN_SAME_WEIGHT {
            list_pixel(id.xy);
            return;
        }
        result = taps.sum / taps.weight;
        if result.a < 1.0 {
            let o = layer.camera_m.xyz;
            front = vec4<f32>(normalize(o + d * t.x), t.x);
        }
    }
    textureStore(cloud_image, id.xy, result);
    textureStore(cloud_front, id.xy, front);
}
