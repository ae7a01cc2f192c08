//! The oneil model on the GPU against its CPU twin: the optical-depth table of
//! `shaders/sky/oneil/optical_depth_table.wgsl` node by node against `OpticalDepthTable::build`, and the
//! frames of `shaders/sky/oneil/pixel.wgsl` through the `Renderer` against `Oneil::radiance` on the
//! same pixel rays (see `support/mod.rs`).

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::oneil::OpticalDepthTable;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::GpuContext;
use render_wgpu::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use render_wgpu::gpu::pipeline::uniform_buffer;
use render_wgpu::sky::oneil::OneilTablePass;
use support::{
    check, check_other_atmospheres, check_standard_frames, check_standard_surfaces,
    check_texel_reads, frame, renderer_or_skip, standard_frames, view,
};

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel: the f16
/// store (4.9e-4), the f32 table and f32 lookups. Measured on lavapipe: see the test
/// output.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

/// Largest allowed relative difference of a table channel between GPU and CPU (density
/// channels relative to the node's own value, columns too, with a floor of 1e-3 m of
/// column). Measured on lavapipe: see the test output.
const MAX_TABLE_ERROR: f64 = 1e-4;

/// Builds the table of `atmosphere` on the GPU and compares it with the CPU's; returns
/// the worst relative error of the density and the column channels.
fn compare_table(
    gpu: &GpuContext,
    name: &str,
    atmosphere: &Atmosphere,
    (heights, angles, ray_samples): (usize, usize, usize),
) -> (f64, f64) {
    let uniform = AtmosphereUniform::new(atmosphere, RGB_WAVELENGTHS_NM).unwrap();
    let buffer = uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>());
    gpu.queue
        .write_buffer(&buffer, 0, bytemuck::bytes_of(&uniform));
    let pass = OneilTablePass::new(gpu, heights as u32, angles as u32).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(gpu, &buffer, ray_samples as u32, &mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    let texels = pass.read_back(gpu).unwrap();
    let cpu = OpticalDepthTable::build(atmosphere, heights, angles, ray_samples);
    assert_eq!(texels.len(), heights * angles);
    let (mut density, mut column) = ((0.0f64, (0, 0)), (0.0f64, (0, 0)));
    for j in 0..angles {
        for i in 0..heights {
            let (g, c) = (texels[j * heights + i], cpu.node(i, j));
            for k in 0..4 {
                let (g, c) = (f64::from(g[k]), f64::from(c[k]));
                assert!(g.is_finite(), "{name}: node ({i}, {j}) channel {k} is {g}");
                let worst = if k % 2 == 0 {
                    // A shadow decided differently would be an error of 1.
                    &mut density
                } else {
                    &mut column
                };
                let error = (g - c).abs() / c.abs().max(if k % 2 == 0 { 1e-30 } else { 1e-3 });
                if error > worst.0 {
                    *worst = (error, (i, j));
                }
            }
        }
    }
    println!(
        "oneil table {name} ({heights} x {angles}, {ray_samples} samples): densities within \
         {:.2e} (node {:?}), columns within {:.2e} (node {:?})",
        density.0, density.1, column.0, column.1
    );
    (density.0, column.0)
}

#[test]
fn the_optical_depth_table_matches_the_cpu_node_by_node() {
    let Some(renderer) = renderer_or_skip("oneil table") else {
        return;
    };
    let gpu = renderer.gpu();
    for (name, atmosphere) in ["earth", "hazy", "mars"].map(|n| (n, Atmosphere::preset(n).unwrap()))
    {
        // The paper's size, and an odd number of angles (a node on the horizon) with more
        // samples per ray.
        for size in [(64, 64, 50), (33, 129, 200)] {
            let (density, column) = compare_table(gpu, name, &atmosphere, size);
            assert!(
                density <= MAX_TABLE_ERROR,
                "{name} {size:?}: density {density:e}"
            );
            assert!(
                column <= MAX_TABLE_ERROR,
                "{name} {size:?}: column {column:e}"
            );
        }
    }
}

/// The texel-by-texel reads, which a device without `FLOAT32_FILTERABLE` runs, against
/// the CPU and against the filtered reads (the default where the adapter filters
/// Rgba32Float, as lavapipe does) pixel by pixel.
#[test]
fn texel_reads_match_the_cpu_and_the_filtered_reads() {
    let frames = standard_frames(ModelId::Oneil);
    let frames = [frames[0].clone(), frames[2].clone()];
    let (name, surface) = &frames[0];
    check_texel_reads("oneil", &frames, Some((name, surface)), MAX_RELATIVE_ERROR);
}

#[test]
fn oneil_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("oneil parity") else {
        return;
    };
    check_standard_frames(&mut renderer, ModelId::Oneil, MAX_RELATIVE_ERROR);
    // A camera just inside the top looking through the limb, where the two-lookup
    // subtraction changes form along the ray; the paper's settings replaced by finer ones.
    let mut f = frame(ModelId::Oneil, view(59_000.0, 95.0, 70.0), 30.0, 64, 36);
    check(&mut renderer, "inside the top", &f, MAX_RELATIVE_ERROR);
    f.settings.options =
        ModelOptions::parse(&["samples=16", "table_heights=128", "table_angles=256"]).unwrap();
    check(&mut renderer, "finer settings", &f, MAX_RELATIVE_ERROR);
    check_other_atmospheres(&mut renderer, ModelId::Oneil, MAX_RELATIVE_ERROR);
}

#[test]
fn oneil_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    check_standard_surfaces("oneil surfaces", ModelId::Oneil, MAX_RELATIVE_ERROR);
}

/// Whether rendering `f` builds the table.
fn builds(renderer: &mut render_wgpu::Renderer, f: &render_wgpu::Frame) -> bool {
    renderer.render(f).unwrap().runs("optical_depth")
}

#[test]
fn the_table_is_rebuilt_only_when_densities_or_its_settings_change() {
    let Some(mut renderer) = renderer_or_skip("oneil plan") else {
        return;
    };
    let mut f = frame(ModelId::Oneil, view(10.0, 80.0, 40.0), 60.0, 16, 9);
    assert!(builds(&mut renderer, &f));
    assert_eq!(renderer.table_bytes(), 64 * 64 * 16);
    f.exposure_ev100 = 12.0;
    assert!(!builds(&mut renderer, &f));
    // The table holds density integrals: more aerosol changes no node.
    f.atmosphere = f.atmosphere.with_aerosol_scale(2.0);
    assert!(!builds(&mut renderer, &f));
    f.settings.options = ModelOptions::parse(&["table_ray_samples=60"]).unwrap();
    assert!(builds(&mut renderer, &f));
    f.settings.options = ModelOptions::parse(&["table_ray_samples=60", "samples=3"]).unwrap();
    assert!(!builds(&mut renderer, &f));
    f.settings.options = ModelOptions::parse(&["table_angles=32"]).unwrap();
    assert!(builds(&mut renderer, &f));
    assert_eq!(renderer.table_bytes(), 64 * 32 * 16);
    f.atmosphere = Atmosphere::preset("hazy").unwrap();
    assert!(builds(&mut renderer, &f));
    f.settings.options = ModelOptions::parse(&["colour=1"]).unwrap();
    let err = renderer.render(&f).unwrap_err();
    assert!(err.to_string().contains("colour"), "{err}");
}
