// Library: the march of one view ray through the cloud layer, twin of atmosphere-core's
// `clouds/layer/march.rs` (its documentation holds the equations): equal steps sampled
// at their middles, the energy-conserving step integral (Hillaire 2016), the sun by
// Riley et al. 2004's expected orders (Eq. 22, 25, 26), Wrenninge et al. 2013's
// octaves or a slab: delta-Eddington's (`eddington.wgsl`) or delta-M four-stream's
// (`four_stream.wgsl`), the sky as isotropic ambient,
// the shadow march through the density with `noise.y` octaves or, with `SUN_FROM_MAP`
// (`sun_light = map`), the optical depth read from the frame's sun map
// (`sun_map_read.wgsl`, Dobashi et al. 2002 section 5.4) in `counts.y` equal parts,
// stopping below the transmittance `detail.z`.
//
// The method, the sun's light and whether the shadow march reads noise are
// pipeline-overridable constants: a pipeline holds one method's code only (render-wgpu's `clouds/march_variants.rs`). A
// software rasteriser such as lavapipe runs every branch some lane of a SIMD group
// takes and keeps the registers of all the code compiled in, so a shader holding every
// method and light, or the shadow march's unread noise, made each sample dearer
// (docs/clouds.md, "What brought it within the target").

#import clouds/layer_medium.wgsl
#import clouds/sun_map_read.wgsl
#import clouds/slab_source.wgsl
#import clouds/orders.wgsl

const MAX_SHADOW_STEPS: u32 = 64u;

// The sun's light method: 0 Riley et al. 2004's orders, 1 the octaves, 2 delta-Eddington,
// 3 delta-M four-stream (2 and 3 the slab methods).
override LAYER_METHOD: u32 = 0u;
// Whether the sun's optical depth comes from the frame's sun map instead of a march.
override SUN_FROM_MAP: bool = false;
// Whether the shadow march reads detail noise (`noise.y` above 0); without it the
// pipeline holds no noise code for the shadow march.
override SHADOW_DETAIL: bool = true;

// The octaves of detail noise the shadow march reads.
fn shadow_octaves() -> u32 {
    return select(0u, layer.noise.y, SHADOW_DETAIL);
}

// The single-scattering phase function's asymmetry g, each wavelength.
fn asymmetry() -> vec3<f32> {
    let base = WAVES * ORDERS * (ANGLES + 1u);
    return vec3<f32>(orders[base], orders[base + 1u], orders[base + 2u]);
}

// The single-scattering phase function's Legendre moments chi_1..chi_4, each wavelength.
fn phase_moments() -> array<vec4<f32>, 3> {
    let base = WAVES * ORDERS * (ANGLES + 1u) + 3u;
    var m: array<vec4<f32>, 3>;
    for (var w = 0u; w < 3u; w++) {
        let i = base + 4u * w;
        m[w] = vec4<f32>(orders[i], orders[i + 1u], orders[i + 2u], orders[i + 3u]);
    }
    return m;
}

// What a sample scatters towards the eye per unit of extinction and albedo, sr^-1:
// J_sun / E_sun seen through the real medium and, for the slab methods,
// J_sun / E_sun and J_sky / E_sky seen through the delta-scaled one.
struct SunParts {
    unscaled: vec3<f32>,
    scaled: vec3<f32>,
    scaled_sky: vec3<f32>,
}

// The optical depth of `counts.y` equal steps from `p` to the layer's boundary along the
// unit `d`, through the density the shadow march reads.
fn layer_depth(p: vec3<f32>, d: vec3<f32>) -> f32 {
    let steps = clamp(layer.counts.y, 1u, MAX_SHADOW_STEPS);
    let ds = layer_boundary(p, d) / f32(steps);
    var tau = 0.0;
    for (var k = 0u; k < steps; k++) {
        tau += layer_extinction(p + d * ((f32(k) + 0.5) * ds), shadow_octaves()) * ds;
    }
    return tau;
}

// The optical depth of part `k` of the shadow path from `p` towards the sun, the parts
// counted inwards from the layer's boundary: a `length_m / steps` step of the shadow
// march, or `tau_map / steps` where the sun map gives the whole path (`from_map`).
fn shadow_part(p: vec3<f32>, k: u32, steps: u32, length_m: f32, tau_map: f32, from_map: bool) -> f32 {
    if from_map {
        return tau_map / f32(steps);
    }
    let ds = length_m / f32(steps);
    let q = p + layer.sun_direction.xyz * (length_m - (f32(k) + 0.5) * ds);
    return layer_extinction(q, shadow_octaves()) * ds;
}

