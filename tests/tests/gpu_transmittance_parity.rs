//! The GPU transmittance table (`shaders/sky/transmittance_table.wgsl`) against its CPU twin
//! (`atmosphere_core::optics::transmittance_table`), texel by texel at 680, 550 and 440 nm.
//!
//! Needs a GPU adapter (lavapipe will do). Without one the tests fail with the
//! `NoAdapter` message saying what to install, unless `ATMOS_SKIP_GPU_TESTS=1`, when
//! they record that they skipped (counted in the suite's summary line).

mod support;

use std::time::Instant;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::optics::transmittance_table::{BRUNETON_TABLE_SIZE, TransmittanceTable};
use render_wgpu::frame::atmosphere_uniform::{AtmosphereUniform, RGB_WAVELENGTHS_NM};
use render_wgpu::sky::transmittance::TransmittancePass;
use support::gpu_or_skip;

/// Largest allowed |T_gpu - T_cpu|: the f32 rounding of a transmittance near 1 plus that
/// of its optical depth, with a margin for GPUs with a less accurate `exp` (Vulkan allows
/// 3 + 2|x| ulp); it still catches the naive f32 altitude `radius_at(r, mu, t) - bottom`,
/// which loses half a metre to the radius's rounding.
const MAX_ABS_ERROR: f64 = 5e-6;

/// Largest allowed |tau_gpu - tau_cpu| / max(tau_cpu, 1) with tau = -ln T: the relative
/// error of the optical depth, which bounds the relative error of the small
/// transmittances near the horizon (tau up to 11 on both planets): some tens of f32 ulps
/// from summing 320 samples, with a margin that the naive altitude still exceeds.
const MAX_OPTICAL_DEPTH_ERROR: f64 = 2e-5;

fn check_parity(preset: &str) {
    let Some(gpu) = gpu_or_skip(preset) else {
        return;
    };
    let atmosphere = Atmosphere::preset(preset).unwrap();
    let start = Instant::now();
    let pass = TransmittancePass::new(&gpu).unwrap();
    pass.run(
        &gpu,
        &AtmosphereUniform::new(&atmosphere, RGB_WAVELENGTHS_NM).unwrap(),
    );
    let texels = pass.read_back(&gpu).unwrap();
    let gpu_time = start.elapsed();

    let (width, height) = BRUNETON_TABLE_SIZE;
    let start = Instant::now();
    let table = TransmittanceTable::build(&atmosphere, width, height);
    let cpu_time = start.elapsed();
    let extinctions =
        RGB_WAVELENGTHS_NM.map(|l| atmosphere.coefficients(l).extinction_per_species());

    assert_eq!(texels.len(), width * height);
    let mut worst_abs = (0.0f64, 0, 0, 0);
    let mut worst_tau = (0.0f64, 0, 0, 0);
    for j in 0..height {
        for i in 0..width {
            let texel = texels[j * width + i];
            assert_eq!(texel[3], 1.0, "alpha at ({i}, {j})");
            for (c, extinction) in extinctions.iter().enumerate() {
                let cpu = table.texel_transmittance(i, j, *extinction);
                let abs = (f64::from(texel[c]) - cpu).abs();
                if abs > worst_abs.0 || abs.is_nan() {
                    worst_abs = (abs, i, j, c);
                }
                let tau_error = (f64::from(texel[c]).ln() - cpu.ln()).abs() / (-cpu.ln()).max(1.0);
                if tau_error > worst_tau.0 || tau_error.is_nan() {
                    worst_tau = (tau_error, i, j, c);
                }
            }
        }
    }
    println!(
        "{preset} on {}: GPU {gpu_time:.1?} (pipeline, dispatch, read-back), CPU {cpu_time:.1?}; \
         worst |dT| {:.2e} at texel ({}, {}) channel {}; worst |d tau|/max(tau, 1) {:.2e} at ({}, {}) channel {}",
        gpu.adapter_summary(),
        worst_abs.0,
        worst_abs.1,
        worst_abs.2,
        worst_abs.3,
        worst_tau.0,
        worst_tau.1,
        worst_tau.2,
        worst_tau.3,
    );
    assert!(
        worst_abs.0 <= MAX_ABS_ERROR,
        "{preset}: worst |dT| {:e}",
        worst_abs.0
    );
    assert!(
        worst_tau.0 <= MAX_OPTICAL_DEPTH_ERROR,
        "{preset}: worst |d tau| {:e}",
        worst_tau.0
    );
}

#[test]
fn earth_transmittance_table_matches_the_cpu() {
    check_parity("earth");
}

#[test]
fn mars_transmittance_table_matches_the_cpu() {
    check_parity("mars");
}
