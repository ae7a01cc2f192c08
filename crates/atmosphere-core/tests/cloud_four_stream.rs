//! The delta-M four-stream slab of the cloud layer's `four-stream` method: its fluxes
//! against the slab path tracer, its conditions at the boundaries and its conservative
//! limit.

use atmosphere_core::clouds::layer::four_stream::{diffuse_fluxes, diffuse_source, truncation};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::slab::Slab;
use atmosphere_core::clouds::slab_transport::slab_fractions;
use atmosphere_core::optics::phase::PhaseFunction;

const G: f64 = 0.85;

/// Henyey and Greenstein's moments chi_l = g^l.
fn moments(g: f64) -> [f64; 5] {
    std::array::from_fn(|l| g.powi(l as i32))
}

/// Transmitted (the delta-scaled direct beam included) and reflected fractions of
/// non-absorbing Henyey-Greenstein slabs within 2 % of the path tracer (20,000 paths)
/// from tau 4 to 60 and within 12 % at tau 1 (where four streams resolve the thin
/// slab's reflection coarsely), and their sum 1.
#[test]
fn fluxes_follow_the_path_tracer() {
    let chi = moments(G);
    let (f, _) = truncation(&chi);
    for &(tau, mu0, tolerance) in &[
        (1.0, 0.8, 0.12),
        (4.0, 0.6, 0.02),
        (10.0, 0.6, 0.02),
        (30.0, 0.8, 0.02),
        (60.0, 0.5, 0.02),
    ] {
        let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: G }).unwrap();
        let slab = Slab::new(1000.0, tau / 1000.0, 1.0, phase).unwrap();
        let mc = slab_fractions(&slab, mu0, 20_000, 3).unwrap();
        let r = diffuse_fluxes(0.0, tau, mu0, 1.0, &chi).beam_up / mu0;
        let direct = (-(1.0 - f) * tau / mu0).exp();
        let t = diffuse_fluxes(tau, 0.0, mu0, 1.0, &chi).beam_down / mu0 + direct;
        println!(
            "tau {tau} mu0 {mu0}: R {r:.4} against {:.4}, T {t:.4} against {:.4}",
            mc.reflected.mean, mc.transmitted.mean
        );
        assert!(
            (r / mc.reflected.mean - 1.0).abs() < tolerance,
            "tau {tau} mu0 {mu0}: R {r} against {} +- {}",
            mc.reflected.mean,
            mc.reflected.standard_error
        );
        assert!(
            (t / mc.transmitted.mean - 1.0).abs() < tolerance,
            "tau {tau} mu0 {mu0}: T {t} against {} +- {}",
            mc.transmitted.mean,
            mc.transmitted.standard_error
        );
        // 1 - T - R: what the smallest absorption taken (1e-6) keeps.
        assert!((t + r - 1.0).abs() < 1e-3, "tau {tau}: T + R = {}", t + r);
    }
}

/// No diffuse light of the beam enters at the top nor leaves the base upwards; the
/// sky's light enters the top with its irradiance; an absorbing slab keeps light; the
/// downward flux falls with depth.
#[test]
fn boundaries_and_absorption() {
    let chi = moments(G);
    let (tau, mu0) = (20.0, 0.7);
    let top = diffuse_fluxes(0.0, tau, mu0, 1.0, &chi);
    let base = diffuse_fluxes(tau, 0.0, mu0, 1.0, &chi);
    for (what, value, expected) in [
        ("beam down at the top", top.beam_down, 0.0),
        ("beam up at the base", base.beam_up, 0.0),
        ("sky down at the top", top.sky_down, 1.0),
        ("sky up at the base", base.sky_up, 0.0),
    ] {
        assert!((value - expected).abs() < 1e-12, "{what}: {value}");
    }
    let absorbing = diffuse_fluxes(0.0, tau, mu0, 0.99, &chi).beam_up;
    assert!(
        absorbing < 0.8 * top.beam_up,
        "{absorbing} against {}",
        top.beam_up
    );
    let down: Vec<f64> = [1.0, 5.0, 10.0, 15.0, 19.0]
        .iter()
        .map(|&above| diffuse_fluxes(above, tau - above, mu0, 1.0, &chi).sky_down)
        .collect();
    assert!(down.windows(2).all(|w| w[1] < w[0]), "{down:?}");
}

/// The conservative slab's small eigenvalue is taken without cancellation: the source
/// moves smoothly as the absorption falls from 1e-3 to none, at every depth and for
/// every direction, and is finite at the sun's resonance with an eigenvalue.
#[test]
fn conservative_limit_is_smooth() {
    let chi = moments(0.87);
    for &(above, below) in &[
        (0.0, 40.0),
        (3.0, 37.0),
        (20.0, 20.0),
        (40.0, 0.0),
        (0.01, 0.02),
    ] {
        for &mu_out in &[-1.0, -0.3, 0.2, 1.0] {
            let values: Vec<f64> = [1e-3, 1e-4, 1e-5, 1e-6, 0.0]
                .iter()
                .map(|&a| diffuse_source(above, below, 0.6, 1.0 - a, &chi, mu_out).0)
                .collect();
            assert!(
                values.iter().all(|v| v.is_finite() && *v >= 0.0),
                "{values:?}"
            );
            let (last, before) = (values[4], values[3]);
            assert!(
                (last - before).abs() <= 1e-3 * last.max(1e-9),
                "{above}/{below} mu {mu_out}: {values:?}"
            );
        }
    }
    for mu0 in (1..100).map(|i| i as f64 / 100.0) {
        let (beam, sky) = diffuse_source(2.0, 3.0, mu0, 1.0, &chi, 0.5);
        assert!(
            beam.is_finite() && sky.is_finite(),
            "mu0 {mu0}: {beam} {sky}"
        );
    }
}
