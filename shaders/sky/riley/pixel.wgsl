// Entry pass: the riley model per pixel, `main` (render-wgpu's `sky/riley.rs`). CPU twin:
// atmosphere-core's `models/riley/`. Paper: Riley et al. 2004, section 4.1: single
// scattering in closed form (Eq. 11, 12, 15, with the factor the printed Eq. 15 lacks
// restored), each species one exponential (`RileyParams`, fitted on the CPU).
//
// The ray is cut into pieces; at each piece's ends the columns of every species from the
// segment's start (`view`) and towards the sun (`sun`) are known exactly, and the
// exponent F of the integrand (the light path's optical depth) is taken linear in the
// scattering species' own optical depth tau_j in between (`pieces.rs`):
//     integral of exp(-F) dtau_j = dtau_j exp(-min F) phi(|dF|),  phi(x) = (1 - e^-x) / x,
// which is Eq. (15) itself for one species on a flat earth. Two geometries
// (`options.x`):
// - sphere (`sphere_path.rs`): columns along the real ray and towards the sun by the
//   Chapman function's parabolic closed form (`chapman.rs`; the sun's up to the top),
//   over the ray's lit parts only
//   (the planet's shadow, `shadow.rs`), each monotone part in `options.z` pieces at equal
//   steps of the air's density;
// - flat (`flat_path.rs`, the paper's): the flattened legs in the tangent frame at the
//   segment's start, one to the ground or to space, or two past the limb, each in
//   `options.z` equal pieces; Eq. (11) and (12) give the columns; no light at l_y <= 0.
// `options.y` 1: F counts every species (and ozone, whose extinction is zero when left
// out); 0: only the scattering species' own and ozone's. The Lambertian ground and
// surfaces are lit through the same sun columns in their own frame. The frame around it
// (surface, sun disk, HDR target) is `common/shade_pixel.wgsl`. Writes spectral radiance
// (W m^-2 sr^-1 nm^-1).
//
// In f32, nothing divides by p_y - l_y or by a small p_y; WGSL has no expm1 and
// `1 - exp(-x)` loses all digits near 0, so phi is its Taylor series for |x| < 1. Heights
// come from q = r^2 - bottom^2 as q / (r + bottom) and the perigee's from q - (r mu)^2,
// not as differences of radii near 6.4e6 m.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/phase.wgsl
#import common/surface.wgsl
#import common/shade_pixel.wgsl

struct RileyParams {
    // x: Rayleigh, y: Mie, z: ozone scale height, m; w: 0.
    scale_heights_m: vec4<f32>,
    // Extinction at the ground (the fitted rho0 included), xyz per channel, m^-1; zero
    // for Mie when its terms are pruned and for ozone when it is left out.
    rayleigh_extinction_per_m: vec4<f32>,
    mie_extinction_per_m: vec4<f32>,
    ozone_extinction_per_m: vec4<f32>,
    // Scattering / extinction, xyz per channel.
    rayleigh_albedo: vec4<f32>,
    mie_albedo: vec4<f32>,
    // x: 1 on the sphere, 0 flat; y: 1 shared extinction, 0 each its own; z: pieces; w: 0.
    options: vec4<u32>,
}

@group(0) @binding(2) var<uniform> riley: RileyParams;
@group(0) @binding(3) var hdr: texture_storage_2d<rgba16float, write>;

// Stands for an infinite column (a hidden sun) without inf * 0 = NaN.
const HIDDEN: f32 = 1e30;

// `riley::phi`: (1 - exp(-x)) / x per component, 1 at 0. For |x| < 1 the series
// sum_n (-x)^n / (n + 1)! to n = 10 (the first term left out is below 1/12! = 2.1e-9).
fn phi(x: vec3<f32>) -> vec3<f32> {
    var s = vec3<f32>(1.0 / 39916800.0);
    s = 1.0 / 3628800.0 - x * s;
    s = 1.0 / 362880.0 - x * s;
    s = 1.0 / 40320.0 - x * s;
    s = 1.0 / 5040.0 - x * s;
    s = 1.0 / 720.0 - x * s;
    s = 1.0 / 120.0 - x * s;
    s = 1.0 / 24.0 - x * s;
    s = 1.0 / 6.0 - x * s;
    s = 0.5 - x * s;
    s = 1.0 - x * s;
    return select((1.0 - exp(-x)) / x, s, abs(x) < vec3<f32>(1.0));
}

