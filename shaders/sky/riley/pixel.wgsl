// Entry pass: the riley model per pixel, `main` (render-wgpu's `sky/riley.rs`). CPU twin:
// atmosphere-core's `models/riley.rs`. Paper: Riley et al. 2004, section 4.1: single
// scattering in closed form (Eq. 11, 12, 15, with the factor the printed Eq. 15 lacks
// restored) in a flat atmosphere per species, Rayleigh and Mie each one exponential
// (`RileyParams`, fitted on the CPU), in the tangent frame at the start of the view
// segment; the flattened ray is one leg (to the ground, or up to space) or two (down past
// the limb to the real ray's lowest altitude, then up), cut where an object (the frame's
// surface) ends the ray; the Lambertian ground and surfaces lit through Eq. (12) in their
// own tangent frame. The frame around it (surface, sun disk, HDR target) is
// `common/shade_pixel.wgsl`. Writes spectral radiance (W m^-2 sr^-1 nm^-1).
//
// Everything stays finite in f32 at the stiff directions (view parallel to the sun's
// elevation, p_y = l_y; horizontal rays, p_y = 0), as on the CPU, because nothing divides
// by p_y - l_y or by a small p_y:
//     L = E P tau exp(f_max) phi(tau |p_y - l_y| / l_y),  phi(x) = (1 - e^-x) / x,
// with tau the leg's optical depth, a u0 (K / H) phi(p_y K / H) when |p_y K / H| <= 1
// (no cancellation of u0 - u1), else Eq. (11). WGSL has no expm1 and `1 - exp(-x)`
// loses all digits near 0 in f32, so phi is its Taylor series for |x| < 1 (only + and
// *, exact on every GPU) and the exponential form beyond, where 1 - e^-x >= 0.63.
// The perigee of a ray passing above the limb is taken from q - (r mu)^2 and the drop to
// it from (r mu)^2 / (r + r_perigee), not as differences of radii near 6.4e6 m.

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/phase.wgsl
#import common/surface.wgsl
#import common/shade_pixel.wgsl

struct RileyParams {
    // x: Rayleigh scale height, y: Mie scale height, m; zw: 0.
    scale_heights_m: vec4<f32>,
    // Extinction at the ground (the fitted rho0 included), xyz per channel, m^-1; zero
    // for Mie when its terms are pruned.
    rayleigh_extinction_per_m: vec4<f32>,
    mie_extinction_per_m: vec4<f32>,
    // Scattering / extinction, xyz per channel.
    rayleigh_albedo: vec4<f32>,
    mie_albedo: vec4<f32>,
}

@group(0) @binding(2) var<uniform> riley: RileyParams;
@group(0) @binding(3) var hdr: texture_storage_2d<rgba16float, write>;

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

// One species along one straight leg of the flattened ray: its optical depth and its
// single-scattered light per unit of E P (`FlatExponential::optical_depth` and
// `single_scattering`, finite length).
struct SpeciesLeg {
    tau: vec3<f32>,
    light: vec3<f32>,
}

// Species of ground extinction `beta` and scale height `h` on the leg from height `y0`
// with vertical direction component `p` (any sign, 0 included) over `k` metres, sun at
// vertical component `l` > 0 (no light at l <= 0).
fn species_leg(beta: vec3<f32>, h: f32, y0: f32, p: f32, k: f32, l: f32) -> SpeciesLeg {
    var out: SpeciesLeg;
    out.tau = vec3<f32>(0.0);
    out.light = vec3<f32>(0.0);
    if k <= 0.0 || h <= 0.0 {
        return out;
    }
    let u0 = exp(-y0 / h);
    let u1 = exp(-(y0 + p * k) / h);
    // The leg's column per unit ground extinction (Eq. 11), m.
    let x = p * k / h;
    var column: f32;
    if abs(x) <= 1.0 {
        column = u0 * k * phi(vec3<f32>(x)).x;
    } else {
        column = h * (u0 - u1) / p;
    }
    out.tau = beta * column;
    if l <= 0.0 {
        return out;
    }
    // The integrand's exponent (sun optical depth plus view optical depth from the leg's
    // start) at both ends; it is linear in the density, so the integral is its larger
    // end's value times tau phi(tau |p - l| / l).
    let a = beta * h;
    let f_start = -a * u0 / l;
    let f_end = -a * u1 / l - out.tau;
    let spread = abs(p - l) / l;
    out.light = out.tau * phi(out.tau * spread) * exp(max(f_start, f_end));
    return out;
}

