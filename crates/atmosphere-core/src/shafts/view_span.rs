//! The part of a view segment the terrain's shadow can reach, and the samples that read
//! the shadow map along it: from where the ray enters the sphere of the map's highest
//! shadow top to where it leaves it, two samples per cell of the map. Shared by the
//! models whose shafts sample the map along the view ray (hillaire's march of the
//! shadowed single scattering, bruneton's shadowed length).

use super::shadow_map::ShadowMap;
use super::sun_visibility::SunVisibility;
use crate::optics::view_segment::ViewSegment;

/// Most samples of the shadowed part of a view segment.
pub const SHAFT_SAMPLES: usize = 32;

/// Fewest samples of a shadowed part, however short.
pub const MIN_SHAFT_SAMPLES: usize = 4;

/// The part of a segment (distances from its start, m) where the shadow can be: from
/// where it enters the sphere of the shadow volume's top (0 from inside it) to where it
/// last leaves it, at most the segment and the (outermost) map's width; `None` when it never dips
/// below that top. The entry is the product of the roots over the exit, exact for f32 on
/// the GPU as well.
pub fn shaft_span_m(
    r: f64,
    mu: f64,
    length: f64,
    top_radius_m: f64,
    width_m: f64,
) -> Option<(f64, f64)> {
    let r_mu = r * mu;
    let above = (r - top_radius_m) * (r + top_radius_m);
    let disc = r_mu * r_mu - above;
    if disc < 0.0 {
        return None;
    }
    let exit = -r_mu + disc.sqrt();
    let entry = if above > 0.0 && exit > 0.0 {
        above / exit
    } else {
        0.0
    };
    let end = exit.min(length).min(width_m);
    (end > entry).then_some((entry, end))
}

/// [`shaft_span_m`] of `segment` under the top of `map` over a ground sphere of radius
/// `bottom_radius_m`.
pub fn segment_span_m(
    segment: &ViewSegment,
    map: &ShadowMap,
    bottom_radius_m: f64,
) -> Option<(f64, f64)> {
    let width_m = map.width_m();
    let top_radius_m = bottom_radius_m + f64::from(map.max_top_m);
    shaft_span_m(segment.r, segment.mu, segment.length, top_radius_m, width_m)
}

/// Samples of a shadowed part `span_m` long in a map of cells `cell_m` wide: two per
/// cell, within [`MIN_SHAFT_SAMPLES`], [`SHAFT_SAMPLES`].
pub fn shaft_samples(span_m: f64, cell_m: f64) -> usize {
    let per_cell = (2.0 * span_m / cell_m).ceil();
    (per_cell.max(MIN_SHAFT_SAMPLES as f64) as usize).min(SHAFT_SAMPLES)
}

/// The total length of `segment`'s shadowed parts, m: the midpoint rule over its span
/// of the sun's invisibility `1 - V` from `map` (Bruneton and Neyret 2008, section 5:
/// the length `l` of Eq. 17-18, here summed along the ray instead of from the shadow
/// volume's faces).
pub fn shadowed_length_m(segment: &ViewSegment, map: &ShadowMap, bottom_radius_m: f64) -> f64 {
    let Some((entry, end)) = segment_span_m(segment, map, bottom_radius_m) else {
        return 0.0;
    };
    let samples = shaft_samples(end - entry, map.sample_cell_m());
    let dt = (end - entry) / samples as f64;
    (0..samples)
        .map(|k| {
            let t = entry + (k as f64 + 0.5) * dt;
            let point = segment.start + t * segment.direction;
            (1.0 - map.sun_visible(point, segment.sun_direction)) * dt
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::geometry::radius_at;

    const R: f64 = 6_360_000.0;

    #[test]
    fn the_span_runs_from_where_the_ray_enters_the_top_to_where_it_leaves() {
        let (r, top) = (R + 6_000.0, R + 2_000.0);
        let mu = -(3.0_f64).to_radians().sin();
        let (entry, end) = shaft_span_m(r, mu, 1e6, top, 1e6).unwrap();
        assert!(
            (radius_at(r, mu, entry) - top).abs() < 1e-3,
            "entry {entry}"
        );
        assert!((radius_at(r, mu, end) - top).abs() < 1e-3, "end {end}");
        assert!(entry > 70_000.0 && end > entry);
        // Cut by the segment and the map's width; nothing for a ray that stays above.
        assert_eq!(
            shaft_span_m(r, mu, 100_000.0, top, 1e6).unwrap().1,
            100_000.0
        );
        assert_eq!(shaft_span_m(r, mu, 50_000.0, top, 1e6), None);
        assert_eq!(shaft_span_m(r, -mu, 1e6, top, 1e6), None);
        // From inside the top's sphere the span starts at the segment's start.
        let (entry, end) = shaft_span_m(R + 300.0, 0.0, 1e6, top, 1e5).unwrap();
        assert_eq!((entry, end), (0.0, 1e5));
    }

    #[test]
    fn two_samples_per_cell_within_the_fewest_and_the_most() {
        assert_eq!(shaft_samples(100.0, 2_000.0), MIN_SHAFT_SAMPLES);
        assert_eq!(shaft_samples(5_000.0, 1_000.0), 10);
        assert_eq!(shaft_samples(1e6, 1_000.0), SHAFT_SAMPLES);
    }
}
