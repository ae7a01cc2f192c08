//! A phase function ready for many evaluations: a table's normalising integral, which
//! [`PhaseFunction::eval`] sums over the whole table at every call, computed once. Path
//! tracers evaluate the phase function at every scattering.

use super::phase::{PhaseFunction, tabulated_integral, tabulated_raw};

/// A phase function with what its evaluation needs precomputed.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedPhase {
    function: PhaseFunction,
    /// 1 / the table's integral over the sphere (1 for the closed forms).
    inverse_integral: f64,
}

impl PreparedPhase {
    pub fn new(function: PhaseFunction) -> PreparedPhase {
        let inverse_integral = match &function {
            PhaseFunction::Tabulated { angles_deg, values } => {
                1.0 / tabulated_integral(angles_deg, values)
            }
            _ => 1.0,
        };
        PreparedPhase {
            function,
            inverse_integral,
        }
    }

    pub fn function(&self) -> &PhaseFunction {
        &self.function
    }

    /// The phase function at the cosine `nu` of the scattering angle, sr^-1: the same
    /// value as [`PhaseFunction::eval`].
    pub fn eval(&self, nu: f64) -> f64 {
        match &self.function {
            PhaseFunction::Tabulated { angles_deg, values } => {
                tabulated_raw(angles_deg, values, nu.clamp(-1.0, 1.0)) * self.inverse_integral
            }
            other => other.eval(nu),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn evaluates_as_the_function_does() {
        let angles_deg: Vec<f64> = (0..=36).map(|i| 5.0 * f64::from(i)).collect();
        let values = angles_deg.iter().map(|a| 1.0 + (a / 30.0).cos()).collect();
        for function in [
            PhaseFunction::Tabulated { angles_deg, values },
            PhaseFunction::HenyeyGreenstein { g: 0.7 },
        ] {
            let prepared = PreparedPhase::new(function.clone());
            for k in 0..=40 {
                let nu = -1.0 + 0.05 * f64::from(k);
                let (a, b) = (prepared.eval(nu), function.eval(nu));
                assert!((a - b).abs() <= 1e-14 * b.abs(), "{nu}: {a} {b}");
            }
        }
    }
}
