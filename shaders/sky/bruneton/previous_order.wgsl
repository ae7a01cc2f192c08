// The radiance field of the previous scattering order as the tables hold it, and the
// light arriving at a point from a direction: the GPU twins of
// `Builder::previous_radiance` and `Builder::incoming` (atmosphere-core
// `bruneton/precompute.rs`). Order 2 (`previous_is_single`) reads single scattering with
// the phase functions applied and lights the ground with direct sunlight; later orders
// read Delta S and Delta E of the order before.

#import sky/bruneton/tables.wgsl
#import common/phase.wgsl

// Radiance of the previous order seen from (q, r) along mu towards nu, sky part only.
fn previous_radiance(q: f32, r: f32, mu: f32, mu_s: f32, nu: f32, ground: bool) -> vec3<f32> {
    let p = table_position(q, r, r * mu, mu_s, nu, ground);
    if bruneton.previous_is_single == 1u {
        var l = rayleigh_phase(nu) * table4(bruneton.single_rayleigh_offset, p);
        if bruneton.mie_on == 1u {
            l += mie_phase(nu) * table4(bruneton.single_mie_offset, p);
        }
        return l;
    }
    return table4(bruneton.delta_s_offset, p);
}

// Radiance of the previous order arriving at (q, r) from direction (mu, nu): its
// scattered light plus, for directions towards the ground, the ground's reflection of
// the irradiance of the order before, attenuated.
fn incoming(q: f32, r: f32, mu: f32, mu_s: f32, nu: f32, ground: bool) -> vec3<f32> {
    var l = previous_radiance(q, r, mu, mu_s, nu, ground);
    if ground {
        let bottom = atmosphere.bottom_radius_m;
        let d = ground_distance(q, r * mu);
        let mu_s_g = clamp((r * mu_s + d * nu) / bottom, -1.0, 1.0);
        var e: vec3<f32>;
        if bruneton.previous_is_single == 1u {
            e = sun_transmittance(0.0, bottom, mu_s_g) * max(mu_s_g, 0.0);
        } else {
            e = irradiance_at(bruneton.delta_e_offset, 0.0, bottom, mu_s_g);
        }
        let t = exp(-optical_depth(segment_column(q, r, r * mu, d, true)));
        l += t * (atmosphere.ground_albedo / PI) * e;
    }
    return l;
}

// The 8-point Gauss-Legendre rule on [-1, 1] (`GAUSS_LEGENDRE_8`).
const GL8_NODES = array<f32, 8>(-0.9602898564975362, -0.7966664774136267, -0.525532409916329, -0.1834346424956498, 0.1834346424956498, 0.525532409916329, 0.7966664774136267, 0.9602898564975362);
const GL8_WEIGHTS = array<f32, 8>(0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.362683783378362, 0.362683783378362, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763);

// Zenith angle node k (of 8 per panel) of the composite rule over [a, b] with `panels`
// panels: x = angle, y = weight (`Builder::theta_nodes`).
fn theta_node(a: f32, b: f32, panels: u32, index: u32) -> vec2<f32> {
    let step = (b - a) / f32(panels);
    let lo = a + step * f32(index / 8u);
    let k = index % 8u;
    return vec2<f32>(lo + 0.5 * step * (1.0 + GL8_NODES[k]), 0.5 * step * GL8_WEIGHTS[k]);
}
