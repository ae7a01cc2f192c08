// Library: the medium along a ray and the segment integral of the hillaire model, shared
// by every hillaire table and the per-pixel pass. CPU twin: atmosphere-core's
// `models/hillaire/medium.rs`. Paper: Hillaire 2020, section 5 (the medium's coefficients
// and the sun's transmittance from the transmittance LUT, section 5.1) with the
// energy-conserving segment integral of Hillaire 2015. Radii enter as
// q = r^2 - bottom^2 and r mu, r mu_s (see `common/frame_params.wgsl`), so that no
// planet-sized f32 numbers are subtracted.

#import common/atmosphere_params.wgsl
#import common/table_sampling.wgsl
#import common/phase.wgsl
#import common/ground_ray.wgsl
#import sky/hillaire/bindings.wgsl

// top^2 - bottom^2: q at the top of the atmosphere.
fn top_q() -> f32 {
    let a = atmosphere;
    return (a.top_radius_m - a.bottom_radius_m) * (a.top_radius_m + a.bottom_radius_m);
}

// 1 - exp(-x) per channel, by its series below 0.01 (where 1 - exp(-x) in f32 loses up
// to 6e-8 absolute: 3e-3 relative for the thin segments high in the atmosphere).
fn one_minus_exp(x: vec3<f32>) -> vec3<f32> {
    let series = x * (1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0))));
    return select(1.0 - exp(-x), series, x < vec3<f32>(0.01));
}

struct SegmentWeight {
    transmittance: vec3<f32>,
    // Integral of the transmittance from the segment's start over its length, m.
    integral: vec3<f32>,
}

// `segment_weight`: exp(-sigma_t dt) and (1 - exp(-sigma_t dt)) / sigma_t (Hillaire 2015's
// energy-conserving integration), dt without extinction.
fn segment_weight(extinction: vec3<f32>, dt: f32) -> SegmentWeight {
    let x = extinction * dt;
    let lost = one_minus_exp(x);
    var w: SegmentWeight;
    w.transmittance = exp(-x);
    w.integral = select(dt * lost / max(x, vec3<f32>(1e-30)), vec3<f32>(dt), x <= vec3<f32>(0.0));
    return w;
}

// A point along a ray: q = r^2 - bottom^2 (below 0 under the ground), its radius and the
// sun's zenith cosine there.
struct RayPoint {
    q: f32,
    r: f32,
    mu_s: f32,
}

// `point_along`: the point at distance t along the ray from (q, r mu) whose start has
// r mu_s = `r_mu_s` (the start's position . sun) and view-sun cosine `nu`.
fn point_along(q: f32, r_mu: f32, r_mu_s: f32, nu: f32, t: f32) -> RayPoint {
    let bottom = atmosphere.bottom_radius_m;
    var p: RayPoint;
    p.q = q + t * (t + 2.0 * r_mu);
    p.r = safe_sqrt(bottom * bottom + p.q);
    p.mu_s = clamp((r_mu_s + t * nu) / max(p.r, 1.0), -1.0, 1.0);
    return p;
}

// `Medium::densities`: relative densities at q, zero above the top, the ground's below it.
fn medium_densities(q: f32) -> vec3<f32> {
    if q > top_q() {
        return vec3<f32>(0.0);
    }
    return densities(altitude_from_q_clamped(q));
}

// The altitude for r^2 - bottom^2 = q, at least 0, as q / (r + bottom).
fn altitude_from_q_clamped(q: f32) -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    let qc = max(q, 0.0);
    return qc / (sqrt(bottom * bottom + qc) + bottom);
}

// `Medium::sun_transmittance`: transmittance towards a point sun at zenith cosine `mu_s`
// from the table, radii clamped to the atmosphere; 0 where the planet hides the sun.
fn sun_transmittance(q: f32, mu_s: f32) -> vec3<f32> {
    return sun_transmittance_in(q, mu_s, 0.0);
}

// The optical depth of a column (or the extinction at densities `rho`) in the
// similarity-scaled medium of delta fraction `delta` (`similarity::scaled`): Mie's
// extinction less `delta` times its scattering; the true medium's for `delta` = 0.
fn scaled_optical_depth(column_m: vec3<f32>, delta: f32) -> vec3<f32> {
    return optical_depth(column_m) - delta * column_m.y * atmosphere.mie_scattering_per_m.xyz;
}

// `Medium::sun_transmittance_in` the similarity-scaled medium of delta fraction `delta`
// (the table holds columns of matter, so any coefficients read it).
fn sun_transmittance_in(q: f32, mu_s: f32, delta: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let qc = clamp(q, 0.0, top_q());
    let r = sqrt(bottom * bottom + qc);
    let mu = clamp(mu_s, -1.0, 1.0);
    if hits_ground(qc, r * mu) {
        return vec3<f32>(0.0);
    }
    return exp(-scaled_optical_depth(read_table_columns(transmittance_columns, qc, mu), delta));
}

// `distance_to_exit` to the top from (q, r mu) inside the atmosphere, by the product of
// the roots for rising rays.
fn exit_distance(q: f32, r_mu: f32) -> f32 {
    let h2 = top_q();
    let root = safe_sqrt(r_mu * r_mu - q + h2);
    if r_mu > 0.0 {
        return max((h2 - q) / (r_mu + root), 0.0);
    }
    return max(-r_mu + root, 0.0);
}

// The centre of texel i of n mapped to [0, 1], first and last centres on the bounds
// (`unit_from_coord((i + 0.5) / n, n)` = i / (n - 1)).
fn unit_from_texel(i: u32, n: u32) -> f32 {
    return f32(i) / f32(n - 1u);
}
