// Bruneton and Neyret 2008 per pixel: the GPU twin of `Bruneton::radiance`
// (atmosphere-core `bruneton/mod.rs`). From the camera (moved to where the ray enters
// the atmosphere when it is in space, `view_segment`):
//     L = E_sun (S(x, v, s) + T(x, x_o) alpha / pi (E_direct + E_sky)(x_o)),
// the ground term for rays ending on the ground at x_o (paper Eq. 13-16 with the ground
// a sphere), where S = P_R(nu) S_R + P_M(nu) S_M + S_multiple from the 3D textures
// (quadrilinear, as `Table4::lookup`), on the half of the mu axis of the ray's end. For
// a ray that ends on the ground the paper's aerial perspective S(x) - T(x, x_o) S(x_o)
// is S(x) on the ground's half: S(x_o) looks straight into the ground from it and is
// zero (its ray has length 0), so it is not looked up; the same holds for the frame's
// surface where it lies beyond the ground. A surface that cuts the ray short
// (`Segment::cut`) subtracts T(x, x_o) S(x_o) looked up at its point x_o, and is lit by
// `bruneton_surface_irradiance`. The sun disk with limb darkening is added where the ray
// reaches space, times its transmittance.

#import bruneton_tables.wgsl
#import frame_params.wgsl
#import phase.wgsl
#import surface.wgsl

@group(0) @binding(6) var single_rayleigh: texture_3d<f32>;
@group(0) @binding(7) var single_mie: texture_3d<f32>;
@group(0) @binding(8) var multiple: texture_3d<f32>;
@group(0) @binding(9) var hdr: texture_storage_2d<rgba16float, write>;

// Trilinear interpolation over (r, mu, mu_s) in nu slice `inu` of a scattering texture.
fn texture_slice(table: texture_3d<f32>, p: Position, inu: u32) -> vec3<f32> {
    let x = inu * bruneton.size.z + p.mu_s.i;
    var out = vec3<f32>(0.0);
    for (var dm = 0u; dm < 2u; dm++) {
        let wm = select(1.0 - p.mu.w, p.mu.w, dm == 1u);
        for (var dr = 0u; dr < 2u; dr++) {
            let w_r = select(1.0 - p.r.w, p.r.w, dr == 1u);
            let at = vec3<u32>(x, p.mu.i + dm, p.r.i + dr);
            let a = textureLoad(table, at, 0).xyz;
            let b = textureLoad(table, at + vec3<u32>(1u, 0u, 0u), 0).xyz;
            out += (wm * w_r) * mix(a, b, p.mu_s.w);
        }
    }
    return out;
}

// Quadrilinear interpolation of a scattering texture (`Table4::at_position`).
fn texture_lookup(table: texture_3d<f32>, p: Position) -> vec3<f32> {
    let lo = texture_slice(table, p, p.nu.i);
    if p.nu.w == 0.0 {
        return lo;
    }
    return mix(lo, texture_slice(table, p, p.nu.i + 1u), p.nu.w);
}

// S = P_R S_R + P_M S_M + S_multiple at table position `p`.
fn scattered(p: Position, nu: f32) -> vec3<f32> {
    var l = rayleigh_phase(nu) * texture_lookup(single_rayleigh, p) + texture_lookup(multiple, p);
    if bruneton.flags.y == 1u {
        l += mie_phase(nu) * texture_lookup(single_mie, p);
    }
    return l;
}

// `Bruneton::radiance` for the view ray with unit `direction` from the camera, ending on
// an object at `object_m` (0: none).
fn bruneton_radiance(direction: vec3<f32>, object_m: f32) -> Radiance {
    let s = view_segment(direction, object_m);
    var out = radiance_of_empty(s, direction);
    if !s.hit {
        return out;
    }
    let bottom = atmosphere.bottom_radius_m;
    let sun = frame.sun_direction.xyz;
    let r = radius_of_q(s.q);
    let mu_s = clamp(s.start_dot_sun / r, -1.0, 1.0);
    let nu = clamp(dot(direction, sun), -1.0, 1.0);
    let p = table_position(s.q, r, s.r_mu, mu_s, nu, s.on_ground);
    var l = scattered(p, nu);
    let t = exp(-optical_depth(segment_column(s.q, r, s.r_mu, s.length, s.on_ground)));
    if s.cut {
        // Aerial perspective (section 4, Eq. 3): S(x) - T(x, x_o) S(x_o), on the same
        // half of the mu axis.
        let q_o = q_along(s, s.length);
        let r_o = radius_of_q(q_o);
        let mu_s_o = clamp((s.start_dot_sun + s.length * nu) / r_o, -1.0, 1.0);
        let p_o = table_position(q_o, r_o, s.r_mu + s.length, mu_s_o, nu, s.on_ground);
        l -= t * scattered(p_o, nu);
    }
    if s.end == END_GROUND {
        let mu_s_g = clamp((s.start_dot_sun + s.length * nu) / bottom, -1.0, 1.0);
        let sky = irradiance_at(bruneton.offsets_b.w, 0.0, bottom, mu_s_g);
        var direct = vec3<f32>(0.0);
        if mu_s_g > 0.0 {
            direct = exp(-optical_depth(table_columns(transmittance_columns, 0.0, mu_s_g))) * mu_s_g;
        }
        l += t * (atmosphere.ground_albedo / PI) * (direct + sky);
    }
    out.radiance = max(atmosphere.solar_irradiance.xyz * l, vec3<f32>(0.0));
    out.transmittance = clamp(t, vec3<f32>(0.0), vec3<f32>(1.0));
    return out;
}

// `Bruneton::surface_irradiance`: the transmitted sun from the transmittance table and
// the sky's irradiance E[L](r, mu_s) from the irradiance table (Eq. 15), at the
// element's radius and sun angle.
fn bruneton_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    let bottom = atmosphere.bottom_radius_m;
    let q = (e.r - bottom) * (e.r + bottom);
    var t = vec3<f32>(0.0);
    if e.sun_cosine > 0.0 && !hits_ground(q, e.r * e.mu_s) {
        t = exp(-optical_depth(table_columns(transmittance_columns, q, e.mu_s)));
    }
    let sky = irradiance_at(bruneton.offsets_b.w, q, e.r, e.mu_s);
    return element_irradiance(e, t, atmosphere.solar_irradiance.xyz * sky);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    let surface = frame_surface(id.xy);
    var r = bruneton_radiance(direction, surface.distance);
    if surface.present {
        let e = bruneton_surface_irradiance(r.end, surface.normal);
        r = add_surface(r, surface, e);
    }
    textureStore(hdr, id.xy, hdr_pixel(direction, r));
}
