// Library: the rain and ice volumes of a frame (render-wgpu's
// `precipitation/volume_uniform.rs`, its Rust twin) and their geometry relative to the
// camera: where a view ray crosses a rain shaft (a vertical cylinder on the ground) or a
// cirrus layer (a spherical shell), and how far the sun's ray from a point inside runs
// before it leaves. CPU twin: atmosphere-core's `hydrometeors/volumes.rs`.

const MAX_VOLUMES: u32 = 2u;
const KIND_SHAFT: u32 = 1u;
const KIND_LAYER: u32 = 2u;
const NO_HIT: f32 = -1.0;

struct VolumeParams {
    // x: KIND_SHAFT or KIND_LAYER; y: its first bin in the phase buffer; z: bins;
    // w: 0 for a table by scattering angle, else its azimuth columns (a table over the
    // sky, row-major, elevation rows from -90 degrees).
    kind: vec4<u32>,
    // Shaft: xyz the unit vertical axis, w the radius, m.
    axis: vec4<f32>,
    // Shaft: xyz the camera relative to the axis's foot on the ground, w the height, m.
    // Layer: x, y: r^2 - R^2 of the camera for the base and top radii (f64 on the CPU),
    // z: the same for the ground, m^2.
    place: vec4<f32>,
    // x: the phase bins' width (over the sky: the elevation bins'), y: over the sky,
    // the azimuth bins' width, degrees.
    bin_deg: vec4<f32>,
    // The march's extinction per channel, beta (1 - f_c), m^-1 (CPU twin:
    // `LitVolume::extinction_per_m`, the forward peak out of it).
    extinction: vec4<f32>,
    // The sun's irradiance through the atmosphere, W m^-2 nm^-1, and the radiance the
    // march scatters isotropically as the sky's light, W m^-2 sr^-1 nm^-1, per channel
    // (CPU twin: `VolumeLight`, `sky_light.rs`).
    sun_irradiance: vec4<f32>,
    sky_radiance: vec4<f32>,
    // The probes of the sun's light scattered more than once (CPU twin:
    // `hydrometeors/sun_orders.rs`): x their first entry in the buffer (per probe one
    // J, H_x, H_y, H_z per channel), y, z, w probes across radius, azimuth and height
    // (w = 0: none).
    probes: vec4<u32>,
    // The lobe table: x its first entry (rgb, rows of G), y its G steps, z its angles,
    // w its largest G (f32 bits).
    lobes: vec4<u32>,
}

struct VolumesParams {
    // x: how many volumes; y: 1 when the frame's rays end on its surface; z, w: the
    // column and row of the first pixel the pass runs over.
    count: vec4<u32>,
    // x: the divisor N (1: every pixel marched); y, z: the first reduced pixel the
    // reduced pass runs over.
    reduction: vec4<u32>,
    volumes: array<VolumeParams, MAX_VOLUMES>,
}

// The whole line's interval [t0, t1] inside a shaft, from `p` (relative to the axis's
// foot) along `d`; t0 > t1 when it misses.
fn shaft_interval(v: VolumeParams, p: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let axis = v.axis.xyz;
    let pz = dot(p, axis);
    let dz = dot(d, axis);
    var t = vec2<f32>(-3.0e38, 3.0e38);
    if abs(dz) < 1e-7 {
        if pz < 0.0 || pz > v.place.w {
            return vec2<f32>(1.0, 0.0);
        }
    } else {
        let a = -pz / dz;
        let b = (v.place.w - pz) / dz;
        t = vec2<f32>(min(a, b), max(a, b));
    }
    let pr = p - axis * pz;
    let dr = d - axis * dz;
    let a = dot(dr, dr);
    let b = dot(pr, dr);
    let c = dot(pr, pr) - v.axis.w * v.axis.w;
    if a < 1e-12 {
        if c > 0.0 {
            return vec2<f32>(1.0, 0.0);
        }
    } else {
        let disc = b * b - a * c;
        if disc < 0.0 {
            return vec2<f32>(1.0, 0.0);
        }
        let s = sqrt(disc);
        t = vec2<f32>(max(t.x, (-b - s) / a), min(t.y, (-b + s) / a));
    }
    return t;
}

// The roots of t^2 + 2 b t + c = 0 (a sphere of r^2 - R^2 = c seen with b = r mu),
// smaller first; x > y when there are none.
fn sphere_roots(b: f32, c: f32) -> vec2<f32> {
    let disc = b * b - c;
    if disc < 0.0 {
        return vec2<f32>(1.0, 0.0);
    }
    let s = sqrt(disc);
    return vec2<f32>(-b - s, -b + s);
}

// From a point with r mu = `b` and r^2 - R^2 = `c_base`, `c_top` inside the layer: the
// distance to where the ray leaves it, through the base (going down) or the top.
fn layer_exit(b: f32, c_base: f32, c_top: f32) -> f32 {
    let base = sphere_roots(b, max(c_base, 0.0));
    if base.x <= base.y && base.x >= 0.0 {
        return base.x;
    }
    return max(sphere_roots(b, min(c_top, 0.0)).y, 0.0);
}

// The first interval of the view ray along `d` inside volume `v`, ended at `max_t`;
// x = NO_HIT when it misses. `b` = camera . d.
fn volume_segment(v: VolumeParams, d: vec3<f32>, b: f32, max_t: f32) -> vec2<f32> {
    var t: vec2<f32>;
    if v.kind.x == KIND_SHAFT {
        t = shaft_interval(v, v.place.xyz, d);
        t = vec2<f32>(max(t.x, 0.0), min(t.y, max_t));
    } else {
        let c_base = v.place.x;
        let c_top = v.place.y;
        let top = sphere_roots(b, c_top);
        let base = sphere_roots(b, c_base);
        if c_top > 0.0 {
            // Above the top: enter it, leave through the base or the top again.
            if top.x > top.y || top.y < 0.0 {
                return vec2<f32>(NO_HIT, 0.0);
            }
            var exit = top.y;
            if base.x <= base.y && base.x >= 0.0 {
                exit = base.x;
            }
            t = vec2<f32>(top.x, exit);
        } else if c_base >= 0.0 {
            t = vec2<f32>(0.0, layer_exit(b, c_base, c_top));
        } else {
            t = vec2<f32>(base.y, top.y);
        }
        // The ground.
        let ground = sphere_roots(b, v.place.z);
        if ground.x <= ground.y && ground.x >= 0.0 {
            t.y = min(t.y, ground.x);
        }
        t.y = min(t.y, max_t);
    }
    if t.x >= t.y {
        return vec2<f32>(NO_HIT, 0.0);
    }
    return t;
}

// The sun's path inside volume `v` from the point at `t` along the view ray `d`
// (`b` = camera . d), towards the unit `sun`.
fn sun_path(v: VolumeParams, d: vec3<f32>, b: f32, t: f32, camera: vec3<f32>, sun: vec3<f32>) -> f32 {
    if v.kind.x == KIND_SHAFT {
        let x = v.place.xyz + d * t;
        return max(shaft_interval(v, x, sun).y, 0.0);
    }
    // r^2 - R^2 at the point, and its r mu towards the sun.
    let grow = t * (t + 2.0 * b);
    let b_sun = dot(camera, sun) + t * dot(d, sun);
    return layer_exit(b_sun, v.place.x + grow, v.place.y + grow);
}
