// The bindings every bruneton shader shares (render-wgpu's `sky/bruneton/bindings.rs`):
// the atmosphere (binding 0, `common/atmosphere_params.wgsl`), the model's parameters,
// the transmittance tables, the store and the density table. Each shader's own resources
// follow from binding 6 on.

#import common/atmosphere_params.wgsl

// The parameters of the model's shaders (render-wgpu's `BrunetonUniform`). Offsets and
// texel counts are in texels of the store (`vec4<f32>`).
struct BrunetonParams {
    // Texels of S along r, mu, mu_s and nu.
    r_size: u32,
    mu_size: u32,
    mu_s_size: u32,
    nu_size: u32,
    // Texels of E along mu_s and r.
    irradiance_mu_s_size: u32,
    irradiance_r_size: u32,
    // The sphere integrals: Gauss-Legendre panels of 8 zenith angles on each side of the
    // horizon, and azimuths over [0, pi].
    sphere_panels: u32,
    sphere_azimuths: u32,
    // Trapezoid intervals along each texel's ray.
    view_samples: u32,
    // 1 when Mie is computed (not pruned).
    mie_on: u32,
    // 1 for order 2: the previous order is single scattering, the previous irradiance
    // direct sunlight.
    previous_is_single: u32,
    // The most orders.
    max_orders: u32,
    // The first texel of each table in the store.
    density_offset: u32,
    single_rayleigh_offset: u32,
    single_mie_offset: u32,
    multiple_offset: u32,
    delta_s_offset: u32,
    delta_j_offset: u32,
    delta_e_offset: u32,
    irradiance_offset: u32,
    // The moments of Delta J (`sky/bruneton/scattering_density.wgsl`), and the partial
    // sums of an order (`sky/bruneton/orders.wgsl`).
    moments_offset: u32,
    partials_offset: u32,
    // Texels of S (and of each table of its size), and of E.
    scattering_texels: u32,
    irradiance_texels: u32,
    // The delta-M Mie phase function: forward fraction, chi1, chi2.
    mie_forward_fraction: f32,
    mie_chi1: f32,
    mie_chi2: f32,
    // The share of all the table's radiance below which an order ends the loop.
    order_threshold: f32,
    // Step of the density table, m.
    density_step_m: f32,
    // The lowest sun cosine of S and E; 1 when u_nu is linear in the scattering angle.
    min_mu_s: f32,
    nu_by_angle: u32,
    mie_directions: u32,
    // Texels of the store each of its bindings covers (the last may cover fewer).
    store_chunk_texels: u32,
    // 1 when u_mu_s continues the paper's curve linearly below -0.2.
    mu_s_knee: u32,
    // 1 when S is read geometrically along mu_s below the horizontal.
    geometric_mu_s: u32,
    // 1 when the nodes along each texel's ray are placed by density.
    density_nodes: u32,
    // 1 when the sun is a disk where it meets the horizon, of this angular radius
    // (radians).
    sun_disk: u32,
    sun_angular_radius: f32,
    // 1 when look-ups weigh their nu texels between the texels' positions clamped to the
    // ray's range of nu.
    nu_edge: u32,
    // 1 when the fourth coordinate is the azimuth between the view's and the sun's
    // vertical planes.
    nu_by_azimuth: u32,
    // 1 when the sky half of the mu axis spreads its texels towards the zenith.
    mu_zenith: u32,
    // 1 when Mie's quadrature lays its directions out in the texel's frame.
    mie_horizon: u32,
}

@group(0) @binding(2) var<uniform> bruneton: BrunetonParams;
// The columns of matter T(r, mu) and the transmittance table: the `columns` and
// `transmittance` outputs of `sky/transmittance_table.wgsl`.
@group(0) @binding(3) var transmittance_columns: texture_2d<f32>;
@group(0) @binding(5) var transmittance: texture_2d<f32>;
// The store: every table being built, each at its offset in `bruneton` (vec4 per texel,
// rgb = the three channels), indexed as on the CPU so that a table read back compares
// texel by texel. One buffer bound as four consecutive ranges (chunks) of
// `store_chunk_texels` texels, so that it may exceed the device's largest storage
// binding; bindings past the last chunk repeat it. Read and written only through
// `store_read` and `store_write`, by the texel's index in the whole store.
@group(0) @binding(4) var<storage, read_write> store0: array<vec4<f32>>;
@group(0) @binding(13) var<storage, read_write> store1: array<vec4<f32>>;
@group(0) @binding(14) var<storage, read_write> store2: array<vec4<f32>>;
@group(0) @binding(15) var<storage, read_write> store3: array<vec4<f32>>;

// Texel `i` of the store.
fn store_read(i: u32) -> vec4<f32> {
    let chunk = i / bruneton.store_chunk_texels;
    let j = i - chunk * bruneton.store_chunk_texels;
    switch chunk {
        case 0u: {
            return store0[j];
        }
        case 1u: {
            return store1[j];
        }
        case 2u: {
            return store2[j];
        }
        default: {
            return store3[j];
        }
    }
}

// Writes `value` to texel `i` of the store.
fn store_write(i: u32, value: vec4<f32>) {
    let chunk = i / bruneton.store_chunk_texels;
    let j = i - chunk * bruneton.store_chunk_texels;
    switch chunk {
        case 0u: {
            store0[j] = value;
        }
        case 1u: {
            store1[j] = value;
        }
        case 2u: {
            store2[j] = value;
        }
        default: {
            store3[j] = value;
        }
    }
}
// The density table, copied from the store into a 1D texture for the shaders' reads.
@group(0) @binding(12) var density_table: texture_1d<f32>;
