//! Gauss-Legendre rules on [-1, 1]: the building block of every integral along a ray.

/// Abscissae and weights of the 5-point rule (exact for polynomials of degree 9).
pub const GAUSS_LEGENDRE_5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// Abscissae and weights of the 8-point rule (exact for polynomials of degree 15).
pub const GAUSS_LEGENDRE_8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_3),
];

/// The nodes and weights of `rule` mapped to [a, b].
pub fn mapped(rule: &[(f64, f64)], a: f64, b: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
    let half = 0.5 * (b - a);
    let mid = 0.5 * (a + b);
    rule.iter().map(move |&(x, w)| (mid + half * x, half * w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_integrate_polynomials_exactly() {
        for (rule, degree) in [(&GAUSS_LEGENDRE_5[..], 9), (&GAUSS_LEGENDRE_8[..], 15)] {
            let weights: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((weights - 2.0).abs() < 1e-14);
            let integral: f64 = mapped(rule, 0.0, 2.0)
                .map(|(x, w)| w * x.powi(degree))
                .sum();
            let exact = 2f64.powi(degree + 1) / (degree + 1) as f64;
            assert!((integral / exact - 1.0).abs() < 1e-13, "degree {degree}");
        }
    }
}
