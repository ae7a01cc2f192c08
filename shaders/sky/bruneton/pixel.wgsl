// Bruneton and Neyret 2008 per pixel: the GPU twin of `Bruneton::radiance`
// (atmosphere-core `bruneton/mod.rs`). From the camera (moved to where the ray enters
// the atmosphere when it is in space, `view_segment`):
//     L = E_sun (S(x, v, s) + T(x, x_o) alpha / pi (E_direct + E_sky)(x_o)),
// the ground term for rays ending on the ground at x_o (section 4, Eq. 13-16, with the
// ground a sphere), where S = P_R(nu) S_R + P_M(nu) S_M + S_multiple from the 3D textures
// (quadrilinear, as `Table4::lookup`), on the half of the mu axis of the ray's end. For
// a ray that ends on the ground the aerial perspective S(x) - T(x, x_o) S(x_o) (Eq. 3)
// is S(x) on the ground's half: S(x_o) looks straight into the ground from it and is
// zero (its ray has length 0), so it is not looked up; the same holds for the frame's
// surface where it lies beyond the ground. A surface that cuts the ray short
// (`Segment::cut`) subtracts T(x, x_o) S(x_o) looked up at its point x_o, and is lit by
// `bruneton_surface_irradiance`; the sea adds `add_sea` (`common/sea_surface.wgsl`) with
// the sky along its mirror ray from the 3D textures. With light shafts, the single
// scattering of the ray's shadowed length is taken out by the shadow-length
// approximation (section 5, Eq. 17-18; `shaft_loss`). The sun disk with limb darkening is added where the ray
// reaches space, times its transmittance. The view slice, E and the transmittance
// table are read through the texture unit's linear filter where the device filters
// Rgba32Float (`common/table_sampling.wgsl`), else texel by texel.

#import sky/bruneton/lookup.wgsl
#import common/frame_params.wgsl
#import common/phase.wgsl
#import common/surface.wgsl
#import common/sea_surface.wgsl
#import common/table_sampling.wgsl
#import shafts/terrain/view_span.wgsl

@group(0) @binding(9) var hdr: texture_storage_2d<rgba16float, write>;
@group(0) @binding(10) var view_slice: texture_2d<f32>;
// E, copied from the store by `sky/bruneton/scattering_texture.wgsl` (x = mu_s, y = r).
@group(0) @binding(11) var irradiance: texture_2d<f32>;
// The terrain's shadow map for light shafts (docs/shafts.md).
@group(0) @binding(16) var shadow_tops: texture_2d<f32>;
@group(0) @binding(17) var<uniform> shadow_map: ShadowMapParams;

// `IrradianceTable::lookup` on the ground (q = 0, as `irradiance_at`): the table's first
// row, the only one with weight there, interpolated along mu_s alone (two texel reads,
// or one filtered where the interpolation is linear; the same value).
fn ground_irradiance_at(mu_s: f32) -> vec3<f32> {
    let am = axis(irradiance_x_mu_s(mu_s), bruneton.irradiance_mu_s_size);
    let geometric = irradiance_geometric_pair(am.i);
    if FILTERED_TABLES && !geometric {
        return sample_2d(irradiance, vec2<f32>(f32(am.i) + am.w, 0.0));
    }
    let low = textureLoad(irradiance, vec2<u32>(am.i, 0u), 0).xyz;
    let high = textureLoad(irradiance, vec2<u32>(am.i + 1u, 0u), 0).xyz;
    return along_mu_s(low, high, am.w, geometric);
}

// Row imu, nu slice inu of scattering texture `k` (0 single Rayleigh, 1 single Mie, 2
// multiple) interpolated at the camera's r and mu_s, from the view slice
// (`sky/bruneton/view_slice.wgsl`).
fn view_slice_row(k: u32, imu: u32, inu: u32) -> vec3<f32> {
    return textureLoad(view_slice, vec2<u32>(k * bruneton.nu_size + inu, imu), 0).xyz;
}

