//! Ice crystals by ray tracing: the 22 and 46 degree halos at the prisms' minimum
//! deviations, energy kept by absorption-free ice, normalisation, Cauchy's mean
//! projected area, sundogs of oriented plates, extreme shapes and bad input.

use atmosphere_core::numerics::sampling::{Sampler, orthonormal_basis};
use atmosphere_core::optics::ice::crystal::HexagonalPrism;
use atmosphere_core::optics::ice::orientation::Orientation;
use atmosphere_core::optics::ice::phase_table::{IcePhaseTable, RaySettings, ice_phase_table};
use atmosphere_core::optics::ice::ray_tracer::{IceOptics, trace};
use atmosphere_core::optics::refractive_index::ice::ice_refractive_index;
use glam::DVec3;
use num_complex::Complex64;

fn settings(rays: usize) -> RaySettings {
    RaySettings {
        rays,
        bin_deg: 0.1,
        seed: 7,
    }
}

/// Minimum deviation of a prism of apex angle `apex_deg`: D = 2 asin(n sin(A / 2)) - A.
fn minimum_deviation_deg(n: f64, apex_deg: f64) -> f64 {
    let a = apex_deg.to_radians();
    (2.0 * (n * (0.5 * a).sin()).asin() - a).to_degrees()
}

/// The centre of the brightest bin within `half_window` degrees of `around`.
fn peak_deg(table: &IcePhaseTable, around: f64, half_window: f64) -> f64 {
    table
        .angles_deg
        .iter()
        .zip(&table.phase)
        .filter(|(a, _)| (*a - around).abs() <= half_window)
        .fold(
            (0.0, f64::MIN),
            |best, (&a, &p)| if p > best.1 { (a, p) } else { best },
        )
        .0
}

#[test]
fn halos_of_randomly_oriented_columns_peak_at_the_prisms_minimum_deviations() {
    let m = ice_refractive_index(550.0).unwrap();
    let crystal = HexagonalPrism::new(20e-6, 40e-6).unwrap();
    let table = ice_phase_table(
        &crystal,
        m,
        550e-9,
        Orientation::Random,
        settings(2_000_000),
    )
    .unwrap();
    for apex in [60.0, 90.0] {
        let d = minimum_deviation_deg(m.re, apex);
        let peak = peak_deg(&table, d, 2.0);
        println!("apex {apex}: minimum deviation {d:.3}, peak {peak:.3}");
        assert!(
            (peak - d).abs() < 0.3,
            "apex {apex}: peak {peak} against {d}"
        );
    }
    assert!((table.integral() - 1.0).abs() < 1e-6);
}

#[test]
fn absorption_free_ice_scatters_every_ray_and_the_table_is_normalised() {
    let crystal = HexagonalPrism::new(30e-6, 100e-6).unwrap();
    let optics = IceOptics {
        index: 1.311,
        absorption_per_m: 0.0,
    };
    let mut sampler = Sampler::new(3);
    let radius = crystal.bounding_radius_m();
    let mut hits = 0;
    for _ in 0..20_000 {
        let z: f64 = 2.0 * sampler.uniform() - 1.0;
        let phi = std::f64::consts::TAU * sampler.uniform();
        let s = (1.0 - z * z).sqrt();
        let d = DVec3::new(s * phi.cos(), s * phi.sin(), z);
        let (e1, e2) = orthonormal_basis(d);
        let origin = radius * (sampler.uniform() - 0.5) * e1
            + radius * (sampler.uniform() - 0.5) * e2
            - 2.0 * radius * d;
        let mut left = 0.0;
        if let Some(o) = trace(&crystal, optics, origin, d, |_, w| left += w) {
            hits += 1;
            assert_eq!(o.absorbed, 0.0);
            assert!(o.dropped < 1e-6);
            assert!((left - 1.0).abs() < 1e-6, "{left}");
            assert!((left + o.dropped - 1.0).abs() < 1e-12);
        }
    }
    assert!(hits > 10_000);
    // Absorbing ice (1/e in 100 um): what leaves, what is absorbed and what is dropped
    // still sum to the incident weight.
    let dark = IceOptics {
        index: 1.311,
        absorption_per_m: 1e4,
    };
    let d = DVec3::new(0.3, -0.5, 0.8).normalize();
    let (e1, e2) = orthonormal_basis(d);
    for i in 0..1000 {
        let u = i as f64 / 1000.0 - 0.5;
        let origin = radius * u * e1 + 0.3 * radius * u * e2 - 2.0 * radius * d;
        let mut left = 0.0;
        if let Some(o) = trace(&crystal, dark, origin, d, |_, w| left += w) {
            assert!(o.absorbed > 0.0);
            assert!((left + o.absorbed + o.dropped - 1.0).abs() < 1e-12);
        }
    }
    let table = ice_phase_table(
        &crystal,
        Complex64::new(1.311, 0.0),
        550e-9,
        Orientation::Random,
        settings(20_000),
    )
    .unwrap();
    assert!((table.integral() - 1.0).abs() < 1e-6);
    assert!((table.scattering_efficiency - 2.0).abs() < 1e-6);
    assert!(table.largest_dropped < 1e-6);
    // Absorbing ice (k = 1e-4 at 550 nm: 1/e in 440 um) scatters less.
    let dark = ice_phase_table(
        &crystal,
        Complex64::new(1.311, 1e-4),
        550e-9,
        Orientation::Random,
        settings(20_000),
    )
    .unwrap();
    assert!(dark.scattering_efficiency < 1.9 && dark.scattering_efficiency > 1.5);
    assert!((dark.integral() - 1.0).abs() < 1e-6);
}

