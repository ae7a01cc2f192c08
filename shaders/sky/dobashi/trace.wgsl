// Library: Eq. 12 of Dobashi, Yamamoto and Nishita 2002 along one view ray, shared by the
// per-pixel pass (`sky/dobashi/pixel.wgsl`) and the ambient table's build
// (`sky/dobashi/ambient.wgsl`). CPU twin: atmosphere-core's `models/dobashi/trace.rs`.
// Paper: Dobashi, Yamamoto and Nishita 2002, sections 5.2-5.3, Eq. 12. The ray is cut by
// sampling planes at t_k = k Delta_t from where it starts in the atmosphere (section 5.2)
// or, for a camera far out, by the sample spheres (section 5.3); each segment's dI_r,
// dI_m, dg_v come from the tables of `sky/dobashi/tables.wgsl`, g_l from the columns
// table (`common/transmittance_lookup.wgsl`) at the segment's start, as Eq. 12 does:
//
// I_v = I_sun (r/pi) g_l(0, theta_g) cos theta_g prod_j dg_v(t_j)
//     + I_sun sum_k g_l(h_k, theta_k) [F_r dI_r(t_k) + F_m dI_m(t_k)] prod_{j<k} dg_v(t_j),
//
// plus the ambient radiance psi, scattered by each segment (dI_r + dI_m) and reflected
// by the ground. Each segment's single scattering is seen through the sun's visibility
// past the terrain at its start, `terrain_visible`, which the including pass defines (the
// pixel pass from the frame's shadow map, section 4.2.2's H; the ambient build 1: orders
// two and up stay unshadowed). Positions are those of `common/frame_params.wgsl`: q = r^2 - bottom^2 and
// r mu along the ray, no difference of radii near 6.4e6 m. The tables are read through
// the texture unit's filter where the device filters Rgba32Float (`common/table_sampling.wgsl`).

#import common/atmosphere_params.wgsl
#import common/frame_params.wgsl
#import common/table_sampling.wgsl
#import common/phase.wgsl
#import common/ground_ray.wgsl
#import sky/dobashi/bindings.wgsl
#import sky/dobashi/plane_mapping.wgsl

// dI_r, dI_m, dg_v of one segment.
struct Segment3 {
    scatter_r: vec3<f32>,
    scatter_m: vec3<f32>,
    transmittance: vec3<f32>,
}

// The three textures of a table at (x, y) in node units, bilinear, clamped to the grid
// (`Grid::sample`): one filtered read each, or four texel reads (`common/table_sampling.wgsl`).
fn sample_planes(x: f32, y: f32) -> Segment3 {
    let size = textureDimensions(plane_scatter_r);
    let xy = clamp(vec2<f32>(x, y), vec2<f32>(0.0), vec2<f32>(size - 1u));
    var out: Segment3;
    if FILTERED_TABLES {
        out.scatter_r = sample_2d(plane_scatter_r, xy);
        out.scatter_m = sample_2d(plane_scatter_m, xy);
        out.transmittance = sample_2d(plane_transmittance, xy);
        return out;
    }
    let i = min(vec2<u32>(xy), size - 2u);
    let a = xy - vec2<f32>(i);
    let o = vec2<u32>(1u, 0u);
    let p = vec2<u32>(0u, 1u);
    out.scatter_r = mix(
        mix(textureLoad(plane_scatter_r, i, 0).xyz, textureLoad(plane_scatter_r, i + o, 0).xyz, a.x),
        mix(textureLoad(plane_scatter_r, i + p, 0).xyz, textureLoad(plane_scatter_r, i + o + p, 0).xyz, a.x),
        a.y);
    out.scatter_m = mix(
        mix(textureLoad(plane_scatter_m, i, 0).xyz, textureLoad(plane_scatter_m, i + o, 0).xyz, a.x),
        mix(textureLoad(plane_scatter_m, i + p, 0).xyz, textureLoad(plane_scatter_m, i + o + p, 0).xyz, a.x),
        a.y);
    out.transmittance = mix(
        mix(textureLoad(plane_transmittance, i, 0).xyz, textureLoad(plane_transmittance, i + o, 0).xyz, a.x),
        mix(textureLoad(plane_transmittance, i + p, 0).xyz, textureLoad(plane_transmittance, i + o + p, 0).xyz, a.x),
        a.y);
    return out;
}

