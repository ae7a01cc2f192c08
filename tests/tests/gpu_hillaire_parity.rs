//! The GPU hillaire model (`render_wgpu::sky::hillaire`, `shaders/sky/hillaire/`) against
//! its CPU twin (`atmosphere_core::models::hillaire`): every table read back and compared texel by
//! texel, rendered pixels against `Hillaire::radiance` on `Frame::pixel_ray` rays (plus
//! the transmitted sun disk), and the frame planner's choices.
//!
//! Needs a GPU adapter (lavapipe will do). Without one the tests fail with the
//! `NoAdapter` message saying what to install, unless `ATMOS_SKIP_GPU_TESTS=1`, when
//! they record that they skipped (counted in the suite's summary line).

mod support;

use atmosphere_core::models::hillaire::view_cache::view_key;
use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
use atmosphere_core::models::id::ModelId;
use render_wgpu::Renderer;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::sky::hillaire::{HillairePass, Table};
use support::{
    check_each, check_standard_surfaces, check_sun_disk, check_texel_reads, frame_in, gpu_or_skip,
    renderer_or_skip, standard_frames, view,
};

/// Largest relative error of a table's texel, |gpu - cpu| / max(|cpu|, 1e-3 of the
/// table's largest value). Both sides march in the same order with the same samples;
/// the GPU in f32 (sums of 20-64 segments, f32 exponentials and the f32 transmittance
/// table's look-ups, whose coordinates carry rounding of the radius) against f64.
/// Measured on lavapipe: see the test output and `tables_match_the_cpu`.
const MAX_TABLE_ERROR: f64 = 1e-3;

/// Largest |gpu - cpu| of the volume's transmittance.
const MAX_TRANSMITTANCE_ERROR: f64 = 1e-5;

/// Largest allowed |L_gpu - L_cpu| / max(L_cpu, FLOOR) per pixel and channel: the f16
/// store (4.9e-4), the tables' f32 error above, and f32 interpolation weights, which
/// move steeply near the horizon where the latitude mapping is a square root.
const MAX_RELATIVE_ERROR: f64 = 2e-3;

/// A hillaire frame on the earth preset ([`support::frame`]).
fn frame(view: LocalView, fov_deg: f64, width: u32, height: u32) -> Frame {
    support::frame(ModelId::Hillaire, view, fov_deg, width, height)
}

fn cpu_model(frame: &Frame) -> Hillaire {
    Hillaire::prepare(
        &frame.atmosphere,
        &frame.settings,
        HillaireSettings::default(),
    )
    .unwrap()
}

/// Worst relative error of `gpu` texels (rgb) against `cpu` values (three per texel,
/// from `offset` every `stride`), with a floor of 1e-3 of the largest CPU value.
fn table_error(gpu: &[[f32; 4]], cpu: &[f32], stride: usize, offset: usize) -> f64 {
    assert_eq!(gpu.len() * stride, cpu.len());
    let largest = cpu.iter().fold(0.0f64, |m, v| m.max(f64::from(v.abs())));
    let floor = 1e-3 * largest;
    let mut worst = 0.0f64;
    for (i, texel) in gpu.iter().enumerate() {
        for c in 0..3 {
            let want = f64::from(cpu[i * stride + offset + c]);
            let error = (f64::from(texel[c]) - want).abs() / want.abs().max(floor);
            if error > worst || error.is_nan() {
                worst = error;
            }
        }
    }
    worst
}

