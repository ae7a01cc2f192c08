// Library: light shafts in the hillaire pass, the single scattering the terrain's shadow
// takes out of a view segment. CPU twin: atmosphere-core's `models/hillaire/shafts.rs`
// (`shadowed_single`; the span and its samples: `shafts/terrain/view_span.wgsl`);
// method: docs/shafts.md. Bindings 9 and 10 of the pass: the shadow map's tops (R32Float)
// and its parameters.

#import sky/hillaire/medium.wgsl
#import common/frame_params.wgsl
#import shafts/terrain/view_span.wgsl

@group(0) @binding(9) var shadow_tops: texture_2d<f32>;
@group(0) @binding(10) var<uniform> shadow_map: ShadowMapParams;

// The transmittance from the segment's start to `entry` along it, a descending ray read
// looking up from both ends in the columns table (`segment_column` with `ground`).
fn shaft_entry_transmittance(s: Segment, entry: f32) -> vec3<f32> {
    if entry <= 0.0 {
        return vec3<f32>(1.0);
    }
    let bottom = atmosphere.bottom_radius_m;
    let r = sqrt(bottom * bottom + s.q);
    let q_e = s.q + entry * (entry + 2.0 * s.r_mu);
    let r_e = sqrt(bottom * bottom + q_e);
    let near = read_table_columns(transmittance_columns, s.q, clamp(-s.r_mu / r, -1.0, 1.0));
    let far = read_table_columns(transmittance_columns, q_e, clamp(-(s.r_mu + entry) / r_e, -1.0, 1.0));
    return exp(-optical_depth(max(far - near, vec3<f32>(0.0))));
}

// `shadowed_single`: per unit solar irradiance, in `shaft_samples` equal segments of the
// span.
fn shafts_loss(s: Segment, direction: vec3<f32>, nu: f32) -> vec3<f32> {
    var loss = vec3<f32>(0.0);
    if shadow_map.size.y == 0u {
        return loss;
    }
    let span = shaft_span(shadow_map, s);
    if span.y <= span.x {
        return loss;
    }
    let samples = shaft_samples(shadow_map, span.y - span.x);
    let dt = (span.y - span.x) / f32(samples);
    let phase_r = rayleigh_phase(nu);
    let phase_m = mie_phase(nu);
    let bottom = atmosphere.bottom_radius_m;
    var throughput = shaft_entry_transmittance(s, span.x);
    for (var k = 0u; k < samples; k++) {
        let t = span.x + (f32(k) + 0.5) * dt;
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
