// Entry pass: a frame's reduced cloud spheres (`frame_reduced.wgsl`) brought to full size
// by the span each ray crossed (render-wgpu's `clouds/spheres/frame_spheres.rs`; CPU
// twin: atmosphere-core's `clouds/spheres/reduced.rs`, with the rule of
// `clouds/layer/segment_upsample.rs`). A pixel whose ray has no span of the layer is
// clear; otherwise it interpolates bilinearly between the reduced rays whose span is
// its own, within SEGMENT_TOLERANCE of its own end plus the length of optical depth
// DEPTH_TOLERANCE at the densest; where their weights sum to less than MIN_SAME_WEIGHT
// (the planet's limb, the edge of terrain in front of the cloud) it is shaded itself.
// Then it is blended with the layer's march and written as `frame_image.wgsl` writes it.

#import clouds/spheres/frame_inputs.wgsl

const SEGMENT_TOLERANCE: f32 = 0.25;
const DEPTH_TOLERANCE: f32 = 0.1;
const MIN_SAME_WEIGHT: f32 = 0.25;

// The reduced spheres and the spans their rays crossed.
@group(0) @binding(9) var reduced_image: texture_2d<f32>;
@group(0) @binding(10) var reduced_segments: texture_2d<f32>;

// The two reduced texels and the weight of the second along an axis.
fn axis_taps(x: u32, size: u32, reduced_size: u32) -> vec3<f32> {
    let u = clamp((f32(x) + 0.5) * f32(reduced_size) / f32(size) - 0.5, 0.0,
        f32(reduced_size - 1u));
    let i0 = floor(u);
    return vec3<f32>(i0, min(i0 + 1.0, f32(reduced_size - 1u)), u - i0);
}

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
        let low = textureDimensions(reduced_image);
        let tx = axis_taps(id.x, size.x, low.x);
        let ty = axis_taps(id.y, size.y, low.y);
        let allowed = SEGMENT_TOLERANCE * t.y + DEPTH_TOLERANCE / frame_spheres.w;
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
        if weight >= MIN_SAME_WEIGHT {
            cloud = sum / weight;
            first = t.x;
        } else {
            let along = spheres_along(o, d, end);
            cloud = along.cloud;
            first = along.first_m;
        }
    }
    store_frame_pixel(id.xy, d, cloud, first);
}
