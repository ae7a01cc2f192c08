//! Riley et al.'s (2004) multiple-scattering phase functions A_n and forward fractions
//! F_n through Legendre coefficients: against the closed form of Henyey-Greenstein
//! functions (whose convolution is another: chi_l = g^l), against a brute-force
//! convolution on a coarse grid, and for the cloud droplet: unit integral, the cut of
//! the series, and the approach to isotropy.

use std::f64::consts::PI;
use std::sync::OnceLock;

use atmosphere_core::numerics::gauss_legendre_rule::gauss_legendre;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::mie::legendre::mie_legendre_series;
use atmosphere_core::optics::mie::size_distribution::SizeDistribution;
use atmosphere_core::optics::multiple_scattering_phase::{
    MultipleScatteringPhase, RILEY_MAX_ORDER,
};
use atmosphere_core::optics::phase::henyey_greenstein;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;

/// The series of a phase function by a Gauss-Legendre rule of `nodes` points.
fn series_of(phase: impl Fn(f64) -> f64, nodes: usize, degree: usize) -> LegendreSeries {
    let rule = gauss_legendre(nodes);
    let values: Vec<f64> = rule.iter().map(|&(nu, _)| phase(nu)).collect();
    LegendreSeries::from_gauss_rule(&rule, &values, degree)
}

/// The cloud droplet of the tests: lognormal, effective radius 10 um, sigma 0.1, green.
/// Computed once for the tests that share it.
fn cloud_series() -> &'static LegendreSeries {
    static CLOUD: OnceLock<LegendreSeries> = OnceLock::new();
    CLOUD.get_or_init(|| {
        let m = water_refractive_index(550.0).unwrap();
        let distribution = SizeDistribution::lognormal(10e-6, 0.1).unwrap();
        mie_legendre_series(m, 550e-9, &distribution, 1e-3)
            .unwrap()
            .series
    })
}

/// 2 pi times the integral of f over nu in [a, b], by a 2000-point rule.
fn integral(f: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let (half, mid) = (0.5 * (b - a), 0.5 * (a + b));
    gauss_legendre(2000)
        .iter()
        .map(|&(x, w)| 2.0 * PI * half * w * f(mid + half * x))
        .sum()
}

/// Henyey-Greenstein's chi_l = g^l, so A_n is Henyey-Greenstein with g^n, and F_n is
/// its forward fraction (1 + g) / (2 g) - (1 - g^2) / (2 g sqrt(1 + g^2)).
#[test]
fn henyey_greenstein_powers_are_henyey_greenstein() {
    let g = 0.6;
    let series = series_of(|nu| henyey_greenstein(g, nu), 400, 200);
    for (l, chi) in series.coefficients().iter().enumerate().take(60) {
        assert!((chi - g.powi(l as i32)).abs() < 1e-12, "chi_{l} = {chi}");
    }
    let orders = MultipleScatteringPhase::new(&series, RILEY_MAX_ORDER);
    for n in 1..=RILEY_MAX_ORDER {
        let gn = g.powi(n as i32);
        for nu in [-1.0, -0.5, 0.0, 0.7, 0.99, 1.0] {
            let want = henyey_greenstein(gn, nu);
            let got = orders.angular_distribution(n, nu);
            assert!(
                (got / want - 1.0).abs() < 1e-9,
                "A_{n}({nu}): {got} vs {want}"
            );
        }
        let forward =
            (1.0 + gn) / (2.0 * gn) - (1.0 - gn * gn) / (2.0 * gn * (1.0 + gn * gn).sqrt());
        let got = orders.forward_fraction(n);
        // The closed form cancels to about 1e-16 / g^n.
        assert!((got - forward).abs() < 1e-10, "F_{n}: {got} vs {forward}");
    }
}

