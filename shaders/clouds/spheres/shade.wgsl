// Library: the cloud spheres' textures, crossings and light, twin of atmosphere-core's
// `clouds/spheres/shells.rs`, `cloud_textures.rs`, `attenuation.rs` (the read) and
// `field.rs` (whose documentation holds the equations: Dobashi et al. 2002 section 5.4,
// the light integrated over each crossing with Wrenninge et al. 2013's octaves, or by the
// layer's slab methods, `slab_light.rs`), and the crossings of a ray composited front to
// back (`composite.rs`, `spheres_only`).

#import clouds/spheres/params.wgsl
#import clouds/slab_source.wgsl
#import common/sphere_roots.wgsl

// The spheres' light: 0 the octaves, 2 delta-Eddington's slab, 3 the four-stream slab
// (the layer's LAYER_METHOD codes); a pipeline holds one (render-wgpu's
// `clouds/spheres/sphere_variants.rs`).
override SPHERE_LIGHT: u32 = 0u;
// Steps of a crossing's view optical depth under a slab light (`slab_light::SLAB_STEPS`).
const SLAB_STEPS: u32 = 4u;

// The four texels around a point of a w x h equirectangular grid and their weights
// (geo's `bilinear_taps`: wraps in longitude, clamps at the poles' rows).
struct Taps {
    index: vec4<u32>,
    weight: vec4<f32>,
}

// The continuous texel coordinates of p's direction on a w x h equirectangular grid,
// whose integers are texel centres.
fn grid_coordinates(w: u32, h: u32, p: vec3<f32>) -> vec2<f32> {
    let lat = atan2(p.z, length(p.xy));
    let lon = atan2(p.y, p.x);
    return vec2<f32>((lon + PI) / (2.0 * PI) * f32(w) - 0.5, (0.5 * PI - lat) / PI * f32(h) - 0.5);
}

