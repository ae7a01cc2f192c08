// Library: the parameters of an atmosphere (bound at 0 by every sky pass) and the
// functions every pass shares: relative densities and ray geometry in (r, mu). Rust twin
// of the uniform: render-wgpu's `frame/atmosphere_uniform.rs`; every struct keeps 16-byte
// alignment by explicit padding so both sides agree byte for byte. CPU twins:
// atmosphere-core's `atmosphere/density.rs`, `optics/column.rs` and `optics/geometry.rs`.
// Paper: the density profiles and ray geometry of Bruneton 2017 (`DensityProfileLayer`,
// `DistanceToTopAtmosphereBoundary`). Lengths in metres, coefficients in m^-1.

// One layer of a density profile: `exp_term * exp(exp_scale_per_m * h)
// + linear_term_per_m * h + constant_term`, clamped to [0, 1] (Bruneton 2017,
// `DensityProfileLayer`).
struct DensityLayer {
    width_m: f32,
    exp_term: f32,
    exp_scale_per_m: f32,
    linear_term_per_m: f32,
    constant_term: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
}

// Two stacked layers: layer 0 below `layers[0].width_m`, layer 1 above it, unbounded.
// A one-layer profile repeats its layer in both slots.
struct DensityProfile {
    layers: array<DensityLayer, 2>,
}

struct AtmosphereParams {
    bottom_radius_m: f32,
    top_radius_m: f32,
    pad0: f32,
    pad1: f32,
    rayleigh_density: DensityProfile,
    mie_density: DensityProfile,
    ozone_density: DensityProfile,
    // Extinction per unit column of each species; xyz = the three channels (680, 550,
    // 440 nm for the default RGB), w = 0.
    rayleigh_extinction_per_m: vec4<f32>,
    mie_extinction_per_m: vec4<f32>,
    ozone_extinction_per_m: vec4<f32>,
    // Scattering per unit column of Rayleigh and Mie, xyz per channel.
    rayleigh_scattering_per_m: vec4<f32>,
    mie_scattering_per_m: vec4<f32>,
    // Solar irradiance at the top of the atmosphere, W m^-2 nm^-1, xyz per channel.
    solar_irradiance: vec4<f32>,
    // 0 Cornette-Shanks, 1 Henyey-Greenstein, 2 Nishita hazy (`PhaseFunction`); see
    // `common/phase.wgsl`.
    mie_phase_kind: u32,
    mie_g: f32,
    ground_albedo: f32,
    pad2: f32,
}

@group(0) @binding(0) var<uniform> atmosphere: AtmosphereParams;

// The density of the layer that holds `altitude_m`, of the two layers `lower` and
// `upper` of a profile: the layer is chosen field by field with `select`, so that one
// `exp` is evaluated whichever layer it is (branches by altitude diverge between
// neighbouring pixels and cost both layers on SIMD hardware). The layers are passed
// one by one, not as the profile's array: an array passed by value becomes a copy in
// memory per call on some drivers, a cost larger than the whole ray march's.
fn profile_density(lower: DensityLayer, upper: DensityLayer, altitude_m: f32) -> f32 {
    let up = altitude_m >= lower.width_m;
    let exp_term = select(lower.exp_term, upper.exp_term, up);
    let exp_scale = select(lower.exp_scale_per_m, upper.exp_scale_per_m, up);
    let linear = select(lower.linear_term_per_m, upper.linear_term_per_m, up);
    let constant = select(lower.constant_term, upper.constant_term, up);
    let d = exp_term * exp(exp_scale * altitude_m) + linear * altitude_m + constant;
    return clamp(d, 0.0, 1.0);
}

// Relative densities (Rayleigh, Mie, ozone) at `altitude_m` above the ground.
fn densities(altitude_m: f32) -> vec3<f32> {
    return vec3<f32>(
        profile_density(atmosphere.rayleigh_density.layers[0], atmosphere.rayleigh_density.layers[1], altitude_m),
        profile_density(atmosphere.mie_density.layers[0], atmosphere.mie_density.layers[1], altitude_m),
        profile_density(atmosphere.ozone_density.layers[0], atmosphere.ozone_density.layers[1], altitude_m),
    );
}

// Optical depth in each channel of columns (Rayleigh, Mie, ozone) in metres.
fn optical_depth(column_m: vec3<f32>) -> vec3<f32> {
    return column_m.x * atmosphere.rayleigh_extinction_per_m.xyz
        + column_m.y * atmosphere.mie_extinction_per_m.xyz
        + column_m.z * atmosphere.ozone_extinction_per_m.xyz;
}

fn safe_sqrt(x: f32) -> f32 {
    return sqrt(max(x, 0.0));
}

// `(r mu)^2 - (r - radius)(r + radius)`: the ray-sphere discriminant, accurate near the
// sphere.
fn discriminant(r: f32, mu: f32, radius: f32) -> f32 {
    return (r * mu) * (r * mu) - (r - radius) * (r + radius);
}

// Distance from a point inside the top sphere (r <= top) to where the ray leaves it;
// for mu > 0 by the product of the roots, which does not cancel.
fn distance_to_top(r: f32, mu: f32) -> f32 {
    let top = atmosphere.top_radius_m;
    let root = safe_sqrt(discriminant(r, mu, top));
    var far = -r * mu + root;
    if mu > 0.0 {
        let q = r * mu + root;
        far = select(0.0, -((r - top) * (r + top)) / q, q > 0.0);
    }
    return max(far, 0.0);
}

// The radius at distance `t` along a ray from (r, mu).
fn radius_at(r: f32, mu: f32, t: f32) -> f32 {
    return safe_sqrt(r * r + t * t + 2.0 * r * mu * t);
}

// Whether a ray from radius `r` (at or above the ground) meets the ground.
fn ray_hits_ground(r: f32, mu: f32) -> bool {
    return mu < 0.0 && discriminant(r, mu, atmosphere.bottom_radius_m) >= 0.0;
}

// Distance to the ground for a ray that meets it, as the near root
// (r^2 - bottom^2) / (-r mu + root), which does not cancel.
fn distance_to_bottom(r: f32, mu: f32) -> f32 {
    let bottom = atmosphere.bottom_radius_m;
    let q = -r * mu + safe_sqrt(discriminant(r, mu, bottom));
    return select(0.0, max((r - bottom) * (r + bottom) / q, 0.0), q > 0.0);
}