/// Every table of a 1 km view looking down (so that the volume is built) against the
/// CPU's. Measured on lavapipe: see the printed worst errors.
#[test]
fn tables_match_the_cpu() {
    let Some(gpu) = gpu_or_skip("hillaire tables") else {
        return;
    };
    let f = frame(view(1_000.0, 120.0, 60.0), 60.0, 16, 9);
    let mut pass = HillairePass::new(&gpu).unwrap();
    let plan = pass.build_tables(&gpu, &f).unwrap();
    for table in [
        "transmittance",
        "multiple_scattering",
        "ground_irradiance",
        "sky_view",
    ] {
        assert!(plan.runs(table), "{table}: {plan}");
    }
    assert!(plan.runs("aerial_perspective"), "{plan}");
    let cpu = cpu_model(&f);
    let r = f.camera_position_m.length();
    let (view_r, view_mu_s) = view_key(
        &f.atmosphere,
        r,
        f.sun_direction.dot(f.camera_position_m / r),
    );

    let columns = pass.read_table(&gpu, Table::Transmittance).unwrap();
    let cpu_columns: Vec<f32> = cpu
        .medium()
        .transmittance
        .columns
        .iter()
        .flat_map(|c| c.map(|v| v as f32))
        .collect();
    let transmittance = table_error(&columns, &cpu_columns, 3, 0);

    let psi = pass.read_table(&gpu, Table::MultipleScattering).unwrap();
    let psi_error = table_error(&psi, &cpu.multiple_scattering().unwrap().values, 3, 0);

    let ground = pass.read_table(&gpu, Table::GroundIrradiance).unwrap();
    let ground_error = table_error(&ground, &cpu.ground_irradiance().unwrap().values, 3, 0);

    let sky = pass.read_table(&gpu, Table::SkyView).unwrap();
    let sky_error = cpu.with_sky_view(view_r, view_mu_s, |s| table_error(&sky, &s.values, 3, 0));

    // The volume: per direction, per slice, radiance then transmittance on the CPU;
    // slices are the GPU texture's outermost index.
    let radiance = pass.read_table(&gpu, Table::AerialPerspective).unwrap();
    let volume_t = pass.read_aerial_transmittance(&gpu).unwrap();
    let (aw, ah, slices) = HillaireSettings::default().aerial_size;
    let (aerial_error, aerial_t_error) = cpu.with_aerial_perspective(view_r, view_mu_s, |volume| {
        let reorder = |second: usize| -> Vec<f32> {
            (0..slices)
                .flat_map(|k| {
                    (0..aw * ah).flat_map(move |d| {
                        let at = ((d * slices + k) * 2 + second) * 3;
                        at..at + 3
                    })
                })
                .map(|i| volume.values[i])
                .collect()
        };
        let t_cpu = reorder(1);
        let t_worst = volume_t
            .iter()
            .zip(t_cpu.chunks_exact(3))
            .flat_map(|(g, c)| (0..3).map(move |i| (f64::from(g[i]) - f64::from(c[i])).abs()))
            .fold(0.0, f64::max);
        (table_error(&radiance, &reorder(0), 3, 0), t_worst)
    });
    println!(
        "hillaire tables on {}: worst relative error: columns {transmittance:.2e}, \
         Psi_ms {psi_error:.2e}, E_sky {ground_error:.2e}, sky view {sky_error:.2e}, \
         volume radiance {aerial_error:.2e}; volume transmittance within {aerial_t_error:.2e}",
        gpu.adapter_summary()
    );
    for (name, error) in [
        ("columns", transmittance),
        ("Psi_ms", psi_error),
        ("E_sky", ground_error),
        ("sky view", sky_error),
        ("volume radiance", aerial_error),
    ] {
        assert!(error <= MAX_TABLE_ERROR, "{name}: {error:e}");
    }
    assert!(
        aerial_t_error <= MAX_TRANSMITTANCE_ERROR,
        "{aerial_t_error:e}"
    );
}

