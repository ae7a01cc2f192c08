// Entry pass: the sky's irradiance at the ground E_sky(mu_s) / E_sun of the hillaire
// model, `main` (render-wgpu's `sky/hillaire/`). CPU twin: atmosphere-core's
// `models/hillaire/ground.rs` (`sky_irradiance`, `GroundIrradiance::build`). Paper:
// Hillaire 2020, section 5 (the lit planet surface). Value i of n lies at
// x = -1 + 2 i / (n - 1), mu_s = x |x|; each is the cosine-weighted integral of the view
// march's radiance (single scattering plus Psi_ms) over the upper hemisphere: panels of
// 8-point Gauss-Legendre in the zenith cosine times azimuths over half the circle,
// counted twice (the sky is symmetric about the sun's vertical plane). One workgroup per
// value; its 64 threads share the rays and sum them in workgroup memory. rgb per
// channel, a = 1, in an n x 1 texture.

#import sky/hillaire/march.wgsl
#import sky/hillaire/directions.wgsl

@group(0) @binding(5) var ground_out: texture_storage_2d<rgba32float, write>;

const THREADS: u32 = 64u;

// `GAUSS_LEGENDRE_8` on [-1, 1].
const GL8_NODES = array<f32, 8>(-0.9602898564975362, -0.7966664774136267, -0.525532409916329, -0.1834346424956498, 0.1834346424956498, 0.525532409916329, 0.7966664774136267, 0.9602898564975362);
const GL8_WEIGHTS = array<f32, 8>(0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.362683783378362, 0.362683783378362, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763);

var<workgroup> irradiance_sum: array<vec3<f32>, 64>;

@compute @workgroup_size(64)
fn main(@builtin(workgroup_id) value: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let bottom = atmosphere.bottom_radius_m;
    let x = -1.0 + 2.0 * unit_from_texel(value.x, textureDimensions(ground_out).x);
    let mu_s = x * abs(x);
    let panels = hillaire.ground_zenith_panels;
    let azimuths = hillaire.ground_azimuths;
    let d_phi = PI / f32(azimuths);
    var e = vec3<f32>(0.0);
    for (var ray = lane; ray < panels * 8u * azimuths; ray += THREADS) {
        let panel = ray / (8u * azimuths);
        let node = (ray / azimuths) % 8u;
        let k = ray % azimuths;
        // `mapped(&GAUSS_LEGENDRE_8, lo, hi)` on the panel [lo, hi] of [0, 1].
        let half_width = 0.5 / f32(panels);
        let mid = (f32(panel) + 0.5) / f32(panels);
        let mu = mid + half_width * GL8_NODES[node];
        let weight = half_width * GL8_WEIGHTS[node];
        let phi = (f32(k) + 0.5) * d_phi;
        let nu = view_sun_cosine(mu, phi, mu_s);
        let r_mu = bottom * mu;
        let m = march_run(view_ray(0.0, r_mu, bottom * mu_s, nu), exit_distance(0.0, r_mu),
            hillaire.sky_view_samples);
        e += m.radiance * (mu * weight * 2.0 * d_phi);
    }
    irradiance_sum[lane] = e;
    workgroupBarrier();
    for (var stride = THREADS / 2u; stride > 0u; stride /= 2u) {
        if lane < stride {
            irradiance_sum[lane] += irradiance_sum[lane + stride];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        textureStore(ground_out, vec2<u32>(value.x, 0u), vec4<f32>(irradiance_sum[0], 1.0));
    }
}
