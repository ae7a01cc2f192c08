// Library: the walk of one light's plane intervals along one view ray, the sum of the
// terms of Dobashi et al. 2002 section 4.2 (Eq. 6, 10) that its planes and sub-planes
// would draw at that pixel: used by `qtable_walk.wgsl` (every pixel of the light's
// rectangle) and `qtable_upsample.wgsl` (the pixels a reduced walk cannot interpolate).
// CPU twin: atmosphere-core's `beams/methods/qtable2002/mod.rs` (`Qtable2002::walk`).
//
// A sample outside the light's beam adds nothing, so the walk visits only the intervals
// where the ray is in the beam's convex hull: a spot's infinite pyramid over its cone,
// a parallel light's half-space (cut to its beam's rectangle where it has one); a point
// light's every interval. f_l (Eq. 7, `q_table.wgsl`) is read once per interval instead
// of once per sample, what the ray's reads share (the table's rows at the light's
// distance from the ray) found once per ray. With `weighted_samples` each sample is
// weighted by g at it (`sample_weights.wgsl`); with `subplanes_per_ray` each interval's
// m comes from this ray's own f_l instead of the centre ray's m_k (both not the paper's).

#import shafts/beams/bindings.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/plane_light.wgsl
#import shafts/beams/q_table.wgsl
#import shafts/beams/sample_weights.wgsl

// m_k of every light's intervals, the lights one after another, row by row.
@group(1) @binding(3) var interval_samples: texture_2d<u32>;

// The beam's hull widened by this share of its half-width: a sample the beam test of
// `lights.wgsl` finds inside in f32 is inside the widened hull.
const HULL_MARGIN: f32 = 1e-3;

// Clips [span.x, span.y] of the ray from `origin` along `dir` (the light's frame) to the
// half-space dot(normal, p) <= offset (Cyrus and Beck 1978).
fn clip(span: vec2<f32>, normal: vec3<f32>, offset: f32, origin: vec3<f32>, dir: vec3<f32>) -> vec2<f32> {
    let start = dot(normal, origin) - offset;
    let rate = dot(normal, dir);
    if rate == 0.0 {
        return select(span, vec2<f32>(1.0, 0.0), start > 0.0);
    }
    let crossing = -start / rate;
    if rate < 0.0 {
        return vec2<f32>(max(span.x, crossing), span.y);
    }
    return vec2<f32>(span.x, min(span.y, crossing));
}

// The part of [0, `t_end`] of the camera's ray along `dir` where `light`'s beam can be.
fn beam_span(light: BeamLight, dir: vec3<f32>, t_end: f32) -> vec2<f32> {
    var span = vec2<f32>(0.0, t_end);
    if light.kind == 0u {
        return span;
    }
    // The camera and the ray in the light's frame (positions are camera-relative).
    let origin = light_frame_local(light, -light.position.xyz);
    let d = light_frame_local(light, dir);
    if light.kind == 1u {
        let tan_cone = light.beam.y * (1.0 + HULL_MARGIN);
        span = clip(span, vec3<f32>(1.0, 0.0, -tan_cone), 0.0, origin, d);
        span = clip(span, vec3<f32>(-1.0, 0.0, -tan_cone), 0.0, origin, d);
        span = clip(span, vec3<f32>(0.0, 1.0, -tan_cone), 0.0, origin, d);
        return clip(span, vec3<f32>(0.0, -1.0, -tan_cone), 0.0, origin, d);
    }
    span = clip(span, vec3<f32>(0.0, 0.0, -1.0), 0.0, origin, d);
    if light.beam.z > 0.0 {
        let half = light.beam.xy * (1.0 + HULL_MARGIN);
        span = clip(span, vec3<f32>(1.0, 0.0, 0.0), half.x, origin, d);
        span = clip(span, vec3<f32>(-1.0, 0.0, 0.0), half.x, origin, d);
        span = clip(span, vec3<f32>(0.0, 1.0, 0.0), half.y, origin, d);
        span = clip(span, vec3<f32>(0.0, -1.0, 0.0), half.y, origin, d);
    }
    return span;
}

