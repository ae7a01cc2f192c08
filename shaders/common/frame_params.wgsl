// Library: the camera and sun of a frame (bound at 1 by every pixel pass), and the view
// ray of a pixel clipped to the atmosphere, relative to the camera (docs/rendering.md,
// "Camera-relative rendering"). Rust twin of the uniform: render-wgpu's
// `frame/uniform.rs`. CPU twins: atmosphere-core's `optics/view_segment.rs` (the
// clipping) and `models/sky_model.rs` (`ViewRay`). No paper: every model's view ray.

#import common/atmosphere_params.wgsl
#import common/sun_disk.wgsl
#import common/f16_max.wgsl

struct FrameParams {
    // xyz: camera position relative to the planet's centre (f32), m; w: its radius.
    camera_m: vec4<f32>,
    // x: r^2 - bottom^2 of the camera, computed in f64; y: 1 above the atmosphere.
    camera_height: vec4<f32>,
    // The camera's axes; right and up scaled by half the image extent at unit distance.
    right: vec4<f32>,
    up: vec4<f32>,
    forward: vec4<f32>,
    // xyz: unit vector towards the sun; w: its angular radius, rad.
    sun_direction: vec4<f32>,
    // xyz per channel: the sun disk's radiance at its centre and its limb-darkening
    // exponent (`common/sun_disk.wgsl`).
    sun_centre_radiance: vec4<f32>,
    sun_limb_exponent: vec4<f32>,
    size_px: vec4<u32>,
    // x: the sea's mean square slope (`common/sea_surface.wgsl`); y: water's refractive
    // index.
    sea: vec4<f32>,
}

@group(0) @binding(1) var<uniform> frame: FrameParams;

// What a model answers for a view ray: the radiance scattered and reflected towards the
// camera (sun disk excluded) and the ray's transmittance, per channel.
struct Radiance {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
    // False when the ray ends on the ground or on a surface.
    reaches_space: bool,
    // The planet-centred point where the ray ends, m (`segment_end`).
    end: vec3<f32>,
}

// The answer for the ray along unit `direction` before any light is added: no radiance,
// transmittance 1, ending where its segment `s` ends.
fn radiance_of_empty(s: Segment, direction: vec3<f32>) -> Radiance {
    return Radiance(vec3<f32>(0.0), vec3<f32>(1.0), s.end == END_SPACE,
        segment_end(s, direction));
}

// The HDR target's value for a pixel looking along `direction` with the model's answer
// `r`: the radiance, plus the transmitted sun disk where the ray reaches space, clamped
// to the largest finite f16; alpha 1.
fn hdr_pixel(direction: vec3<f32>, r: Radiance) -> vec4<f32> {
    var radiance = r.radiance;
    if r.reaches_space {
        radiance += frame_sun_disk(direction, r.transmittance);
    }
    return vec4<f32>(min(radiance, vec3<f32>(F16_MAX)), 1.0);
}

// The transmitted sun disk seen along `direction` by a ray that reaches space with
// `transmittance`.
fn frame_sun_disk(direction: vec3<f32>, transmittance: vec3<f32>) -> vec3<f32> {
    return transmittance * sun_disk_radiance(direction, frame.sun_direction.xyz,
        frame.sun_direction.w, frame.sun_centre_radiance.xyz, frame.sun_limb_exponent.xyz);
}

// The unit direction through the centre of pixel `px` (`Frame::pixel_ray`).
fn pixel_direction(px: vec2<u32>) -> vec3<f32> {
    return pixel_direction_at(vec2<f32>(px));
}

// The unit direction through the fractional pixel `p`, pixel x's centre at x
// (`Frame::direction_through(x + 0.5, y + 0.5)`): a reduced-resolution pass's rays.
fn pixel_direction_at(p: vec2<f32>) -> vec3<f32> {
    let size = vec2<f32>(frame.size_px.xy);
    let ndc = vec2<f32>(2.0, -2.0) * (p + 0.5) / size + vec2<f32>(-1.0, 1.0);
    return normalize(frame.forward.xyz + ndc.x * frame.right.xyz + ndc.y * frame.up.xyz);
}

// The part of a view ray inside the atmosphere, in the variables that stay accurate in
// f32: `q` = r^2 - bottom^2 and `r_mu` = r mu at its start, so that at distance t along
// it r^2 - bottom^2 = q + t (t + 2 r_mu) (see `altitude_along`).
struct Segment {
    // False when the ray misses the atmosphere or meets its object before it.
    hit: bool,
    // Whether the ray, continued, meets the ground sphere (which half of the sky's
    // tables it looks up), even where an object ends it first.
    on_ground: bool,
    // How the segment ends: END_GROUND, END_OBJECT or END_SPACE (`SegmentEnd`).
    end: u32,
    // True when the object ends the ray before the ground or the top would
    // (`ViewSegment::cut`); an object beyond the ground ends it there without cutting.
    cut: bool,
    // Distance from the camera to the start, m.
    t_enter: f32,
    q: f32,
    r_mu: f32,
    // Planet-centred start (f32, rounded to about 0.5 m near the ground) and its dot
    // product with the sun direction, m.
    start: vec3<f32>,
    start_dot_sun: f32,
    length: f32,
}

