// Entry pass: the cloud layer's shadow in the air below its base, per pixel, for every
// sky model (render-wgpu's `clouds/air_shadow_pass.rs`), run after the sun map's fill
// when the map shades the air: the single scattering that the cloud takes from the
// sun beyond the terrain's shadow, V_terrain (1 - T_cloud), out of the pixel's view
// segment. CPU twin: atmosphere-core's `clouds/layer/air_shadow.rs` (`AirShadow::
// cloud_single`); method: docs/clouds.md, "Cloud shadows in the air". Writes, per
// pixel, the sun map's transmittance at the pixel's surface (copied from what
// `clouds/sun_map_pixels.wgsl` wrote) and that single scattering per unit solar
// irradiance into the image the pixel passes read at 32 (`common/surface.wgsl`); each
// model subtracts it beside its own terrain shafts (`pixel_cloud_air_loss`). The march
// is the light shafts' (`sky/hillaire/shafts.wgsl`) through this pass's own columns
// table at 3; the hillaire uniform that library declares at 2 is not read. The map is
// read here, not inside the models' pixel passes: bound and read there, it crashed
// lavapipe (Mesa 22.3.6) in its worker thread.
// At a resolution divisor above 1 (the layer settings' `air_shadow_divisor`), `reduced`
// marches one ray per block of pixels first, and `main` reads its taps whose span below
// the base ends as far as the pixel's own; where none does it lists the pixel
// (`common/pixel_list.wgsl`) for `listed` to march. CPU twin of that:
// `clouds/layer/air_shadow_upsample.rs`.

#import sky/hillaire/shafts.wgsl
#import clouds/sun_map_read.wgsl
#import common/frame_params.wgsl
#import common/pixel_list.wgsl

// Whether the pixels end on a surface (the pipeline's variant; without one the buffer
// is not read).
override SURFACE: bool = true;

// Whether `main` takes its loss from `reduced`'s taps (the pipeline's variant).
override UPSAMPLE: bool = false;

// `SPAN_TOLERANCE`, `MIN_SAME_WEIGHT` (`air_shadow_upsample.rs`).
const SPAN_TOLERANCE: f32 = 0.25;
const MIN_SAME_WEIGHT: f32 = 0.5;

// xyz: the surface's normal; w: its distance along the pixel's ray, m (0: none).
@group(0) @binding(30) var pixel_geometry: texture_2d<f32>;
@group(0) @binding(34) var pixel_shafts: texture_storage_2d<rgba32float, write>;
// The reduced march: rgb the loss, a the span's far end, m (-1: no span); written by
// `reduced` at 36, read by `main` at 37.
@group(0) @binding(36) var reduced_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(37) var reduced_in: texture_2d<f32>;
// x: the surface's cloud transmittance per pixel, written by `sun_map_pixels.wgsl` before
// this pass; read in the surface's variant and copied. Computed here from the map
// instead, it crashed lavapipe (Mesa 22.3.6) in frames with a surface.
@group(0) @binding(38) var surface_sun: texture_2d<f32>;
// The pixels `main` lists for `listed` to march, and that march's dispatch.
@group(0) @binding(39) var<storage, read_write> march_list: MarchList;
@group(0) @binding(40) var<storage, read_write> list_dispatch: ListDispatch;

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
fn cloud_air_loss(s: Segment, direction: vec3<f32>, nu: f32, part: vec3<f32>) -> vec3<f32> {
    var loss = vec3<f32>(0.0);
    let terrain = shadow_map.size.y != 0u;
    let clouds = cloud_shafts_on();
    let samples = u32(part.z);
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

// Whether the span `part` (`air_span`) holds any air to march.
fn span_holds_air(part: vec3<f32>) -> bool {
    return part.y > part.x && part.z > 0.0;
}

// The surface's distance along full pixel `px`'s ray, m (0: none, or no surface).
fn surface_distance(px: vec2<u32>) -> f32 {
    if !SURFACE {
        return 0.0;
    }
    return max(textureLoad(pixel_geometry, px, 0).w, 0.0);
}

// `axis_taps` (`clouds/layer/upsample.rs`): the two reduced pixels full pixel `x` of an
// axis of `full` reads from an axis of `reduced`, and the weight of the second.
fn axis_taps(x: u32, full: u32, reduced: u32) -> vec3<f32> {
    let last = f32(reduced - 1u);
    let u = clamp((f32(x) + 0.5) * f32(reduced) / f32(full) - 0.5, 0.0, last);
    let i0 = floor(u);
    return vec3<f32>(i0, min(i0 + 1.0, last), u - i0);
}

// `air_shadow_upsample::interpolate`: rgb the loss of full pixel `px`, whose span ends at
// `end`, from the taps of its span; a: their weight (below `MIN_SAME_WEIGHT`: march).
fn upsampled(px: vec2<u32>, end: f32) -> vec4<f32> {
    let full = frame.size_px.xy;
    let low = textureDimensions(reduced_in);
    let tx = axis_taps(px.x, full.x, low.x);
    let ty = axis_taps(px.y, full.y, low.y);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var k = 0u; k < 4u; k++) {
        let right = (k & 1u) == 1u;
        let down = k >= 2u;
        let i = u32(select(tx.x, tx.y, right));
        let j = u32(select(ty.x, ty.y, down));
        let w = select(1.0 - tx.z, tx.z, right) * select(1.0 - ty.z, ty.z, down);
        let tap = textureLoad(reduced_in, vec2<u32>(i, j), 0);
        if w > 0.0 && tap.w >= 0.0 && abs(tap.w - end) <= SPAN_TOLERANCE * end {
            sum += w * tap.xyz;
            weight += w;
        }
    }
    return vec4<f32>(sum / max(weight, 1e-30), weight);
}