/// The anisotropic multiple-scattering term (`ms_order=2`): Psi_ms's four blocks of
/// moments and the sky view of a hazy 1 km view against the CPU's, texel by texel, then
/// pixels of hazy views towards and away from the sun and a clear sunset. Measured on
/// lavapipe: see the printed worst errors.
#[test]
fn the_anisotropic_term_matches_the_cpu() {
    let Some(gpu) = gpu_or_skip("hillaire anisotropic tables") else {
        return;
    };
    let hazy = |view, fov| {
        let mut f = frame_in(
            atmosphere_core::atmosphere::Atmosphere::preset("hazy").unwrap(),
            ModelId::Hillaire,
            view,
            fov,
            64,
            36,
        );
        f.settings.options.set("ms_order", 2);
        f
    };
    let f = hazy(view(1_000.0, 120.0, 60.0), 60.0);
    let mut pass = HillairePass::new(&gpu).unwrap();
    pass.build_tables(&gpu, &f).unwrap();
    let settings = HillaireSettings::from_options(&f.settings.options).unwrap();
    let cpu = Hillaire::prepare(&f.atmosphere, &f.settings, settings).unwrap();
    let psi = pass.read_table(&gpu, Table::MultipleScattering).unwrap();
    let table = cpu.multiple_scattering().unwrap();
    assert_eq!(table.order, 2);
    let psi_error = table_error(&psi, &table.values, 3, 0);
    let r = f.camera_position_m.length();
    let (view_r, view_mu_s) = view_key(
        &f.atmosphere,
        r,
        f.sun_direction.dot(f.camera_position_m / r),
    );
    let sky = pass.read_table(&gpu, Table::SkyView).unwrap();
    let sky_error = cpu.with_sky_view(view_r, view_mu_s, |s| table_error(&sky, &s.values, 3, 0));
    println!(
        "hillaire ms_order=2 tables on {}: worst relative error: Psi_ms blocks {psi_error:.2e}, \
         sky view {sky_error:.2e}",
        gpu.adapter_summary()
    );
    assert!(psi_error <= MAX_TABLE_ERROR, "Psi_ms: {psi_error:e}");
    assert!(sky_error <= MAX_TABLE_ERROR, "sky view: {sky_error:e}");
    drop(pass);

    let Some(mut renderer) = renderer_or_skip("hillaire anisotropic parity") else {
        return;
    };
    let mut sunset = frame(view(2_000.0, 88.0, 89.0), 60.0, 64, 36);
    sunset.settings.options.set("ms_order", 2);
    let frames = [
        ("hazy, towards the sun", hazy(view(2.0, 60.0, 45.0), 70.0)),
        (
            "hazy, ground and far ground",
            hazy(view(10_000.0, 100.0, 50.0), 60.0),
        ),
        ("sunset", sunset),
    ];
    check_each(&mut renderer, &frames, MAX_RELATIVE_ERROR);
}

/// The similarity-scaled multiple scattering (`ms_delta=0.45`): Psi_ms, the ground's sky
/// irradiance and the sky view of a hazy 1 km view against the CPU's, texel by texel (and
/// Psi_ms away from the paper's, so that the setting reached the shaders), then pixels of
/// hazy views (sky view, volume, per-pixel march) and a clear sunset. Measured on
/// lavapipe: see the printed worst errors.
#[test]
fn the_similarity_scaled_term_matches_the_cpu() {
    let Some(gpu) = gpu_or_skip("hillaire similarity-scaled tables") else {
        return;
    };
    let hazy = |view, fov| {
        let mut f = frame_in(
            atmosphere_core::atmosphere::Atmosphere::preset("hazy").unwrap(),
            ModelId::Hillaire,
            view,
            fov,
            64,
            36,
        );
        f.settings.options.set("ms_delta", 0.45);
        f
    };
    let f = hazy(view(1_000.0, 120.0, 60.0), 60.0);
    let mut pass = HillairePass::new(&gpu).unwrap();
    pass.build_tables(&gpu, &f).unwrap();
    let settings = HillaireSettings::from_options(&f.settings.options).unwrap();
    let cpu = Hillaire::prepare(&f.atmosphere, &f.settings, settings).unwrap();
    let paper = Hillaire::prepare(&f.atmosphere, &f.settings, HillaireSettings::default()).unwrap();
    let psi = pass.read_table(&gpu, Table::MultipleScattering).unwrap();
    let psi_error = table_error(&psi, &cpu.multiple_scattering().unwrap().values, 3, 0);
    let from_paper = table_error(&psi, &paper.multiple_scattering().unwrap().values, 3, 0);
    let ground = pass.read_table(&gpu, Table::GroundIrradiance).unwrap();
    let ground_error = table_error(&ground, &cpu.ground_irradiance().unwrap().values, 3, 0);
    let r = f.camera_position_m.length();
    let (view_r, view_mu_s) = view_key(
        &f.atmosphere,
        r,
        f.sun_direction.dot(f.camera_position_m / r),
    );
    let sky = pass.read_table(&gpu, Table::SkyView).unwrap();
    let sky_error = cpu.with_sky_view(view_r, view_mu_s, |s| table_error(&sky, &s.values, 3, 0));
    println!(
        "hillaire ms_delta=0.45 tables on {}: worst relative error: Psi_ms {psi_error:.2e} \
         (against the paper's Psi_ms {from_paper:.2e}), E_sky {ground_error:.2e}, sky view \
         {sky_error:.2e}",
        gpu.adapter_summary()
    );
    assert!(from_paper > 0.1, "Psi_ms is the paper's: {from_paper:e}");
    for (name, error) in [
        ("Psi_ms", psi_error),
        ("E_sky", ground_error),
        ("sky view", sky_error),
    ] {
        assert!(error <= MAX_TABLE_ERROR, "{name}: {error:e}");
    }
    drop(pass);

    let Some(mut renderer) = renderer_or_skip("hillaire similarity-scaled parity") else {
        return;
    };
    let mut sunset = frame(view(2_000.0, 88.0, 89.0), 60.0, 64, 36);
    sunset.settings.options.set("ms_delta", 0.45);
    let frames = [
        ("hazy, towards the sun", hazy(view(2.0, 60.0, 45.0), 70.0)),
        (
            "hazy, ground and far ground",
            hazy(view(10_000.0, 100.0, 50.0), 60.0),
        ),
        (
            "hazy, from 100 km",
            hazy(view(100_000.0, 100.0, 60.0), 40.0),
        ),
        ("sunset", sunset),
    ];
    check_each(&mut renderer, &frames, MAX_RELATIVE_ERROR);
}

