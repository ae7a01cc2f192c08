// Library: the delta-Eddington slab of the cloud layer's `eddington` method, twin of
// atmosphere-core's `clouds/layer/eddington.rs` (its documentation holds the equations:
// Shettle and Weinman 1970, Joseph, Wiscombe and Weinman 1976), for the three
// wavelengths at once (g per wavelength).

const EDDINGTON_MIN_ABSORPTION: f32 = 1e-6;
const EDDINGTON_MIN_SUN_COSINE: f32 = 0.02;

// The diffuse field's source (1 - f) (I_0 + g' mu_out I_1), sr^-1, per unit sun
// irradiance (beam) and per unit sky irradiance (sky).
struct EddingtonDiffuse {
    beam: vec3<f32>,
    sky: vec3<f32>,
}

// The source at optical depth `tau_above` below the top of a slab of optical depth
// `tau_above + tau_below`, sun cosine `mu0_in`.
fn eddington_diffuse(
    tau_above: f32,
    tau_below: f32,
    mu0_in: f32,
    albedo: f32,
    g: vec3<f32>,
    mu_out: f32,
) -> EddingtonDiffuse {
    let f = g * g;
    let absorption = max(1.0 - albedo, EDDINGTON_MIN_ABSORPTION);
    let omega = 1.0 - absorption;
    let scale = 1.0 - omega * f;
    let tau = max(tau_above, 0.0) * scale;
    let total = tau + max(tau_below, 0.0) * scale;
    let omega_s = 1.0 - absorption / scale;
    let g_s = g / (1.0 + g);
    let diffusion = 1.0 - omega_s * g_s;
    let k = sqrt(3.0 * absorption / scale * diffusion);
    let p = k / diffusion;
    var mu0 = vec3<f32>(clamp(mu0_in, EDDINGTON_MIN_SUN_COSINE, 1.0));
    mu0 = select(mu0, mu0 * 1.002, abs(k * mu0 - 1.0) < vec3<f32>(1e-3));
    let s = 1.0 / (4.0 * PI);
    let a = 3.0 * omega_s * mu0 * mu0 * s * (1.0 + g_s * (1.0 - omega_s)) / (k * k * mu0 * mu0 - 1.0);
    let b = 3.0 * mu0 * (omega_s * s - (1.0 - omega_s) * a);
    let u0 = exp(-k * total);
    let m = 1.0 - 2.0 * p / 3.0;
    let q = 1.0 + 2.0 * p / 3.0;
    let det = -((1.0 - u0) + 2.0 * p / 3.0 * (1.0 + u0)) * (u0 * m + q);
    let rising = exp(-k * (total - tau));
    let falling = exp(-k * tau);
    let beam = exp(-tau / mu0);
    // The beam's solution: Marshak's conditions with the particular part.
    let r1 = 2.0 * b / 3.0 - a;
    let r2 = -(a + 2.0 * b / 3.0) * exp(-total / mu0);
    let c1 = (r1 * u0 * m - q * r2) / det;
    let c2 = (u0 * m * r2 - q * r1) / det;
    let i0 = c1 * rising + c2 * falling + a * beam;
    let i1 = p * (c1 * rising - c2 * falling) + b * beam;
    // The sky's: pi (I_0 - 2/3 I_1) = 1 at the top, no particular part.
    let s1 = u0 * m / PI / det;
    let s2 = -q / PI / det;
    let j0 = s1 * rising + s2 * falling;
    let j1 = p * (s1 * rising - s2 * falling);
    return EddingtonDiffuse(
        max((1.0 - f) * (i0 + g_s * mu_out * i1), vec3<f32>(0.0)),
        max((1.0 - f) * (j0 + g_s * mu_out * j1), vec3<f32>(0.0)),
    );
}

// Henyey and Greenstein 1941's phase function of asymmetry g at the cosine `nu`, sr^-1.
fn eddington_henyey_greenstein(g: vec3<f32>, nu: f32) -> vec3<f32> {
    let d = 1.0 + g * g - 2.0 * g * nu;
    return (1.0 - g * g) / (4.0 * PI * d * sqrt(d));
}
