// Library: the sun's light scattered more than once inside a volume, read from its
// probes (CPU twin: atmosphere-core's `hydrometeors/sun_orders.rs`, which states the
// method): J and H per channel trilinear between the probes' cell centres, the
// radiance read as a Henyey-Greenstein lobe about H of mean cosine G = |H| / J, and
// the light a unit of scattering sends towards the camera J times the lobe table at G
// and the angle between that direction and H. Reads the importer's `phase` buffer.

// `i` (as f32) and the fraction for reading `n` cells at the fraction `f` of their
// extent, linear between centres.
fn cell_between(f: f32, n: u32) -> vec2<f32> {
    if n < 2u {
        return vec2<f32>(0.0, 0.0);
    }
    let u = clamp(f * f32(n) - 0.5, 0.0, f32(n - 1u));
    let i = min(floor(u), f32(n - 2u));
    return vec2<f32>(i, u - i);
}

// `i` (as f32) and the fraction for reading `n` nodes at the node position `u`.
fn node_between(u: f32, n: u32) -> vec2<f32> {
    let v = clamp(u, 0.0, f32(n - 1u));
    let i = min(floor(v), f32(n - 2u));
    return vec2<f32>(i, v - i);
}

// The point at `t` along the view ray `d` (`b` = camera . d) as fractions of the probes'
// three extents: a shaft's radius, azimuth from the sun's vertical plane (0 to 1 for 0
// to 180 degrees) and height; a layer's (r^2 - R_b^2) / (R_t^2 - R_b^2).
fn probe_fractions(v: VolumeParams, d: vec3<f32>, b: f32, t: f32, sun: vec3<f32>) -> vec3<f32> {
    if v.kind.x == KIND_SHAFT {
        let axis = v.axis.xyz;
        let p = v.place.xyz + d * t;
        let z = dot(p, axis);
        let radial = p - axis * z;
        let flat = sun - axis * dot(sun, axis);
        var azimuth = 0.0;
        if length(flat) >= 1e-6 {
            let towards = normalize(flat);
            let across = cross(axis, towards);
            azimuth = atan2(abs(dot(radial, across)), dot(radial, towards)) / 3.141592654;
        }
        return vec3<f32>(length(radial) / v.axis.w, azimuth, z / v.place.w);
    }
    let grow = t * (t + 2.0 * b);
    return vec3<f32>(0.0, 0.0, (v.place.x + grow) / (v.place.x - v.place.y));
}

// One channel's lobe table at G (a node position) and the angle alpha (a node position).
fn lobe_at(v: VolumeParams, c: u32, g: f32, alpha: f32) -> f32 {
    let gi = node_between(g, v.lobes.y);
    let ai = node_between(alpha, v.lobes.z);
    let first = v.lobes.x + u32(gi.x) * v.lobes.z + u32(ai.x);
    let low = mix(phase[first][c], phase[first + 1u][c], ai.y);
    let high = mix(phase[first + v.lobes.z][c], phase[first + v.lobes.z + 1u][c], ai.y);
    return mix(low, high, gi.y);
}

// The light a unit of scattering sends along the unit `toward` at `t` along the view
// ray `d`, per channel, for a sun of unit irradiance; zero without probes.
fn orders_source(
    v: VolumeParams, d: vec3<f32>, b: f32, t: f32, sun: vec3<f32>, toward: vec3<f32>,
) -> vec3<f32> {
    if v.probes.w == 0u {
        return vec3<f32>(0.0);
    }
    let f = probe_fractions(v, d, b, t, sun);
    let r = cell_between(f.x, v.probes.y);
    let a = cell_between(f.y, v.probes.z);
    let h = cell_between(f.z, v.probes.w);
    var m = array<vec4<f32>, 3>(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
    for (var corner = 0u; corner < 8u; corner++) {
        let di = corner & 1u;
        let dj = (corner >> 1u) & 1u;
        let dk = corner >> 2u;
        let w = select(1.0 - r.y, r.y, di == 1u) * select(1.0 - a.y, a.y, dj == 1u)
            * select(1.0 - h.y, h.y, dk == 1u);
        if w == 0.0 {
            continue;
        }
        let index = ((u32(h.x) + dk) * v.probes.z + u32(a.x) + dj) * v.probes.y + u32(r.x) + di;
        let entry = v.probes.x + 3u * index;
        for (var c = 0u; c < 3u; c++) {
            m[c] += w * phase[entry + c];
        }
    }
    let g_max = bitcast<f32>(v.lobes.w);
    var out = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        let j = m[c].x;
        if j <= 0.0 {
            continue;
        }
        let flux = m[c].yzw;
        let length_h = length(flux);
        var cos_alpha = 1.0;
        if length_h > 0.0 {
            cos_alpha = dot(toward, flux) / length_h;
        }
        let g = min(length_h / j, g_max) / g_max * f32(v.lobes.y - 1u);
        let alpha = acos(clamp(cos_alpha, -1.0, 1.0)) / 3.141592654 * f32(v.lobes.z - 1u);
        out[c] = j * max(lobe_at(v, c, g, alpha), 0.0);
    }
    return out;
}
