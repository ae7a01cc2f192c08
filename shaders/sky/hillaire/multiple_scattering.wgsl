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
// With `ms_order` above 0 (CPU twin: `models/hillaire/moments.rs`, `psi_moments`) the
// directions crowd around the sun, the first scattering has the medium's phase functions,
// and block l of rows (l = 0..ms_order) holds Psi_l = mean of L P_l(c) / (1 - f_l); with
// ms_order 2 a fourth block holds the second moment about the zenith, mean of L P_2(mu)
// / (1 - f_2).
// With `ms_delta` above 0 (`models/hillaire/similarity.rs`) the medium is the
// similarity-scaled one: Mie scattering times 1 - ms_delta, extinction and the sun's
// transmittance less ms_delta times Mie scattering (ms_order is then 0; ms_delta is 0
// otherwise).

#import sky/hillaire/medium.wgsl

@group(0) @binding(4) var psi_out: texture_storage_2d<rgba32float, write>;

const THREADS: u32 = 64u;
// `MAX_F_MS`.
const MAX_F_MS: f32 = 0.999999;
// `moments::blocks(MAX_ORDER)`.
const BLOCKS: u32 = 4u;

// Per lane, per moment block: the sum over its directions of L P_l (the paper's
// L_2nd order in block 0) and of the transfer f_l.
var<workgroup> mean_sum: array<array<vec3<f32>, BLOCKS>, THREADS>;
var<workgroup> transfer_sum: array<array<vec3<f32>, BLOCKS>, THREADS>;

// A texel's point: radius, r^2 - bottom^2 and the sun's zenith cosine.
struct Texel {
    r: f32,
    q: f32,
    mu_s: f32,
}

// The light of one direction from the texel's point (zenith cosine `mu`, sun cosine
// `nu`), marched to the ground or the top: the once-scattered light with the phase
// functions `phase_r`, `phase_m` at the first scattering plus the ground's reflection of
// the sun; and the integrals of sigma_s g_l T along it, g_l the phase moments of block l.
struct DirectionLight {
    radiance: vec3<f32>,
    returned: array<vec3<f32>, BLOCKS>,
}

fn direction_light(t: Texel, mu: f32, nu: f32, phase_r: f32, phase_m: f32) -> DirectionLight {
    let a = atmosphere;
    let r_mu = t.r * mu;
    let ground = hits_ground(t.q, r_mu);
    let length = select(exit_distance(t.q, r_mu), ground_distance(t.q, r_mu), ground);
    let dt = length / f32(hillaire.ms_samples);
    var light = DirectionLight(vec3<f32>(0.0), array<vec3<f32>, BLOCKS>());
    var throughput = vec3<f32>(1.0);
    let delta = hillaire.ms_delta;
    for (var k = 0u; k < hillaire.ms_samples; k++) {
        let p = point_along(t.q, r_mu, t.r * t.mu_s, nu, (f32(k) + 0.5) * dt);
        let rho = medium_densities(p.q);
        let sun = sun_transmittance_in(p.q, p.mu_s, delta);
        let w = segment_weight(scaled_optical_depth(rho, delta), dt);
        let s_r = a.rayleigh_scattering_per_m.xyz * rho.x;
        let s_m = (1.0 - delta) * a.mie_scattering_per_m.xyz * rho.y;
        let reach = throughput * w.integral;
        light.radiance += (s_r * phase_r + s_m * phase_m) * sun * reach;
        // All blocks, unrolled: a loop here would count against lavapipe's loop trips.
        light.returned[0] += (s_r + s_m) * reach;
        light.returned[1] += s_m * hillaire.mie_g1 * reach;
        light.returned[2] += (0.1 * s_r + s_m * hillaire.mie_g2) * reach;
        light.returned[3] = light.returned[2];
        throughput *= w.transmittance;
    }
    if ground {
        let p = point_along(t.q, r_mu, t.r * t.mu_s, nu, length);
        light.radiance += throughput * sun_transmittance_in(0.0, p.mu_s, delta) * max(p.mu_s, 0.0)
            * a.ground_albedo / PI;
    }
    return light;
}

