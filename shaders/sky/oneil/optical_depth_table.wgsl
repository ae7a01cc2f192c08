// Entry pass: the optical-depth table of the oneil model, `main` (render-wgpu's
// `sky/oneil.rs`). CPU twin: atmosphere-core's `models/oneil.rs`
// (`OpticalDepthTable::build`). Paper: O'Neil 2004, "Real-time atmospheric scattering".
// Texel (i, j) is the node at height thickness i / (w - 1) above the ground and angle
// 180 deg j / (h - 1) from the vertical (w x h = the texture's size): r = Rayleigh
// density, or 0 where the ray meets the planet; g = Rayleigh column (m) along the whole
// line to the top sphere, through the planet if it meets it, with the density held at
// its ground value inside; b, a = the same for Mie. Each column is the midpoint rule with
// `ray_samples` samples (`oneil::line_column`).
//
// f32: a radius near 6.4e6 m carries 0.5 m of rounding, too much for a 1.2 km scale
// height, so no altitude is a difference of radii. With q = r^2 - bottom^2, d the
// distance to the top sphere and H^2 = top^2 - bottom^2, the point at fraction s of the
// line has q(s) = (1 - s) q0 + s H^2 - s (1 - s) d^2 (as in `sky/transmittance_table.wgsl`),
// and its altitude is q / (r + bottom). The node's cosine comes from Taylor series
// (`node_cosine`), not from the GPU's `cos`, whose error Vulkan allows up to 2^-11.

#import common/atmosphere_params.wgsl

struct OneilTableParams {
    ray_samples: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(1) var<uniform> params: OneilTableParams;
@group(0) @binding(2) var table: texture_storage_2d<rgba32float, write>;

const HALF_PI: f32 = 1.5707963267948966;

// sin(y) for |y| <= pi/4, to y^11 (the first term left out is below 8e-12).
fn sin_series(y: f32) -> f32 {
    let y2 = y * y;
    return y * (1.0 - y2 / 6.0 * (1.0 - y2 / 20.0 * (1.0 - y2 / 42.0 * (1.0 - y2 / 72.0
        * (1.0 - y2 / 110.0)))));
}

// cos(y) for |y| <= pi/4, to y^12 (the first term left out is below 4e-13).
fn cos_series(y: f32) -> f32 {
    let y2 = y * y;
    return 1.0 - y2 / 2.0 * (1.0 - y2 / 12.0 * (1.0 - y2 / 30.0 * (1.0 - y2 / 56.0
        * (1.0 - y2 / 90.0 * (1.0 - y2 / 132.0)))));
}

// cos(pi j / m) to f32 rounding: cos(theta) = sin(pi/2 - theta), with pi/2 - theta =
// pi (m - 2j) / (2m) formed from integers, reduced to a series argument within pi/4.
fn node_cosine(j: u32, m: u32) -> f32 {
    let k = i32(m) - 2 * i32(j);
    if 4 * abs(k) <= i32(m) {
        return sin_series(HALF_PI * f32(k) / f32(m));
    }
    // |pi/2 - theta| > pi/4: sin(x) = sign(x) cos(pi/2 - |x|).
    return sign(f32(k)) * cos_series(HALF_PI * f32(i32(m) - abs(k)) / f32(m));
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(table);
    if any(id.xy >= size) {
        return;
    }
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let thickness = top - bottom;
    let horizon_sq = thickness * (top + bottom);
    let h = thickness * f32(id.x) / f32(size.x - 1u);
    let mu = node_cosine(id.y, size.y - 1u);
    let r = bottom + h;
    let q0 = h * (h + 2.0 * bottom);
    // distance_to_exit(r, mu, top), with r^2 - top^2 = -(thickness - h)(top + r).
    let c = (thickness - h) * (top + r);
    let root = sqrt((r * mu) * (r * mu) + c);
    var d = max(-r * mu + root, 0.0);
    if mu > 0.0 {
        d = c / (r * mu + root);
    }
    var column = vec2<f32>(0.0);
    let n = params.ray_samples;
    for (var k = 0u; k < n; k++) {
        let s = (f32(k) + 0.5) / f32(n);
        let q = max((1.0 - s) * q0 + s * horizon_sq - s * (1.0 - s) * d * d, 0.0);
        column += densities(q / (sqrt(bottom * bottom + q) + bottom)).xy;
    }
    column *= d / f32(n);
    // The ray meets the ground when it points below the horizon, mu r <= -sqrt(q0).
    var rho = densities(h).xy;
    if mu < 0.0 && -mu * r >= sqrt(q0) {
        rho = vec2<f32>(0.0);
    }
    textureStore(table, id.xy, vec4<f32>(rho.x, column.x, rho.y, column.y));
}
