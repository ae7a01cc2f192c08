// Entry passes: the sampling planes of Dobashi et al. 2002 section 4.2 with the q(u, v)
// table, walked per pixel: `vertex` and `fragment` (render-wgpu's
// `shafts/beams/qtable_pass.rs`, the default `gpu_raster_planes=false`). CPU twin:
// atmosphere-core's `beams/methods/qtable2002/mod.rs` (`radiance`).
//
// The same terms as the planes of `qtable.wgsl` drawn one by one, summed in one
// fragment per pixel and light: one instance per light covers the rectangle of the
// screen its bounding volume projects to (section 4.2.1), and each fragment walks the
// light's plane intervals k with their m_k samples (the main plane and its sub-planes,
// section 4.2.2, Eq. 10) in front of its ray's end. A plane's fragment outside the
// light's beam adds nothing, so the walk visits only the intervals where the ray is in
// the beam's convex hull: a spot's infinite pyramid over its cone, a parallel light's
// half-space (cut to its beam's rectangle where it has one); a point light's every
// interval (`qtable_walk_light.wgsl`).

#import shafts/beams/bindings.wgsl
#import shafts/beams/qtable_bindings.wgsl
#import shafts/beams/qtable_walk_light.wgsl
#import shafts/beams/screen_rectangle.wgsl

struct LightWalk {
    @builtin(position) position: vec4<f32>,
    // Light, intervals, the first interval's index in `interval_samples`, 0.
    @location(0) @interpolate(flat) walk: vec4<u32>,
    // The light's first plane's depth, m.
    @location(1) @interpolate(flat) first_depth_m: f32,
}

@vertex
fn vertex(
    @builtin(vertex_index) v: u32,
    @location(0) walk: vec4<u32>,
    @location(1) first_depth_m: f32,
    @location(2) bounds: vec4<f32>,
) -> LightWalk {
    var out: LightWalk;
    out.position = screen_rectangle_position(bounds, v);
    out.walk = walk;
    out.first_depth_m = first_depth_m;
    return out;
}

@fragment
fn fragment(in: LightWalk) -> @location(0) vec4<f32> {
    let pixel = in.position.xy;
    let t_end = textureLoad(ray_end, vec2<i32>(pixel), 0).x;
    let sum = walk_light(in.walk, in.first_depth_m, pixel_direction(pixel), t_end);
    return vec4<f32>(sum, 0.0);
}