// Distance from the point with q = r^2 - bottom^2 and r mu = `r_mu` to where its ray
// leaves the atmosphere: on the ground, or at the top.
fn distance_out(q: f32, r_mu: f32) -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let ground_disc = r_mu * r_mu - q;
    if r_mu < 0.0 && ground_disc >= 0.0 {
        let denom = -r_mu + sqrt(ground_disc);
        return select(0.0, q / denom, denom > 0.0);
    }
    let root = sqrt(max(ground_disc + horizon_sq, 0.0));
    if r_mu > 0.0 {
        return max((horizon_sq - q) / (r_mu + root), 0.0);
    }
    return max(-r_mu + root, 0.0);
}

// The plane tables for the segment from the point with q = r^2 - bottom^2 and r mu =
// `r_mu` (`PlaneTables::coordinates`): rows by rho / H, the angle axis split at the
// horizon, each half by the distance to where the ray leaves the atmosphere.
fn plane_lookup(q: f32, r_mu: f32) -> Segment3 {
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let horizon = sqrt(horizon_sq);
    let size = textureDimensions(plane_scatter_r);
    let half = size.x / 2u;
    let r = sqrt(bottom * bottom + q);
    let rho = sqrt(q);
    let ground = hits_ground(q, r_mu);
    let d = distance_out(q, r_mu);
    let range = plane_distance_range(q, r, rho, ground);
    let unit = select(0.0, clamp((d - range.x) / (range.y - range.x), 0.0, 1.0),
        range.y > range.x);
    let x = unit * f32(half - 1u) + select(f32(half), 0.0, ground);
    return sample_planes(x, clamp(rho / horizon, 0.0, 1.0) * f32(size.y - 1u));
}

// The sphere tables' entry of row `row` for a segment of `length` (`SphereTables::lookup`):
// linear in the length between the row's shortest and longest segment.
fn sphere_lookup(row: u32, length: f32) -> Segment3 {
    let range = sphere_rows[row];
    let size = textureDimensions(sphere_scatter_r);
    let x = select(0.0, (length - range.z) / (range.w - range.z) * f32(size.x - 1u),
        range.w > range.z);
    let xc = clamp(x, 0.0, f32(size.x - 1u));
    var out: Segment3;
    if FILTERED_TABLES {
        let at = vec2<f32>(xc, f32(row));
        out.scatter_r = sample_2d(sphere_scatter_r, at);
        out.scatter_m = sample_2d(sphere_scatter_m, at);
        out.transmittance = sample_2d(sphere_transmittance, at);
        return out;
    }
    let i = min(u32(xc), size.x - 2u);
    let a = xc - f32(i);
    let p0 = vec2<u32>(i, row);
    let p1 = vec2<u32>(i + 1u, row);
    out.scatter_r = mix(textureLoad(sphere_scatter_r, p0, 0).xyz, textureLoad(sphere_scatter_r, p1, 0).xyz, a);
    out.scatter_m = mix(textureLoad(sphere_scatter_m, p0, 0).xyz, textureLoad(sphere_scatter_m, p1, 0).xyz, a);
    out.transmittance = mix(textureLoad(sphere_transmittance, p0, 0).xyz, textureLoad(sphere_transmittance, p1, 0).xyz, a);
    return out;
}

// The sums of Eq. 12 along a ray, per unit solar irradiance (`trace::Terms`).
struct Terms {
    single: vec3<f32>,
    ambient: vec3<f32>,
    transmittance: vec3<f32>,
}

// The sums before the first segment: nothing scattered, transmittance 1.
fn no_terms() -> Terms {
    return Terms(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(1.0));
}

