// Library: the view ray march of the hillaire model, with the read of the Psi_ms LUT it
// needs, shared by the sky view, the aerial-perspective volume, the ground irradiance and
// the per-pixel pass. CPU twin: atmosphere-core's `models/hillaire/march.rs` and
// `MultipleScattering::lookup` (`models/hillaire/multiple_scattering.rs`). Paper:
// Hillaire 2020, section 5 ("Ray marching") and section 5.5 (Psi_ms): along a view ray
// the light scattered towards the camera at each segment's midpoint is
// sigma_s (T_sun p(nu) + Psi_ms), integrated with `segment_weight`; per unit solar
// irradiance. With `ms_order` above 0 the Psi_ms term is the anisotropic one of
// `models/hillaire/moments.rs`. With `ms_delta` above 0 (`models/hillaire/similarity.rs`)
// the light travels through the similarity-scaled medium: the sun's transmittance and
// the throughput to the camera are the scaled medium's, Psi_ms scatters with Mie
// scattering times 1 - ms_delta, and the throughput the march reports stays the true
// one. The Psi_ms LUT is bound at 4 in every shader that marches view rays, and
// read as `common/table_sampling.wgsl` says.

#import sky/hillaire/medium.wgsl
#import common/texel_bilinear.wgsl

@group(0) @binding(4) var psi_ms: texture_2d<f32>;

// `MultipleScattering::lookup`: moment `block` of Psi_ms (0: Psi_ms itself) at a point of
// radius `r` (r^2 - bottom^2 = q) with the sun at zenith cosine `mu_s`, clamped to the
// table; the texture stacks `psi_blocks()` blocks of rows.
fn psi_ms_lookup(q: f32, r: f32, mu_s: f32, block: u32) -> vec3<f32> {
    let a = atmosphere;
    let dims = textureDimensions(psi_ms);
    let rows = dims.y / psi_blocks();
    let size = vec2<f32>(f32(dims.x), f32(rows));
    let x = (clamp(mu_s, -1.0, 1.0) + 1.0) * 0.5;
    let y = clamp((q / (r + a.bottom_radius_m)) / (a.top_radius_m - a.bottom_radius_m), 0.0, 1.0);
    let f = vec2<f32>(x, y) * (size - 1.0) + vec2<f32>(0.0, f32(block * rows));
    if FILTERED_TABLES {
        return sample_2d(psi_ms, f);
    }
    return texel_bilinear(psi_ms, f);
}

// A view ray: start (q, r mu, r mu_s), view-sun cosine and the phase functions there;
// for the anisotropic term, Rayleigh's weight of Psi_2, 5 g_2 P_2(nu) with g_2 = 1/10.
struct ViewRay {
    q: f32,
    r_mu: f32,
    r_mu_s: f32,
    nu: f32,
    phase_rayleigh: f32,
    phase_mie: f32,
    rayleigh_2: f32,
}

fn view_ray(q: f32, r_mu: f32, r_mu_s: f32, nu: f32) -> ViewRay {
    let rayleigh_2 = 0.25 * (3.0 * nu * nu - 1.0);
    return ViewRay(q, r_mu, r_mu_s, nu, rayleigh_phase(nu), mie_phase(nu), rayleigh_2);
}

// `moments::MAX_LOBE_G`.
const MAX_LOBE_G: f32 = 0.99;