// The reduced march: one ray per reduced pixel through `upsample.rs`'s marched
// coordinate, ended on the surface of its nearest full pixel; rgb its loss, a its span's
// far end (-1 where it has none).
@compute @workgroup_size(8, 8)
fn reduced(@builtin(global_invocation_id) id: vec3<u32>) {
    let low = textureDimensions(reduced_out);
    if any(id.xy >= low) {
        return;
    }
    let full = frame.size_px.xy;
    let p = (vec2<f32>(id.xy) + 0.5) * vec2<f32>(full) / vec2<f32>(low) - 0.5;
    let nearest = vec2<u32>(clamp(floor(p + 0.5), vec2<f32>(0.0), vec2<f32>(full - 1u)));
    let direction = pixel_direction_at(p);
    let s = view_segment(direction, surface_distance(nearest));
    var out = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    if s.hit {
        let part = air_span(s, cloud_shafts_on());
        if span_holds_air(part) {
            let nu = dot(direction, frame.sun_direction.xyz);
            out = vec4<f32>(cloud_air_loss(s, direction, nu, part), part.y);
        }
    }
    textureStore(reduced_out, id.xy, out);
}

// The surface's cloud transmittance at full pixel `px` (1 without a surface).
fn surface_transmittance(px: vec2<u32>) -> f32 {
    if !SURFACE {
        return 1.0;
    }
    return textureLoad(surface_sun, px, 0).x;
}

// The loss of full pixel `px` marched along its own ray.
fn marched_loss(px: vec2<u32>) -> vec3<f32> {
    let direction = pixel_direction(px);
    let s = view_segment(direction, surface_distance(px));
    var loss = vec3<f32>(0.0);
    if s.hit {
        let part = air_span(s, cloud_shafts_on());
        if span_holds_air(part) {
            loss = cloud_air_loss(s, direction, dot(direction, frame.sun_direction.xyz), part);
        }
    }
    return loss;
}

// Every pixel: marched, or (`UPSAMPLE`) from the reduced march's taps of the same span,
// else listed for `listed`.
@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= frame.size_px.xy) {
        return;
    }
    var loss = vec3<f32>(0.0);
    if UPSAMPLE {
        let direction = pixel_direction(id.xy);
        let s = view_segment(direction, surface_distance(id.xy));
        if s.hit {
            let part = air_span(s, cloud_shafts_on());
            if span_holds_air(part) {
                let taps = upsampled(id.xy, part.y);
                if taps.w >= MIN_SAME_WEIGHT {
                    loss = taps.xyz;
                } else {
                    list_pixel(id.xy);
                }
            }
        }
    } else {
        loss = marched_loss(id.xy);
    }
    textureStore(pixel_shafts, id.xy, vec4<f32>(surface_transmittance(id.xy), loss));
}

// The pixels `main` listed, marched, each invocation taking every (groups x 256)-th
// entry; dispatched indirectly with the workgroup count `main` wrote.
@compute @workgroup_size(256)
fn listed(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let count = atomicLoad(&march_list.count);
    for (var i = id.x; i < count; i += groups.x * LIST_GROUP) {
        let px = listed_pixel(i);
        textureStore(pixel_shafts, px, vec4<f32>(surface_transmittance(px), marched_loss(px)));
    }
}
