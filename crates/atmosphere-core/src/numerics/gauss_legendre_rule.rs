//! Gauss-Legendre rules of any order on [-1, 1], for integrals whose integrand is a
//! polynomial of known degree (a Mie phase function times a Legendre polynomial): the
//! n-point rule integrates degree 2n - 1 exactly.
//!
//! Nodes by Newton's method on P_n from Tricomi's first approximation
//! cos(pi (i + 3/4) / (n + 1/2)) (Abramowitz and Stegun 1964, 22.16.6); weights
//! 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz and Stegun 1964, 25.4.29).

use std::f64::consts::PI;

use rayon::prelude::*;

/// P_n(x) and P_n'(x) by the three-term recurrence.
fn legendre_and_derivative(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    for k in 1..n {
        let k = k as f64;
        let next = ((2.0 * k + 1.0) * x * current - k * previous) / (k + 1.0);
        previous = current;
        current = next;
    }
    let derivative = n as f64 * (previous - x * current) / ((1.0 - x) * (1.0 + x));
    (current, derivative)
}

/// The i-th largest root of P_n (from 0) and its weight.
fn root(n: usize, i: usize) -> (f64, f64) {
    let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
    for _ in 0..100 {
        let (p, dp) = legendre_and_derivative(n, x);
        let step = p / dp;
        x -= step;
        if step.abs() <= 4.0 * f64::EPSILON * x.abs().max(1e-3) {
            break;
        }
    }
    let (_, dp) = legendre_and_derivative(n, x);
    (x, 2.0 / ((1.0 - x) * (1.0 + x) * dp * dp))
}

/// The `n`-point rule (n >= 1) as (node, weight) pairs, nodes increasing.
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    let n = n.max(1);
    let upper: Vec<(f64, f64)> = (0..n / 2).into_par_iter().map(|i| root(n, i)).collect();
    let mut rule = Vec::with_capacity(n);
    rule.extend(upper.iter().map(|&(x, w)| (-x, w)));
    if n % 2 == 1 {
        rule.push((0.0, root(n, n / 2).1));
    }
    rule.extend(upper.iter().rev().copied());
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_of_many_orders_integrate_their_degree_exactly() {
        for n in [1, 2, 5, 8, 33, 400, 3001] {
            let rule = gauss_legendre(n);
            assert_eq!(rule.len(), n);
            assert!(rule.windows(2).all(|w| w[0].0 < w[1].0), "n = {n}");
            let weights: f64 = rule.iter().map(|(_, w)| w).sum();
            assert!((weights - 2.0).abs() < 1e-12, "n = {n}: {weights}");
            // x^(2n-2) is the highest even power the rule holds exactly.
            let degree = 2 * n as i32 - 2;
            let integral: f64 = rule.iter().map(|(x, w)| w * x.powi(degree)).sum();
            let exact = 2.0 / (degree + 1) as f64;
            assert!((integral / exact - 1.0).abs() < 1e-11, "n = {n}");
        }
    }

    #[test]
    fn the_five_point_rule_matches_the_tabulated_one() {
        let rule = gauss_legendre(5);
        for (&(x, w), &(x5, w5)) in rule
            .iter()
            .zip(&crate::numerics::quadrature::GAUSS_LEGENDRE_5)
        {
            assert!((x - x5).abs() < 1e-14 && (w - w5).abs() < 1e-14);
        }
    }
}