/// Pixels of five 64x36 views against the CPU model. Measured on lavapipe: see the
/// printed worst errors.
#[test]
fn hillaire_frames_match_the_cpu_from_the_ground_to_far_orbit() {
    let Some(mut renderer) = renderer_or_skip("hillaire parity") else {
        return;
    };
    let mut sunset = view(2_000.0, 88.0, 89.0);
    sunset.sun_azimuth_deg = 5.0;
    let frames = [
        // 1 m above the ground at noon, looking at the horizon: sky view, volume, ground.
        ("ground, noon", frame(view(1.0, 85.0, 10.0), 70.0, 64, 36)),
        // Sunset from 2 km, looking towards the sun.
        ("sunset", frame(sunset, 60.0, 64, 36)),
        // 10 km, looking down past the horizon: ground within and beyond the volume's
        // range.
        ("10 km", frame(view(10_000.0, 100.0, 50.0), 60.0, 64, 36)),
        // The limb from 100 km: marched from where the rays enter the atmosphere.
        ("100 km", frame(view(100_000.0, 100.0, 60.0), 40.0, 64, 36)),
        // The whole planet from 1e8 m, the terminator in view.
        ("1e8 m", frame(view(1e8, 180.0, 80.0), 9.0, 64, 36)),
    ];
    check_each(&mut renderer, &frames, MAX_RELATIVE_ERROR);
}

/// The texel-by-texel reads, which a device without `FLOAT32_FILTERABLE` runs, against
/// the CPU on views that read the tables and one that marches (whose every segment reads
/// the transmittance table and Psi_ms), and against the filtered reads (the default where
/// the adapter filters Rgba32Float, as lavapipe does) pixel by pixel.
#[test]
fn texel_reads_match_the_cpu_and_the_filtered_reads() {
    let frames = [
        ("ground, noon", frame(view(1.0, 85.0, 10.0), 70.0, 64, 36)),
        ("10 km", frame(view(10_000.0, 100.0, 50.0), 60.0, 64, 36)),
        ("100 km", frame(view(100_000.0, 100.0, 60.0), 40.0, 64, 36)),
    ];
    let (name, surface) = &standard_frames(ModelId::Hillaire)[0];
    check_texel_reads(
        "hillaire",
        &frames,
        Some((name, surface)),
        MAX_RELATIVE_ERROR,
    );
}

#[test]
fn hillaire_lights_surfaces_and_sees_them_through_the_air_as_on_the_cpu() {
    // Surfaces within the volume's range read it, those beyond are marched (the planner
    // picks the entry point that does both), and from space every ray is marched.
    check_standard_surfaces("hillaire surfaces", ModelId::Hillaire, MAX_RELATIVE_ERROR);
}

#[test]
fn the_sun_disk_is_added_through_the_sky_view_transmittance() {
    // A sun 60 deg from the zenith seen from 500 m with 1 deg of field: about 10 pixels
    // across.
    check_sun_disk("hillaire sun disk", ModelId::Hillaire, MAX_RELATIVE_ERROR);
}

/// The HDR image of `frame` rendered by `renderer`, and its plan.
fn render(renderer: &mut Renderer, frame: &Frame) -> (FramePlan, Vec<[f32; 4]>) {
    let plan = renderer.render(frame).unwrap();
    (plan, renderer.read_hdr().unwrap())
}

/// A frame of the planner test: its name, the frame, the tables it must build and steps
/// it must skip (with why).
type Step = (
    &'static str,
    Frame,
    &'static [&'static str],
    &'static [(&'static str, &'static str)],
);

