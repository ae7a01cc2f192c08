// Library: light shafts in the hillaire pass, the single scattering the terrain's shadow
// and the cloud layer's shadow below its base take out of a view segment. CPU twins:
// atmosphere-core's `models/hillaire/shafts.rs` (`shadowed_single`; the span and its
// samples: `shafts/terrain/view_span.wgsl`) and, with the cloud,
// `clouds/layer/air_shadow.rs` (`AirShadow`); method: docs/shafts.md and docs/clouds.md
// ("Cloud shadows in the air"). Bindings 9 and 10 of the pass: the shadow map's tops
// (R32Float) and its parameters; 35 and 33: the cloud's sun map and its parameters
// (`clouds/sun_map_read.wgsl`).

#import sky/hillaire/medium.wgsl
#import common/frame_params.wgsl
#import shafts/terrain/view_span.wgsl
#import clouds/sun_map_read.wgsl

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

// Whether the frame's sun map shades the air under the layer's base (radii.z).
fn cloud_shafts_on() -> bool {
    return sun_map_params.counts.w == 1u && sun_map_params.radii.z > 0.5;
}

// `AirShadow::span` (and `shaft_span` without the cloud): x, y the part of the segment
// below the higher of the terrain shadow's top and the layer's base, as far as the wider
// of the two maps; z: its samples, two per cell of the finer map.
fn air_span(s: Segment, terrain: bool, clouds: bool) -> vec3<f32> {
    var h = 0.0;
    var width = 0.0;
    var cell = 1e30;
    if terrain {
        h = shadow_map.up_top.w;
        width = shadow_map_width(shadow_map);
        cell = width / f32(shadow_map.size.x);
    }
    if clouds {
        let m = sun_map_params;
        h = max(h, m.radii.x - atmosphere.bottom_radius_m);
        width = max(width, m.east_cell.w * f32(m.counts.x));
        cell = min(cell, m.east_cell.w);
    }
    let span = span_below(s, h, width);
    var samples = shaft_samples(shadow_map, span.y - span.x);
    if clouds {
        samples = samples_per_cell(shadow_map, span.y - span.x, cell);
    }
    return vec3<f32>(span, f32(samples));
}

// `shadowed_single` (with the cloud, `AirShadow::shadowed_single`): per unit solar
// irradiance, in equal segments of the span; the sun's visibility at a sample is the
// terrain's times, below the layer's base, the sun map's transmittance.
fn shafts_loss(s: Segment, direction: vec3<f32>, nu: f32) -> vec3<f32> {
    var loss = vec3<f32>(0.0);
    let terrain = shadow_map.size.y != 0u;
    let clouds = cloud_shafts_on();
    if !terrain && !clouds {
        return loss;
    }
    let part = air_span(s, terrain, clouds);
    let samples = u32(part.z);
    if part.y <= part.x || samples == 0u {
        return loss;
    }
    let dt = (part.y - part.x) / f32(samples);
    let phase_r = rayleigh_phase(nu);
    let phase_m = mie_phase(nu);
    let bottom = atmosphere.bottom_radius_m;
    let base = sun_map_params.radii.x;
    var throughput = shaft_entry_transmittance(s, part.x);
    for (var k = 0u; k < samples; k++) {
        let t = part.x + (f32(k) + 0.5) * dt;
        let p = point_along(s.q, s.r_mu, s.start_dot_sun, nu, t);
        let rho = medium_densities(p.q);
        let altitude = p.q / (p.r + bottom);
        let position = s.start + t * direction;
        var visible = 1.0;
        if terrain {
            visible = shadow_map_visible(shadow_tops, shadow_map, bottom, position, altitude);
        }
        if clouds && visible > 0.0 && p.r < base {
            visible *= cloud_sun_transmittance(position);
        }
        let shadow = 1.0 - visible;
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
