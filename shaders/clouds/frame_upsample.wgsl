// Entry pass: a frame's reduced cloud march brought to full size by the segment each
// ray marched (render-wgpu's `clouds/frame_pass.rs`; CPU twin: atmosphere-core's
// `clouds/layer/segment_upsample.rs`, which states the rule). A pixel whose ray meets
// no cloud before the surface is clear; otherwise it interpolates bilinearly between the
// reduced rays that marched the same segment of the layer, within SEGMENT_TOLERANCE of
// its own end plus the length of optical depth DEPTH_TOLERANCE at the densest; where
// their weights sum to less than MIN_SAME_WEIGHT (the edge of a mountain in front of or
// inside the cloud) it lists the pixel (`frame_list.wgsl`) for `frame_march_list.wgsl` to march.

#import clouds/frame_list.wgsl

const SEGMENT_TOLERANCE: f32 = 0.25;
const DEPTH_TOLERANCE: f32 = 0.1;
const MIN_SAME_WEIGHT: f32 = 0.25;

// The reduced march (`frame_march_reduced.wgsl`) and the segments it marched.
@group(0) @binding(7) var reduced_image: texture_2d<f32>;
@group(0) @binding(8) var reduced_segments: texture_2d<f32>;

// The two reduced texels and the weight of the second along an axis.
fn axis_taps(x: u32, size: u32, reduced_size: u32) -> vec3<f32> {
    let u = clamp((f32(x) + 0.5) * f32(reduced_size) / f32(size) - 0.5, 0.0,
        f32(reduced_size - 1u));
    let i0 = floor(u);
    return vec3<f32>(i0, min(i0 + 1.0, f32(reduced_size - 1u)), u - i0);
}

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
        let low = textureDimensions(reduced_image);
        let tx = axis_taps(id.x, size.x, low.x);
        let ty = axis_taps(id.y, size.y, low.y);
        let allowed = SEGMENT_TOLERANCE * t.y + DEPTH_TOLERANCE / layer.medium.x;
        var sum = vec4<f32>(0.0);
        var weight = 0.0;
        for (var k = 0u; k < 4u; k++) {
            let second = vec2<bool>((k & 1u) == 1u, (k & 2u) == 2u);
            let texel = vec2<u32>(u32(select(tx.x, tx.y, second.x)),
                u32(select(ty.x, ty.y, second.y)));
            let w = select(1.0 - tx.z, tx.z, second.x) * select(1.0 - ty.z, ty.z, second.y);
            let s = textureLoad(reduced_segments, texel, 0).xy;
            let same = s.y > 0.0 && abs(s.x - t.x) + abs(s.y - t.y) <= allowed;
            if w > 0.0 && same {
                weight += w;
                sum += w * textureLoad(reduced_image, texel, 0);
            }
        }
        if weight < MIN_SAME_WEIGHT {
            list_pixel(id.xy);
            return;
        }
        result = sum / weight;
        if result.a < 1.0 {
            let o = layer.camera_m.xyz;
            front = vec4<f32>(normalize(o + d * t.x), t.x);
        }
    }
    textureStore(cloud_image, id.xy, result);
    textureStore(cloud_front, id.xy, front);
}