// `texture_lookup` of scattering texture `k` for a camera inside the atmosphere: every
// ray starts at the camera's r and mu_s, so the interpolation in r and mu_s, the same for
// every pixel, is done once per frame into the view slice, and each pixel interpolates
// in mu and nu (4 texel reads instead of 16, or one filtered; the same quadrilinear
// interpolation).
fn view_slice_lookup(k: u32, p: Position) -> vec3<f32> {
    if FILTERED_TABLES {
        let nu = f32(k * bruneton.nu_size + p.nu.i) + p.nu.w;
        return sample_2d(view_slice, vec2<f32>(nu, f32(p.mu.i) + p.mu.w));
    }
    var lo = vec3<f32>(0.0);
    var hi = vec3<f32>(0.0);
    for (var dm = 0u; dm < 2u; dm++) {
        let wm = select(1.0 - p.mu.w, p.mu.w, dm == 1u);
        lo += wm * view_slice_row(k, p.mu.i + dm, p.nu.i);
        hi += wm * view_slice_row(k, p.mu.i + dm, p.nu.i + 1u);
    }
    if p.nu.w == 0.0 {
        return lo;
    }
    return mix(lo, hi, p.nu.w);
}

// S without phase functions at `p` in scattering texture `k`: from the view slice for a
// camera inside the atmosphere (`inside`, fixed by the entry point, so that lavapipe,
// which runs every branch for every pixel, does not pay for the other way), else from
// the 3D textures. The view slice holds the camera's r and mu_s only: points elsewhere
// (a surface's x_o) read the 3D textures.
fn scattering_at(k: u32, p: Position, inside: bool) -> vec3<f32> {
    if inside {
        return view_slice_lookup(k, p);
    }
    switch k {
        case 0u: {
            return texture_lookup(single_rayleigh, p);
        }
        case 1u: {
            return texture_lookup(single_mie, p);
        }
        default: {
            return texture_lookup(multiple, p);
        }
    }
}

// S = P_R S_R + P_M S_M + S_multiple at table position `p`.
fn scattered(p: Position, nu: f32, inside: bool) -> vec3<f32> {
    var l = rayleigh_phase(nu) * scattering_at(0u, p, inside) + scattering_at(2u, p, inside);
    if bruneton.mie_on == 1u {
        l += mie_phase(nu) * scattering_at(1u, p, inside);
    }
    return l;
}

// `ShaftRay::single_beyond` (atmosphere-core `bruneton/shafts.rs`): T(x, x_d) S|x_d, the
// single scattering of the part of segment `s` beyond distance `d` seen from its start,
// from the 3D textures; zero where x_d ends the segment on the ground or at the top.
fn single_beyond(s: Segment, d: f32, nu: f32) -> vec3<f32> {
    if d >= s.length && !s.cut {
        return vec3<f32>(0.0);
    }
    let r = radius_of_q(s.q);
    let q_d = q_along(s, d);
    let r_d = radius_of_q(q_d);
    let mu_s_d = clamp((s.start_dot_sun + d * nu) / r_d, -1.0, 1.0);
    let p = table_position(q_d, r_d, s.r_mu + d, mu_s_d, nu, s.on_ground);
    let ends = segment_ends(s.q, r, s.r_mu, d, s.on_ground);
    let columns = read_table_columns(transmittance_columns, ends.x, ends.y)
        - read_table_columns(transmittance_columns, ends.z, ends.w);
    let t = exp(-optical_depth(max(columns, vec3<f32>(0.0))));
    var single = rayleigh_phase(nu) * texture_lookup(single_rayleigh, p);
    if bruneton.mie_on == 1u {
        single += mie_phase(nu) * texture_lookup(single_mie, p);
    }
    return t * single;
}

// What the shadow takes out of segment `s` along unit `direction` (`shadowed_segment`
// and `ShaftRay::single_taken_out`): its shadowed length l from the shadow map as one
// segment at the far end of a ray that ends on the ground or an object (Eq. 17), at the
// camera's end of one that ends in space (Eq. 18); T(x, x_a) S|x_a - T(x, x_b) S|x_b.
fn shaft_loss(s: Segment, direction: vec3<f32>, nu: f32) -> vec3<f32> {
    let l = min(shadowed_length(shadow_tops, shadow_map, s, direction), s.length);
    if l <= 0.0 {
        return vec3<f32>(0.0);
    }
    var part = vec2<f32>(0.0, l);
    if s.end != END_SPACE {
        part = vec2<f32>(s.length - l, s.length);
    }
    return single_beyond(s, part.x, nu) - single_beyond(s, part.y, nu);
}

// `Bruneton::radiance` for the view ray with unit `direction` from the camera, ending on
// an object at `object_m` (0: none); `inside`: the camera is inside the atmosphere and
// the view slice holds S at its r and mu_s.
fn bruneton_radiance(direction: vec3<f32>, object_m: f32, inside: bool) -> Radiance {
    return segment_radiance(direction, view_segment(direction, object_m), inside);
}

