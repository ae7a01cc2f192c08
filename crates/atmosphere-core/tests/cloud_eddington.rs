//! The delta-Eddington slab of the cloud layer's `eddington` method: its fluxes against
//! the slab path tracer and its conditions at the boundaries.

use atmosphere_core::clouds::layer::eddington::{
    diffuse_source, downward_flux, upward_flux_at_top,
};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::slab::Slab;
use atmosphere_core::clouds::slab_transport::slab_fractions;
use atmosphere_core::optics::phase::PhaseFunction;

const G: f64 = 0.85;

/// Transmitted (direct beam included) and reflected fractions of non-absorbing
/// Henyey-Greenstein slabs from tau 1 to 60 within 7 % of the path tracer (20,000
/// paths; delta-Eddington's own error is a few per cent), and their sum 1.
#[test]
fn fluxes_follow_the_path_tracer() {
    for &(tau, mu0) in &[
        (1.0, 0.8),
        (4.0, 0.6),
        (10.0, 0.6),
        (30.0, 0.8),
        (60.0, 0.5),
    ] {
        let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: G }).unwrap();
        let slab = Slab::new(1000.0, tau / 1000.0, 1.0, phase).unwrap();
        let mc = slab_fractions(&slab, mu0, 20_000, 3).unwrap();
        let t = downward_flux(tau, 0.0, mu0, 1.0, G) / mu0;
        let r = upward_flux_at_top(tau, mu0, 1.0, G) / mu0;
        assert!(
            (t / mc.transmitted.mean - 1.0).abs() < 0.07,
            "tau {tau} mu0 {mu0}: T {t} against {} +- {}",
            mc.transmitted.mean,
            mc.transmitted.standard_error
        );
        assert!(
            (r / mc.reflected.mean - 1.0).abs() < 0.07,
            "tau {tau} mu0 {mu0}: R {r} against {} +- {}",
            mc.reflected.mean,
            mc.reflected.standard_error
        );
        // 1 - T - R: what the smallest absorption taken (1e-6) keeps.
        assert!((t + r - 1.0).abs() < 1e-3, "tau {tau}: T + R = {}", t + r);
    }
}

/// An absorbing slab keeps some light; the flux falls with depth; at the top no
/// diffuse light of the beam comes down, the sky's irradiance does, and at the base
/// none goes up; the sky's light reaches the base as the closed form says.
#[test]
fn absorption_and_the_boundaries() {
    let (tau, mu0) = (20.0, 0.7);
    let t = downward_flux(tau, 0.0, mu0, 0.99, G);
    let r = upward_flux_at_top(tau, mu0, 0.99, G);
    assert!(t + r < 0.9 * mu0, "albedo 0.99: T + R = {}", (t + r) / mu0);
    let fluxes: Vec<f64> = [0.0, 5.0, 10.0, 15.0, 20.0]
        .iter()
        .map(|&above| downward_flux(above, tau - above, mu0, 1.0, G))
        .collect();
    assert!(fluxes.windows(2).all(|w| w[1] < w[0]), "{fluxes:?}");
    // The diffuse field I_0 + mu I_1 from the source at mu_out = +-1 (g' = G / (1 + G)).
    let g_s = G / (1.0 + G);
    let field = |above: f64, sky: bool| {
        let pick = |s: (f64, f64)| if sky { s.1 } else { s.0 };
        let up = pick(diffuse_source(above, tau - above, mu0, 1.0, G, 1.0));
        let down = pick(diffuse_source(above, tau - above, mu0, 1.0, G, -1.0));
        let scale = 1.0 - G * G;
        let (i0, i1) = (
            (up + down) / (2.0 * scale),
            (up - down) / (2.0 * g_s * scale),
        );
        let pi = std::f64::consts::PI;
        (pi * (i0 - 2.0 / 3.0 * i1), pi * (i0 + 2.0 / 3.0 * i1))
    };
    let (down_at_top, _) = field(0.0, false);
    let (_, up_at_base) = field(tau, false);
    assert!(
        down_at_top.abs() < 1e-9,
        "beam: diffuse down at the top {down_at_top}"
    );
    assert!(
        up_at_base.abs() < 1e-9,
        "beam: diffuse up at the base {up_at_base}"
    );
    let (sky_at_top, _) = field(0.0, true);
    let (sky_below, sky_up_at_base) = field(tau, true);
    assert!(
        (sky_at_top - 1.0).abs() < 1e-9,
        "sky: down at the top {sky_at_top}"
    );
    assert!(
        sky_up_at_base.abs() < 1e-9,
        "sky: up at the base {sky_up_at_base}"
    );
    // Eddington's diffuse transmittance of a conservative slab under isotropic light,
    // 1 / (1 + 3/4 (1 - g) tau) (the scaled tau' (1 - g') is (1 - g) tau).
    let closed = 1.0 / (1.0 + 0.75 * (1.0 - G) * tau);
    assert!(
        (sky_below / closed - 1.0).abs() < 1e-3,
        "sky: down at the base {sky_below} against {closed}"
    );
}