// J_sun / E_sun at `p`, sr^-1, seen along `d`, `up` the local vertical, `g` the
// droplets' asymmetry (read by the slab methods only).
fn sun_source(p: vec3<f32>, d: vec3<f32>, up: vec3<f32>, nu: f32, albedo: f32, g: vec3<f32>) -> SunParts {
    let s = layer.sun_direction.xyz;
    let steps = min(layer.counts.y, MAX_SHADOW_STEPS);
    let from_map = SUN_FROM_MAP;
    var tau_map = 0.0;
    var length_m = 0.0;
    if from_map {
        tau_map = cloud_sun_optical_depth(p);
    } else {
        length_m = layer_boundary(p, s);
    }
    if LAYER_METHOD == 0u {
        var intensity = vec3<f32>(1.0);
        var walked = 0.0;
        for (var k = 0u; k < steps; k++) {
            let d = shadow_part(p, k, steps, length_m, tau_map, from_map);
            if d > 0.0 {
                let m = u32(floor(albedo * walked + 1.0 + d));
                let kept = albedo * forward_fraction(m);
                let t = exp(-d);
                let kept_d = select(pow(kept, vec3<f32>(d)), vec3<f32>(0.0), kept <= vec3<f32>(0.0));
                intensity *= t + (1.0 - t) * kept_d;
                walked += d;
            }
        }
        let tau = select(walked, tau_map, from_map);
        let n = u32(floor(albedo * tau)) + 1u;
        return SunParts(intensity * (distribution(n, nu) + layer.medium.w), vec3<f32>(0.0), vec3<f32>(0.0));
    }
    var tau = tau_map;
    if !from_map {
        for (var k = 0u; k < steps; k++) {
            tau += shadow_part(p, k, steps, length_m, tau_map, false);
        }
    }
    if LAYER_METHOD >= 2u {
        let parts = slab_sources(
            LAYER_METHOD == 3u,
            tau,
            dot(s, up),
            layer_depth(p, -up),
            -dot(d, up),
            nu,
            albedo,
            distribution(1u, nu),
            g,
            phase_moments(),
        );
        return SunParts(parts.real, parts.scaled, parts.scaled_sky);
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
    return SunParts(j, vec3<f32>(0.0), vec3<f32>(0.0));
}

// The cloud's radiance (rgb) and transmittance (a) along `d` from `o` over (t0, t1).
fn march_layer(o: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32) -> vec4<f32> {
    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    // The delta-scaled view transmittance the slab methods' diffuse part sees.
    var scaled_transmittance = vec3<f32>(1.0);
    let slab_method = LAYER_METHOD >= 2u;
    let dt = max(t1 - t0, 0.0) / f32(layer.counts.x);
    let nu = dot(d, layer.sun_direction.xyz);
    let up = normalize(o + d * t0);
    let albedo = layer.medium.y;
    let g = asymmetry();
    // The delta-scaling of the slab methods' extinction (unread by the others).
    var scale = vec3<f32>(1.0);
    if slab_method {
        scale = 1.0 - albedo * slab_peak_share(LAYER_METHOD == 3u, g, phase_moments());
    }
    for (var i = 0u; i < layer.counts.x; i++) {
        let p = o + d * (t0 + (f32(i) + 0.5) * dt);
        let sigma = layer_extinction(p, layer.noise.x);
        if sigma <= 0.0 {
            continue;
        }
        let step_t = exp(-sigma * dt);
        let weight = transmittance * (1.0 - step_t) * albedo;
        let sky = exp(-sigma * layer_boundary(p, up)) / (2.0 * PI);
        let sun = sun_source(p, d, up, nu, albedo, g);
        transmittance *= step_t;
        var seen = transmittance;
        if slab_method {
            radiance += weight * layer.sun_irradiance.xyz * sun.unscaled;
            let step = exp(-scale * sigma * dt);
            let scattered = layer.sun_irradiance.xyz * sun.scaled + layer.sky_irradiance.xyz * sun.scaled_sky;
            radiance += scaled_transmittance * (1.0 - step) / scale * albedo * scattered;
            scaled_transmittance *= step;
            seen = max(scaled_transmittance.x, max(scaled_transmittance.y, scaled_transmittance.z));
        } else {
            radiance += weight * (layer.sun_irradiance.xyz * sun.unscaled + layer.sky_irradiance.xyz * sky);
        }
        if seen < layer.detail.z {
            break;
        }
    }
    return vec4<f32>(radiance, transmittance);
}