// `Bruneton::radiance` for the ray along unit `direction` whose segment in the atmosphere
// is `s` (a camera's, or the sea's mirror ray, `common/sea_surface.wgsl`, which reads
// the 3D textures: `inside` false).
fn segment_radiance(direction: vec3<f32>, s: Segment, inside: bool) -> Radiance {
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
    var l = scattered(p, nu, inside);
    let ends = segment_ends(s.q, r, s.r_mu, s.length, s.on_ground);
    let columns = read_table_columns(transmittance_columns, ends.x, ends.y)
        - read_table_columns(transmittance_columns, ends.z, ends.w);
    let t = exp(-optical_depth(max(columns, vec3<f32>(0.0))));
    if s.cut {
        // Aerial perspective (section 4, Eq. 3): S(x) - T(x, x_o) S(x_o), on the same
        // half of the mu axis.
        let q_o = q_along(s, s.length);
        let r_o = radius_of_q(q_o);
        let mu_s_o = clamp((s.start_dot_sun + s.length * nu) / r_o, -1.0, 1.0);
        let p_o = table_position(q_o, r_o, s.r_mu + s.length, mu_s_o, nu, s.on_ground);
        l -= t * scattered(p_o, nu, false);
    }
    l -= shaft_loss(s, direction, nu);
    if s.end == END_GROUND {
        let mu_s_g = clamp((s.start_dot_sun + s.length * nu) / bottom, -1.0, 1.0);
        let sky = ground_irradiance_at(mu_s_g);
        var direct = vec3<f32>(0.0);
        if mu_s_g > 0.0 {
            direct = exp(-optical_depth(read_ground_columns(transmittance_columns, mu_s_g))) * mu_s_g;
        }
        l += t * (atmosphere.ground_albedo / PI) * (direct + sky);
    }
    out.radiance = max(atmosphere.solar_irradiance.xyz * l, vec3<f32>(0.0));
    out.transmittance = clamp(t, vec3<f32>(0.0), vec3<f32>(1.0));
    return out;
}

// `Bruneton::surface_irradiance`: the transmitted sun (a point, or with `sun_disk` the
// disk's visible part along its centroid) from the transmittance table and
// the sky's irradiance E[L](r, mu_s) from the irradiance table (section 4, Eq. 15), at the
// element's radius and sun angle.
fn bruneton_surface_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let e = surface_element(point, normal);
    let bottom = atmosphere.bottom_radius_m;
    let q = (e.r - bottom) * (e.r + bottom);
    var t = vec3<f32>(0.0);
    if bruneton.sun_disk == 1u {
        let visible = visible_sun(q, e.r, e.mu_s);
        if e.sun_cosine > 0.0 && visible.x > 0.0 {
            t = visible.x * exp(-optical_depth(read_table_columns(transmittance_columns, q, visible.y)));
        }
    } else if e.sun_cosine > 0.0 && !hits_ground(q, e.r * e.mu_s) {
        t = exp(-optical_depth(read_table_columns(transmittance_columns, q, e.mu_s)));
    }
    let sky = irradiance_at(bruneton.irradiance_offset, q, e.r, e.mu_s);
    return element_irradiance(e, t, atmosphere.solar_irradiance.xyz * sky);
}

// The pass for a camera above the atmosphere (rays start where they enter it, at
// different sun cosines).
@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    shade(id.xy, false);
}

// The pass for a camera inside the atmosphere, after the view slice.
@compute @workgroup_size(8, 8)
fn inside(@builtin(global_invocation_id) id: vec3<u32>) {
    shade(id.xy, true);
}

// Pixel `px`: the radiance and the sun disk into the HDR target.
fn shade(px: vec2<u32>, inside: bool) {
    if any(px >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(px);
    let surface = frame_surface(px);
    var r = bruneton_radiance(direction, surface.distance, inside);
    r.radiance = without_cloud_air_shadow(px, r.radiance);
    if surface.present {
        let e = bruneton_surface_irradiance(r.end, surface.normal);
        if SEA && surface.water {
            let mirror = sea_mirror(r.end, direction, surface.normal);
            let sky = segment_radiance(mirror, mirror_segment(r.end, mirror), false).radiance;
            let sun = sea_sun(r.end, bruneton_surface_irradiance(r.end, frame.sun_direction.xyz),
                bruneton_surface_irradiance(r.end, across_normal(r.end)));
            r = add_sea(r, surface, direction, e, sky, sun);
        } else {
            r = add_surface(r, surface, e);
        }
    }
    textureStore(hdr, px, hdr_pixel(direction, r));
}
