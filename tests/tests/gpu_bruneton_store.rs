//! The bruneton store split over several storage bindings
//! (`BrunetonPass::with_store_binding`): small tables whose store spans four bindings,
//! with chunk boundaries inside single Mie, the multiple part and Delta S, built as with
//! one binding bit for bit and as the CPU builds them; a store that needs more bindings
//! than the shaders have is an error naming the sizes and the limit.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

mod support;

use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::sky::bruneton::{BrunetonPass, StoreTable};
use render_wgpu::{Frame, GpuContext, RenderError};
use support::{frame, gpu_or_skip, view};

/// S of 8 x 32 x 16 x 8 = 32768 texels and E of 64 x 16: a store of 175232 texels
/// (density 8192, five tables of S, two of E, moments 896, partials 256), 2.8 MB.
const REDUCED: [&str; 4] = ["r=8", "mu=32", "mu_s=16", "nu=8"];

/// Bindings of 700 KiB: chunks of 44800 texels, four of them, the boundaries at texels
/// 44800 (single Mie), 89600 (the multiple part) and 134400 (Delta S).
const FOUR_CHUNKS: u64 = 700 * 1024;

/// Bindings of 256 KiB: the store would need eleven.
const TOO_SMALL: u64 = 256 * 1024;

/// The tables the comparisons read, in the CPU's order.
const TABLES: [StoreTable; 4] = [
    StoreTable::SingleRayleigh,
    StoreTable::SingleMie,
    StoreTable::Multiple,
    StoreTable::Irradiance,
];

fn reduced_frame() -> Frame {
    let mut f = frame(ModelId::Bruneton, view(10.0, 80.0, 50.0), 60.0, 8, 8);
    let mut settings = ModelSettings::default();
    for item in REDUCED {
        let (k, v) = item.split_once('=').unwrap();
        settings.options.set(k, v);
    }
    f.settings = settings;
    f
}

/// The tables of `f` built by a pass whose store is bound in ranges of at most
/// `binding_bytes`.
fn build(gpu: &GpuContext, f: &Frame, binding_bytes: u64) -> Vec<Vec<[f32; 4]>> {
    let mut pass = BrunetonPass::with_store_binding(gpu, binding_bytes).unwrap();
    pass.build_tables(gpu, f).unwrap();
    TABLES
        .iter()
        .map(|&t| pass.read_table(gpu, t).unwrap())
        .collect()
}

/// Worst |gpu - cpu| / max(|cpu|, 1e-3 of the table's peak) over a table's channels.
fn worst(gpu: &[[f32; 4]], cpu: &[[f32; 3]]) -> f64 {
    assert_eq!(gpu.len(), cpu.len());
    let peak = cpu
        .iter()
        .flatten()
        .fold(0.0f64, |m, &x| m.max(f64::from(x).abs()));
    let floor = (peak * 1e-3).max(1e-30);
    let mut out = 0.0f64;
    for (g, c) in gpu.iter().zip(cpu) {
        for k in 0..3 {
            let e = (f64::from(g[k]) - f64::from(c[k])).abs() / f64::from(c[k]).abs().max(floor);
            out = if e.is_nan() {
                f64::INFINITY
            } else {
                out.max(e)
            };
        }
    }
    out
}

#[test]
fn a_store_over_four_bindings_builds_as_one_binding_and_as_the_cpu() {
    let Some(gpu) = gpu_or_skip("bruneton store bindings") else {
        return;
    };
    let f = reduced_frame();
    let split = build(&gpu, &f, FOUR_CHUNKS);
    let whole = build(&gpu, &f, u64::MAX);
    for ((table, a), b) in TABLES.iter().zip(&split).zip(&whole) {
        let differ = a.iter().zip(b).filter(|(x, y)| x != y).count();
        assert_eq!(
            differ, 0,
            "{table:?}: {differ} texels differ from one binding"
        );
    }
    let cpu = Bruneton::prepare(&f.atmosphere, &f.settings).unwrap();
    let t = &cpu.tables()[0];
    let mie = t.single_mie.as_ref().expect("Mie is not pruned on Earth");
    let cpu_tables = [
        &t.single_rayleigh.data,
        &mie.data,
        &t.multiple.data,
        &t.irradiance.data,
    ];
    for ((table, gpu_table), cpu_table) in TABLES.iter().zip(&split).zip(cpu_tables) {
        let e = worst(gpu_table, cpu_table);
        // The tolerance of the one-binding parity test (`gpu_bruneton_parity.rs`).
        assert!(e < 1e-2, "{table:?}: worst relative error {e:.2e}");
    }
}

#[test]
fn a_store_needing_more_bindings_than_the_shaders_have_is_an_error_naming_it() {
    let Some(gpu) = gpu_or_skip("bruneton store bindings") else {
        return;
    };
    let mut pass = BrunetonPass::with_store_binding(&gpu, TOO_SMALL).unwrap();
    let err = pass.build_tables(&gpu, &reduced_frame()).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, RenderError::Unsupported(_)), "{text}");
    for part in [
        "r=8 mu=32 mu_s=16 nu=8",
        "2803712 bytes",
        "4 storage bindings",
    ] {
        assert!(text.contains(part), "{part:?} not in: {text}");
    }
}
