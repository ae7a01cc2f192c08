// Library: the rain and ice volumes marched along a pixel's ray and composited
// (render-wgpu's `precipitation/volumes_pass.rs`). CPU twin: atmosphere-core's
// `hydrometeors/render.rs`, which states the method: single scattering in MARCH_STEPS steps, the phase function at
// the frame's wavelengths from the buffer (linear between bin centres; by scattering
// angle, or over the sky for falling plates; truncated where the forward peak counts
// as no scattering, with each channel's extinction beta (1 - f_c)), the sun's path in
// the volume, the sun's light scattered more than once from the volume's probes
// (`sun_orders.wgsl`, read once per ORDERS_EVERY steps at their group's middle), the
// sky's light (one radiance) scattered isotropically; with L_front = (1 - T_front) L_full,
// L = L_front + T_v (L_full - L_front) + T_front L_v, farthest volume first, kept as
// the terms L = A L_full + B (`CompositeTerms`). Declares the bindings both volumes
// passes read.

#import common/frame_params.wgsl
#import precipitation/volume_params.wgsl
#import precipitation/sun_orders.wgsl

const MARCH_STEPS: u32 = 12u;
const FRONT_STEPS: u32 = 8u;
const ORDERS_EVERY: u32 = 3u;

@group(0) @binding(2) var<uniform> volumes: VolumesParams;
// Every volume's phase function, rgb per bin.
@group(0) @binding(3) var<storage, read> phase: array<vec4<f32>>;
// w: the distance to the frame's surface, m (0: none).
@group(0) @binding(5) var surface: texture_2d<f32>;

fn phase_at(v: VolumeParams, angle_deg: f32) -> vec3<f32> {
    let last = f32(v.kind.z - 1u);
    let x = clamp(angle_deg / v.bin_deg.x - 0.5, 0.0, last);
    let i = min(u32(floor(x)), v.kind.z - 2u);
    let f = x - f32(i);
    let first = v.kind.y + i;
    return mix(phase[first].rgb, phase[first + 1u].rgb, f);
}

// The value for light seen along `d` from a table over the sky: bilinear in the
// elevation above the camera's horizon and the azimuth from the sun's (atan2, as the CPU
// twin's `sky_angles_deg`), linear between bin centres.
fn sky_phase_at(v: VolumeParams, d: vec3<f32>, sun: vec3<f32>) -> vec3<f32> {
    let up = normalize(frame.camera_m.xyz);
    let z = dot(d, up);
    let flat = d - up * z;
    let sun_flat = sun - up * dot(sun, up);
    let elevation = degrees(atan2(z, length(flat)));
    var azimuth = 0.0;
    if length(flat) * length(sun_flat) >= 1e-12 {
        azimuth = degrees(atan2(abs(dot(cross(flat, sun_flat), up)), dot(flat, sun_flat)));
    }
    let columns = v.kind.w;
    let rows = v.kind.z / columns;
    let x = clamp((elevation + 90.0) / v.bin_deg.x - 0.5, 0.0, f32(rows - 1u));
    let y = clamp(azimuth / v.bin_deg.y - 0.5, 0.0, f32(columns - 1u));
    let i = min(u32(floor(x)), rows - 2u);
    let j = min(u32(floor(y)), columns - 2u);
    let s = x - f32(i);
    let t = y - f32(j);
    let first = v.kind.y + i * columns + j;
    let low = mix(phase[first].rgb, phase[first + 1u].rgb, t);
    let high = mix(phase[first + columns].rgb, phase[first + columns + 1u].rgb, t);
    return mix(low, high, s);
}

// The angle between unit vectors `a` and `b`, degrees, within 2e-8 rad: Abramowitz and
// Stegun 1964, Eq. 4.4.46, arccos x = sqrt(1 - x) P7(x) on [0, 1], with 1 -+ cos taken
// as |a -+ b|^2 / 2 so that nothing cancels. The shader's own acos is not accurate
// enough at the bows' sharp edges (docs/optics-rendering.md).
fn angle_deg(a: vec3<f32>, b: vec3<f32>) -> f32 {
    let c = clamp(dot(a, b), -1.0, 1.0);
    let x = abs(c);
    let p = 1.5707963050 + x * (-0.2145988016 + x * (0.0889789874 + x * (-0.0501743046
        + x * (0.0308918810 + x * (-0.0170881256 + x * (0.0066700901 - x * 0.0012624911))))));
    if c >= 0.0 {
        let e = a - b;
        return degrees(sqrt(0.5 * dot(e, e)) * p);
    }
    let e = a + b;
    return degrees(3.141592654 - sqrt(0.5 * dot(e, e)) * p);
}