// `chapman::erfcx`: exp(z^2) erfc(z) for z >= 0 (Numerical Recipes' `erfcc`).
fn erfcx(z_in: f32) -> f32 {
    let t = 1.0 / (1.0 + 0.5 * max(z_in, 0.0));
    let poly = -1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418
        + t * (-0.18628806 + t * (0.27886807 + t * (-1.13520398 + t * (1.48851587
        + t * (-0.82215223 + t * 0.17087277))))))));
    return t * exp(poly);
}

// `chapman::column_upwards`, for the three species at once: the column of exp(-h / H)
// from height `h` to infinity along a direction of cosine `mu` >= 0, m. A species of
// scale height 0 (none) has none.
fn column_upwards(h: f32, mu: f32) -> vec3<f32> {
    let hs = max(riley.scale_heights_m.xyz, vec3<f32>(1e-3));
    let x = (atmosphere.bottom_radius_m + h) / hs;
    let c = hs * sqrt(0.5 * PI * x) * exp(-h / hs) * vec3<f32>(
        erfcx(max(mu, 0.0) * sqrt(0.5 * x.x)),
        erfcx(max(mu, 0.0) * sqrt(0.5 * x.y)),
        erfcx(max(mu, 0.0) * sqrt(0.5 * x.z)));
    return select(vec3<f32>(0.0), c, riley.scale_heights_m.xyz > vec3<f32>(0.0));
}

// `chapman::column_to_space` for a point of height `h` and r mu = `r_mu`, with
// `q_low` = r^2 - bottom^2 - (r mu)^2 its ray's perigee's q (clamped at the ground).
fn column_to_space(h: f32, r_mu: f32, q_low: f32) -> vec3<f32> {
    let r = atmosphere.bottom_radius_m + h;
    let mu = clamp(r_mu / r, -1.0, 1.0);
    if mu >= 0.0 {
        return column_upwards(h, mu);
    }
    let perigee = altitude_from_q(max(q_low, 0.0));
    return 2.0 * column_upwards(perigee, 0.0) - column_upwards(h, -mu);
}

// `chapman::column_to_top`: `column_to_space` less the column beyond the atmosphere's
// top, where the ray leaves with r_top mu_exit = sqrt(q_top - q_low).
fn column_to_top(h: f32, r_mu: f32, q_low: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let q_top = (top - bottom) * (top + bottom);
    let mu_exit = sqrt(max(q_top - q_low, 0.0)) / top;
    let beyond = column_upwards(top - bottom, mu_exit);
    return max(column_to_space(h, r_mu, q_low) - beyond, vec3<f32>(0.0));
}

// Columns at one point of the ray (`pieces::PointColumns`): x Rayleigh, y Mie, z ozone.
struct Columns {
    view: vec3<f32>,
    sun: vec3<f32>,
}

// The light path's optical depth F per channel, the species weighted by `include`.
fn path_depth(c: Columns, include: vec3<f32>) -> vec3<f32> {
    let k = c.view + c.sun;
    return riley.rayleigh_extinction_per_m.xyz * (include.x * k.x)
        + riley.mie_extinction_per_m.xyz * (include.y * k.y)
        + riley.ozone_extinction_per_m.xyz * (include.z * k.z);
}

// `pieces::piece_integrals` for one species `j` (0 Rayleigh, 1 Mie) of ground extinction
// `beta` per channel.
fn piece_integral(a: Columns, b: Columns, beta: vec3<f32>, j: u32) -> vec3<f32> {
    let own = select(b.view.y - a.view.y, b.view.x - a.view.x, j == 0u);
    let dtau = beta * max(own, 0.0);
    var include = vec3<f32>(1.0);
    if riley.options.y == 0u {
        include = select(vec3<f32>(0.0, 1.0, 1.0), vec3<f32>(1.0, 0.0, 1.0), j == 0u);
    }
    let fa = path_depth(a, include);
    let fb = path_depth(b, include);
    return dtau * exp(-min(fa, fb)) * phi(abs(fb - fa));
}

struct Light {
    radiance: vec3<f32>,
    // Columns at the previous point of the current part.
    previous: Columns,
}

// `light` with the piece from its previous point to `next`; `phase_r`, `phase_m` are the
// phase functions times the species' albedo.
fn add_piece(light: Light, next: Columns, phase_r: vec3<f32>, phase_m: vec3<f32>) -> Light {
    var out = light;
    let r = piece_integral(light.previous, next, riley.rayleigh_extinction_per_m.xyz, 0u);
    let m = piece_integral(light.previous, next, riley.mie_extinction_per_m.xyz, 1u);
    out.radiance += atmosphere.solar_irradiance.xyz * (r * phase_r + m * phase_m);
    out.previous = next;
    return out;
}

