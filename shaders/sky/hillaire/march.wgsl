// Library: the view ray march of the hillaire model, with the read of the Psi_ms LUT it
// needs, shared by the sky view, the aerial-perspective volume, the ground irradiance and
// the per-pixel pass. CPU twin: atmosphere-core's `models/hillaire/march.rs` and
// `MultipleScattering::lookup` (`models/hillaire/multiple_scattering.rs`). Paper:
// Hillaire 2020, section 5 ("Ray marching") and section 5.5 (Psi_ms): along a view ray
// the light scattered towards the camera at each segment's midpoint is
// sigma_s (T_sun p(nu) + Psi_ms), integrated with `segment_weight`; per unit solar
// irradiance. The Psi_ms LUT is bound at 4 in every shader that marches view rays, and
// read as `common/table_sampling.wgsl` says.

#import sky/hillaire/medium.wgsl
#import common/texel_bilinear.wgsl

@group(0) @binding(4) var psi_ms: texture_2d<f32>;

// `MultipleScattering::lookup`: Psi_ms at a point of radius `r` (r^2 - bottom^2 = q) with
// the sun at zenith cosine `mu_s`, clamped to the table.
fn psi_ms_lookup(q: f32, r: f32, mu_s: f32) -> vec3<f32> {
    let a = atmosphere;
    let size = vec2<f32>(textureDimensions(psi_ms));
    let x = (clamp(mu_s, -1.0, 1.0) + 1.0) * 0.5;
    let y = clamp((q / (r + a.bottom_radius_m)) / (a.top_radius_m - a.bottom_radius_m), 0.0, 1.0);
    if FILTERED_TABLES {
        return sample_2d(psi_ms, vec2<f32>(x, y) * (size - 1.0));
    }
    return texel_bilinear(psi_ms, vec2<f32>(x, y) * (size - 1.0));
}

// A view ray: start (q, r mu, r mu_s), view-sun cosine and the phase functions there.
struct ViewRay {
    q: f32,
    r_mu: f32,
    r_mu_s: f32,
    nu: f32,
    phase_rayleigh: f32,
    phase_mie: f32,
}

fn view_ray(q: f32, r_mu: f32, r_mu_s: f32, nu: f32) -> ViewRay {
    return ViewRay(q, r_mu, r_mu_s, nu, rayleigh_phase(nu), mie_phase(nu));
}

// Radiance so far per unit solar irradiance, and the throughput from the start.
struct ViewMarch {
    radiance: vec3<f32>,
    throughput: vec3<f32>,
}

fn view_march() -> ViewMarch {
    return ViewMarch(vec3<f32>(0.0), vec3<f32>(1.0));
}

// `ViewMarch::segment`: the segment [t_mid - dt/2, t_mid + dt/2] with the medium of its
// midpoint; nothing where the medium is empty.
fn march_segment(ray: ViewRay, m: ptr<function, ViewMarch>, t_mid: f32, dt: f32) {
    let p = point_along(ray.q, ray.r_mu, ray.r_mu_s, ray.nu, t_mid);
    let rho = medium_densities(p.q);
    if all(rho == vec3<f32>(0.0)) {
        return;
    }
    let sun = sun_transmittance(p.q, p.mu_s);
    var psi = vec3<f32>(0.0);
    if hillaire.multiple_on != 0u {
        psi = psi_ms_lookup(p.q, p.r, p.mu_s);
    }
    let s_r = atmosphere.rayleigh_scattering_per_m.xyz * rho.x;
    let s_m = atmosphere.mie_scattering_per_m.xyz * rho.y;
    let source = sun * (s_r * ray.phase_rayleigh + s_m * ray.phase_mie) + psi * (s_r + s_m);
    let w = segment_weight(optical_depth(rho), dt);
    (*m).radiance += (*m).throughput * source * w.integral;
    (*m).throughput *= w.transmittance;
}

// `ViewMarch::run`: `length` metres in `samples` equal segments.
fn march_run(ray: ViewRay, length: f32, samples: u32) -> ViewMarch {
    var m = view_march();
    let dt = length / f32(samples);
    for (var k = 0u; k < samples; k++) {
        march_segment(ray, &m, (f32(k) + 0.5) * dt, dt);
    }
    return m;
}
