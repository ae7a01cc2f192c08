//! The bruneton model on the GPU against its CPU twin (atmosphere-core `bruneton`): every
//! table read back texel by texel, the number of scattering orders, rendered pixels
//! against `Bruneton::radiance` on the same pixel rays (plus the sun disk), and the
//! frame plan's table skipping.
//!
//! Needs a GPU adapter (lavapipe will do), with the skip policy of the other GPU tests.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::bruneton::Bruneton;
use atmosphere_core::model::{ModelSettings, SkyModel};
use atmosphere_core::sun_disk;
use atmosphere_core::view_segment::{SegmentEnd, ViewSegment};
use render_wgpu::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use render_wgpu::bruneton_pass::{BrunetonPass, StoreTable};
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::{GpuContext, GpuError, RenderError, Renderer};

/// Reduced table sizes for the parity tests (S 8 x 32 x 16 x 8, the paper's sample
/// counts), so that the CPU and lavapipe build them in seconds.
const REDUCED: [&str; 4] = ["r=8", "mu=32", "mu_s=16", "nu=8"];

fn settings(options: &[&str]) -> ModelSettings {
    let mut s = ModelSettings::default();
    for item in options {
        let (k, v) = item.split_once('=').unwrap();
        s.options.set(k, v);
    }
    s
}

fn gpu_or_skip(test: &str) -> Option<GpuContext> {
    match GpuContext::headless() {
        Ok(g) => Some(g),
        Err(e @ GpuError::NoAdapter { .. })
            if std::env::var("ATMOS_SKIP_GPU_TESTS").as_deref() == Ok("1") =>
        {
            println!("{test}: SKIPPED (ATMOS_SKIP_GPU_TESTS=1): {e}");
            None
        }
        Err(e) => panic!("{e}"),
    }
}

fn view(altitude_m: f64, view_zenith_deg: f64, sun_zenith_deg: f64) -> LocalView {
    LocalView {
        altitude_m,
        view_zenith_deg,
        view_azimuth_deg: 0.0,
        sun_zenith_deg,
        sun_azimuth_deg: 30.0,
    }
}

fn frame(preset: &str, settings: ModelSettings, v: LocalView, fov: f64, w: u32, h: u32) -> Frame {
    let atmosphere = Atmosphere::preset(preset).unwrap();
    Frame {
        camera_position_m: v.position_m(atmosphere.bottom_radius_m),
        orientation: v.orientation(),
        vertical_fov_deg: fov,
        sun_direction: v.sun_direction(),
        atmosphere,
        model: "bruneton".into(),
        settings,
        exposure_ev100: 14.0,
        width: w,
        height: h,
    }
}

/// Worst |gpu - cpu| / max(|cpu|, floor) over a table's channels, with the floor a
/// fraction `floor_share` of the table's largest value; and where.
fn worst(gpu: &[[f32; 4]], cpu: &[[f32; 3]], floor_share: f64) -> (f64, usize) {
    assert_eq!(gpu.len(), cpu.len());
    let peak = cpu
        .iter()
        .flat_map(|v| v.iter())
        .fold(0.0f64, |m, &x| m.max(f64::from(x).abs()));
    let floor = (peak * floor_share).max(1e-30);
    let mut out = (0.0, 0);
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        for k in 0..3 {
            let e = (f64::from(g[k]) - f64::from(c[k])).abs() / f64::from(c[k]).abs().max(floor);
            if e > out.0 || e.is_nan() {
                out = (e, i);
            }
        }
    }
    out
}

/// Builds the tables of `preset` on both sides and compares them; returns the worst
/// relative errors (single Rayleigh, single Mie, multiple, irradiance).
fn compare_tables(gpu: &GpuContext, preset: &str, options: &[&str]) -> [f64; 4] {
    let f = frame(
        preset,
        settings(options),
        view(10.0, 80.0, 50.0),
        60.0,
        8,
        8,
    );
    let cpu = Bruneton::prepare(&f.atmosphere, &f.settings).unwrap();
    let mut pass = BrunetonPass::new(gpu).unwrap();
    let plan = pass.build_tables(gpu, &f).unwrap();
    let t = &cpu.tables()[0];
    let size = t.single_rayleigh.size;
    // The 3D textures in the CPU's order: texel (x = nu * mu_s + mu_s, y = mu, z = r).
    let from_texture = |k: usize| {
        let tex = pass.read_scattering_texture(gpu, k).unwrap();
        (0..size.texels())
            .map(|i| {
                let (ir, imu, imus, inu) = size.coords(i);
                tex[((ir * size.mu + imu) * size.nu + inu) * size.mu_s + imus]
            })
            .collect::<Vec<_>>()
    };
    let floor = 1e-3;
    let rayleigh = worst(&from_texture(0), &t.single_rayleigh.data, floor);
    let mie = t
        .single_mie
        .as_ref()
        .map_or((0.0, 0), |m| worst(&from_texture(1), &m.data, floor));
    let multiple = worst(&from_texture(2), &t.multiple.data, floor);
    let e = pass.read_table(gpu, StoreTable::Irradiance).unwrap();
    let irradiance = worst(&e, &t.irradiance.data, floor);
    let state = pass.read_orders(gpu).unwrap();
    let cpu_orders: Vec<_> = cpu.orders().iter().map(|o| (o.order, o.share)).collect();
    let cpu_last = cpu
        .orders()
        .iter()
        .filter(|o| o.share.is_finite())
        .map(|o| o.order)
        .max()
        .unwrap();
    println!(
        "{preset} {options:?}: worst relative error (floor 1e-3 of the peak): single Rayleigh {:.2e} at {}, \
         single Mie {:.2e} at {}, multiple {:.2e} at {}, irradiance {:.2e} at {}; orders GPU {} {:?}, CPU {:?}; plan {plan}",
        rayleigh.0,
        rayleigh.1,
        mie.0,
        mie.1,
        multiple.0,
        multiple.1,
        irradiance.0,
        irradiance.1,
        state.last_order,
        &state.shares[1..=(state.last_order as usize + 1).min(63)],
        cpu_orders,
    );
    assert_eq!(state.last_order, cpu_last, "orders differ");
    [rayleigh.0, mie.0, multiple.0, irradiance.0]
}

#[test]
fn tables_match_the_cpu() {
    let Some(gpu) = gpu_or_skip("bruneton tables") else {
        return;
    };
    let errors = compare_tables(&gpu, "earth", &REDUCED);
    assert!(errors.iter().all(|e| *e < 1e-2), "{errors:?}");
}
