//! The dobashi model on the GPU against its CPU twin: the plane and sphere tables of
//! `shaders/sky/dobashi/tables.wgsl` node by node against `PlaneTables::build` and
//! `SphereTables::build`, and the frames of `shaders/sky/dobashi/pixel.wgsl` (with the ambient table
//! of `sky/dobashi/ambient.wgsl`) through the `Renderer` against `Dobashi::radiance` on the
//! same pixel rays (see `support/mod.rs`).

mod support;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::models::dobashi::grid::Grid;
use atmosphere_core::models::dobashi::settings::{AMBIENT_DIRECTIONS, PLANES};
use atmosphere_core::models::dobashi::{DobashiSettings, PlaneTables, SphereTables};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use render_wgpu::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use render_wgpu::gpu::pipeline::uniform_buffer;
use render_wgpu::sky::dobashi::{DobashiTables, plane_interval_m, sphere_rows};
use support::{
    check, check_other_atmospheres, check_standard_frames, check_standard_surfaces,
    check_texel_reads, frame, ground_frame_in, renderer_or_skip, standard_frames, view,
};

/// Largest allowed difference of a table value between GPU and CPU, relative to the
/// value (dI with a floor of 1e-7, dg_v absolute). Measured on lavapipe: see the test
/// output.
const MAX_TABLE_ERROR: f64 = 1e-4;

/// The worst error of the GPU `texels` (rgb) against the CPU `grid`, and where.
fn worst(texels: &[[f32; 4]], grid: &Grid, floor: f64) -> (f64, (usize, usize)) {
    let mut worst = (0.0f64, (0, 0));
    for j in 0..grid.height {
        for i in 0..grid.width {
            let gpu = texels[j * grid.width + i];
            for (c, cpu) in grid.node(i, j).iter().enumerate() {
                let (g, c) = (f64::from(gpu[c]), f64::from(*cpu));
                assert!(g.is_finite(), "node ({i}, {j}) is {g}");
                let error = (g - c).abs() / c.abs().max(floor);
                if error > worst.0 {
                    worst = (error, (i, j));
                }
            }
        }
    }
    worst
}

#[test]
fn plane_and_sphere_tables_match_the_cpu_node_by_node() {
    let Some(renderer) = renderer_or_skip("dobashi tables") else {
        return;
    };
    let gpu = renderer.gpu();
    let small = DobashiSettings {
        table_heights: 16,
        table_angles: 64,
        sphere_table_angles: 32,
        ..DobashiSettings::default()
    };
    for (name, settings) in [("earth", DobashiSettings::default()), ("earth", small)]
        .into_iter()
        .chain(["hazy", "mars"].map(|n| (n, small)))
    {
        let atmosphere = Atmosphere::preset(name).unwrap();
        let spectra = Spectra::new(&atmosphere, &RGB_WAVELENGTHS_NM);
        let uniform = AtmosphereUniform::new(&atmosphere, RGB_WAVELENGTHS_NM).unwrap();
        let buffer = uniform_buffer(&gpu.device, "atmosphere", size_of::<AtmosphereUniform>());
        gpu.queue
            .write_buffer(&buffer, 0, bytemuck::bytes_of(&uniform));
        let tables = DobashiTables::new(gpu, &settings).unwrap();
        let interval = plane_interval_m(&atmosphere, &settings).unwrap();
        let rows = sphere_rows(&atmosphere, settings.spheres);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        for spheres in [false, true] {
            tables.encode(gpu, &buffer, interval, &rows, spheres, &mut encoder, None);
        }
        gpu.queue.submit([encoder.finish()]);

        let planes = PlaneTables::build(&atmosphere, &spectra, &settings, true);
        assert!((planes.interval_m / interval - 1.0).abs() < 1e-12);
        let spheres = SphereTables::build(
            &atmosphere,
            &spectra,
            settings.spheres,
            settings.sphere_table_angles,
            true,
        );
        let size = (settings.table_angles, settings.table_heights);
        for (what, gpu_tables, cpu) in [
            (
                "planes",
                &tables.planes,
                [
                    &planes.scatter_r,
                    planes.scatter_m.as_ref().unwrap(),
                    &planes.transmittance,
                ],
            ),
            (
                "spheres",
                &tables.spheres,
                [
                    &spheres.scatter_r,
                    spheres.scatter_m.as_ref().unwrap(),
                    &spheres.transmittance,
                ],
            ),
        ] {
            let texels = gpu_tables.read_back(gpu).unwrap();
            let errors = [
                worst(&texels[0], cpu[0], 1e-7),
                worst(&texels[1], cpu[1], 1e-7),
                worst(&texels[2], cpu[2], 1.0),
            ];
            println!(
                "dobashi {what} {name} {size:?}: dI_r within {:.2e} at {:?}, dI_m {:.2e} at {:?}, dg_v {:.2e} at {:?}",
                errors[0].0, errors[0].1, errors[1].0, errors[1].1, errors[2].0, errors[2].1
            );
            for (e, _) in errors {
                assert!(e <= MAX_TABLE_ERROR, "{what} {name}: {e:e}");
            }
        }
    }
}

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel: the f16
/// store (4.9e-4), the f32 tables and f32 sums over up to 230 planes. Measured on
/// lavapipe: see the test output.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

