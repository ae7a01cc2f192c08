// Library: the march of one view ray through the cloud layer, twin of atmosphere-core's
// `clouds/layer/march.rs` (its documentation holds the equations): equal steps sampled
// at their middles, the energy-conserving step integral (Hillaire 2016), the sun by
// Riley et al. 2004's expected orders (Eq. 22, 25, 26) or Wrenninge et al. 2013's
// octaves, the sky as isotropic ambient, the shadow march through the density with
// `noise.y` octaves or, where `noise.w` is 1 (`sun_light = map`), the optical depth
// read from the frame's sun map (`sun_map_read.wgsl`, Dobashi et al. 2002 section 5.4)
// in `counts.y` equal parts, stopping below the transmittance `detail.z`.

#import clouds/layer_medium.wgsl
#import clouds/sun_map_read.wgsl

const MAX_SHADOW_STEPS: u32 = 64u;

// A_n (n clamped to 1..26) at the scattering angle of cosine `nu`, each wavelength.
fn distribution(n: u32, nu: f32) -> vec3<f32> {
    let row = clamp(n, 1u, ORDERS) - 1u;
    let x = acos(clamp(nu, -1.0, 1.0)) / PI * f32(ANGLES - 1u);
    let k = min(u32(floor(x)), ANGLES - 2u);
    let f = x - f32(k);
    var a = vec3<f32>(0.0);
    for (var w = 0u; w < WAVES; w++) {
        let base = (w * ORDERS + row) * ANGLES + k;
        a[w] = mix(orders[base], orders[base + 1u], f);
    }
    return a;
}

// F_n (n clamped to 1..26), each wavelength.
fn forward_fraction(n: u32) -> vec3<f32> {
    let row = clamp(n, 1u, ORDERS) - 1u;
    let base = WAVES * ORDERS * ANGLES + row;
    return vec3<f32>(orders[base], orders[base + ORDERS], orders[base + 2u * ORDERS]);
}

// J_sun / E_sun at `p`, sr^-1.
fn sun_source(p: vec3<f32>, nu: f32, albedo: f32) -> vec3<f32> {
    let s = layer.sun_direction.xyz;
    let steps = min(layer.counts.y, MAX_SHADOW_STEPS);
    var depths: array<f32, MAX_SHADOW_STEPS>;
    var tau = 0.0;
    if layer.noise.w == 1u {
        tau = cloud_sun_optical_depth(p);
        let part = tau / f32(steps);
        for (var k = 0u; k < steps; k++) {
            depths[k] = part;
        }
    } else {
        let length_m = layer_boundary(p, s);
        let ds = length_m / f32(steps);
        for (var k = 0u; k < steps; k++) {
            let q = p + s * (length_m - (f32(k) + 0.5) * ds);
            depths[k] = layer_extinction(q, layer.noise.y) * ds;
            tau += depths[k];
        }
    }
    if layer.counts.z == 0u {
        var intensity = vec3<f32>(1.0);
        var walked = 0.0;
        for (var k = 0u; k < steps; k++) {
            let d = depths[k];
            if d > 0.0 {
                let m = u32(floor(albedo * walked + 1.0 + d));
                let kept = albedo * forward_fraction(m);
                let t = exp(-d);
                let kept_d = select(pow(kept, vec3<f32>(d)), vec3<f32>(0.0), kept <= vec3<f32>(0.0));
                intensity *= t + (1.0 - t) * kept_d;
                walked += d;
            }
        }
        let n = u32(floor(albedo * tau)) + 1u;
        return intensity * (distribution(n, nu) + layer.medium.w);
    }
    let single = distribution(1u, nu);
    var j = vec3<f32>(0.0);
    var a = 1.0;
    var b = 1.0;
    var c = 1.0;
    for (var i = 0u; i < layer.counts.w; i++) {
        j += a * exp(-b * tau) * (c * single + (1.0 - c) / (4.0 * PI));
        a *= 0.5;
        b *= 0.5;
        c *= 0.5;
    }
    return j;
}

// The cloud's radiance (rgb) and transmittance (a) along `d` from `o` over (t0, t1).
fn march_layer(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32) -> vec4<f32> {
    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    let dt = max(t1 - t0, 0.0) / f32(layer.counts.x);
    let nu = dot(d, layer.sun_direction.xyz);
    let up = normalize(o + d * t0);
    let albedo = layer.medium.y;
    for (var i = 0u; i < layer.counts.x; i++) {
        let p = o + d * (t0 + (f32(i) + 0.5) * dt);
        let sigma = layer_extinction(p, layer.noise.x);
        if sigma <= 0.0 {
            continue;
        }
        let step_t = exp(-sigma * dt);
        let weight = transmittance * (1.0 - step_t) * albedo;
        let sky = exp(-sigma * layer_boundary(p, up)) / (2.0 * PI);
        let sun = sun_source(p, nu, albedo);
        radiance += weight * (layer.sun_irradiance.xyz * sun + layer.sky_irradiance.xyz * sky);
        transmittance *= step_t;
        if transmittance < layer.detail.z {
            break;
        }
    }
    return vec4<f32>(radiance, transmittance);
}
