// Entry pass: the multiple-scattering LUT Psi_ms(mu_s, h) of the hillaire model, `main`
// (render-wgpu's `sky/hillaire/`). CPU twin: atmosphere-core's
// `models/hillaire/multiple_scattering.rs` (`transfer`, `MultipleScattering::build`).
// Paper: Hillaire 2020, section 5.5. One workgroup per texel; its 64 threads
// share the sphere's directions (`ms_sqrt_directions`^2 strata of equal solid angle, each
// stratum's centre), as the paper's implementation does, and sum them in workgroup
// memory:
// - L_2nd order = (1 / N) sum over directions of the single scattering (isotropic phase,
//   P_u = 1 / (4 pi)) along the direction plus the ground's Lambertian reflection of the
//   sun where the ray meets it;
// - f_ms = (1 / N) sum of the integral of sigma_s T along each direction;
// - Psi_ms = L_2nd order F_ms = L_2nd order / (1 - f_ms), f_ms bounded by 1 - 1e-6.
// rgb = Psi_ms (sr^-1, per unit solar irradiance) in the three channels, a = 1.

#import sky/hillaire/medium.wgsl

@group(0) @binding(4) var psi_out: texture_storage_2d<rgba32float, write>;

const THREADS: u32 = 64u;
// `MAX_F_MS`.
const MAX_F_MS: f32 = 0.999999;

var<workgroup> l_2nd_sum: array<vec3<f32>, 64>;
var<workgroup> f_ms_sum: array<vec3<f32>, 64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) texel: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let a = atmosphere;
    let size = textureDimensions(psi_out);
    // `MultipleScattering::texel_r_mu_s`, the altitude kept apart from the radius.
    let altitude = (a.top_radius_m - a.bottom_radius_m) * unit_from_texel(texel.y, size.y);
    let q = altitude * (2.0 * a.bottom_radius_m + altitude);
    let r = a.bottom_radius_m + altitude;
    let mu_s = -1.0 + 2.0 * unit_from_texel(texel.x, size.x);
    let sin_s = safe_sqrt(1.0 - mu_s * mu_s);
    let n = hillaire.ms_sqrt_directions;
    let samples = hillaire.ms_samples;

    var l_2nd = vec3<f32>(0.0);
    var f_ms = vec3<f32>(0.0);
    for (var d = lane; d < n * n; d += THREADS) {
        let mu = 1.0 - 2.0 * (f32(d / n) + 0.5) / f32(n);
        let phi = 2.0 * PI * (f32(d % n) + 0.5) / f32(n);
        let sin_v = safe_sqrt(1.0 - mu * mu);
        let r_mu = r * mu;
        let ground = hits_ground(q, r_mu);
        let length = select(exit_distance(q, r_mu), ground_distance(q, r_mu), ground);
        let dt = length / f32(samples);
        let nu = mu * mu_s + sin_v * sin_s * cos(phi);
        var throughput = vec3<f32>(1.0);
        for (var k = 0u; k < samples; k++) {
            let p = point_along(q, r_mu, r * mu_s, nu, (f32(k) + 0.5) * dt);
            let rho = medium_densities(p.q);
            let sun = sun_transmittance(p.q, p.mu_s);
            let w = segment_weight(optical_depth(rho), dt);
            let scattering = (a.rayleigh_scattering_per_m.xyz * rho.x
                + a.mie_scattering_per_m.xyz * rho.y) * throughput * w.integral;
            // Isotropic phase at the first scattering; the sphere's P_u and solid angle
            // give the 1 / N below.
            l_2nd += scattering * sun / (4.0 * PI);
            f_ms += scattering;
            throughput *= w.transmittance;
        }
        if ground {
            let p = point_along(q, r_mu, r * mu_s, nu, length);
            l_2nd += throughput * sun_transmittance(0.0, p.mu_s) * max(p.mu_s, 0.0)
                * a.ground_albedo / PI;
        }
    }
    l_2nd_sum[lane] = l_2nd;
    f_ms_sum[lane] = f_ms;
    workgroupBarrier();
    for (var stride = THREADS / 2u; stride > 0u; stride /= 2u) {
        if lane < stride {
            l_2nd_sum[lane] += l_2nd_sum[lane + stride];
            f_ms_sum[lane] += f_ms_sum[lane + stride];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        let directions = f32(n * n);
        let f = clamp(f_ms_sum[0] / directions, vec3<f32>(0.0), vec3<f32>(MAX_F_MS));
        textureStore(psi_out, texel.xy, vec4<f32>(l_2nd_sum[0] / directions / (1.0 - f), 1.0));
    }
}