// The ray on the sphere, as `sphere_path.rs` sees it.
struct SphereRay {
    q: f32,
    r_mu: f32,
    // r^2 - bottom^2 - (r mu)^2 of the ray: its perigee's q (negative: it meets the ground).
    q_low: f32,
    start_dot_sun: f32,
    nu: f32,
    // Columns from the start to space, forwards and backwards.
    forward: vec3<f32>,
    backward: vec3<f32>,
}

// The view's columns from the start to distance `t` along the ray.
fn sphere_view(ray: SphereRay, t: f32) -> vec3<f32> {
    let q = max(ray.q + t * (t + 2.0 * ray.r_mu), 0.0);
    let h = altitude_from_q(q);
    let r_mu = ray.r_mu + t;
    var view: vec3<f32>;
    if r_mu >= 0.0 {
        view = ray.forward - column_to_space(h, r_mu, ray.q_low);
    } else {
        view = column_to_space(h, -r_mu, ray.q_low) - ray.backward;
    }
    return max(view, vec3<f32>(0.0));
}

// `sphere_path::sphere_pieces`'s `at`: the columns at distance `t` along the ray.
fn sphere_columns(ray: SphereRay, t: f32) -> Columns {
    let q = max(ray.q + t * (t + 2.0 * ray.r_mu), 0.0);
    var c: Columns;
    c.view = sphere_view(ray, t);
    // The sun ray's own perigee: q - (r mu_s)^2.
    let r_mu_s = ray.start_dot_sun + t * ray.nu;
    c.sun = column_to_top(altitude_from_q(q), r_mu_s, q - r_mu_s * r_mu_s);
    return c;
}

// `shadow::shadowed_interval`: the part of [0, length] in the planet's shadow, as
// (start, end), start >= end when none.
fn shadowed_interval(start: vec3<f32>, direction: vec3<f32>, segment_length: f32) -> vec2<f32> {
    let sun = frame.sun_direction.xyz;
    let none = vec2<f32>(1.0, 0.0);
    let o_along = dot(start, sun);
    let d_along = dot(direction, sun);
    let o_across = start - o_along * sun;
    let d_across = direction - d_along * sun;
    let bottom = atmosphere.bottom_radius_m;
    let a = dot(d_across, d_across);
    let b = dot(o_across, d_across);
    let lo = length(o_across);
    let c = (lo - bottom) * (lo + bottom);
    var t1: f32;
    var t2: f32;
    if a < 1e-12 {
        if c >= 0.0 {
            return none;
        }
        t1 = -3e38;
        t2 = 3e38;
    } else {
        let disc = b * b - a * c;
        if disc <= 0.0 {
            return none;
        }
        let q = -(b + select(-1.0, 1.0, b >= 0.0) * sqrt(disc));
        var r1: f32;
        var r2: f32;
        if q == 0.0 {
            r1 = -sqrt(-c / a);
            r2 = -r1;
        } else {
            r1 = q / a;
            r2 = c / q;
        }
        t1 = min(r1, r2);
        t2 = max(r1, r2);
    }
    if d_along > 0.0 {
        t2 = min(t2, -o_along / d_along);
    } else if d_along < 0.0 {
        t1 = max(t1, -o_along / d_along);
    } else if o_along >= 0.0 {
        return none;
    }
    return vec2<f32>(max(t1, 0.0), min(t2, segment_length));
}

