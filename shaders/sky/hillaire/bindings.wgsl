// Library: the bindings every pass of the hillaire model shares: its uniform at 2 and the
// columns table at 3 (the `columns` of `sky/transmittance_table.wgsl`, the CPU's shared
// table), read as `common/table_sampling.wgsl` says; each pass adds its own from 4 on.
// Rust twin: render-wgpu's `sky/hillaire/` (`HillaireUniform`, the bind group
// layouts). CPU twin of the settings: atmosphere-core's `models/hillaire/mod.rs`
// (`HillaireSettings`) and `models/hillaire/view_cache.rs`. Paper: Hillaire 2020,
// section 5 (the LUTs and their sample counts).

struct HillaireParams {
    // The view of the per-view tables (`view_cache::view_key`): camera radius, its
    // r^2 - bottom^2 (from f64) and the sun's zenith cosine there.
    view_r: f32,
    view_q: f32,
    view_mu_s: f32,
    // Depth covered by the aerial-perspective volume, m.
    aerial_range_m: f32,
    // `HillaireSettings`' sample counts.
    ms_sqrt_directions: u32,
    ms_samples: u32,
    sky_view_samples: u32,
    ap_samples_per_slice: u32,
    march_samples: u32,
    ground_zenith_panels: u32,
    ground_azimuths: u32,
    // 1: orders two and up (Psi_ms and the sky's light on the ground); 0: single
    // scattering (`max_orders = 1`).
    multiple_on: u32,
    // Zenith angle of the geometric horizon at the view's radius (`horizon_zenith`, f64).
    view_theta_h: f32,
    // The anisotropic multiple-scattering term (`moments.rs`): highest Legendre moment
    // of Psi_ms (0: the paper's isotropic term; the table stacks `psi_blocks()` blocks of
    // rows), and the Mie phase function's moments g_1, g_2.
    ms_order: u32,
    mie_g1: f32,
    mie_g2: f32,
    // The delta fraction of the similarity-scaled medium of orders two and up
    // (`models/hillaire/similarity.rs`; 0: the paper's medium, and always without orders
    // two and up), and padding.
    ms_delta: f32,
    pad_0: f32,
    pad_1: f32,
    pad_2: f32,
    // The camera's zenith, and two horizontal unit vectors there: towards the sun's
    // azimuth and 90 degrees from it (any horizontal pair when the sun is at the zenith
    // or nadir); xyz, w = 0. The pass measures view angles in this frame.
    view_up: vec4<f32>,
    view_sun_side: vec4<f32>,
    view_across: vec4<f32>,
}

@group(0) @binding(2) var<uniform> hillaire: HillaireParams;

// `moments::blocks`: blocks of rows of the Psi_ms table, Psi_0..Psi_ms_order about the
// sun and, with ms_order 2, the second moment about the local zenith.
fn psi_blocks() -> u32 {
    return select(hillaire.ms_order + 1u, hillaire.ms_order + 2u, hillaire.ms_order >= 2u);
}
@group(0) @binding(3) var transmittance_columns: texture_2d<f32>;
