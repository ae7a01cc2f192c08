// Library: the bindings of the dobashi model's passes over its tables, the per-pixel pass
// (`sky/dobashi/pixel.wgsl`) and the ambient table's build (`sky/dobashi/ambient.wgsl`),
// which bind the same group 0 at 2 to 11 (the build writes its table at 12; the pass
// reads the terrain's shadow map at 12 and 13 and writes at 14). Rust twins:
// render-wgpu's `sky/dobashi/` (`DobashiUniform`, the bind group layout). CPU twin of
// the tables: atmosphere-core's `models/dobashi/` (`plane_tables.rs`, `sphere_tables.rs`,
// `ambient.rs`). Paper: Dobashi, Yamamoto and Nishita 2002, sections 5.2-5.3 (g_l, the
// tables of the sampling planes and of the sample spheres).

#import common/atmosphere_params.wgsl

struct DobashiParams {
    // Delta_t, m.
    interval_m: f32,
    // 1: the frame's camera is far enough out to use the sample spheres (decided in f64
    // on the CPU, `Tracer::uses_spheres`).
    use_spheres: u32,
    // 1: the ambient term is on (every `max_orders` but 1).
    ambient_on: u32,
    // Scattering orders of the ambient term, 0 for all (`AmbientTable::build`).
    max_orders: u32,
    // The ambient table's sphere integral: this many zenith steps times this many
    // azimuths.
    ambient_directions: u32,
    spheres: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(2) var<uniform> dobashi: DobashiParams;
@group(0) @binding(3) var g_l: texture_2d<f32>;
@group(0) @binding(4) var plane_scatter_r: texture_2d<f32>;
@group(0) @binding(5) var plane_scatter_m: texture_2d<f32>;
@group(0) @binding(6) var plane_transmittance: texture_2d<f32>;
@group(0) @binding(7) var sphere_scatter_r: texture_2d<f32>;
@group(0) @binding(8) var sphere_scatter_m: texture_2d<f32>;
@group(0) @binding(9) var sphere_transmittance: texture_2d<f32>;
// Per sphere and kind (down, chord, up): q0 of the sphere, q of the end sphere minus q0,
// shortest and longest segment (negative: no such segment) (`sphere_rows`).
@group(0) @binding(10) var<storage, read> sphere_rows: array<vec4<f32>>;
// psi per unit solar irradiance (rgb) at equal steps of the sun's cosine from -1 to 1,
// an n x 1 texture: in the pass the table `sky/dobashi/ambient.wgsl` wrote; while that table
// is built, a table of ones, the unit ambient radiance its rays see.
@group(0) @binding(11) var ambient_table: texture_2d<f32>;