/// Cauchy: the projected area averaged over random orientations is a quarter of the
/// surface; the rays' hit fraction estimates it within three binomial deviations.
#[test]
fn rays_find_cauchys_mean_projected_area() {
    for (radius, length) in [(50e-6, 1e-6), (10e-6, 400e-6), (20e-6, 40e-6)] {
        let crystal = HexagonalPrism::new(radius, length).unwrap();
        let rays = 20_000;
        let table = ice_phase_table(
            &crystal,
            Complex64::new(1.311, 0.0),
            550e-9,
            Orientation::Random,
            settings(rays),
        )
        .unwrap();
        let disc = std::f64::consts::PI * crystal.bounding_radius_m().powi(2);
        let p = crystal.surface_area_m2() / 4.0 / disc;
        let sigma = disc * (p * (1.0 - p) / rays as f64).sqrt();
        let expected = crystal.surface_area_m2() / 4.0;
        assert!(
            (table.projected_area_m2 - expected).abs() < 3.0 * sigma,
            "{radius} {length}: {} against {expected}",
            table.projected_area_m2
        );
    }
}

/// Plates falling flat, the sun on the horizon: light crosses the prism faces in the
/// horizontal plane, at the 60 degree prism's minimum deviation (the sundogs).
#[test]
fn oriented_plates_with_the_sun_on_the_horizon_make_sundogs_at_minimum_deviation() {
    let m = ice_refractive_index(550.0).unwrap();
    let plate = HexagonalPrism::new(50e-6, 10e-6).unwrap();
    let orientation = Orientation::horizontal_plates(0.5, 0.0).unwrap();
    let table = ice_phase_table(&plate, m, 550e-9, orientation, settings(100_000)).unwrap();
    let d = minimum_deviation_deg(m.re, 60.0);
    let peak = peak_deg(&table, d, 2.0);
    assert!((peak - d).abs() < 0.3, "peak {peak} against {d}");
    assert!((table.integral() - 1.0).abs() < 1e-6);
    // The sun overhead: light along the axis, no prism path through side faces.
    let overhead = Orientation::horizontal_plates(0.5, 90.0).unwrap();
    let table = ice_phase_table(&plate, m, 550e-9, overhead, settings(20_000)).unwrap();
    assert!((table.integral() - 1.0).abs() < 1e-6);
    assert!(table.phase.iter().all(|p| p.is_finite() && *p >= 0.0));
}

#[test]
fn extreme_shapes_stay_finite_and_normalised_and_bad_input_is_named() {
    let m = ice_refractive_index(440.0).unwrap();
    for (radius, length) in [(100e-6, 2e-6), (5e-6, 1e-3)] {
        let crystal = HexagonalPrism::new(radius, length).unwrap();
        let table =
            ice_phase_table(&crystal, m, 440e-9, Orientation::Random, settings(10_000)).unwrap();
        assert!(table.phase.iter().all(|p| p.is_finite() && *p >= 0.0));
        assert!((table.integral() - 1.0).abs() < 1e-6);
        assert!(table.asymmetry > 0.5 && table.asymmetry < 1.0);
    }
    let e = HexagonalPrism::new(100e-6, 1e-6).unwrap_err().to_string();
    assert!(e.contains("aspect ratio"), "{e}");
    let e = HexagonalPrism::new(0.0, 1e-6).unwrap_err().to_string();
    assert!(e.contains("radius"), "{e}");
    let e = Orientation::horizontal_plates(0.5, 91.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("sun elevation"), "{e}");
    let crystal = HexagonalPrism::new(10e-6, 10e-6).unwrap();
    let bad_bin = RaySettings {
        bin_deg: 0.07,
        ..settings(10_000)
    };
    assert!(ice_phase_table(&crystal, m, 440e-9, Orientation::Random, bad_bin).is_err());
    assert!(ice_phase_table(&crystal, m, 440e-9, Orientation::Random, settings(10)).is_err());
    // The same seed gives the same table.
    let a = ice_phase_table(&crystal, m, 440e-9, Orientation::Random, settings(5_000)).unwrap();
    let b = ice_phase_table(&crystal, m, 440e-9, Orientation::Random, settings(5_000)).unwrap();
    assert_eq!(a, b);
}
