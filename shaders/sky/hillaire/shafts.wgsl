// Library: light shafts in the hillaire pass, the single scattering the terrain's shadow
// takes out of a view segment. CPU twin: atmosphere-core's `models/hillaire/shafts.rs`
// (`shadowed_single`, `shaft_reach_m`); method: docs/shafts.md. Bindings 9 and 10 of
// the pass: the shadow map's tops (R32Float) and its parameters.

#import sky/hillaire/medium.wgsl
#import common/frame_params.wgsl
#import shafts/terrain/shadow_map.wgsl

@group(0) @binding(9) var shadow_tops: texture_2d<f32>;
@group(0) @binding(10) var<uniform> shadow_map: ShadowMapParams;

// `shaft_reach_m`: from the segment's start to where it last leaves the sphere of the
// shadow volume's top, at most the map's width and the segment; (r - top)(r + top)
// written as q - h (2 bottom + h) for f32.
fn shaft_reach(s: Segment) -> f32 {
    let h = shadow_map.up_top.w;
    let disc = s.r_mu * s.r_mu - (s.q - h * (2.0 * atmosphere.bottom_radius_m + h));
    if disc < 0.0 {
        return 0.0;
    }
    let width = shadow_map.east_cell.w * f32(shadow_map.size.x);
    return clamp(-s.r_mu + sqrt(disc), 0.0, min(s.length, width));
}

// `shadowed_single`: per unit solar irradiance, in `size.z` equal segments of the reach.
fn shafts_loss(s: Segment, direction: vec3<f32>, nu: f32) -> vec3<f32> {
    var loss = vec3<f32>(0.0);
    if shadow_map.size.y == 0u {
        return loss;
    }
    let reach = shaft_reach(s);
    if reach <= 0.0 {
        return loss;
    }
    let samples = shadow_map.size.z;
    let dt = reach / f32(samples);
    let phase_r = rayleigh_phase(nu);
    let phase_m = mie_phase(nu);
    let bottom = atmosphere.bottom_radius_m;
    var throughput = vec3<f32>(1.0);
    for (var k = 0u; k < samples; k++) {
        let t = (f32(k) + 0.5) * dt;
        let p = point_along(s.q, s.r_mu, s.start_dot_sun, nu, t);
        let rho = medium_densities(p.q);
        let altitude = p.q / (p.r + bottom);
        let position = s.start + t * direction;
        let shadow = 1.0 - shadow_map_visible(shadow_tops, shadow_map, bottom, position, altitude);
        let w = segment_weight(optical_depth(rho), dt);
        if shadow > 0.0 {
            let s_r = atmosphere.rayleigh_scattering_per_m.xyz * rho.x;
            let s_m = atmosphere.mie_scattering_per_m.xyz * rho.y;
            let single = sun_transmittance(p.q, p.mu_s) * (s_r * phase_r + s_m * phase_m);
            loss += throughput * shadow * single * w.integral;
        }
        throughput *= w.transmittance;
    }
    return loss;
}