/// A sequence of frames rendered by one renderer, which skips what did not change,
/// against each frame rendered by a fresh renderer, which builds everything it needs:
/// the images must be identical, bit for bit, and each frame must run and skip the
/// steps its changes call for (the dependency sets of the CPU's `Hillaire::update`).
#[test]
fn skipped_steps_change_nothing_and_only_changed_inputs_rebuild() {
    let Some(mut renderer) = renderer_or_skip("hillaire plan") else {
        return;
    };
    let (w, h) = (32, 18);
    let down = frame(view(1_000.0, 120.0, 40.0), 60.0, w, h);
    let mut steps: Vec<Step> = Vec::new();
    let all: &[&str] = &[
        "transmittance",
        "multiple_scattering",
        "ground_irradiance",
        "sky_view",
        "aerial_perspective",
    ];
    steps.push(("first frame", down.clone(), all, &[]));
    steps.push((
        "the same frame again",
        down.clone(),
        &[],
        &[("aerial_perspective", "inputs unchanged")],
    ));
    let mut exposure = down.clone();
    exposure.exposure_ev100 = 10.0;
    steps.push((
        "another exposure",
        exposure,
        &[],
        &[("sky_view", "inputs unchanged")],
    ));
    // Same camera and sun, looking up: the volume is not needed.
    let mut up = frame(view(1_000.0, 30.0, 40.0), 60.0, w, h);
    up.camera_position_m = down.camera_position_m;
    steps.push((
        "looking up",
        up,
        &[],
        &[("aerial_perspective", "no ground in view")],
    ));
    // From 10 km at the horizon the ground is in view, but beyond the volume's 32 km:
    // those rays are marched, and the volume is skipped.
    let far = frame(view(10_000.0, 93.0, 40.0), 20.0, w, h);
    steps.push((
        "ground beyond the volume",
        far,
        &["sky_view"],
        &[("aerial_perspective", "no ground in view")],
    ));
    let mut sun = down.clone();
    sun.sun_direction = view(1_000.0, 0.0, 70.0).sun_direction();
    steps.push((
        "the sun moved",
        sun.clone(),
        &["sky_view", "aerial_perspective"],
        &[("multiple_scattering", "inputs unchanged")],
    ));
    let mut aerosol = sun.clone();
    aerosol.atmosphere = aerosol.atmosphere.with_aerosol_scale(3.0);
    steps.push((
        "more aerosol",
        aerosol.clone(),
        &[
            "multiple_scattering",
            "ground_irradiance",
            "sky_view",
            "aerial_perspective",
        ],
        &[("transmittance", "inputs unchanged")],
    ));
    let mut albedo = aerosol.clone();
    albedo.atmosphere.ground_albedo = 0.3;
    steps.push((
        "brighter ground",
        albedo.clone(),
        &[
            "multiple_scattering",
            "ground_irradiance",
            "sky_view",
            "aerial_perspective",
        ],
        &[("transmittance", "inputs unchanged")],
    ));
    let mut phase = albedo.clone();
    phase.atmosphere.mie.phase =
        atmosphere_core::optics::phase::PhaseFunction::HenyeyGreenstein { g: 0.7 };
    steps.push((
        "another Mie phase function",
        phase.clone(),
        &["ground_irradiance", "sky_view", "aerial_perspective"],
        &[("multiple_scattering", "inputs unchanged")],
    ));
    let mut single = phase;
    single.settings.max_orders = Some(1);
    steps.push((
        "single scattering",
        single,
        &["sky_view", "aerial_perspective"],
        &[("multiple_scattering", "single scattering")],
    ));
    for (name, f, runs, skips) in steps {
        let (plan, incremental) = render(&mut renderer, &f);
        let mut fresh = renderer_or_skip(name).unwrap();
        let (full_plan, full) = render(&mut fresh, &f);
        println!("{name}: {plan} (fresh: {full_plan})");
        let builds: Vec<&str> = plan
            .steps
            .iter()
            .filter(|s| s.kind == render_wgpu::frame::plan::StepKind::TableBuild)
            .map(|s| s.name)
            .collect();
        for table in all {
            assert_eq!(
                builds.contains(table),
                runs.contains(table),
                "{name}: {table}: {plan}"
            );
        }
        for skip in skips {
            assert!(plan.skipped.contains(skip), "{name}: {skip:?}: {plan}");
        }
        assert!(
            incremental == full,
            "{name}: the image differs from a full render"
        );
    }
}
