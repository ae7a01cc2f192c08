//! The view ray on a flat earth for the riley model (`sphere=false`, Riley et al. 2004
//! section 4.1): the flattened legs of [`super::flat::flat_legs`] in the tangent frame at
//! the segment's start, columns by Eq. (11) along them and Eq. (12) towards a sun of
//! vertical component l_y, none with the sun at or below the flat horizon.

use crate::models::riley::flat::{FlatExponential, Leg};
use crate::models::riley::pieces::{PointColumns, RayPieces, SPECIES};

/// The columns at the ends of `pieces` equal pieces of each leg, for species of scale
/// heights `scale_heights_m` and a sun of vertical component `sun_up`.
pub fn flat_pieces(
    legs: &[Leg],
    sun_up: f64,
    scale_heights_m: [f64; SPECIES],
    pieces: usize,
) -> RayPieces {
    let unit = |k: usize| FlatExponential {
        beta_sea_level_per_m: 1.0,
        scale_height_m: scale_heights_m[k],
        irradiance: 0.0,
    };
    let mut before = [0.0; SPECIES];
    let mut parts = Vec::with_capacity(legs.len());
    for leg in legs {
        let at = |t: f64| PointColumns {
            view: std::array::from_fn(|k| {
                before[k] + unit(k).optical_depth(leg.height_m, leg.view_up, t)
            }),
            sun: std::array::from_fn(|k| {
                let h = scale_heights_m[k];
                if sun_up > 0.0 {
                    h * (-(leg.height_m + leg.view_up * t) / h).exp() / sun_up
                } else {
                    f64::INFINITY
                }
            }),
        };
        let points: Vec<PointColumns> = (0..=pieces)
            .map(|i| at(leg.length_m * i as f64 / pieces as f64))
            .collect();
        before = points[pieces].view;
        parts.push(points);
    }
    RayPieces {
        parts,
        end_view: before,
    }
}