struct Light {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// `light` after the leg from height `y0`, vertical component `p`, length `k`: both
// species' light, attenuated by the legs before it, and the leg's transmittance.
// `phase_r` and `phase_m` are the phase functions times the species' albedo.
fn add_leg(light: Light, y0: f32, p: f32, k: f32, l: f32, phase_r: vec3<f32>,
           phase_m: vec3<f32>) -> Light {
    let rayleigh = species_leg(riley.rayleigh_extinction_per_m.xyz, riley.scale_heights_m.x,
        y0, p, k, l);
    let mie = species_leg(riley.mie_extinction_per_m.xyz, riley.scale_heights_m.y, y0, p, k, l);
    var out: Light;
    out.radiance = light.radiance + light.transmittance * atmosphere.solar_irradiance.xyz
        * (rayleigh.light * phase_r + mie.light * phase_m);
    out.transmittance = light.transmittance * exp(-(rayleigh.tau + mie.tau));
    return out;
}

// `Riley::surface_irradiance`: the transmitted sun only, its optical depth by Eq. (12)
// in the element's tangent frame, none where the sun is below its flat horizon.
fn model_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    let y = e.r - atmosphere.bottom_radius_m;
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 && e.mu_s > 0.0 {
        // The vertical column above height y per unit ground extinction, H exp(-y / H),
        // per species; none for a pruned species (H = 0).
        let h = riley.scale_heights_m.xy;
        let column = select(vec2<f32>(0.0), h * exp(-y / max(h, vec2<f32>(1e-30))),
            h > vec2<f32>(0.0));
        let tau = (riley.rayleigh_extinction_per_m.xyz * column.x
            + riley.mie_extinction_per_m.xyz * column.y) / e.mu_s;
        t = exp(-tau);
    }
    return element_irradiance(e, t, vec3<f32>(0.0));
}

// `Riley::radiance` for the view ray with unit `direction` from the camera and its
// segment `s` in the atmosphere (`common/shade_pixel.wgsl`): the legs are cut where the
// segment ends on an object, as on the CPU.
fn model_radiance(direction: vec3<f32>, s: Segment, empty: Radiance) -> Radiance {
    var out = empty;
    let bottom = atmosphere.bottom_radius_m;
    let r = sqrt(bottom * bottom + s.q);
    let y0 = altitude_from_q(s.q);
    let p = clamp(s.r_mu / r, -1.0, 1.0);
    let l = clamp(s.start_dot_sun / r, -1.0, 1.0);
    let nu = dot(direction, frame.sun_direction.xyz);
    let phase_r = riley.rayleigh_albedo.xyz * rayleigh_phase(nu);
    let phase_m = riley.mie_albedo.xyz * mie_phase(nu);
    var light: Light;
    light.radiance = vec3<f32>(0.0);
    light.transmittance = vec3<f32>(1.0);
    if s.on_ground {
        // Down to the flat ground (`flat_legs`): on_ground implies r mu < 0.
        light = add_leg(light, y0, p, min(y0 / -p, s.length), l, phase_r, phase_m);
        if s.end == END_GROUND {
            // The Lambertian ground, lit as a surface facing up at the ray's end.
            let end = s.start + s.length * direction;
            light.radiance += light.transmittance * atmosphere.ground_albedo / PI
                * model_surface_irradiance(end, normalize(end));
        }
    } else if p >= 0.0 {
        light = add_leg(light, y0, p, s.length, l, phase_r, phase_m);
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
        light = add_leg(light, y0, p, down, l, phase_r, phase_m);
        light = add_leg(light, perigee, -p, s.length - down, l, phase_r, phase_m);
    }
    out.radiance = light.radiance;
    out.transmittance = light.transmittance;
    return out;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade_pixel(id.xy);
}
