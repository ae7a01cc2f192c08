// Entry passes: the virtual planes of Dobashi, Yamamoto and Nishita 2000 section 5,
// `vertex` and `fragment` (render-wgpu's `shafts/beams/planes_pass.rs`). CPU twin:
// atmosphere-core's `beams/methods/planes2000.rs`.
//
// One instance per plane and light draws the plane's lattice mesh, perpendicular to the
// view and spanning the frustum at depth (k + 1/2) spacing. The vertex stage computes
// the smooth factor at its lattice point (section 5.3 step (a)),
//   xi = sigma_s F(alpha) exp(-sigma_t (t + r)) / r^2,
// which the rasteriser interpolates linearly over each triangle (Gouraud shading). The
// fragment stage multiplies it by the sharp factors at the pixel's crossing of the
// plane: the light's intensity distribution with its cone and projected light map
// (section 5.1), the shadow map's visibility (section 5.2), and the ray's spacing
// between planes dt (Eq. 5); additive blending sums the planes. Crossings beyond the
// ray's end (`ray_end.wgsl`) are discarded.

#import shafts/beams/bindings.wgsl
#import shafts/beams/planes_bindings.wgsl
#import shafts/beams/plane_light.wgsl
#import shafts/beams/phase.wgsl

struct LatticePoint {
    @builtin(position) position: vec4<f32>,
    // xi at the three wavelengths, sr^-1 m^-3 (times the emission, W m^-2 sr^-1 nm^-1
    // per metre).
    @location(0) @interpolate(linear) xi: vec3<f32>,
    @location(1) @interpolate(flat) plane: u32,
    @location(2) @interpolate(flat) light: u32,
}

fn plane_depth_m(k: u32) -> f32 {
    return (f32(k) + 0.5) * planes.spacing_m.x;
}

struct LightGeometry {
    to_light: vec3<f32>,
    distance_m: f32,
    inverse_square: f32,
}

// The way from `point` to `light`, inside its beam or not (`Light::geometry`).
fn light_geometry(light: BeamLight, point: vec3<f32>) -> LightGeometry {
    var g: LightGeometry;
    if light.kind == 2u {
        g.to_light = -light.frame_z.xyz;
        g.distance_m = max(dot(light.frame_z.xyz, point - light.position.xyz), 0.0);
        g.inverse_square = 1.0;
        return g;
    }
    let offset = light.position.xyz - point;
    let r = length(offset);
    let clamped = max(r, light.position.w);
    g.to_light = select(vec3<f32>(0.0, 1.0, 0.0), offset / r, r > 0.0);
    g.distance_m = r;
    g.inverse_square = 1.0 / (clamped * clamped);
    return g;
}

@vertex
fn vertex(@builtin(vertex_index) v: u32, @builtin(instance_index) instance: u32) -> LatticePoint {
    let n = planes.planes_lattice_lights.y;
    let lights_count = planes.planes_lattice_lights.z;
    let i = v % n;
    let j = v / n;
    let k = instance / lights_count;
    let l = instance % lights_count;
    let x = -1.0 + 2.0 * f32(i) / f32(n - 1u);
    let y = 1.0 - 2.0 * f32(j) / f32(n - 1u);
    let depth = plane_depth_m(k);
    let offset = params.camera_forward.xyz + params.camera_right.xyz * (x * params.camera_right.w)
        + params.camera_up.xyz * (y * params.camera_up.w);
    let point = offset * depth;
    let t = length(offset) * depth;
    let view = normalize(offset);
    let light = lights[l];
    let g = light_geometry(light, point);
    let f = beams_phase(dot(g.to_light, view)) * g.inverse_square;
    var out: LatticePoint;
    out.position = vec4<f32>(x, y, 0.0, 1.0);
    out.xi = params.scattering_per_m.xyz * f * exp(-params.extinction_per_m.xyz * (t + g.distance_m));
    out.plane = k;
    out.light = l;
    return out;
}

@fragment
fn fragment(in: LatticePoint) -> @location(0) vec4<f32> {
    let pixel = in.position.xy;
    let dir = pixel_direction(pixel);
    let cos_forward = dot(dir, params.camera_forward.xyz);
    let depth = plane_depth_m(in.plane);
    let t = depth / cos_forward;
    if t >= textureLoad(ray_end, vec2<i32>(pixel), 0).x {
        discard;
    }
    let point = dir * t;
    let lit = plane_light(lights[in.light], point);
    if !lit.lit {
        discard;
    }
    let dt = planes.spacing_m.x / cos_forward;
    return vec4<f32>(lit.light * in.xi * dt, 0.0);
}
