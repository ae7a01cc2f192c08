// Entry passes: the q(u, v) table's walk at reduced resolution brought to the frame's
// size, `vertex` and `fragment` (render-wgpu's `shafts/beams/qtable_upsample.rs`, the
// setting `resolution_divisor` above 1). CPU twin: atmosphere-core's
// `beams/methods/qtable2002/upsample.rs` (`upsampled`).
//
// One triangle covers the frame, twice. First (`fragment`) each pixel reads the four
// reduced pixels about it (the reduced walk's radiance and ray ends, group 1 bindings 4
// and 1) and takes their bilinear mean where their ray ends and radiances agree within
// the tolerances of `qtable.upsample` and some light is among them, depth 0; elsewhere
// (an occluder's outline, a beam's or a shadow's edge or a beam's thin tip between
// them) it adds nothing and marks the pixel with depth 1. Then (`walk_fragment`, drawn
// at depth 0.5 and tested against the marks) the marked pixels alone walk every light's
// planes along their own ray, ended where it meets an occluder.

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/qtable_walk_light.wgsl

// One light's walk: light, intervals (0: no light), first interval's index in
// `interval_samples`, 0;
// its part of the screen [x0, y0, x1, y1] in normalised device coordinates; x the
// first plane's depth, m.
struct WalkEntry {
    walk: vec4<u32>,
    bounds: vec4<f32>,
    first_depth_m: vec4<f32>,
}

// The reduced walk's radiance (xyz).
@group(1) @binding(4) var reduced_radiance: texture_2d<f32>;
// One per light with planes, then zeroed walks; as many as a scene's lights may be.
const MAX_WALKS: u32 = 64u;
@group(1) @binding(5) var<uniform> walks: array<WalkEntry, MAX_WALKS>;

@vertex
fn vertex(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((v << 1u) & 2u), f32(v & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.5, 1.0);
}

struct Interpolated {
    @location(0) radiance: vec4<f32>,
    // 1: the pixel is to be walked.
    @builtin(frag_depth) mark: f32,
}

// Every light's walk along the pixel's own ray: nothing where the ray meets no light's
// beam (as the walk would find), else ended where it meets an occluder.
fn walked(pixel: vec2<f32>) -> vec3<f32> {
    let dir = pixel_direction(pixel);
    let limit = params.camera_forward.w;
    let size = vec2<f32>(params.size_steps_lights.xy);
    let ndc = vec2<f32>(2.0 * pixel.x / size.x - 1.0, 1.0 - 2.0 * pixel.y / size.y);
    var reached = false;
    for (var l = 0u; l < MAX_WALKS && walks[l].walk.y > 0u; l++) {
        let entry = walks[l];
        if in_bounds(entry, ndc) {
            let span = beam_span(lights[entry.walk.x], dir, limit);
            reached = reached || span.x <= span.y;
        }
    }
    if !reached {
        return vec3<f32>(0.0);
    }
    let hit = nearest_occluder(vec3<f32>(0.0), dir, limit);
    let t_end = select(limit, hit, hit != MISS);
    var sum = vec3<f32>(0.0);
    for (var l = 0u; l < MAX_WALKS && walks[l].walk.y > 0u; l++) {
        let entry = walks[l];
        if in_bounds(entry, ndc) {
            sum += walk_light(entry.walk, entry.first_depth_m.x, dir, t_end);
        }
    }
    return sum;
}

// Whether the light of `entry` has planes over the point `ndc` of the screen.
fn in_bounds(entry: WalkEntry, ndc: vec2<f32>) -> bool {
    let b = entry.bounds;
    return all(ndc >= b.xy) && all(ndc <= b.zw);
}

@fragment
fn walk_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(walked(position.xy), 0.0);
}

@fragment
fn fragment(@builtin(position) position: vec4<f32>) -> Interpolated {
    let pixel = position.xy;
    let full = vec2<f32>(params.size_steps_lights.xy);
    let reduced = vec2<f32>(textureDimensions(reduced_radiance));
    let uv = clamp(pixel * reduced / full - 0.5, vec2<f32>(0.0), reduced - 1.0);
    let low = floor(uv);
    let f = uv - low;
    let i0 = vec2<i32>(low);
    let i1 = min(i0 + 1, vec2<i32>(reduced) - 1);
    let taps = array<vec2<i32>, 4>(i0, vec2<i32>(i1.x, i0.y), vec2<i32>(i0.x, i1.y), i1);
    let weights = vec4<f32>((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    var lo = vec3<f32>(3.4e38);
    var hi = vec3<f32>(-3.4e38);
    var near = 3.4e38;
    var far = -3.4e38;
    var mean = vec3<f32>(0.0);
    for (var k = 0u; k < 4u; k++) {
        let radiance = textureLoad(reduced_radiance, taps[k], 0).xyz;
        let end = textureLoad(ray_end, taps[k], 0).x;
        lo = min(lo, radiance);
        hi = max(hi, radiance);
        near = min(near, end);
        far = max(far, end);
        mean += weights[k] * radiance;
    }
    let agree = far - near <= qtable.upsample.y * near
        && all(hi - lo <= qtable.upsample.x * hi);
    var out: Interpolated;
    out.radiance = select(vec4<f32>(0.0), vec4<f32>(mean, 0.0), agree);
    out.mark = select(1.0, 0.0, agree);
    return out;
}