// `moments::source`: the multiple-scattering source of the Psi_ms blocks at a sample whose
// view direction has zenith cosine `mu`: Rayleigh's two-moment sum plus Mie's lobe
// (`moments::lobe`) and, with ms_order 2, the zenith's second moment less the sun's
// share of it, per channel; Mie's part clamped at 0.
fn anisotropic_source(ray: ViewRay, p: RayPoint, mu: f32, psi_0: vec3<f32>, s_r: vec3<f32>, s_m: vec3<f32>) -> vec3<f32> {
    let zero = vec3<f32>(0.0);
    let psi_1 = psi_ms_lookup(p.q, p.r, p.mu_s, 1u);
    var psi_2 = zero;
    var zenith = zero;
    if hillaire.ms_order >= 2u {
        psi_2 = psi_ms_lookup(p.q, p.r, p.mu_s, 2u);
        let psi_2z = psi_ms_lookup(p.q, p.r, p.mu_s, 3u);
        let p2_s = 0.5 * (3.0 * p.mu_s * p.mu_s - 1.0);
        zenith = 5.0 * (psi_2z - psi_2 * p2_s) * (0.5 * (3.0 * mu * mu - 1.0));
    }
    let dark = psi_0 <= zero;
    let r1 = select(clamp(psi_1 / psi_0, vec3<f32>(-MAX_LOBE_G), vec3<f32>(MAX_LOBE_G)), zero, dark);
    let fitted = clamp(psi_2 / psi_0 / r1, r1, vec3<f32>(MAX_LOBE_G));
    let g_f = select(r1, fitted, (r1 > zero) & vec3<bool>(hillaire.ms_order >= 2u));
    let a = select(zero, r1 / g_f, g_f != zero);
    let g = g_f * hillaire.mie_g1;
    let d = 1.0 + g * g - 2.0 * g * ray.nu;
    let lobe = (1.0 - g * g) / (d * sqrt(d));
    let rayleigh = psi_0 + ray.rayleigh_2 * psi_2 + 0.1 * zenith;
    let mie = psi_0 * ((1.0 - a) + a * lobe) + hillaire.mie_g2 * zenith;
    return s_r * rayleigh + s_m * max(mie, zero);
}

// Radiance so far per unit solar irradiance and the throughput from the start. With
// `ms_delta` above 0 a segment updates the throughput of the similarity-scaled medium and
// the Mie column marched (m) instead, and `march_throughput` gives the true throughput.
struct ViewMarch {
    radiance: vec3<f32>,
    throughput: vec3<f32>,
    mie_column_m: f32,
}

fn view_march() -> ViewMarch {
    return ViewMarch(vec3<f32>(0.0), vec3<f32>(1.0), 0.0);
}

// `ViewMarch::throughput`: the true medium's throughput. The product over segments of
// exp(-sigma_t dt) is that of exp(-sigma_t' dt) times exp(-ms_delta sigma_s,Mie times the
// Mie column), the extinction the scaling took out: one exponential for the whole march
// in place of one per segment.
fn march_throughput(m: ViewMarch) -> vec3<f32> {
    if hillaire.ms_delta > 0.0 {
        let removed = hillaire.ms_delta * atmosphere.mie_scattering_per_m.xyz * m.mie_column_m;
        return m.throughput * exp(-removed);
    }
    return m.throughput;
}

// `ViewMarch::segment`: the segment [t_mid - dt/2, t_mid + dt/2] with the medium of its
// midpoint; nothing where the medium is empty.
fn march_segment(ray: ViewRay, m: ptr<function, ViewMarch>, t_mid: f32, dt: f32) {
    let p = point_along(ray.q, ray.r_mu, ray.r_mu_s, ray.nu, t_mid);
    let rho = medium_densities(p.q);
    if all(rho == vec3<f32>(0.0)) {
        return;
    }
    let delta = hillaire.ms_delta;
    let sun = sun_transmittance_in(p.q, p.mu_s, delta);
    let s_r = atmosphere.rayleigh_scattering_per_m.xyz * rho.x;
    let s_m = atmosphere.mie_scattering_per_m.xyz * rho.y;
    var multiple = vec3<f32>(0.0);
    if hillaire.multiple_on != 0u {
        let psi_0 = psi_ms_lookup(p.q, p.r, p.mu_s, 0u);
        if hillaire.ms_order == 0u {
            multiple = psi_0 * (s_r + (1.0 - delta) * s_m);
        } else {
            let mu = clamp((ray.r_mu + t_mid) / p.r, -1.0, 1.0);
            multiple = anisotropic_source(ray, p, mu, psi_0, s_r, s_m);
        }
    }
    let source = sun * (s_r * ray.phase_rayleigh + s_m * ray.phase_mie) + multiple;
    let w = segment_weight(scaled_optical_depth(rho, delta), dt);
    (*m).radiance += (*m).throughput * source * w.integral;
    (*m).throughput *= w.transmittance;
    (*m).mie_column_m += rho.y * dt;
}

// `ViewMarch::run`: `length` metres in `samples` equal segments; the true throughput.
fn march_run(ray: ViewRay, length: f32, samples: u32) -> ViewMarch {
    var m = view_march();
    let dt = length / f32(samples);
    for (var k = 0u; k < samples; k++) {
        march_segment(ray, &m, (f32(k) + 0.5) * dt, dt);
    }
    m.throughput = march_throughput(m);
    m.mie_column_m = 0.0;
    return m;
}
