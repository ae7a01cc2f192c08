//! The view ray on the sphere for the riley model (`sphere=true`): columns of each
//! species along the real, straight ray and towards the sun in the Chapman function's
//! closed form ([`super::chapman`]), only over the parts of the ray the sun lights
//! ([`super::shadow`]), each part split where the ray turns from descending to climbing.

use crate::models::riley::chapman::{column_to_space, column_to_top, perigee_height_m};
use crate::models::riley::pieces::{PointColumns, RayPieces, SPECIES};
use crate::models::riley::shadow::shadowed_interval;
use crate::optics::geometry::{mu_at, radius_at};
use crate::optics::view_segment::ViewSegment;

/// The segment's columns at the ends of `pieces` pieces per lit, monotone part, for
/// species of scale heights `scale_heights_m` between the radii `bottom_m` and `top_m`
/// (the sun's columns end at the top). The
/// pieces of a part are equal steps of the first species' (the air's) density between
/// its ends, which for a flat earth are equal steps of its optical depth.
pub fn sphere_pieces(
    segment: &ViewSegment,
    (bottom_m, top_m): (f64, f64),
    scale_heights_m: [f64; SPECIES],
    pieces: usize,
) -> RayPieces {
    let top_height = top_m - bottom_m;
    let (r0, mu0, length) = (segment.r, segment.mu, segment.length);
    let h0 = r0 - bottom_m;
    let columns_from_start = |mu: f64| -> [f64; SPECIES] {
        std::array::from_fn(|k| column_to_space(h0, mu, scale_heights_m[k], bottom_m))
    };
    let (forward, backward) = (columns_from_start(mu0), columns_from_start(-mu0));
    let at = |t: f64| -> PointColumns {
        let r = radius_at(r0, mu0, t);
        let (h, mu) = (r - bottom_m, mu_at(r0, mu0, t));
        let point = segment.start + t * segment.direction;
        let mu_sun = (point.dot(segment.sun_direction) / r).clamp(-1.0, 1.0);
        PointColumns {
            // Climbing, the column from the start is what the start sees to space less
            // what the point sees; descending, the same along the reversed ray.
            view: std::array::from_fn(|k| {
                let hk = scale_heights_m[k];
                let column = if mu >= 0.0 {
                    forward[k] - column_to_space(h, mu, hk, bottom_m)
                } else {
                    column_to_space(h, -mu, hk, bottom_m) - backward[k]
                };
                column.max(0.0)
            }),
            sun: std::array::from_fn(|k| {
                column_to_top(h, mu_sun, scale_heights_m[k], bottom_m, top_height)
            }),
        }
    };
    // Where the ray passes its perigee, and its lit parts.
    let t_perigee = -r0 * mu0;
    let h_perigee = perigee_height_m(h0, mu0, bottom_m);
    let shadow = shadowed_interval(
        segment.start,
        segment.direction,
        segment.sun_direction,
        bottom_m,
        length,
    );
    let mut cuts = vec![0.0, length];
    if t_perigee > 0.0 && t_perigee < length {
        cuts.push(t_perigee);
    }
    if let Some((a, b)) = shadow {
        cuts.extend([a, b]);
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut parts = Vec::new();
    for pair in cuts.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let middle = 0.5 * (a + b);
        if shadow.is_some_and(|(s, e)| middle > s && middle < e) || b <= a {
            continue;
        }
        let descending = middle < t_perigee;
        let h_air = scale_heights_m[0];
        let density = |t: f64| (-(radius_at(r0, mu0, t) - bottom_m) / h_air).exp();
        let (u_a, u_b) = (density(a), density(b));
        let points = (0..=pieces)
            .map(|i| {
                let f = i as f64 / pieces as f64;
                let t = if i == 0 {
                    a
                } else if i == pieces {
                    b
                } else if u_a != u_b && u_a > 0.0 && u_b > 0.0 {
                    // Where the air's density is the i-th step: from the height, the
                    // distance to the perigee, |t - t_p| = sqrt(r^2 - r_p^2).
                    let h = -h_air * (u_a + (u_b - u_a) * f).ln();
                    let r_p = bottom_m + h_perigee;
                    let half_chord = ((h - h_perigee).max(0.0) * (bottom_m + h + r_p)).sqrt();
                    let t = if descending {
                        t_perigee - half_chord
                    } else {
                        t_perigee + half_chord
                    };
                    t.clamp(a, b)
                } else {
                    a + (b - a) * f
                };
                at(t)
            })
            .collect();
        parts.push(points);
    }
    RayPieces {
        parts,
        end_view: at(length).view,
    }
}