// m_k of the interval at `index` of `interval_samples`.
fn samples_of(index: u32) -> u32 {
    let width = textureDimensions(interval_samples).x;
    return textureLoad(interval_samples, vec2<u32>(index % width, index / width), 0).x;
}

// m of an interval whose largest f_l over the wavelengths is `f` on a ray counting its
// own sub-planes: f over the f_l one sample stands for (`unit`; 0: the most samples
// everywhere), at least 1 and at most `most` (`LightPlanes::samples_for`).
fn samples_for(f: f32, unit: f32, most: u32) -> u32 {
    if unit <= 0.0 {
        return most;
    }
    return u32(clamp(floor(f / unit), 1.0, f32(most)));
}

// The light `walk.x`'s sum along the camera's ray along the unit `dir` ending at
// `t_end`: its `walk.y` intervals from depth `first_depth_m` along the view, their m_k
// from `interval_samples` at index `walk.z` on (or counted on this ray from the f_l one
// sample stands for, `walk.w`'s bits).
fn walk_light(walk: vec4<u32>, first_depth_m: f32, dir: vec3<f32>, t_end: f32) -> vec3<f32> {
    let cos_forward = dot(dir, params.camera_forward.xyz);
    let light = lights[walk.x];
    let span = beam_span(light, dir, t_end);
    let intervals = walk.y;
    if span.x > span.y || intervals == 0u {
        return vec3<f32>(0.0);
    }
    let dt = qtable.interval_m.x;
    let weighted = qtable.interval_m.y > 0.5;
    let most = u32(qtable.interval_m.z);
    let per_ray = qtable.interval_m.w > 0.5;
    let unit = bitcast<f32>(walk.w);
    let dt_ray = dt / cos_forward;
    // The intervals whose depths along the view meet the beam's part of the ray.
    let first = (span.x * cos_forward - first_depth_m) / dt;
    let last = (span.y * cos_forward - first_depth_m) / dt;
    let count = f32(intervals);
    let k_first = u32(clamp(floor(first), 0.0, count));
    let k_end = u32(clamp(floor(last) + 1.0, 0.0, count));
    let ray = ray_table(light, dir);
    var sum = vec3<f32>(0.0);
    for (var k = k_first; k < k_end; k++) {
        let t_k = (first_depth_m + f32(k) * dt) / cos_forward;
        // A plane within a thousandth of the ray's length of its end is left out, as
        // on the CPU, and so are all behind it.
        if t_k >= t_end * (1.0 - 1e-3) {
            break;
        }
        let covered = min(dt_ray, t_end - t_k);
        var interval_f_l = vec3<f32>(0.0);
        var m = samples_of(walk.z + k);
        if per_ray {
            interval_f_l = f_l_on_ray(light, ray, dir, t_k, covered);
            m = samples_for(max(interval_f_l.x, max(interval_f_l.y, interval_f_l.z)), unit, most);
        }
        let spacing = dt_ray / f32(m);
        // The sliver by the end's surface is left out for sub-planes as for planes.
        let visible = clamp(u32(ceil((t_end * (1.0 - 1e-3) - t_k) / spacing)), 1u, m);
        var f_h = vec3<f32>(0.0);
        var weight_sum = vec3<f32>(0.0);
        var base = -1.0;
        var lit = false;
        for (var j = 0u; j < visible; j++) {
            let t = t_k + f32(j) * spacing;
            var weight = vec3<f32>(1.0);
            if weighted {
                let g = smooth_factor(light, dir, t, base);
                weight = g.xyz;
                base = select(base, g.w, base < 0.0);
            }
            weight_sum += weight;
            let at = plane_light(light, dir * t);
            f_h += weight * at.light;
            lit = lit || at.lit;
        }
        if lit {
            if !per_ray {
                interval_f_l = f_l_on_ray(light, ray, dir, t_k, covered);
            }
            sum += select(vec3<f32>(0.0), f_h / weight_sum, weight_sum > vec3<f32>(0.0)) * interval_f_l;
        }
    }
    return sum;
}
