// Entry passes: the pre-integrated segment tables of the dobashi model, `planes` and
// `spheres` (render-wgpu's `sky/dobashi/`). CPU twins: atmosphere-core's
// `models/dobashi/plane_tables.rs` and `models/dobashi/sphere_tables.rs`, each segment by
// `models/dobashi/segment.rs` (`integrate`). Paper: Dobashi, Yamamoto and Nishita 2002,
// sections 5.2-5.3 and appendix A.2, Eq. A.5-A.6. Each texel holds, for one segment,
// dI_r = int K_r rho_r exp(-tau(0 -> t)) dt, dI_m likewise with Mie, and
// dg_v = exp(-tau(0 -> L)), rgb = the three channels of the uniform, tau counting every
// species (ozone included).
//
// The integrals are composite 5-point Gauss-Legendre over equal panels, the column to
// each node by a nested 5-point rule over its panel: converged f32 quadrature, against
// the CPU's converged f64 (checked node by node by the parity test). A segment is given
// by q0 = r^2 - bottom^2 at its start, r mu there and its length; at distance t the
// altitude is q(t) / (r(t) + bottom) with q(t) = q0 + t (t + 2 r mu): no difference of
// radii near 6.4e6 m, a few centimetres of rounding on the longest chords.

#import common/atmosphere_params.wgsl
#import sky/dobashi/plane_mapping.wgsl

struct DobashiTableParams {
    // Delta_t, the interval between sampling planes, m.
    interval_m: f32,
    // Panels per segment of the plane tables and of the sphere tables.
    plane_panels: u32,
    sphere_panels: u32,
    pad0: u32,
}

// One row of the sphere tables (sphere k, kind of segment), computed in f64 on the CPU:
// x = q0 of the sphere, y = q of the sphere where the segment ends minus q0,
// z, w = the shortest and longest segment (w < 0: the kind does not exist).
@group(0) @binding(1) var<uniform> params: DobashiTableParams;
@group(0) @binding(2) var<storage, read> sphere_rows: array<vec4<f32>>;
@group(0) @binding(3) var scatter_r: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var scatter_m: texture_storage_2d<rgba32float, write>;
@group(0) @binding(5) var transmittance: texture_storage_2d<rgba32float, write>;

const GL5_NODES = array<f32, 5>(-0.906179845938664, -0.538469310105683, 0.0, 0.538469310105683, 0.906179845938664);
const GL5_WEIGHTS = array<f32, 5>(0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891);

// Relative densities (Rayleigh, Mie, ozone) at distance t along the segment.
fn density_along(q0: f32, r_mu: f32, t: f32) -> vec3<f32> {
    let bottom = atmosphere.bottom_radius_m;
    let q = max(q0 + t * (t + 2.0 * r_mu), 0.0);
    return densities(q / (sqrt(bottom * bottom + q) + bottom));
}

struct SegmentValues {
    scatter_r: vec3<f32>,
    scatter_m: vec3<f32>,
    transmittance: vec3<f32>,
}

// dI_r, dI_m, dg_v of the segment from (q0, r_mu) over [0, length] with `panels` panels.
fn integrate_segment(q0: f32, r_mu: f32, length: f32, panels: u32) -> SegmentValues {
    var out: SegmentValues;
    out.scatter_r = vec3<f32>(0.0);
    out.scatter_m = vec3<f32>(0.0);
    out.transmittance = vec3<f32>(1.0);
    if length <= 0.0 {
        return out;
    }
    let dl = length / f32(panels);
    var column = vec3<f32>(0.0);
    for (var p = 0u; p < panels; p++) {
        let a = f32(p) * dl;
        var panel = vec3<f32>(0.0);
        for (var k = 0u; k < 5u; k++) {
            let node = 0.5 + 0.5 * GL5_NODES[k];
            let t = a + node * dl;
            let rho = density_along(q0, r_mu, t);
            panel += GL5_WEIGHTS[k] * rho;
            // The column from the panel's start to the node.
            var partial = vec3<f32>(0.0);
            for (var m = 0u; m < 5u; m++) {
                partial += GL5_WEIGHTS[m]
                    * density_along(q0, r_mu, a + (0.5 + 0.5 * GL5_NODES[m]) * node * dl);
            }
            let to_node = column + partial * (0.5 * node * dl);
            let weight = 0.5 * dl * GL5_WEIGHTS[k] * exp(-optical_depth(to_node));
            out.scatter_r += weight * rho.x * atmosphere.rayleigh_scattering_per_m.xyz;
            out.scatter_m += weight * rho.y * atmosphere.mie_scattering_per_m.xyz;
        }
        column += panel * (0.5 * dl);
    }
    out.transmittance = exp(-optical_depth(column));
    return out;
}

fn store(id: vec2<u32>, v: SegmentValues) {
    textureStore(scatter_r, id, vec4<f32>(v.scatter_r, 1.0));
    textureStore(scatter_m, id, vec4<f32>(v.scatter_m, 1.0));
    textureStore(transmittance, id, vec4<f32>(v.transmittance, 1.0));
}

// Texel (i, j) of the plane tables (`plane_tables::texel_ray`): row j at
// rho = H j / (height - 1); columns i < width / 2 for rays that meet the ground, at equal
// steps of the distance to it from r - bottom (straight down) to rho (the horizon), the
// others for rays to the top, from top - r (straight up) to rho + H. The segment runs
// Delta_t, or less where its ray leaves the atmosphere.
@compute @workgroup_size(8, 8)
fn planes(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(scatter_r);
    if any(id.xy >= size) {
        return;
    }
    let bottom = atmosphere.bottom_radius_m;
    let top = atmosphere.top_radius_m;
    let horizon_sq = (top - bottom) * (top + bottom);
    let horizon = sqrt(horizon_sq);
    let half = size.x / 2u;
    let rho = horizon * f32(id.y) / f32(size.y - 1u);
    let q0 = rho * rho;
    let r = sqrt(bottom * bottom + q0);
    let ground = id.x < half;
    let x = f32(id.x % half) / f32(half - 1u);
    let range = plane_distance_range(q0, r, rho, ground);
    let d = range.x + x * max(range.y - range.x, 0.0);
    var v: SegmentValues;
    if d <= 0.0 {
        v = integrate_segment(q0, 0.0, 0.0, 1u);
    } else {
        // r mu from bottom^2 = r^2 + d^2 + 2 r mu d (or top^2), without forming mu.
        var r_mu = (horizon_sq - q0 - d * d) / (2.0 * d);
        if ground {
            r_mu = -(q0 + d * d) / (2.0 * d);
        }
        v = integrate_segment(q0, r_mu, min(params.interval_m, d), params.plane_panels);
    }
    store(id.xy, v);
}

// Texel (i, row) of the sphere tables: sphere k = row / 3, kind row % 3 (down, chord,
// up); the segment of length d = d_min + (d_max - d_min) i / (entries - 1) to its end
// sphere (`SphereTables::build`). Kinds that do not exist keep dI = 0, dg_v = 1.
@compute @workgroup_size(8, 8)
fn spheres(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(scatter_r);
    if any(id.xy >= size) {
        return;
    }
    let row = sphere_rows[id.y];
    var length = 0.0;
    var r_mu = 0.0;
    if row.w >= 0.0 {
        length = row.z + (row.w - row.z) * f32(id.x) / f32(size.x - 1u);
        // q_end = q0 + d^2 + 2 r mu d.
        r_mu = select(0.0, (row.y - length * length) / (2.0 * length), length > 0.0);
    }
    store(id.xy, integrate_segment(row.x, r_mu, length, params.sphere_panels));
}
