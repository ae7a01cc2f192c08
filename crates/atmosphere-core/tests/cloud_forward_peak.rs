//! The forward peak taken as no scattering (delta-M's truncation, Wiscombe 1977) as the
//! voxel cloud's path tracer takes it: the fraction cut from Henyey-Greenstein's peak
//! against its closed form, the cut table normalised and unchanged past the cone but
//! for 1 / (1 - f), the cut medium's scattering past the cone unchanged, and the cut
//! tracer against the exact one in a thick ball.

use atmosphere_core::clouds::layer::orders::{ANGLES, ScatteringOrders};
use atmosphere_core::clouds::medium::CloudMedium;
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::reference::forward_peak::{ForwardPeakCut, truncated_phase};
use atmosphere_core::clouds::volume::camera::{VolumeCamera, VolumeSun};
use atmosphere_core::clouds::volume::cloud::VoxelCloud;
use atmosphere_core::clouds::volume::path_traced::{
    PathTracedImage, PathTracing, path_traced_image,
};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

mod common;

use common::voxel_ball::smooth_ball;

fn orders(g: f64) -> ScatteringOrders {
    ScatteringOrders::new(&[LegendreSeries::henyey_greenstein(g, 400)]).unwrap()
}

/// Henyey-Greenstein at the cosine `mu`, sr^-1.
fn hg(g: f64, mu: f64) -> f64 {
    (1.0 - g * g) / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5))
}

/// The peak above its value at the cone's edge, in closed form: Henyey-Greenstein's
/// integral over the cone of cosine `mu_c`, (1 - g^2) / (2 g) (1 / (1 - g) - 1 /
/// sqrt(1 + g^2 - 2 g mu_c)), less the edge's value times the cone's solid angle.
fn hg_peak_fraction(g: f64, mu_c: f64) -> f64 {
    let within =
        (1.0 - g * g) / (2.0 * g) * (1.0 / (1.0 - g) - 1.0 / (1.0 + g * g - 2.0 * g * mu_c).sqrt());
    within - hg(g, mu_c) * 2.0 * std::f64::consts::PI * (1.0 - mu_c)
}

#[test]
fn the_cut_fraction_of_henyey_greenstein_is_its_closed_form() {
    for (g, cone_deg) in [(0.85, 5.0), (0.85, 15.0), (0.9, 10.0)] {
        let orders = orders(g);
        let table = &orders.table(0)[..ANGLES];
        let (cut, fraction) = truncated_phase(table, cone_deg);
        let mu_c = f64::cos(f64::to_radians(cone_deg));
        let expected = hg_peak_fraction(g, mu_c);
        println!("g {g}, cone {cone_deg} deg: f {fraction:.5}, closed form {expected:.5}");
        assert!(expected > 0.02, "the case cuts a real peak");
        assert!((fraction - expected).abs() < 2e-3, "{fraction} {expected}");
        assert!((cut.integral() - 1.0).abs() < 1e-9, "{}", cut.integral());
        // Past the cone the cut table is the original over 1 - f; within it, the
        // edge's value over 1 - f.
        for angle_deg in [cone_deg + 1.0, 40.0, 120.0, 180.0] {
            let mu = f64::cos(f64::to_radians(angle_deg));
            let ratio = cut.value(mu) * (1.0 - fraction) / hg(g, mu);
            assert!((ratio - 1.0).abs() < 2e-3, "{angle_deg} deg: {ratio}");
        }
        for angle_deg in [0.0, cone_deg / 3.0, 0.9 * cone_deg] {
            let inside = cut.value(f64::cos(f64::to_radians(angle_deg))) * (1.0 - fraction);
            let edge = hg(g, mu_c);
            assert!(
                (inside / edge - 1.0).abs() < 2e-3,
                "{angle_deg} deg: {inside} {edge}"
            );
        }
    }
    let orders = orders(0.85);
    let (_, fraction) = truncated_phase(&orders.table(0)[..ANGLES], 0.0);
    assert_eq!(fraction, 0.0, "no cone cuts nothing");
}

/// A smooth ball of cloud (`common/voxel_ball.rs`, optical depth about 10 through its
/// centre), albedo `albedo`, Henyey-Greenstein `g`.
fn ball(albedo: f64, g: f64) -> VoxelCloud {
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g }).unwrap();
    smooth_ball(0.05, albedo, phase)
}

/// beta' omega' = beta omega (1 - f): what scatters past the cone is unchanged, and
/// beta' (1 - omega') = beta (1 - omega): so is what is absorbed.
#[test]
fn the_cut_medium_keeps_its_absorption_and_its_scattering_past_the_cone() {
    let cloud = ball(0.9, 0.85);
    let cut = ForwardPeakCut {
        medium: &cloud,
        fraction: 0.3,
    };
    let x = DVec3::new(5.0, -3.0, 2.0);
    let (beta, omega) = (cloud.extinction(x), cloud.single_scattering_albedo(x));
    let (beta_cut, omega_cut) = (cut.extinction(x), cut.single_scattering_albedo(x));
    assert!(beta > 0.0);
    assert!((beta_cut * omega_cut - beta * omega * 0.7).abs() < 1e-12 * beta);
    assert!((beta_cut * (1.0 - omega_cut) - beta * (1.0 - omega)).abs() < 1e-12 * beta);
    assert!(beta_cut <= cut.majorant());
}

/// In the thick ball under a forward-peaked Henyey-Greenstein (g = 0.85) the tracer
/// with 10 degrees cut (f about 0.15) answers the exact tracer's image: the means
/// within three standard errors plus 1 %, and pixel by pixel what is left beyond the
/// exact image's noise is the cut image's noise plus at most 1 %.
#[test]
fn the_cut_tracer_agrees_with_the_exact_one_in_a_thick_ball() {
    let g = 0.85;
    let cloud = ball(1.0, g);
    let orders = orders(g);
    let sun = VolumeSun::new(30.0, 40.0, vec![1.0]).unwrap();
    let camera =
        VolumeCamera::looking_at(DVec3::new(-500.0, -300.0, 100.0), DVec3::ZERO, 30.0, 8, 6)
            .unwrap();
    let run = |forward_peak_deg, seed| {
        let tracing = PathTracing {
            paths: 32_768,
            seed,
            forward_peak_deg,
        };
        path_traced_image(&cloud, &camera, &sun, &orders, &tracing, &|| {}).unwrap()
    };
    let (exact, cut) = (run(0.0, 1), run(10.0, 2));
    // The image's mean and its standard error.
    let mean = |image: &PathTracedImage| {
        let n = image.image.radiance.len() as f64;
        let variance: f64 = image.standard_error.iter().map(|s| s * s).sum();
        (
            image.image.radiance.iter().sum::<f64>() / n,
            variance.sqrt() / n,
        )
    };
    let ((m_exact, s_exact), (m_cut, s_cut)) = (mean(&exact), mean(&cut));
    let error = exact.relative_rms_error(&cut.image);
    println!(
        "mean exact {m_exact:.5} +- {s_exact:.5} (noise {:.4}), cut {m_cut:.5} +- {s_cut:.5} \
         (noise {:.4}); cut against exact beyond the exact's noise {error:.4}",
        exact.relative_noise(),
        cut.relative_noise()
    );
    assert!(
        m_exact > 0.0 && s_exact < 0.01 * m_exact,
        "the test's own noise"
    );
    let sigma = s_exact.hypot(s_cut);
    assert!(
        (m_cut - m_exact).abs() < 3.0 * sigma + 0.01 * m_exact,
        "{m_cut} {m_exact}"
    );
    assert!(error < 1.5 * cut.relative_noise() + 0.01, "{error}");
}
