// Bruneton and Neyret 2008 per pixel: the GPU twin of `Bruneton::radiance`
// (atmosphere-core `bruneton/mod.rs`). From the camera (moved to where the ray enters
// the atmosphere when it is in space, `view_segment`):
//     L = E_sun (S(x, v, s) + T(x, x_o) alpha / pi (E_direct + E_sky)(x_o)),
// the ground term for rays ending on the ground at x_o (paper Eq. 13-16 with the ground
// a sphere), where S = P_R(nu) S_R + P_M(nu) S_M + S_multiple from the 3D textures
// (quadrilinear, as `Table4::lookup`), on the half of the mu axis of the ray's end. For
// a ray that ends on the ground the paper's aerial perspective S(x) - T(x, x_o) S(x_o)
// is S(x) on the ground's half: S(x_o) looks straight into the ground from it and is
// zero (its ray has length 0), so it is not looked up. The sun disk with limb darkening
// is added where the ray reaches space, times its transmittance.

#import bruneton_tables.wgsl
#import frame_params.wgsl
#import phase.wgsl

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

fn bruneton_radiance(direction: vec3<f32>) -> Radiance {
    var out: Radiance;
    out.radiance = vec3<f32>(0.0);
    out.transmittance = vec3<f32>(1.0);
    out.reaches_space = true;
    let s = view_segment(direction);
    if !s.hit {
        return out;
    }
    let bottom = atmosphere.bottom_radius_m;
    let sun = frame.sun_direction.xyz;
    let r = radius_of_q(s.q);
    let mu_s = clamp(s.start_dot_sun / r, -1.0, 1.0);
    let nu = clamp(dot(direction, sun), -1.0, 1.0);
    let p = table_position(s.q, r, s.r_mu, mu_s, nu, s.on_ground);
    var l = rayleigh_phase(nu) * texture_lookup(single_rayleigh, p) + texture_lookup(multiple, p);
    if bruneton.flags.y == 1u {
        l += mie_phase(nu) * texture_lookup(single_mie, p);
    }
    let t = exp(-optical_depth(segment_column(s.q, r, s.r_mu, s.length, s.on_ground)));
    if s.on_ground {
        let mu_s_g = clamp((s.start_dot_sun + s.length * nu) / bottom, -1.0, 1.0);
        let sky = ground_irradiance_at(bruneton.offsets_b.w, mu_s_g);
        var direct = vec3<f32>(0.0);
        if mu_s_g > 0.0 {
            direct = exp(-optical_depth(ground_columns(transmittance_columns, mu_s_g))) * mu_s_g;
        }
        l += t * (atmosphere.ground_albedo / PI) * (direct + sky);
    }
    out.radiance = max(atmosphere.solar_irradiance.xyz * l, vec3<f32>(0.0));
    out.transmittance = clamp(t, vec3<f32>(0.0), vec3<f32>(1.0));
    out.reaches_space = !s.on_ground;
    return out;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    let r = bruneton_radiance(direction);
    textureStore(hdr, id.xy, hdr_pixel(direction, r));
}