#[test]
fn dobashi_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("dobashi parity") else {
        return;
    };
    // The standard frames: planes up to 100 km, spheres from 1e8 m.
    check_standard_frames(&mut renderer, ModelId::Dobashi, MAX_RELATIVE_ERROR);
    // Single scattering (no ambient term), a hazy atmosphere, Mars.
    let mut f = standard_frames(ModelId::Dobashi)[0].1.clone();
    f.settings.max_orders = Some(1);
    check(&mut renderer, "single scattering", &f, MAX_RELATIVE_ERROR);
    f.settings.max_orders = Some(3);
    check(&mut renderer, "three orders", &f, MAX_RELATIVE_ERROR);
    check_other_atmospheres(&mut renderer, ModelId::Dobashi, MAX_RELATIVE_ERROR);
    // Spheres from 30,000 km looking down, and planes from there when allowed more.
    let mut f = frame(ModelId::Dobashi, view(3e7, 180.0, 40.0), 30.0, 48, 27);
    check(&mut renderer, "30,000 km, spheres", &f, MAX_RELATIVE_ERROR);
    f.settings.options = ModelOptions::parse(&["max_planes=100000"]).unwrap();
    check(&mut renderer, "30,000 km, planes", &f, MAX_RELATIVE_ERROR);
}

/// The most loop trips the settings' ranges allow in one GPU invocation: the ambient
/// term's 16^2 rays through up to 4096 planes each, shared by 64 lanes (one lane tracing
/// them all ran past 65535 trips, where lavapipe silently ends an invocation's loops),
/// and pixel rays through up to 2 x 4096 planes.
#[test]
fn the_largest_loops_the_settings_allow_match_the_cpu() {
    let Some(mut renderer) = renderer_or_skip("dobashi largest loops") else {
        return;
    };
    let most = [
        format!("ambient_directions={}", AMBIENT_DIRECTIONS.range.end()),
        format!("planes={}", PLANES.range.end()),
        "ambient_sun_angles=4".to_string(),
    ];
    let mut f = frame(ModelId::Dobashi, view(1.0, 80.0, 60.0), 60.0, 8, 6);
    f.settings.options = ModelOptions::parse(&most).unwrap();
    check(&mut renderer, "loops at their most", &f, MAX_RELATIVE_ERROR);
}

/// The texel-by-texel reads, which a device without `FLOAT32_FILTERABLE` runs, against
/// the CPU through the planes (with the ambient table, which traces rays too) and the
/// spheres, and against the filtered reads (the default where the adapter filters
/// Rgba32Float, as lavapipe does) pixel by pixel.
#[test]
fn texel_reads_match_the_cpu_and_the_filtered_reads() {
    let frames = [
        (
            "ground",
            ground_frame_in(Atmosphere::preset("earth").unwrap(), ModelId::Dobashi),
        ),
        (
            "30,000 km, spheres",
            frame(ModelId::Dobashi, view(3e7, 180.0, 40.0), 30.0, 48, 27),
        ),
    ];
    check_texel_reads("dobashi", &frames, None, MAX_RELATIVE_ERROR);
}

#[test]
fn dobashi_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    // Planes up to 100 km, spheres from 1e8 m: both cut where an object ends the ray.
    check_standard_surfaces("dobashi surfaces", ModelId::Dobashi, MAX_RELATIVE_ERROR);
}

/// Whether rendering `f` runs step `step`.
fn runs(renderer: &mut render_wgpu::Renderer, f: &render_wgpu::Frame, step: &str) -> bool {
    renderer.render(f).unwrap().runs(step)
}

#[test]
fn dobashi_tables_are_rebuilt_only_when_their_inputs_change() {
    let Some(mut renderer) = renderer_or_skip("dobashi plan") else {
        return;
    };
    let mut f = frame(ModelId::Dobashi, view(10.0, 80.0, 40.0), 60.0, 16, 9);
    let all = ["g_l", "plane_tables", "sphere_tables", "ambient"];
    let plan = renderer.render(&f).unwrap();
    assert!(all.iter().all(|s| plan.runs(s)), "{plan}");
    f.exposure_ev100 = 12.0;
    let plan = renderer.render(&f).unwrap();
    assert_eq!(plan.skipped.len(), 4, "{plan}");
    // More aerosol: the segments' optical depths change, the columns do not.
    f.atmosphere = f.atmosphere.with_aerosol_scale(2.0);
    let plan = renderer.render(&f).unwrap();
    assert!(
        !plan.runs("g_l") && plan.runs("plane_tables") && plan.runs("ambient"),
        "{plan}"
    );
    // The ground albedo: only the ambient term.
    f.atmosphere.ground_albedo = 0.5;
    let plan = renderer.render(&f).unwrap();
    assert!(!plan.runs("plane_tables") && plan.runs("ambient"), "{plan}");
    // Single scattering: no ambient term at all.
    f.settings.max_orders = Some(1);
    assert!(!runs(&mut renderer, &f, "ambient"));
    f.settings.options = ModelOptions::parse(&["table_max=0.5"]).unwrap();
    let err = renderer.render(&f).unwrap_err();
    assert!(err.to_string().contains("table_max"), "{err}");
}