const END_GROUND: u32 = 0u;
const END_OBJECT: u32 = 1u;
const END_SPACE: u32 = 2u;

// The segment of the ray with unit `direction` from the camera that ends on an object at
// `object_m` from the camera (0: none), as `ViewSegment::new`: a camera above the
// atmosphere is moved to where the ray enters it, found from the ray's closest approach
// to the centre, `p`, whose length `h` carries no cancellation even at 1e8 m; the segment
// ends on the object, or on the ground, or at the top. An object beyond the ground ends
// the ray on the ground as an object (terrain drawn over the sphere); one before the
// atmosphere leaves no segment (`hit` false, END_OBJECT at `t_enter` = `object_m`).
fn view_segment(direction: vec3<f32>, object_m: f32) -> Segment {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let camera = frame.camera_m.xyz;
    let sun = frame.sun_direction.xyz;
    var s: Segment;
    s.hit = true;
    s.end = END_SPACE;
    s.cut = false;
    s.t_enter = 0.0;
    s.q = frame.camera_height.x;
    s.r_mu = dot(camera, direction);
    s.start = camera;
    s.start_dot_sun = dot(camera, sun);
    if frame.camera_height.y > 0.5 {
        let p = camera - s.r_mu * direction;
        let h = length(p);
        if s.r_mu >= 0.0 || h > top {
            return missed_segment(s, object_m);
        }
        let half_chord = safe_sqrt((top - h) * (top + h));
        s.t_enter = -s.r_mu - half_chord;
        if object_m > 0.0 && object_m <= s.t_enter {
            return missed_segment(s, object_m);
        }
        s.q = horizon_sq;
        s.r_mu = -half_chord;
        s.start = p - half_chord * direction;
        s.start_dot_sun = dot(s.start, sun);
    }
    s = to_boundary(s);
    if object_m > 0.0 {
        let remaining = object_m - s.t_enter;
        s.cut = remaining < s.length;
        if s.cut || s.end == END_GROUND {
            s.length = min(remaining, s.length);
            s.end = END_OBJECT;
        }
    }
    return s;
}

// The segment `s_in` (start, q and r_mu set, inside the atmosphere) run to the ground or
// the top, whichever it meets: `on_ground`, `end` and `length`.
fn to_boundary(s_in: Segment) -> Segment {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    var s = s_in;
    let ground_disc = s.r_mu * s.r_mu - s.q;
    s.on_ground = s.r_mu < 0.0 && ground_disc >= 0.0;
    if s.on_ground {
        s.end = END_GROUND;
        let denom = -s.r_mu + safe_sqrt(ground_disc);
        s.length = select(0.0, max(s.q / denom, 0.0), denom > 0.0);
    } else {
        s.end = END_SPACE;
        let root = safe_sqrt(ground_disc + horizon_sq);
        if s.r_mu > 0.0 {
            s.length = max((horizon_sq - s.q) / (s.r_mu + root), 0.0);
        } else {
            s.length = max(-s.r_mu + root, 0.0);
        }
    }
    return s;
}

// A ray that leaves no segment: into space, or onto its object before the atmosphere.
fn missed_segment(s_in: Segment, object_m: f32) -> Segment {
    var s = s_in;
    s.hit = false;
    s.length = 0.0;
    if object_m > 0.0 {
        s.end = END_OBJECT;
        s.t_enter = object_m;
    }
    return s;
}

// The planet-centred point where the segment `s` of the ray along unit `direction` ends
// (`ViewSegment::end_point`): from its start, not from the camera, so that a camera far
// in space (1e8 m, rounded to about 8 m in f32) does not move the point; for a ray that
// leaves no segment, the camera's point at `t_enter` (its object, if any).
fn segment_end(s: Segment, direction: vec3<f32>) -> vec3<f32> {
    return s.start + select(s.length, s.t_enter, !s.hit) * direction;
}

// r^2 - bottom^2 at distance t along a segment, clamped at the ground.
fn q_along(s: Segment, t: f32) -> f32 {
    return max(s.q + t * (t + 2.0 * s.r_mu), 0.0);
}

// The altitude for r^2 - bottom^2 = q, as q / (r + bottom): no cancellation.
fn altitude_from_q(q: f32) -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    return q / (sqrt(bottom * bottom + q) + bottom);
}