// The paper's sphere (`transfer`): equal solid angle strata about the zenith, isotropic
// phase at the first scattering; this lane's sums in block 0.
fn isotropic_lane(t: Texel, lane: u32) {
    let n = hillaire.ms_sqrt_directions;
    let sin_s = safe_sqrt(1.0 - t.mu_s * t.mu_s);
    var l_2nd = vec3<f32>(0.0);
    var f_ms = vec3<f32>(0.0);
    for (var d = lane; d < n * n; d += THREADS) {
        let mu = 1.0 - 2.0 * (f32(d / n) + 0.5) / f32(n);
        let phi = 2.0 * PI * (f32(d % n) + 0.5) / f32(n);
        let nu = mu * t.mu_s + safe_sqrt(1.0 - mu * mu) * sin_s * cos(phi);
        // Isotropic phase at the first scattering; the sphere's P_u and solid angle give
        // the 1 / N of the store.
        let light = direction_light(t, mu, nu, 1.0 / (4.0 * PI), 1.0 / (4.0 * PI));
        l_2nd += light.radiance;
        f_ms += light.returned[0];
    }
    mean_sum[lane][0] = l_2nd / f32(n * n);
    transfer_sum[lane][0] = f_ms / f32(n * n);
}

// `psi_moments`: directions about the sun (`moments::sun_direction`), the medium's
// phase functions at the first scattering; this lane's sums in blocks 0..=ms_order.
fn moments_lane(t: Texel, lane: u32) {
    let n = hillaire.ms_sqrt_directions;
    let blocks = psi_blocks();
    let sin_s = safe_sqrt(1.0 - t.mu_s * t.mu_s);
    var mean = array<vec3<f32>, BLOCKS>();
    var transfer = array<vec3<f32>, BLOCKS>();
    for (var d = lane; d < n * n; d += THREADS) {
        let u = (f32(d / n) + 0.5) / f32(n);
        let c = 1.0 - 2.0 * u * u;
        let psi = 2.0 * PI * (f32(d % n) + 0.5) / f32(n);
        let mu = clamp(c * t.mu_s - safe_sqrt(1.0 - c * c) * cos(psi) * sin_s, -1.0, 1.0);
        let weight = 2.0 * u / f32(n * n);
        let light = direction_light(t, mu, c, rayleigh_phase(c), mie_phase(c));
        let p = array<f32, BLOCKS>(1.0, c, 0.5 * (3.0 * c * c - 1.0), 0.5 * (3.0 * mu * mu - 1.0));
        for (var l = 0u; l < blocks; l++) {
            mean[l] += weight * light.radiance * p[l];
            transfer[l] += weight * light.returned[l];
        }
    }
    mean_sum[lane] = mean;
    transfer_sum[lane] = transfer;
}

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) texel: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let a = atmosphere;
    let blocks = psi_blocks();
    let size = vec2<u32>(textureDimensions(psi_out).x, textureDimensions(psi_out).y / blocks);
    // `MultipleScattering::texel_r_mu_s`, the altitude kept apart from the radius.
    let altitude = (a.top_radius_m - a.bottom_radius_m) * unit_from_texel(texel.y, size.y);
    let t = Texel(
        a.bottom_radius_m + altitude,
        altitude * (2.0 * a.bottom_radius_m + altitude),
        -1.0 + 2.0 * unit_from_texel(texel.x, size.x),
    );
    if hillaire.ms_order == 0u {
        isotropic_lane(t, lane);
    } else {
        moments_lane(t, lane);
    }
    workgroupBarrier();
    for (var stride = THREADS / 2u; stride > 0u; stride /= 2u) {
        if lane < stride {
            for (var l = 0u; l < blocks; l++) {
                mean_sum[lane][l] += mean_sum[lane + stride][l];
                transfer_sum[lane][l] += transfer_sum[lane + stride][l];
            }
        }
        workgroupBarrier();
    }
    if lane < blocks {
        let f = clamp(transfer_sum[0][lane], vec3<f32>(-MAX_F_MS), vec3<f32>(MAX_F_MS));
        let at = vec2<u32>(texel.x, texel.y + lane * size.y);
        textureStore(psi_out, at, vec4<f32>(mean_sum[0][lane] / (1.0 - f), 1.0));
    }
}
