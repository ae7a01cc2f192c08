// Entry passes: the q(u, v) table's walk at reduced resolution brought to the frame's
// size, `vertex` and `fragment`, then `walk_vertex` and `walk_fragment` (render-wgpu's
// `shafts/beams/qtable_upsample.rs`, the setting `resolution_divisor` above 1). CPU twin: atmosphere-core's
// `beams/methods/qtable2002/upsample.rs` (`upsampled`).
//
// First one triangle over the frame (`fragment`): each pixel reads the four reduced
// pixels about it (the reduced walk's radiance and ray ends, group 1 bindings 4 and 5)
// and takes their bilinear mean where their ray ends and radiances agree within the
// tolerances of `qtable.upsample`, depth 0; elsewhere (an occluder's outline, a beam's
// or a shadow's edge between them) it adds nothing and marks the pixel with depth 1. Then each light's rectangle
// (`walk_vertex`, `walk_fragment`, drawn at depth 0.5 and tested against the marks)
// walks the light's planes at the marked pixels alone, along their own ray ended where
// it meets an occluder: one light per fragment, as the walk itself draws them. Where the
// scene has glTF meshes (`qtable.upsample.z` 1) the frame's own ray ends, traced for
// every pixel before (binding 1), give that end: the meshes' BVH traversal and the walk
// in one invocation came out short of light on lavapipe (docs/beams/qtable2002.md);
// without meshes the marked pixels trace their end themselves (binding 1 then holds the
// reduced ends too).

#import shafts/beams/bindings.wgsl
#import shafts/beams/occluders.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/qtable_walk_light.wgsl
#import shafts/beams/screen_rectangle.wgsl

// The reduced walk's radiance (xyz) and its rays' ends, m.
@group(1) @binding(4) var reduced_radiance: texture_2d<f32>;
@group(1) @binding(5) var reduced_ray_end: texture_2d<f32>;

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

struct LightWalk {
    @builtin(position) position: vec4<f32>,
    // Light, intervals, the first interval's index in `interval_samples`, 0.
    @location(0) @interpolate(flat) walk: vec4<u32>,
    // The light's first plane's depth, m.
    @location(1) @interpolate(flat) first_depth_m: f32,
}

// One light's rectangle (`qtable_walk.wgsl`'s instances) at depth 0.5, tested against
// the marks.
@vertex
fn walk_vertex(
    @builtin(vertex_index) v: u32,
    @location(0) walk: vec4<u32>,
    @location(1) first_depth_m: f32,
    @location(2) bounds: vec4<f32>,
) -> LightWalk {
    var out: LightWalk;
    out.position = screen_rectangle_position(bounds, v);
    out.position.z = 0.5;
    out.walk = walk;
    out.first_depth_m = first_depth_m;
    return out;
}

// One light's walk along a marked pixel's own ray: nothing where the ray misses the
// light's beam (as the walk finds), else ended where the ray meets an occluder.
@fragment
fn walk_fragment(in: LightWalk) -> @location(0) vec4<f32> {
    let dir = pixel_direction(in.position.xy);
    if qtable.upsample.z > 0.5 {
        let t_end = textureLoad(ray_end, vec2<i32>(in.position.xy), 0).x;
        return vec4<f32>(walk_light(in.walk, in.first_depth_m, dir, t_end), 0.0);
    }
    let limit = params.camera_forward.w;
    let span = beam_span(lights[in.walk.x], dir, limit);
    if span.x > span.y {
        return vec4<f32>(0.0);
    }
    let hit = nearest_occluder(vec3<f32>(0.0), dir, limit);
    let t_end = select(limit, hit, hit != MISS);
    return vec4<f32>(walk_light(in.walk, in.first_depth_m, dir, t_end), 0.0);
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
        let end = textureLoad(reduced_ray_end, taps[k], 0).x;
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