fn grid_taps(w: u32, h: u32, p: vec3<f32>) -> Taps {
    let c = grid_coordinates(w, h, p);
    let x = c.x;
    let y = c.y;
    let x0 = floor(x);
    let fx = x - x0;
    let i0 = u32((i32(x0) % i32(w) + i32(w)) % i32(w));
    let i1 = (i0 + 1u) % w;
    var j0 = 0u;
    var j1 = 0u;
    var fy = 0.0;
    if y >= f32(h) - 1.0 {
        j0 = h - 1u;
        j1 = h - 1u;
    } else if y > 0.0 {
        j0 = u32(floor(y));
        j1 = j0 + 1u;
        fy = y - floor(y);
    }
    return Taps(
        vec4<u32>(j0 * w + i0, j0 * w + i1, j1 * w + i0, j1 * w + i1),
        vec4<f32>((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy),
    );
}

// The vertical optical depth of shell k at p (T_k, bilinear).
fn cloud_depth(k: u32, p: vec3<f32>) -> f32 {
    let w = spheres.grids.x;
    let h = spheres.grids.y;
    let t = grid_taps(w, h, p);
    let base = k * w * h;
    return dot(t.weight, vec4<f32>(
        cloud_depths[base + t.index.x], cloud_depths[base + t.index.y],
        cloud_depths[base + t.index.z], cloud_depths[base + t.index.w]));
}

// The quadratic B-spline's weights of texels -1, 0 and 1 around offset t in [-0.5, 0.5]
// from texel 0's centre (geo's `quadratic_bspline_weights`).
fn quadratic_bspline_weights(t: f32) -> vec3<f32> {
    return vec3<f32>(0.5 * (0.5 - t) * (0.5 - t), 0.75 - t * t, 0.5 * (0.5 + t) * (0.5 + t));
}

// The optical depth towards the sun of sphere k at p's direction: -ln of G_k's
// attenuation ratio read by the quadratic B-spline of 3 x 3 texels (geo's
// `bspline_taps`: no creases along the lines between texel centres), at most
// SHADOWED_DEPTH.
fn sun_depth(k: u32, p: vec3<f32>) -> f32 {
    let w = spheres.grids.z;
    let h = spheres.grids.w;
    let c = grid_coordinates(w, h, p);
    let nearest = round(c);
    let corner = vec2<i32>(nearest) - vec2<i32>(1);
    let wx = quadratic_bspline_weights(c.x - nearest.x);
    let wy = quadratic_bspline_weights(c.y - nearest.y);
    let base = k * w * h;
    var ratio = 0.0;
    for (var b = 0; b < 3; b++) {
        let row = u32(clamp(corner.y + b, 0, i32(h) - 1));
        var along = 0.0;
        for (var a = 0; a < 3; a++) {
            let column = u32(((corner.x + a) % i32(w) + i32(w)) % i32(w));
            along += wx[a] * sun_ratios[base + row * w + column];
        }
        ratio += wy[b] * along;
    }
    return min(-log(max(ratio, exp(-SHADOWED_DEPTH))), SHADOWED_DEPTH);
}

// The sun's optical depth at `p` inside shell k of mean extinction `sigma`: G_k at the
// sphere under p, its own path through the shell swapped for p's.
fn sun_depth_at(k: u32, p: vec3<f32>, sigma: f32) -> f32 {
    let g = sun_depth(k, p);
    if g >= SHADOWED_DEPTH {
        return SHADOWED_DEPTH;
    }
    let s = spheres.sun_direction.xyz;
    let h = spheres.radii_m.w;
    let outer = spheres.radii_m.y + f32(k + 1u) * h;
    let sphere_r = spheres.radii_m.y + (f32(k) + 0.5) * h;
    let r = length(p);
    let u = p / r;
    let here = max(sphere_roots(r, dot(u, s), outer).y, 0.0);
    let there = max(sphere_roots(sphere_r, dot(u, s), outer).y, 0.0);
    return clamp(g + sigma * (here - there), 0.0, SHADOWED_DEPTH);
}

// (1 - exp(-k)) / k, 1 at k = 0 (its series below 1e-3 in magnitude).
fn exp_ratio(k: f32) -> f32 {
    if abs(k) < 1e-3 {
        return 1.0 - k / 2.0;
    }
    return (1.0 - exp(-k)) / k;
}

// A_1 at the scattering angle of cosine nu, each wavelength.
fn phase_a1(nu: f32) -> vec3<f32> {
    let x = acos(clamp(nu, -1.0, 1.0)) / PI * f32(ANGLES - 1u);
    let k = min(u32(floor(x)), ANGLES - 2u);
    let f = x - f32(k);
    var a = vec3<f32>(0.0);
    for (var w = 0u; w < 3u; w++) {
        a[w] = mix(single_phase[w * ANGLES + k], single_phase[w * ANGLES + k + 1u], f);
    }
    return a;
}

// The droplets' asymmetry and Legendre moments chi_1..chi_4 per wavelength, stored after
// A_1's tables.
fn sphere_moments() -> array<vec4<f32>, 3> {
    var m: array<vec4<f32>, 3>;
    for (var w = 0u; w < 3u; w++) {
        let i = 3u * ANGLES + 4u * w;
        m[w] = vec4<f32>(single_phase[i], single_phase[i + 1u], single_phase[i + 2u], single_phase[i + 3u]);
    }
    return m;
}

// A crossing's light towards its start: `real` seen through the real medium in front,
// `scaled` (the slab light's diffuse and broad parts) through the delta-scaled one; its
// transmittance through either (`field.rs`'s SphereCrossing).
struct SphereCrossing {
    real: vec3<f32>,
    scaled: vec3<f32>,
    transmittance: f32,
    scaled_transmittance: vec3<f32>,
}

// The crossing [t0, t1] of shell k by the ray from o along the unit d lit by a slab
// method (`slab_light.rs`), of mean extinction `sigma`.
fn shade_slab(o: vec3<f32>, d: vec3<f32>, k: u32, t0: f32, t1: f32, sigma: f32, single: vec3<f32>) -> SphereCrossing {
    let four = SPHERE_LIGHT == 3u;
    let moments = sphere_moments();
    let g = vec3<f32>(moments[0].x, moments[1].x, moments[2].x);
    let albedo = spheres.medium.x;
    let scale = 1.0 - albedo * slab_peak_share(four, g, moments);
    let s = spheres.sun_direction.xyz;
    let nu = dot(d, s);
    let inner = spheres.radii_m.y + f32(k) * spheres.radii_m.w;
    let length_m = t1 - t0;
    let step_depth = sigma * length_m / f32(SLAB_STEPS);
    let step_real = exp(-step_depth);
    let step_scaled = exp(-scale * step_depth);
    var out = SphereCrossing(vec3<f32>(0.0), vec3<f32>(0.0), 1.0, vec3<f32>(1.0));
    // Four streams: each wavelength's slab solved once, for the column at the crossing's
    // middle (`slab_light.rs`).
    var solved: array<FourStreamSlab, 3>;
    if four {
        let middle = o + d * (t0 + 0.5 * length_m);
        let up = normalize(middle);
        let mu0 = dot(s, up);
        var below = 0.0;
        for (var j = 0u; j < k; j++) {
            below += cloud_depth(j, middle);
        }
        let column = sun_depth_at(k, middle, sigma) * max(mu0, EDDINGTON_MIN_SUN_COSINE)
            + sigma * max(length(middle) - inner, 0.0) + below;
        var chi = moments;
        for (var w = 0u; w < 3u; w++) {
            solved[w] = four_stream_solve(column, mu0, albedo, chi[w]);
        }
    }
    for (var i = 0u; i < SLAB_STEPS; i++) {
        let p = o + d * (t0 + length_m * (f32(i) + 0.5) / f32(SLAB_STEPS));
        let up = normalize(p);
        let tau_sun = sun_depth_at(k, p, sigma);
        let mu0 = dot(s, up);
        var parts: SlabSources;
        if four {
            var diffuse = EddingtonDiffuse(vec3<f32>(0.0), vec3<f32>(0.0));
            let above = tau_sun * max(mu0, EDDINGTON_MIN_SUN_COSINE);
            for (var w = 0u; w < 3u; w++) {
                let j = four_stream_source(solved[w], above, -dot(d, up));
                diffuse.beam[w] = j.x;
                diffuse.sky[w] = j.y;
            }
            parts = slab_parts(four, tau_sun, nu, albedo, single, g, moments, diffuse);
        } else {
            var below = 0.0;
            for (var j = 0u; j < k; j++) {
                below += cloud_depth(j, p);
            }
            parts = slab_sources(
                four,
                tau_sun,
                mu0,
                sigma * max(length(p) - inner, 0.0) + below,
                -dot(d, up),
                nu,
                albedo,
                single,
                g,
                moments,
            );
        }
        let sun = select(spheres.sun_irradiance.xyz, vec3<f32>(0.0), tau_sun >= SHADOWED_DEPTH);
        out.real += out.transmittance * (1.0 - step_real) * albedo * sun * parts.real;
        out.scaled += out.scaled_transmittance * (1.0 - step_scaled) / scale * albedo
            * (sun * parts.scaled + spheres.sky_irradiance.xyz * parts.scaled_sky);
        out.transmittance *= step_real;
        out.scaled_transmittance *= step_scaled;
    }
    return out;
}

// The crossing [t0, t1] of shell k by the ray from o along the unit d, whose scattering
// angle gives A_1 = `single` (one read per ray).
fn shade_crossing(o: vec3<f32>, d: vec3<f32>, k: u32, t0: f32, t1: f32, single: vec3<f32>) -> SphereCrossing {
    let start = o + d * t0;
    let end = o + d * t1;
    let middle = (start + end) / 2.0;
    let sigma = cloud_depth(k, middle) / spheres.radii_m.w;
    if sigma <= 0.0 {
        return SphereCrossing(vec3<f32>(0.0), vec3<f32>(0.0), 1.0, vec3<f32>(1.0));
    }
    if SPHERE_LIGHT >= 2u {
        return shade_slab(o, d, k, t0, t1, sigma, single);
    }
    let tau_v = sigma * (t1 - t0);
    let tau_a = sun_depth_at(k, start, sigma);
    let tau_b = sun_depth_at(k, end, sigma);
    let top = spheres.radii_m.y + spheres.radii_m.z;
    let up_a = sigma * max(top - length(start), 0.0);
    let up_b = sigma * max(top - length(end), 0.0);
    let sky = exp(-up_a) * tau_v * exp_ratio(tau_v + up_b - up_a) / (2.0 * PI);
    var sun = vec3<f32>(0.0);
    var a = 1.0;
    var b = 1.0;
    var c = 1.0;
    for (var i = 0u; i < spheres.counts.y; i++) {
        let weight = a * (c * single + (1.0 - c) / (4.0 * PI));
        sun += weight * exp(-b * tau_a) * tau_v * exp_ratio(tau_v + b * (tau_b - tau_a));
        a *= 0.5;
        b *= 0.5;
        c *= 0.5;
    }
    let radiance = spheres.medium.x
        * (spheres.sun_irradiance.xyz * sun + spheres.sky_irradiance.xyz * sky);
    let t = exp(-tau_v);
    return SphereCrossing(radiance, vec3<f32>(0.0), t, vec3<f32>(t));
}

// Below this transmittance the crossings behind are left out (`composite.rs`'s
// MIN_TRANSMITTANCE).
const MIN_TRANSMITTANCE: f32 = 1e-4;

// The spheres along a ray: rgb their radiance, a their transmittance; and where the ray
// first enters a shell (clamped to the camera; -1 when it crosses none before its end).
struct SpheresAlong {
    cloud: vec4<f32>,
    first_m: f32,
}

// The spheres along the ray from o along the unit d, ended on the ground or at `end_m`.
// Along a ray the radius falls to its closest approach and rises after it, so the
// shells' first intervals, outermost first, then their second intervals, innermost
// first, are the crossings in order of distance (`shells.rs` sorts them); each is
// composited front to back until the transmittance falls below MIN_TRANSMITTANCE, where
// the loop stops. A ray that meets the ground ends before its closest approach, so it
// has no second intervals and the loop takes the first ones only.
fn spheres_along(o: vec3<f32>, d: vec3<f32>, end_m: f32) -> SpheresAlong {
    let r = length(o);
    let mu = clamp(dot(o, d) / r, -1.0, 1.0);
    var end = end_m;
    var halves = 2u;
    let ground = sphere_roots(r, mu, spheres.radii_m.x);
    if ground.x <= ground.y && ground.x >= 0.0 && mu < 0.0 {
        end = min(end, ground.x);
        halves = 1u;
    }
    let m = spheres.counts.x;
    let single = phase_a1(dot(d, spheres.sun_direction.xyz));
    var result = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    // The crossings' delta-scaled transmittance so far (a slab light's scaled part).
    var seen_scaled = vec3<f32>(1.0);
    var first = -1.0;
    for (var half = 0u; half < halves; half++) {
        for (var n = 0u; n < m; n++) {
            if max(result.a, seen_scaled.x) < MIN_TRANSMITTANCE {
                break;
            }
            // First intervals from the outermost shell in, then second ones outwards.
            var k = n;
            if half == 0u {
                k = m - 1u - n;
            }
            let inner = spheres.radii_m.y + f32(k) * spheres.radii_m.w;
            let outer_roots = sphere_roots(r, mu, inner + spheres.radii_m.w);
            if outer_roots.x > outer_roots.y {
                continue;
            }
            let inner_roots = sphere_roots(r, mu, inner);
            var t = outer_roots;
            if inner_roots.x <= inner_roots.y {
                if half == 0u {
                    t.y = min(t.y, inner_roots.x);
                } else {
                    t.x = max(t.x, inner_roots.y);
                }
            } else if half == 1u {
                continue;
            }
            let t0 = max(t.x, 0.0);
            let t1 = min(t.y, end);
            if t0 < t1 {
                if first < 0.0 {
                    first = t0;
                }
                let c = shade_crossing(o, d, k, t0, t1, single);
                result = vec4<f32>(
                    result.rgb + result.a * c.real + seen_scaled * c.scaled,
                    result.a * c.transmittance,
                );
                seen_scaled *= c.scaled_transmittance;
            }
        }
        if max(result.a, seen_scaled.x) < MIN_TRANSMITTANCE {
            break;
        }
    }
    return SpheresAlong(result, first);
}
