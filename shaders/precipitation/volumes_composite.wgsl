// Entry pass: rain and ice volumes composited over a frame's pixels (render-wgpu's
// `precipitation/volumes_pass.rs`), L = A L_full + B with the terms A, B marched for
// the pixel itself (`volumes_march.wgsl`) or, at a divisor N above 1, the bilinear
// mean of the up to four reduced pixels around it (`volumes_reduced.wgsl`) whose spans
// (nearest entry, length inside) agree with its own within SPAN_TOLERANCE,
// renormalised; a pixel where none agrees is marched itself. CPU twins: atmosphere-core's
// `hydrometeors/render.rs` and `hydrometeors/reduced.rs`.

#import precipitation/volumes_march.wgsl

const SPAN_TOLERANCE: f32 = 0.1;

@group(0) @binding(4) var full_image: texture_2d<f32>;
@group(0) @binding(6) var hdr: texture_storage_2d<rgba16float, write>;
// The reduced pass's images (read only at a divisor above 1).
@group(0) @binding(9) var reduced_a: texture_2d<f32>;
@group(0) @binding(10) var reduced_b: texture_2d<f32>;

// Whether a tap of spans `tap` may stand for a pixel of spans `own`.
fn spans_agree(own: vec2<f32>, tap: vec2<f32>) -> bool {
    if own.y <= 0.0 || tap.y <= 0.0 {
        return own.y <= 0.0 && tap.y <= 0.0;
    }
    let tolerance = SPAN_TOLERANCE * max(abs(own), abs(tap));
    return all(abs(own - tap) <= tolerance);
}

// Over the rectangle of pixels the volumes may cover, from pixel `volumes.count.zw`.
@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let px = id.xy + volumes.count.zw;
    if any(px >= frame.size_px.xy) {
        return;
    }
    let d = pixel_direction(px);
    let max_t = max_distance(px);
    var terms = Terms(vec3<f32>(1.0), vec3<f32>(0.0));
    var weight = 0.0;
    let n = volumes.reduction.x;
    if n > 1u {
        let own = pixel_spans(d, max_t);
        let base = px / n;
        let f = vec2<f32>(px % n) / f32(n);
        var sum_a = vec3<f32>(0.0);
        var sum_b = vec3<f32>(0.0);
        for (var k = 0u; k < 4u; k++) {
            let step = vec2<u32>(k & 1u, k >> 1u);
            let w = select(1.0 - f.x, f.x, step.x == 1u) * select(1.0 - f.y, f.y, step.y == 1u);
            if w <= 0.0 {
                continue;
            }
            let a = textureLoad(reduced_a, base + step, 0);
            let b = textureLoad(reduced_b, base + step, 0);
            if spans_agree(own, vec2<f32>(a.w, b.w)) {
                weight += w;
                sum_a += w * a.rgb;
                sum_b += w * b.rgb;
            }
        }
        if weight > 0.0 {
            terms = Terms(sum_a / weight, sum_b / weight);
        }
    }
    if n <= 1u || weight <= 0.0 {
        terms = pixel_terms(d, max_t);
    }
    let out = terms.times_full * textureLoad(full_image, px, 0).rgb + terms.added;
    textureStore(hdr, px, vec4<f32>(min(out, vec3<f32>(F16_MAX)), 1.0));
}