// The sphere's pieces over the lit, monotone parts of the segment `s`: their light, and
// the view's columns to the segment's end in `previous.view`.
fn sphere_light(direction: vec3<f32>, s: Segment, phase_r: vec3<f32>,
                phase_m: vec3<f32>) -> Light {
    let bottom = atmosphere.bottom_radius_m;
    var ray: SphereRay;
    ray.q = s.q;
    ray.r_mu = s.r_mu;
    ray.q_low = s.q - s.r_mu * s.r_mu;
    ray.start_dot_sun = s.start_dot_sun;
    ray.nu = dot(direction, frame.sun_direction.xyz);
    let h0 = altitude_from_q(s.q);
    ray.forward = column_to_space(h0, s.r_mu, ray.q_low);
    ray.backward = column_to_space(h0, -s.r_mu, ray.q_low);
    let t_perigee = -s.r_mu;
    // Below the ground (negative) for a ray that meets it: q_low / (r_p + bottom).
    let h_perigee = ray.q_low / (sqrt(max(bottom * bottom + ray.q_low, 0.0)) + bottom);
    let shadow = shadowed_interval(s.start, direction, s.length);
    // The cuts, sorted: 0, the perigee, the shadow's ends, the length.
    var cuts = array<f32, 5>(0.0, s.length, s.length, s.length, s.length);
    var n = 1u;
    if t_perigee > 0.0 && t_perigee < s.length {
        cuts[n] = t_perigee;
        n += 1u;
    }
    if shadow.x < shadow.y {
        cuts[n] = shadow.x;
        cuts[n + 1u] = shadow.y;
        n += 2u;
    }
    cuts[n] = s.length;
    n += 1u;
    for (var i = 1u; i < n; i++) {
        for (var k = i; k > 0u && cuts[k - 1u] > cuts[k]; k--) {
            let swap = cuts[k];
            cuts[k] = cuts[k - 1u];
            cuts[k - 1u] = swap;
        }
    }
    let pieces = max(riley.options.z, 1u);
    let h_air = max(riley.scale_heights_m.x, 1e-3);
    var light: Light;
    light.radiance = vec3<f32>(0.0);
    for (var part = 0u; part + 1u < n; part++) {
        let a = cuts[part];
        let b = cuts[part + 1u];
        let middle = 0.5 * (a + b);
        if b <= a || (shadow.x < shadow.y && middle > shadow.x && middle < shadow.y) {
            continue;
        }
        let descending = middle < t_perigee;
        let h_a = altitude_from_q(max(ray.q + a * (a + 2.0 * ray.r_mu), 0.0));
        let h_b = altitude_from_q(max(ray.q + b * (b + 2.0 * ray.r_mu), 0.0));
        let u_a = exp(-h_a / h_air);
        let u_b = exp(-h_b / h_air);
        light.previous = sphere_columns(ray, a);
        for (var i = 1u; i <= pieces; i++) {
            let f = f32(i) / f32(pieces);
            var t = b;
            if i < pieces {
                if u_a != u_b && u_a > 0.0 && u_b > 0.0 {
                    let h = -h_air * log(u_a + (u_b - u_a) * f);
                    let r_p = bottom + h_perigee;
                    let half_chord = sqrt(max(h - h_perigee, 0.0) * (bottom + h + r_p));
                    t = clamp(select(t_perigee + half_chord, t_perigee - half_chord,
                        descending), a, b);
                } else {
                    t = a + (b - a) * f;
                }
            }
            light = add_piece(light, sphere_columns(ray, t), phase_r, phase_m);
        }
    }
    light.previous.view = sphere_view(ray, s.length);
    return light;
}

// `FlatExponential::optical_depth` per unit ground extinction for the three species: the
// column over `k` metres from height `y0` at vertical component `p`, m.
fn flat_column(y0: f32, p: f32, k: f32) -> vec3<f32> {
    let hs = max(riley.scale_heights_m.xyz, vec3<f32>(1e-3));
    let u0 = exp(-y0 / hs);
    let x = p * k / hs;
    let u1 = exp(-(y0 + p * k) / hs);
    let c = select(hs * (u0 - u1) / p, u0 * k * phi(x), abs(x) <= vec3<f32>(1.0));
    return select(vec3<f32>(0.0), c, (riley.scale_heights_m.xyz > vec3<f32>(0.0)) & vec3<bool>(k > 0.0));
}

// The columns at `t` along a flat leg from height `y0` at slope `p`, after the columns
// `before` of the legs before it, sun at vertical component `l`.
fn flat_columns(before: vec3<f32>, y0: f32, p: f32, t: f32, l: f32) -> Columns {
    var c: Columns;
    c.view = before + flat_column(y0, p, t);
    let hs = max(riley.scale_heights_m.xyz, vec3<f32>(1e-3));
    c.sun = select(vec3<f32>(HIDDEN), hs * exp(-(y0 + p * t) / hs) / max(l, 1e-30), l > 0.0);
    return c;
}

// `light` with one flat leg in `pieces` equal pieces.
fn add_flat_leg(light_in: Light, y0: f32, p: f32, k: f32, l: f32, phase_r: vec3<f32>,
                phase_m: vec3<f32>) -> Light {
    var light = light_in;
    let before = light.previous.view;
    let pieces = max(riley.options.z, 1u);
    for (var i = 1u; i <= pieces; i++) {
        let t = k * f32(i) / f32(pieces);
        light = add_piece(light, flat_columns(before, y0, p, t, l), phase_r, phase_m);
    }
    return light;
}

