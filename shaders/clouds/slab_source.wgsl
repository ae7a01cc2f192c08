// Library: the sources of one sample under the cloud layer's slab methods, twin of
// atmosphere-core's `clouds/layer/march.rs` (`slab_source`, `peak_share`): the diffuse
// light of the slab around the sample (delta-Eddington's, `eddington.wgsl`, or delta-M
// four-stream's, `four_stream.wgsl`), the broad part (1 - f) p_HG((g - f) / (1 - f)) of
// the sun's single scattering from the scaled beam, and the rest of A_1 from the real
// one. The layer's march and the cloud spheres both take it.

#import clouds/eddington.wgsl
#import clouds/four_stream.wgsl

// Per unit of extinction and albedo, sr^-1, per unit sun irradiance: J_sun seen through
// the real medium (real) and through the delta-scaled one (scaled); per unit sky
// irradiance, J_sky seen through the scaled one.
struct SlabSources {
    real: vec3<f32>,
    scaled: vec3<f32>,
    scaled_sky: vec3<f32>,
}

// The forward peak's share f, each wavelength: chi_4 with four streams, else g^2.
fn slab_peak_share(four_stream: bool, g: vec3<f32>, moments: array<vec4<f32>, 3>) -> vec3<f32> {
    if four_stream {
        return clamp(vec3<f32>(moments[0].w, moments[1].w, moments[2].w), vec3<f32>(0.0), vec3<f32>(0.999));
    }
    return g * g;
}

// The sources at a sample whose path towards the sun has optical depth `tau`, the sun's
// cosine `mu0` and the optical depth `tau_below` straight down, seen along a direction
// of cosine `mu_out` from the upward vertical at the scattering angle of cosine `nu`;
// the droplets' A_1 there (`a1`), asymmetry `g` and moments chi_1..chi_4 per wavelength.
fn slab_sources(
    four_stream: bool,
    tau: f32,
    mu0: f32,
    tau_below: f32,
    mu_out: f32,
    nu: f32,
    albedo: f32,
    a1: vec3<f32>,
    g: vec3<f32>,
    moments: array<vec4<f32>, 3>,
) -> SlabSources {
    let tau_above = tau * max(mu0, EDDINGTON_MIN_SUN_COSINE);
    var diffuse = EddingtonDiffuse(vec3<f32>(0.0), vec3<f32>(0.0));
    if four_stream {
        var chi = moments;
        for (var w = 0u; w < 3u; w++) {
            let j = four_stream_diffuse(tau_above, tau_below, mu0, albedo, chi[w], mu_out);
            diffuse.beam[w] = j.x;
            diffuse.sky[w] = j.y;
        }
    } else {
        diffuse = eddington_diffuse(tau_above, tau_below, mu0, albedo, g, mu_out);
    }
    return slab_parts(four_stream, tau, nu, albedo, a1, g, moments, diffuse);
}

// `slab_sources` with the slab's diffuse sources given (march.rs's `slab_parts`): the
// sun's single scattering split into its broad part from the scaled beam and the rest
// of A_1 from the real one.
fn slab_parts(
    four_stream: bool,
    tau: f32,
    nu: f32,
    albedo: f32,
    a1: vec3<f32>,
    g: vec3<f32>,
    moments: array<vec4<f32>, 3>,
    diffuse: EddingtonDiffuse,
) -> SlabSources {
    let f = slab_peak_share(four_stream, g, moments);
    let broad = (1.0 - f) * eddington_henyey_greenstein((g - f) / (1.0 - f), nu);
    return SlabSources(
        (a1 - broad) * exp(-tau),
        diffuse.beam + broad * exp(-(1.0 - albedo * f) * tau),
        diffuse.sky,
    );
}