/// A_2 = P * P and A_3 = A_2 * P by the 2D integral over the sphere,
/// A(nu) = int P_a(nu') P_b(cos gamma) dOmega', on a coarse grid (48 Gauss-Legendre
/// cosines by 96 azimuths), for a small water sphere (x = 3) whose phase function the
/// grid resolves.
#[test]
fn powers_match_brute_force_convolution_on_a_coarse_grid() {
    let m = water_refractive_index(550.0).unwrap();
    let radius = 3.0 * 550e-9 / (2.0 * PI);
    let sphere = SizeDistribution::Monodisperse { radius_m: radius };
    let single = mie_legendre_series(m, 550e-9, &sphere, 1e-6)
        .unwrap()
        .series;
    let orders = MultipleScatteringPhase::new(&single, 3);
    let rule = gauss_legendre(48);
    let azimuths = 96;
    let convolve = |a: &dyn Fn(f64) -> f64, nu: f64| -> f64 {
        let sin = (1.0 - nu * nu).sqrt();
        let mut sum = 0.0;
        for &(nu_in, w) in &rule {
            let sin_in = (1.0 - nu_in * nu_in).sqrt();
            for k in 0..azimuths {
                let phi = 2.0 * PI * k as f64 / azimuths as f64;
                let cos_gamma = nu * nu_in + sin * sin_in * phi.cos();
                sum += w * (2.0 * PI / azimuths as f64) * a(nu_in) * single.eval(cos_gamma);
            }
        }
        sum
    };
    for nu in [-0.9, -0.3, 0.0, 0.5, 0.95] {
        let a2 = convolve(&|x| single.eval(x), nu);
        let want2 = orders.angular_distribution(2, nu);
        assert!(
            (a2 / want2 - 1.0).abs() < 1e-6,
            "A_2({nu}): {a2} vs {want2}"
        );
        let a3 = convolve(&|x| orders.angular_distribution(2, x), nu);
        let want3 = orders.angular_distribution(3, nu);
        assert!(
            (a3 / want3 - 1.0).abs() < 1e-6,
            "A_3({nu}): {a3} vs {want3}"
        );
    }
}

/// The cloud droplet's A_n keep unit integral, F_n falls from the single-scattering
/// forward fraction towards 1/2, and A_n tends to isotropic (1 / (4 pi)) as n grows.
#[test]
fn cloud_orders_keep_unit_integral_and_tend_to_isotropic() {
    let single = cloud_series();
    let g = single.asymmetry();
    assert!((0.84..0.90).contains(&g), "g = {g}");
    let orders = MultipleScatteringPhase::new(single, 200);
    let isotropic = 1.0 / (4.0 * PI);
    let mut previous_deviation = f64::INFINITY;
    let mut previous_forward = 1.0;
    for n in [1, 2, 4, 8, 16, 26, 50, 100, 200] {
        let a = |nu: f64| orders.angular_distribution(n, nu);
        // The forward peak narrows the rule's panel near nu = 1.
        let total = integral(a, -1.0, 0.99) + integral(a, 0.99, 1.0);
        assert!((total - 1.0).abs() < 1e-6, "integral of A_{n} = {total}");
        let forward = orders.forward_fraction(n);
        let direct = integral(a, 0.0, 0.99) + integral(a, 0.99, 1.0);
        assert!(
            (forward - direct).abs() < 1e-6,
            "F_{n}: {forward} vs {direct}"
        );
        assert!(
            forward < previous_forward && forward > 0.5,
            "F_{n} = {forward}"
        );
        let deviation = (0..=400)
            .map(|i| (a(-1.0 + i as f64 / 200.0) / isotropic - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(deviation < previous_deviation, "A_{n}: {deviation}");
        (previous_deviation, previous_forward) = (deviation, forward);
    }
    // chi_1^200 = g^200 < 1e-12: isotropic to that.
    assert!(previous_deviation < 1e-9, "A_200: {previous_deviation}");
}

/// Cutting A_n's series where chi_l^n falls below 1e-13 changes no value by more than
/// 1e-9 of the larger of it and the isotropic value, against the full series of degree
/// 2N.
#[test]
fn the_cut_series_equals_the_full_one() {
    let single = cloud_series();
    let orders = MultipleScatteringPhase::new(single, RILEY_MAX_ORDER);
    for n in [1, 2, 5, 26] {
        let full = single.power(n, 0.0);
        let cut = orders.series(n);
        assert!(cut.degree() <= full.degree());
        for i in 0..=200 {
            let nu = (PI * i as f64 / 200.0).cos();
            let scale = full.eval(nu).max(1.0 / (4.0 * PI));
            let difference = (cut.eval(nu) - full.eval(nu)).abs() / scale;
            assert!(difference < 1e-9, "A_{n}({nu}): {difference}");
        }
    }
}

#[test]
fn the_closed_form_henyey_greenstein_series_is_the_function() {
    for g in [-0.3, 0.5, 0.85] {
        let closed = LegendreSeries::henyey_greenstein(g, 300);
        let quadrature = series_of(|nu| henyey_greenstein(g, nu), 600, 300);
        for (l, (a, b)) in closed
            .coefficients()
            .iter()
            .zip(quadrature.coefficients())
            .enumerate()
        {
            assert!((a - b).abs() < 1e-9, "g {g}, chi_{l}: {a} against {b}");
        }
        for k in 0..=20 {
            let nu = -1.0 + 0.1 * f64::from(k);
            let (series, exact) = (closed.eval(nu), henyey_greenstein(g, nu));
            assert!(
                (series - exact).abs() < 1e-9 * exact,
                "g {g}, nu {nu}: {series} against {exact}"
            );
        }
    }
}