// The flattened legs of the segment `s` (`flat::flat_legs`, cut at an object).
fn flat_light(s: Segment, phase_r: vec3<f32>, phase_m: vec3<f32>) -> Light {
    let bottom = atmosphere.bottom_radius_m;
    let r = sqrt(bottom * bottom + s.q);
    let y0 = altitude_from_q(s.q);
    let p = clamp(s.r_mu / r, -1.0, 1.0);
    let l = clamp(s.start_dot_sun / r, -1.0, 1.0);
    var light: Light;
    light.radiance = vec3<f32>(0.0);
    light.previous = flat_columns(vec3<f32>(0.0), y0, p, 0.0, l);
    if s.on_ground {
        // Down to the flat ground: on_ground implies r mu < 0.
        light = add_flat_leg(light, y0, p, min(y0 / -p, s.length), l, phase_r, phase_m);
    } else if p >= 0.0 {
        light = add_flat_leg(light, y0, p, s.length, l, phase_r, phase_m);
    } else {
        // Down past the limb: to the real ray's lowest altitude at slope p, then up at
        // -p for the rest of the chord. With q_low = r_low^2 - bottom^2 = q - (r mu)^2
        // (>= 0, the ray misses the ground), the lowest altitude is q_low / (r_low +
        // bottom) and the drop to it (r mu)^2 / (r + r_low), run at slope p over
        // -r_mu r / (r + r_low).
        let q_low = max(s.q - s.r_mu * s.r_mu, 0.0);
        let r_low = sqrt(bottom * bottom + q_low);
        let perigee = min(q_low / (r_low + bottom), y0);
        let down = min(-s.r_mu * r / (r + r_low), s.length);
        light = add_flat_leg(light, y0, p, down, l, phase_r, phase_m);
        if s.length > down {
            light = add_flat_leg(light, perigee, -p, s.length - down, l, phase_r, phase_m);
        }
    }
    return light;
}

// The sun's transmittance from a point at height `y` whose sun has cosine `mu_s` and
// r mu_s = `r_mu_s`, q = r^2 - bottom^2 = `q` (`Riley::surface_irradiance`): zero where
// the ground hides it.
fn sun_transmittance(q: f32, r_mu_s: f32, mu_s: f32) -> vec3<f32> {
    let y = altitude_from_q(q);
    var columns: vec3<f32>;
    if riley.options.x == 1u {
        if r_mu_s < 0.0 && r_mu_s * r_mu_s >= q {
            return vec3<f32>(0.0);
        }
        columns = column_to_top(y, r_mu_s, q - r_mu_s * r_mu_s);
    } else {
        if mu_s <= 0.0 {
            return vec3<f32>(0.0);
        }
        let hs = max(riley.scale_heights_m.xyz, vec3<f32>(1e-3));
        columns = select(vec3<f32>(0.0), hs * exp(-y / hs) / mu_s,
            riley.scale_heights_m.xyz > vec3<f32>(0.0));
    }
    return exp(-(riley.rayleigh_extinction_per_m.xyz * columns.x
        + riley.mie_extinction_per_m.xyz * columns.y
        + riley.ozone_extinction_per_m.xyz * columns.z));
}

// `Riley::surface_irradiance`: the transmitted sun only.
fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 {
        t = sun_transmittance(e.q, e.r * e.mu_s, e.mu_s);
    }
    return element_irradiance(e, t, vec3<f32>(0.0));
}

// `Riley::radiance` for the view ray with unit `direction` from the camera and its
// segment `s` in the atmosphere (`common/shade_pixel.wgsl`).
fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance {
    var out = empty;
    let nu = dot(direction, frame.sun_direction.xyz);
    let phase_r = riley.rayleigh_albedo.xyz * rayleigh_phase(nu);
    let phase_m = riley.mie_albedo.xyz * mie_phase(nu);
    var light: Light;
    if riley.options.x == 1u {
        light = sphere_light(direction, s, phase_r, phase_m);
    } else {
        light = flat_light(s, phase_r, phase_m);
    }
    var radiance = light.radiance;
    let view = light.previous.view;
    let transmittance = exp(-(riley.rayleigh_extinction_per_m.xyz * view.x
        + riley.mie_extinction_per_m.xyz * view.y
        + riley.ozone_extinction_per_m.xyz * view.z));
    if s.end == END_GROUND {
        // The Lambertian ground, lit as a surface facing up at the ray's end.
        let end = s.start + s.length * direction;
        radiance += transmittance * atmosphere.ground_albedo / PI
            * model_surface_irradiance(end, normalize(end));
    }
    out.radiance = radiance;
    out.transmittance = transmittance;
    return out;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade_pixel(id.xy);
}