// What `Accumulator::add` and `add_ground` need of a ray.
struct Ray {
    segment: Segment,
    // Unit direction of the ray.
    direction: vec3<f32>,
    // cos(view, sun) and the phase functions there.
    nu: f32,
    phase_r: f32,
    phase_m: f32,
}

// The ambient radiance psi per unit solar irradiance for a sun of cosine `mu_sun`
// (`AmbientTable::lookup`): 0 when the ambient term is off.
fn ambient_at(mu_sun: f32) -> vec3<f32> {
    if dobashi.ambient_on == 0u {
        return vec3<f32>(0.0);
    }
    let n = textureDimensions(ambient_table).x;
    let x = 0.5 * (clamp(mu_sun, -1.0, 1.0) + 1.0) * f32(n - 1u);
    if FILTERED_TABLES {
        return sample_2d(ambient_table, vec2<f32>(x, 0.0));
    }
    let i = min(u32(x), n - 2u);
    let low = textureLoad(ambient_table, vec2<u32>(i, 0u), 0).xyz;
    let high = textureLoad(ambient_table, vec2<u32>(i + 1u, 0u), 0).xyz;
    return mix(low, high, x - f32(i));
}

// g_l at the point at distance t (q = r^2 - bottom^2 there) per channel, 0 where the
// sun's centre is behind the planet (`nishita::sun_column`); `mu_sun` its cosine.
fn sunlight_at(q: f32, mu_sun: f32) -> vec3<f32> {
    let r = sqrt(atmosphere.bottom_radius_m * atmosphere.bottom_radius_m + q);
    if mu_sun < 0.0 && (r * mu_sun) * (r * mu_sun) - q >= 0.0 {
        return vec3<f32>(0.0);
    }
    return exp(-optical_depth(read_table_columns(g_l, q, mu_sun)));
}

// `Accumulator::add` for the segment starting at distance t whose table values are `v`.
fn add_segment(terms: Terms, ray: Ray, t: f32, v: Segment3) -> Terms {
    let s = ray.segment;
    let q = q_along(s, t);
    let r = sqrt(atmosphere.bottom_radius_m * atmosphere.bottom_radius_m + q);
    let mu_sun = clamp((s.start_dot_sun + t * ray.nu) / r, -1.0, 1.0);
    let psi = ambient_at(mu_sun);
    var out = terms;
    let visible = terrain_visible(s.start + t * ray.direction, q / (r + atmosphere.bottom_radius_m));
    out.single += terms.transmittance * visible * sunlight_at(q, mu_sun)
        * (ray.phase_r * v.scatter_r + ray.phase_m * v.scatter_m);
    out.ambient += terms.transmittance * psi * (v.scatter_r + v.scatter_m);
    out.transmittance = terms.transmittance * v.transmittance;
    return out;
}

// (1 - exp(-x)) / x per component, 1 at 0: below 0.1 its series to x^3 (the next term,
// x^4 / 120, is under 1e-6 there), beyond the exponential form (no cancellation left
// worth a digit in f32).
fn one_minus_exp_over(x: vec3<f32>) -> vec3<f32> {
    let series = 1.0 - x * (0.5 - x * (1.0 / 6.0 - x / 24.0));
    return select((1.0 - exp(-x)) / x, series, abs(x) < vec3<f32>(0.1));
}

// The first `fraction` (0 < fraction < 1) of segment `v` where an object cuts it
// (`Accumulator::add`): the segment taken as uniform, dg_v^fraction and
// dI (1 - dg_v^fraction) / (1 - dg_v), the ratio written fraction phi(fraction tau) /
// phi(tau) with phi above, which stays exact as tau goes to 0 or grows large.
fn cut_segment(v: Segment3, fraction: f32) -> Segment3 {
    let tau = -log(max(v.transmittance, vec3<f32>(1e-30)));
    let ratio = fraction * one_minus_exp_over(fraction * tau) / one_minus_exp_over(tau);
    var out: Segment3;
    out.scatter_r = v.scatter_r * ratio;
    out.scatter_m = v.scatter_m * ratio;
    out.transmittance = exp(-fraction * tau);
    return out;
}

