// Library: a frame's reduced cloud march brought to one full-size pixel by the segment
// each ray marched (CPU twin: atmosphere-core's `clouds/layer/segment_upsample.rs`,
// which states the rule). A pixel whose ray meets no cloud before the surface is clear;
// otherwise it interpolates bilinearly between the reduced rays that marched the same
// segment of the layer (`segment_taps.wgsl`); where they weigh too little (the edge of a
// mountain in front of or inside the cloud) the pixel is listed (`frame_list.wgsl`) for
// a pass that marches the list. Used by `frame_upsample.wgsl`.

#import clouds/frame_list.wgsl
#import clouds/segment_taps.wgsl

// The reduced march (`frame_march_reduced.wgsl`) and the segments it marched.
@group(0) @binding(7) var reduced_image: texture_2d<f32>;
@group(0) @binding(8) var reduced_segments: texture_2d<f32>;

// Pixel `px` interpolated, or listed to be marched (false).
fn upsample_pixel(px: vec2<u32>, out: ptr<function, PixelCloud>) -> bool {
    let d = frame_direction(vec2<f32>(px));
    let t = frame_segment(d, px);
    *out = CLEAR_PIXEL;
    if t.x < t.y {
        let taps = same_span_taps(reduced_image, reduced_segments, px, layer.sizes.zw, t,
            layer.medium.x);
        if taps.weight < MIN_SAME_WEIGHT {
            list_pixel(px);
            return false;
        }
        *out = pixel_cloud(taps.sum / taps.weight, d, t.x);
    }
    return true;
}