// The atmosphere's transmittance from the camera over `distance_m` along `d`.
fn front_transmittance(d: vec3<f32>, distance_m: f32) -> vec3<f32> {
    let camera = frame.camera_m.xyz;
    // t = distance s^2: the midpoint rule in s, steps short near the camera.
    let ds = 1.0 / f32(FRONT_STEPS);
    var column = vec3<f32>(0.0);
    for (var k = 0u; k < FRONT_STEPS; k++) {
        let s = (f32(k) + 0.5) * ds;
        let x = camera + d * (distance_m * s * s);
        column += 2.0 * distance_m * s * ds * densities(length(x) - atmosphere.bottom_radius_m);
    }
    return exp(-optical_depth(column));
}

struct Met {
    entry: f32,
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

fn march(v: VolumeParams, d: vec3<f32>, t: vec2<f32>) -> Met {
    let camera = frame.camera_m.xyz;
    let sun = frame.sun_direction.xyz;
    let b = dot(camera, d);
    let beta = v.extinction.xyz;
    let dt = (t.y - t.x) / f32(MARCH_STEPS);
    let step_t = exp(-beta * dt);
    var p: vec3<f32>;
    if v.kind.w == 0u {
        p = phase_at(v, angle_deg(d, sun));
    } else {
        p = sky_phase_at(v, d, sun);
    }
    var radiance = vec3<f32>(0.0);
    var t_v = vec3<f32>(1.0);
    var orders = vec3<f32>(0.0);
    for (var k = 0u; k < MARCH_STEPS; k++) {
        let s = t.x + (f32(k) + 0.5) * dt;
        let lit = exp(-beta * sun_path(v, d, b, s, camera, sun));
        if k % ORDERS_EVERY == 0u {
            let group = f32(min(ORDERS_EVERY, MARCH_STEPS - k));
            orders = orders_source(v, d, b, t.x + (f32(k) + 0.5 * group) * dt, sun, -d);
        }
        radiance += t_v * (1.0 - step_t)
            * (v.sun_irradiance.xyz * (p * lit + orders) + v.sky_radiance.xyz);
        t_v *= step_t;
    }
    return Met(t.x, radiance, t_v);
}

// L = times_full L_full + added per channel.
struct Terms {
    times_full: vec3<f32>,
    added: vec3<f32>,
}

// Where pixel `px`'s ray ends: the frame's surface there (the pixel clamped to the
// frame), else far away.
fn max_distance(px: vec2<u32>) -> f32 {
    if volumes.count.y == 1u {
        let distance = textureLoad(surface, min(px, frame.size_px.xy - vec2<u32>(1u)), 0).w;
        if distance > 0.0 {
            return distance;
        }
    }
    return 3.0e38;
}

// The ray along `d` ended at `max_t` through the volumes: its nearest entry and its
// whole length inside them, m (both 0 where it meets none). CPU twin: `reduced.rs`.
fn pixel_spans(d: vec3<f32>, max_t: f32) -> vec2<f32> {
    let b = dot(frame.camera_m.xyz, d);
    var entry = 3.0e38;
    var length = 0.0;
    for (var i = 0u; i < min(volumes.count.x, MAX_VOLUMES); i++) {
        let t = volume_segment(volumes.volumes[i], d, b, max_t);
        if t.x != NO_HIT {
            entry = min(entry, t.x);
            length += t.y - t.x;
        }
    }
    if length <= 0.0 {
        return vec2<f32>(0.0);
    }
    return vec2<f32>(entry, length);
}

// The composite's terms for the ray along `d` ended at `max_t`.
fn pixel_terms(d: vec3<f32>, max_t: f32) -> Terms {
    let b = dot(frame.camera_m.xyz, d);
    var met: array<Met, MAX_VOLUMES>;
    var n = 0u;
    for (var i = 0u; i < min(volumes.count.x, MAX_VOLUMES); i++) {
        let v = volumes.volumes[i];
        let t = volume_segment(v, d, b, max_t);
        if t.x != NO_HIT {
            met[n] = march(v, d, t);
            n++;
        }
    }
    // Farthest entry first.
    if n == 2u && met[0].entry < met[1].entry {
        let near = met[0];
        met[0] = met[1];
        met[1] = near;
    }
    var terms = Terms(vec3<f32>(1.0), vec3<f32>(0.0));
    for (var i = 0u; i < n; i++) {
        let front = front_transmittance(d, met[i].entry);
        let keep = 1.0 - front * (1.0 - met[i].transmittance);
        terms = Terms(terms.times_full * keep, terms.added * keep + front * met[i].radiance);
    }
    return terms;
}
