//! Rain: the rainbows of Lorenz-Mie drops at Descartes's angles, Lorenz-Mie at x = 2e4
//! against the asymptotic extinction of Nussenzveig and Wiscombe (1980), and the
//! Marshall-Palmer average settling at coarse angles.

use std::f64::consts::PI;

use atmosphere_core::optics::mie::amplitudes::phase_function;
use atmosphere_core::optics::mie::coefficients::MieCoefficients;
use atmosphere_core::optics::mie::efficiencies::Efficiencies;
use atmosphere_core::optics::mie::marshall_palmer::MarshallPalmer;
use atmosphere_core::optics::mie::rain::{rain_optics, rain_optics_converged};
use atmosphere_core::optics::refractive_index::water::water_refractive_index;
use num_complex::Complex64;

/// Descartes's minimum deviation after `k` internal reflections as a scattering angle in
/// degrees: cos^2 i = (n^2 - 1) / (k (k + 2)), D = 2 (i - r) + k (pi - 2 r).
fn descartes_scattering_angle_deg(n: f64, k: f64) -> f64 {
    let i = ((n * n - 1.0) / (k * (k + 2.0))).sqrt().acos();
    let r = (i.sin() / n).asin();
    let d = (2.0 * (i - r) + k * (PI - 2.0 * r)).to_degrees() % 360.0;
    if d > 180.0 { 360.0 - d } else { d }
}

/// The angle of the largest phase function of a drop of radius 1 mm within 1.5 degrees
/// of `around_deg`, smoothed over 0.05 degree (the ripple of the externally reflected
/// light's interference is a few thousandths of a degree wide).
fn bow_peak_deg(coefficients: &MieCoefficients, q_sca: f64, around_deg: f64) -> f64 {
    let step = 0.002;
    let angles: Vec<f64> = (0..=1500)
        .map(|i| around_deg - 1.5 + step * i as f64)
        .collect();
    let p: Vec<f64> = angles
        .iter()
        .map(|a| phase_function(coefficients, q_sca, a.to_radians().cos()))
        .collect();
    let half = 12;
    (half..p.len() - half)
        .map(|i| (angles[i], p[i - half..=i + half].iter().sum::<f64>()))
        .fold(
            (0.0, f64::MIN),
            |best, s| if s.1 > best.1 { s } else { best },
        )
        .0
}

/// Airy's (1838) shift of the bow's brightest point from Descartes's angle, degrees:
/// near the rainbow ray D(u) = D_R + D''(u_R) (u - u_R)^2 / 2 in u = sin i, and the
/// amplitude is Ai(-z) with z = (theta - D_R) x^(2/3) / (D''/2)^(1/3), brightest at
/// z = 1.0188 (van de Hulst 1957, section 13.23); towards larger deviations.
fn airy_shift_deg(n: f64, k: f64, x: f64) -> f64 {
    let deviation = |u: f64| {
        let (i, r) = (u.asin(), (u / n).asin());
        2.0 * (i - r) + k * (PI - 2.0 * r)
    };
    let u = (1.0 - (n * n - 1.0) / (k * (k + 2.0))).sqrt();
    let h = 1e-4;
    let second = (deviation(u + h) - 2.0 * deviation(u) + deviation(u - h)) / (h * h);
    (1.0188 * (second / 2.0).cbrt() * x.powf(-2.0 / 3.0)).to_degrees()
}

#[test]
fn primary_and_secondary_bows_of_one_millimetre_drops_lie_at_descartes_angles_shifted_by_airy() {
    let (mut primary, mut secondary) = (Vec::new(), Vec::new());
    for wavelength_nm in [400.0, 550.0, 700.0] {
        let m = water_refractive_index(wavelength_nm).unwrap();
        let x = 2.0 * PI * 1e-3 / (wavelength_nm * 1e-9);
        let c = MieCoefficients::new(m, x).unwrap();
        let q = Efficiencies::of(&c);
        for k in [1.0, 2.0] {
            let descartes = descartes_scattering_angle_deg(m.re, k);
            // Larger deviations: larger scattering angles for the primary (D < 180),
            // smaller for the secondary (D > 180).
            let shift = airy_shift_deg(m.re, k, x) * if k == 1.0 { 1.0 } else { -1.0 };
            let peak = bow_peak_deg(&c, q.scattering, descartes);
            assert!(
                (peak - (descartes + shift)).abs() < 0.1,
                "{wavelength_nm} nm, {k} reflections: Mie peak {peak:.3} deg, Descartes \
                 {descartes:.3} + Airy {shift:.3}"
            );
            // Without Airy's shift the peak is off by more than the tolerance: the shift
            // is what is being checked, not a tolerance wide enough to hide it.
            assert!((peak - descartes).abs() > 0.1);
            if k == 1.0 {
                primary.push(peak);
            } else {
                secondary.push(peak);
            }
        }
    }
    // Red outside in the primary (smaller scattering angle), inside in the secondary.
    assert!(
        primary[0] > primary[1] && primary[1] > primary[2],
        "{primary:?}"
    );
    assert!(
        secondary[0] < secondary[1] && secondary[1] < secondary[2],
        "{secondary:?}"
    );
}

