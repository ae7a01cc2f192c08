// The four bilinear taps of a reduced cloud image about a full-size pixel, kept where the
// reduced ray crossed the same span of the layer as the pixel's (the rule of
// atmosphere-core's `clouds/layer/segment_upsample.rs`): within SEGMENT_TOLERANCE of the
// span's end plus the length of optical depth DEPTH_TOLERANCE at the densest. Where the
// kept taps weigh less than MIN_SAME_WEIGHT the caller shades the pixel itself. Used by
// the layer's upsample (`frame_upsample.wgsl`) and the spheres'
// (`spheres/frame_upsample.wgsl`).

const SEGMENT_TOLERANCE: f32 = 0.25;
const DEPTH_TOLERANCE: f32 = 0.1;
const MIN_SAME_WEIGHT: f32 = 0.25;

// The two reduced texels and the weight of the second along an axis.
fn axis_taps(x: u32, size: u32, reduced_size: u32) -> vec3<f32> {
    let u = clamp((f32(x) + 0.5) * f32(reduced_size) / f32(size) - 0.5, 0.0,
        f32(reduced_size - 1u));
    let i0 = floor(u);
    return vec3<f32>(i0, min(i0 + 1.0, f32(reduced_size - 1u)), u - i0);
}

// The kept taps' weighted sum and their weight.
struct SameSpanTaps {
    sum: vec4<f32>,
    weight: f32,
}

// The taps of `image` (its spans in `spans`: start and end, m) about `pixel` of a
// frame of `size` whose ray crossed the span `t`, in a layer of densest extinction
// `densest` (m^-1).
fn same_span_taps(image: texture_2d<f32>, spans: texture_2d<f32>, pixel: vec2<u32>,
    size: vec2<u32>, t: vec2<f32>, densest: f32) -> SameSpanTaps {
    let low = textureDimensions(image);
    let tx = axis_taps(pixel.x, size.x, low.x);
    let ty = axis_taps(pixel.y, size.y, low.y);
    let allowed = SEGMENT_TOLERANCE * t.y + DEPTH_TOLERANCE / densest;
    var taps = SameSpanTaps(vec4<f32>(0.0), 0.0);
    for (var k = 0u; k < 4u; k++) {
        let second = vec2<bool>((k & 1u) == 1u, (k & 2u) == 2u);
        let texel = vec2<u32>(u32(select(tx.x, tx.y, second.x)),
            u32(select(ty.x, ty.y, second.y)));
        let w = select(1.0 - tx.z, tx.z, second.x) * select(1.0 - ty.z, ty.z, second.y);
        let s = textureLoad(spans, texel, 0).xy;
        let same = s.y > 0.0 && abs(s.x - t.x) + abs(s.y - t.y) <= allowed;
        if w > 0.0 && same {
            taps.weight += w;
            taps.sum += w * textureLoad(image, texel, 0);
        }
    }
    return taps;
}
