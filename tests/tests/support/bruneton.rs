//! What the bruneton parity tests share: model settings from `key=value` items, a frame
//! of a preset, and its tables built on the GPU and the CPU compared texel by texel.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::Bruneton;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::sky_model::ModelSettings;
use render_wgpu::GpuContext;
use render_wgpu::frame::{Frame, LocalView};
use render_wgpu::sky::bruneton::{BrunetonPass, StoreTable};

use super::view;

/// Model settings with `key=value` items as options.
pub fn settings(options: &[&str]) -> ModelSettings {
    let mut s = ModelSettings::default();
    for item in options {
        let (k, v) = item.split_once('=').unwrap();
        s.options.set(k, v);
    }
    s
}

/// A `w` x `h` bruneton frame of `preset` seen from `v` with a vertical field of view of
/// `fov` degrees.
pub fn frame(
    preset: &str,
    settings: ModelSettings,
    v: LocalView,
    fov: f64,
    w: u32,
    h: u32,
) -> Frame {
    let atmosphere = Atmosphere::preset(preset).unwrap();
    Frame {
        camera_position_m: v.position_m(atmosphere.bottom_radius_m),
        orientation: v.orientation(),
        vertical_fov_deg: fov,
        sun_direction: v.sun_direction(),
        atmosphere,
        model: ModelId::Bruneton,
        settings,
        exposure_ev100: 14.0,
        width: w,
        height: h,
        terrain: None,
    }
}

/// Worst |gpu - cpu| / max(|cpu|, floor) over a table's channels, with the floor a
/// fraction `floor_share` of the table's largest value; and where.
pub fn worst(gpu: &[[f32; 4]], cpu: &[[f32; 3]], floor_share: f64) -> (f64, usize) {
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
pub fn compare_tables(gpu: &GpuContext, preset: &str, options: &[&str]) -> [f64; 4] {
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
