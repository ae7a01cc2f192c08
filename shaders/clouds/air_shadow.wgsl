// Entry pass: the cloud layer's shadow in the air below its base, per pixel, for every
// sky model (render-wgpu's `clouds/air_shadow_pass.rs`), run after the sun map's fill
// when the map shades the air: the single scattering that the cloud takes from the
// sun beyond the terrain's shadow, V_terrain (1 - T_cloud), out of the pixel's view
// segment. CPU twin: atmosphere-core's `clouds/layer/air_shadow.rs` (`AirShadow::
// cloud_single`); method: docs/clouds.md, "Cloud shadows in the air". Writes, per
// pixel, the sun map's transmittance at the pixel's surface (as
// `clouds/sun_map_pixels.wgsl` does) and that single scattering per unit solar
// irradiance into the image the pixel passes read at 32 (`common/surface.wgsl`); each
// model subtracts it beside its own terrain shafts (`pixel_cloud_air_loss`). The march
// is the light shafts' (`sky/hillaire/shafts.wgsl`) through this pass's own columns
// table at 3; the hillaire uniform that library declares at 2 is not read. The map is
// read here, not inside the models' pixel passes: bound and read there, it crashed
// lavapipe (Mesa 22.3.6) in its worker thread.

#import sky/hillaire/shafts.wgsl
#import clouds/sun_map_read.wgsl
#import common/frame_params.wgsl

// Whether the pixels end on a surface (the pipeline's variant; without one the buffer
// is not read).
override SURFACE: bool = true;

// xyz: the surface's normal; w: its distance along the pixel's ray, m (0: none).
@group(0) @binding(30) var pixel_geometry: texture_2d<f32>;
@group(0) @binding(34) var pixel_shafts: texture_storage_2d<rgba32float, write>;

// `AirShadow::span`: x, y the part of the segment below the layer's base, as far as the
// map reaches; z: its samples, two per cell; empty unless the map shades the air
// (`clouds`). Lavapipe (Mesa 22.3.6) crashed running the march with the span taken
// from the map's parameters without that flag.
fn air_span(s: Segment, clouds: bool) -> vec3<f32> {
    var h = 0.0;
    var width = 0.0;
    var cell = 1e30;
    if clouds {
        let m = sun_map_params;
        h = m.radii.x - atmosphere.bottom_radius_m;
        width = m.east_cell.w * f32(m.counts.x);
        cell = m.east_cell.w;
    }
    let span = span_below(s, h, width);
    let samples = samples_per_cell(shadow_map, span.y - span.x, cell);
    return vec3<f32>(span, f32(samples));
}

// `AirShadow::cloud_single`: per unit solar irradiance, in equal segments of the span;
// the cloud's part of the shadow at a sample is the terrain's visibility times one
// less the sun map's transmittance.
fn cloud_air_loss(s: Segment, direction: vec3<f32>, nu: f32) -> vec3<f32> {
    var loss = vec3<f32>(0.0);
    let terrain = shadow_map.size.y != 0u;
    let clouds = cloud_shafts_on();
    let part = air_span(s, clouds);
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
        var shadow = 0.0;
        if clouds && visible > 0.0 && p.r < base {
            shadow = visible * (1.0 - cloud_sun_transmittance(position));
        }
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

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    let direction = pixel_direction(id.xy);
    var distance = 0.0;
    if SURFACE {
        distance = max(textureLoad(pixel_geometry, id.xy, 0).w, 0.0);
    }
    var t = 1.0;
    if distance > 0.0 {
        t = cloud_sun_transmittance(frame.camera_m.xyz + direction * distance);
    }
    let s = view_segment(direction, distance);
    var loss = vec3<f32>(0.0);
    if s.hit {
        loss = cloud_air_loss(s, direction, dot(direction, frame.sun_direction.xyz));
    }
    textureStore(pixel_shafts, id.xy, vec4<f32>(t, loss));
}