// Section 5.2: segments of Delta_t from the start of the ray.
fn through_planes(ray: Ray) -> Terms {
    var terms = no_terms();
    let s = ray.segment;
    let dt = dobashi.interval_m;
    let n = u32(ceil(s.length / dt));
    for (var k = 0u; k < n; k++) {
        let t = f32(k) * dt;
        let q = q_along(s, t);
        var v = plane_lookup(q, s.r_mu + t);
        if s.cut && k + 1u == n {
            // An object cuts the last segment: a fraction of what the table holds for
            // Delta_t, or less where the ray leaves the atmosphere first.
            let full = min(distance_out(q, s.r_mu + t), dt);
            let remaining = s.length - t;
            if remaining < full {
                v = cut_segment(v, remaining / full);
            }
        }
        terms = add_segment(terms, ray, t, v);
    }
    return terms;
}

// Section 5.3: segments between crossings of the sample spheres, from the top sphere
// where the ray enters (`Tracer::through_spheres`, `SphereTables::step`), following the
// sphere index and r mu at each crossing.
fn through_spheres(ray: Ray) -> Terms {
    var terms = no_terms();
    let s = ray.segment;
    let n = dobashi.spheres;
    var k = n - 1u;
    var r_mu = s.r_mu;
    var t = 0.0;
    // Down through every sphere and up again at most.
    for (var steps = 0u; steps < 3u * n; steps++) {
        var kind = 2u;
        var length = 0.0;
        var next_r_mu = 0.0;
        var next = k;
        if r_mu < 0.0 && k > 0u {
            // q of sphere k minus q of sphere k - 1.
            let dq = -sphere_rows[3u * k].y;
            let disc = r_mu * r_mu - dq;
            if disc >= 0.0 {
                kind = 0u;
                let denom = -r_mu + sqrt(disc);
                length = select(0.0, dq / denom, denom > 0.0);
                next = k - 1u;
                next_r_mu = r_mu + length;
            } else {
                kind = 1u;
                length = -2.0 * r_mu;
                next_r_mu = -r_mu;
            }
        } else {
            if k + 1u >= n {
                break;
            }
            let up = max(r_mu, 0.0);
            let dq = sphere_rows[3u * k + 2u].y;
            length = dq / (up + sqrt(up * up + dq));
            next = k + 1u;
            next_r_mu = up + length;
        }
        let remaining = s.length - t;
        if remaining <= 0.0 {
            break;
        }
        let v = sphere_lookup(3u * k + kind, length);
        if s.cut && remaining < length {
            terms = add_segment(terms, ray, t, cut_segment(v, remaining / length));
            break;
        }
        terms = add_segment(terms, ray, t, v);
        t += length;
        k = next;
        r_mu = next_r_mu;
        if k == 0u {
            break;
        }
    }
    return terms;
}

// Eq. 12 along the ray, with the ground at its end (`Tracer::trace`, `add_ground`).
fn trace(ray: Ray, spheres: bool) -> Terms {
    var terms: Terms;
    if spheres {
        terms = through_spheres(ray);
    } else {
        terms = through_planes(ray);
    }
    let s = ray.segment;
    if s.end == END_GROUND {
        let bottom = atmosphere.bottom_radius_m;
        let cos_g = clamp((s.start_dot_sun + s.length * ray.nu) / bottom, -1.0, 1.0);
        let psi = ambient_at(cos_g);
        let albedo = atmosphere.ground_albedo;
        if cos_g > 0.0 {
            terms.single += terms.transmittance * albedo / PI * sunlight_at(0.0, cos_g) * cos_g;
        }
        terms.ambient += terms.transmittance * albedo * psi;
    }
    return terms;
}

// The ray of `direction` from the segment `s` towards the sun `sun`.
fn make_ray(s: Segment, direction: vec3<f32>, sun: vec3<f32>) -> Ray {
    var ray: Ray;
    ray.segment = s;
    ray.direction = direction;
    ray.nu = dot(direction, sun);
    ray.phase_r = rayleigh_phase(ray.nu);
    ray.phase_m = mie_phase(ray.nu);
    return ray;
}
