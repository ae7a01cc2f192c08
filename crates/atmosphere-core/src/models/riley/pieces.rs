//! The closed form of the riley model over one piece of a view ray, for every geometry.
//!
//! Single scattering along a ray is, for each scattering species j,
//! E P_j w_j ∫ exp(-F) dτ_j, with τ_j the species' own optical depth from the camera and
//! F the optical depth of the light's path: from the sun to the point and on to the
//! camera. In Riley et al. 2004 (Eq. 11, 12, 14) F is linear in τ_j on a flat earth with
//! one species, which gives Eq. (15). Here F is taken linear in τ_j between the two ends
//! of a piece, where the columns are known exactly, so that
//!
//! ∫ exp(-F) dτ_j = Δτ_j exp(-min F) φ(|ΔF|),  φ(x) = (1 - e^-x) / x,
//!
//! the paper's closed form in its stable writing ([`super::flat::FlatExponential`]) when
//! F is linear, as it is for one species on a flat earth; with other species' extinction
//! or on the sphere it is exact at the ends of each piece.

use crate::models::riley::flat::phi;

/// Species whose columns are carried: Rayleigh, Mie, ozone.
pub const SPECIES: usize = 3;
/// Species that scatter: Rayleigh, Mie (the first two of [`SPECIES`]).
pub const SCATTERING: usize = 2;
/// Index of ozone, which only absorbs.
pub const OZONE: usize = 2;

/// Columns (m of each species' relative density) at one point of the view ray: from the
/// segment's start to the point, and from the point towards the sun (infinite where the
/// sun is hidden).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointColumns {
    pub view: [f64; SPECIES],
    pub sun: [f64; SPECIES],
}

/// The view ray as the closed form sees it: its lit parts, each a chain of points whose
/// neighbours bound one piece, and the columns from the segment's start to its end.
#[derive(Clone, Debug, PartialEq)]
pub struct RayPieces {
    pub parts: Vec<Vec<PointColumns>>,
    pub end_view: [f64; SPECIES],
}

/// The optical depth F of the light's path through a point, counting the species
/// `included` (a species of zero extinction counts nothing, even with an infinite column).
fn path_depth(point: &PointColumns, extinction: &[f64; SPECIES], included: [bool; SPECIES]) -> f64 {
    (0..SPECIES)
        .filter(|&k| included[k] && extinction[k] > 0.0)
        .map(|k| extinction[k] * (point.view[k] + point.sun[k]))
        .sum()
}

/// ∫ exp(-F) dτ_j over the piece from `start` to `end`, for the scattering species j
/// (Rayleigh, Mie), at one wavelength of ground `extinction` per species. With
/// `shared_extinction` F counts every species; without, species j's own and ozone's.
pub fn piece_integrals(
    start: &PointColumns,
    end: &PointColumns,
    extinction: &[f64; SPECIES],
    shared_extinction: bool,
) -> [f64; SCATTERING] {
    let mut out = [0.0; SCATTERING];
    for (j, integral) in out.iter_mut().enumerate() {
        let own_depth = extinction[j] * (end.view[j] - start.view[j]);
        if own_depth <= 0.0 {
            continue;
        }
        let included = std::array::from_fn(|k| shared_extinction || k == j || k == OZONE);
        let (f_start, f_end) = (
            path_depth(start, extinction, included),
            path_depth(end, extinction, included),
        );
        let f_min = f_start.min(f_end);
        if f_min.is_infinite() {
            continue;
        }
        *integral = own_depth * (-f_min).exp() * phi((f_end - f_start).abs());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With F linear in τ_j the piece is exact: against a midpoint sum of exp(-F).
    #[test]
    fn a_linear_exponent_is_integrated_exactly() {
        let start = PointColumns {
            view: [0.0, 0.0, 0.0],
            sun: [3.0e4, 2.0e3, 1.0e4],
        };
        let end = PointColumns {
            view: [5.0e4, 1.0e4, 2.0e4],
            sun: [1.0e4, 1.0e2, 8.0e3],
        };
        let extinction = [3.3e-5, 4.4e-6, 8.0e-8];
        let got = piece_integrals(&start, &end, &extinction, true);
        let depth = |p: &PointColumns| -> f64 {
            (0..SPECIES)
                .map(|k| extinction[k] * (p.view[k] + p.sun[k]))
                .sum()
        };
        let (fa, fb) = (depth(&start), depth(&end));
        for (j, integral) in got.iter().enumerate() {
            let total = extinction[j] * (end.view[j] - start.view[j]);
            let n = 100_000;
            let sum: f64 = (0..n)
                .map(|i| {
                    let x = (i as f64 + 0.5) / n as f64;
                    (-(fa + (fb - fa) * x)).exp() * total / n as f64
                })
                .sum();
            assert!(
                (integral / sum - 1.0).abs() < 1e-9,
                "{j}: {integral} vs {sum}"
            );
        }
    }

    /// Without shared extinction a species ignores the other's columns, even infinite ones
    /// of a species that does not attenuate.
    #[test]
    fn own_extinction_ignores_the_other_species() {
        let start = PointColumns {
            view: [0.0; 3],
            sun: [1.0e4, f64::INFINITY, 0.0],
        };
        let end = PointColumns {
            view: [1.0e4, 5.0e3, 0.0],
            sun: [5.0e3, f64::INFINITY, 0.0],
        };
        let own = piece_integrals(&start, &end, &[1e-5, 0.0, 0.0], false);
        let shared = piece_integrals(&start, &end, &[1e-5, 0.0, 0.0], true);
        assert!(own[0] > 0.0 && own[0] == shared[0]);
        let dimmed = piece_integrals(&start, &end, &[1e-5, 1e-6, 0.0], true);
        assert_eq!(dimmed, [0.0, 0.0]);
        let alone = piece_integrals(&start, &end, &[1e-5, 1e-6, 0.0], false);
        assert_eq!((alone[0], alone[1]), (own[0], 0.0));
    }
}