/// Nussenzveig and Wiscombe 1980 ("Efficiency factors in Mie scattering", Physical Review
/// Letters 45, 1490): Q_ext = 2 + 1.992386 x^(-2/3) + O(x^(-1)) for large spheres,
/// the remainder oscillating in x. Averaged over 64 units of x at 2e4, Lorenz-Mie must
/// follow the edge term, which lifts Q_ext by 2.7e-3 above 2, to 3e-5.
#[test]
fn extinction_at_twenty_thousand_follows_the_edge_term_of_nussenzveig_and_wiscombe() {
    for m in [Complex64::new(1.333, 0.0), Complex64::new(1.5, 0.0)] {
        let xs: Vec<f64> = (0..256).map(|i| 2e4 + 0.25 * i as f64).collect();
        let mean = xs
            .iter()
            .map(|&x| Efficiencies::of(&MieCoefficients::new(m, x).unwrap()).extinction)
            .sum::<f64>()
            / xs.len() as f64;
        let x: f64 = 2e4 + 32.0;
        let edge = 2.0 + 1.992_386 * x.powf(-2.0 / 3.0);
        assert!((mean - edge).abs() < 3e-5, "m = {m}: {mean} against {edge}");
    }
}

/// The Marshall-Palmer average at coarse angles (every 10 degrees) settles: the rule
/// that stops at tolerance 3e-3 (phase function 3e-2) agrees with a rule on other radii
/// (one interval fewer: every node but the ends moves) to those tolerances.
#[test]
fn marshall_palmer_rain_settles_at_coarse_angles() {
    let rain = MarshallPalmer::new(10.0).unwrap();
    let cosines: Vec<f64> = (0..=18)
        .map(|i| (10.0 * i as f64).to_radians().cos())
        .collect();
    let m = water_refractive_index(700.0).unwrap();
    let settled = rain_optics_converged(m, 700e-9, &rain, &cosines, 3e-3).unwrap();
    let other = rain_optics(m, 700e-9, &rain, &cosines, settled.radii - 2).unwrap();
    println!(
        "radii {} q {} {} g {}",
        settled.radii,
        settled.extinction_efficiency(),
        settled.scattering_efficiency(),
        settled.asymmetry
    );
    let close = |a: f64, b: f64, tolerance: f64| ((a - b) / b).abs() < tolerance;
    assert!(close(
        settled.extinction_efficiency(),
        other.extinction_efficiency(),
        3e-3
    ));
    assert!(close(
        settled.scattering_efficiency(),
        other.scattering_efficiency(),
        3e-3
    ));
    assert!(close(settled.asymmetry, other.asymmetry, 3e-3));
    for (i, (a, b)) in settled.phase.iter().zip(&other.phase).enumerate() {
        let scale = b.max(1.0 / (4.0 * PI));
        assert!(
            (a - b).abs() / scale < 3e-2,
            "{} deg: {a} against {b}",
            10 * i
        );
    }
    // Large drops: Q_ext a little above 2 (the edge term lifts a 0.1 mm drop's by 0.02
    // at 700 nm), strongly forward.
    let q_ext = settled.extinction_efficiency();
    assert!(q_ext > 2.0 && q_ext < 2.02, "{q_ext}");
    assert!(settled.asymmetry > 0.85);
}

#[test]
fn rain_rates_outside_their_range_are_named() {
    for rate in [0.0, -1.0, 1e3, f64::NAN] {
        let e = MarshallPalmer::new(rate).unwrap_err().to_string();
        assert!(e.contains("rain rate"), "{e}");
    }
    let heavy = MarshallPalmer::new(200.0).unwrap();
    let light = MarshallPalmer::new(1.0).unwrap();
    // Lambda = 4.1 R^-0.21 per mm: heavier rain, larger drops, more of them.
    assert!((light.slope_per_mm() - 4.1).abs() < 1e-12);
    assert!(heavy.number_density_m3() > light.number_density_m3());
}
