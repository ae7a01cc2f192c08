//! Spheres averaged over size distributions: effective radii against closed forms,
//! unit-integral phase functions whose mean cosine is the g of the cross-sections, the
//! one-radius limit, and phase tables whose steps resolve the forward peak and glory.

use std::f64::consts::PI;

use atmosphere_core::optics::mie::coefficients::MieCoefficients;
use atmosphere_core::optics::mie::efficiencies::Efficiencies;
use atmosphere_core::optics::mie::legendre::mie_legendre_series;
use atmosphere_core::optics::mie::phase_table::{PhaseTable, table_angles_deg};
use atmosphere_core::optics::mie::polydisperse::particle_optics;
use atmosphere_core::optics::mie::size_distribution::SizeDistribution;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;

/// Deirmendjian's modified gamma with gamma = 1 has <r^3> / <r^2> = r_c (alpha + 3) /
/// alpha; the numeric moments find the mode radius of a given effective radius.
#[test]
fn modified_gamma_effective_radius_matches_its_closed_form() {
    for alpha in [2.0, 6.0, 20.0] {
        let d = SizeDistribution::modified_gamma(10e-6, alpha, 1.0).unwrap();
        let SizeDistribution::ModifiedGamma { mode_radius_m, .. } = d else {
            unreachable!()
        };
        let want = 10e-6 * alpha / (alpha + 3.0);
        assert!((mode_radius_m / want - 1.0).abs() < 1e-9, "alpha {alpha}");
        assert!((d.effective_radius_m() / 10e-6 - 1.0).abs() < 1e-9);
    }
    let d = SizeDistribution::lognormal(10e-6, 0.3).unwrap();
    assert!((d.effective_radius_m() / 10e-6 - 1.0).abs() < 1e-12);
}

#[test]
fn parameters_out_of_range_are_named() {
    for (result, what) in [
        (SizeDistribution::lognormal(10e-6, 0.0), "lognormal sigma"),
        (SizeDistribution::lognormal(10e-6, 1.5), "lognormal sigma"),
        (SizeDistribution::lognormal(-1.0, 0.2), "radius"),
        (SizeDistribution::modified_gamma(10e-6, 0.1, 1.0), "alpha"),
        (SizeDistribution::modified_gamma(10e-6, 6.0, 20.0), "gamma"),
        (SizeDistribution::lognormal(f64::NAN, 0.2), "radius"),
    ] {
        let e = result.unwrap_err().to_string();
        assert!(e.contains(what), "{e}");
    }
}

/// One radius through the average is that sphere.
#[test]
fn one_radius_is_the_single_sphere() {
    let m = water_refractive_index(550.0).unwrap();
    let radius_m = 2e-6;
    let d = SizeDistribution::Monodisperse { radius_m };
    let optics = particle_optics(m, 550e-9, &d, &[1.0, 0.0, -1.0], 1e-4).unwrap();
    let q = Efficiencies::of(&MieCoefficients::new(m, 2.0 * PI * radius_m / 550e-9).unwrap());
    assert_eq!(optics.radii, 1);
    assert!((optics.extinction_efficiency() / q.extinction - 1.0).abs() < 1e-12);
    assert!((optics.asymmetry - q.asymmetry).abs() < 1e-12);
}

/// The averaged phase function at the Gauss-Legendre nodes of the exact rule has unit
/// integral to 1e-6 and mean cosine g (from the coefficients) to 1e-6, for both kinds of
/// distribution and an absorbing material.
#[test]
fn averaged_phase_functions_are_normalised_with_mean_cosine_g() {
    let water = water_refractive_index(440.0).unwrap();
    let soot = num_complex::Complex64::new(1.75, 0.45);
    let cases = [
        (water, SizeDistribution::lognormal(2e-6, 0.2).unwrap()),
        (
            water,
            SizeDistribution::modified_gamma(3e-6, 6.0, 1.0).unwrap(),
        ),
        (soot, SizeDistribution::lognormal(0.3e-6, 0.5).unwrap()),
    ];
    for (m, d) in cases {
        let mie = mie_legendre_series(m, 440e-9, &d, 1e-3).unwrap();
        let (mut integral, mut mean_cosine) = (0.0, 0.0);
        for (&(nu, w), p) in mie.rule.iter().zip(&mie.optics.phase) {
            integral += 2.0 * PI * w * p;
            mean_cosine += 2.0 * PI * w * p * nu;
        }
        assert!((integral - 1.0).abs() < 1e-6, "{d:?}: {integral}");
        assert!((mean_cosine - mie.optics.asymmetry).abs() < 1e-6, "{d:?}");
        assert!((mie.series.asymmetry() - mie.optics.asymmetry).abs() < 1e-6);
        assert!(mie.optics.radii >= 65 && mie.optics.scattering_efficiency() > 0.0);
    }
}

/// A table's steps reach a tenth of its uniform step at 0 and 180 degrees, and the
/// table of cloud droplets (effective radius 3 um) integrates to 1 by the trapezoid rule on its own angles.
#[test]
fn phase_tables_resolve_both_ends_and_integrate_to_one() {
    for x in [1.0, 100.0, 2e4] {
        let angles = table_angles_deg(x);
        assert_eq!((angles[0], *angles.last().unwrap()), (0.0, 180.0));
        assert!(angles.windows(2).all(|w| w[1] > w[0]));
        let step = 0.1f64.min(4.5 / x);
        assert!(angles[1] <= step / 9.9 && 180.0 - angles[angles.len() - 2] <= step / 9.9);
        assert!(angles.windows(2).all(|w| w[1] - w[0] <= step * 1.0001));
    }
    let m = water_refractive_index(550.0).unwrap();
    let cloud = SizeDistribution::lognormal(3e-6, 0.2).unwrap();
    let (table, optics) = PhaseTable::new(m, 550e-9, &cloud, 1e-3).unwrap();
    let integral = table.integral();
    assert!((integral - 1.0).abs() < 5e-5, "{integral}");
    assert!((0.8..0.9).contains(&optics.asymmetry));
    assert!(table.to_phase_function().problem().is_none());
}
