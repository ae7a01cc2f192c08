//! Light shafts in the hillaire model: the single scattering that the terrain's shadow
//! takes out of a view segment, subtracted from what the tables or the march give.
//!
//! Bruneton and Neyret 2008 (section 5, Eq. 17-18) subtract the in-scattering of the
//! shadowed length from the precomputed unshadowed integral; here the shadowed part is
//! marched instead, with the shadow test at each sample (the usual shadow-map march the
//! paper compares with): with `V` the sun's visibility past the terrain,
//!
//! `dL = sum_k T(x, x_k) (1 - V(x_k)) T_sun(x_k) (sigma_s,R p_R + sigma_s,M p_M) w_k`,
//!
//! `w_k` the segment integral of Hillaire 2020's march (`medium.rs`, `segment_weight`),
//! over the part of the segment below the shadow volume's top only (`shaft_span_m`): a
//! camera above that top enters it after `T(x, x_entry)`, the difference of two columns
//! of the transmittance table (Bruneton and Neyret 2008, section 4). The part is cut in
//! two samples per cell of the map it spans, at least `MIN_SHAFT_SAMPLES` and at most
//! `SHAFT_SAMPLES` equal segments (`shaft_samples`). Orders two and up (Psi_ms) stay
//! unshadowed, and so does the similarity scaling's light path: the true medium's
//! transmittances are used.

use crate::models::hillaire::medium::{Medium, point_along, segment_weight};
use crate::optics::column::optical_depth;
use crate::optics::phase::rayleigh;
use crate::optics::view_segment::ViewSegment;
use crate::shafts::{ShadowMap, SunVisibility};

/// Most samples of the shadowed part of a view segment.
pub const SHAFT_SAMPLES: usize = 32;

/// Fewest samples of a shadowed part, however short.
pub const MIN_SHAFT_SAMPLES: usize = 4;

/// The part of a segment (distances from its start, m) where the shadow can be: from
/// where it enters the sphere of the shadow volume's top (0 from inside it) to where it
/// last leaves it, at most the segment and the map's width; `None` when it never dips
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

/// Samples of a shadowed part `span_m` long in a map of cells `cell_m` wide: two per
/// cell, within [`MIN_SHAFT_SAMPLES`], [`SHAFT_SAMPLES`].
pub fn shaft_samples(span_m: f64, cell_m: f64) -> usize {
    let per_cell = (2.0 * span_m / cell_m).ceil();
    (per_cell.max(MIN_SHAFT_SAMPLES as f64) as usize).min(SHAFT_SAMPLES)
}

/// The single scattering per unit solar irradiance (sr^-1) that the shadow of `map`
/// takes out of `segment`, per wavelength, into `out`.
pub fn shadowed_single(
    medium: &Medium<'_>,
    segment: &ViewSegment,
    map: &ShadowMap,
    out: &mut [f64],
) {
    out.fill(0.0);
    let bottom = medium.atmosphere.bottom_radius_m;
    let width_m = map.grid.cell_m * map.grid.size as f64;
    let top_radius_m = bottom + f64::from(map.max_top_m);
    let Some((entry, end)) =
        shaft_span_m(segment.r, segment.mu, segment.length, top_radius_m, width_m)
    else {
        return;
    };
    let sun = segment.sun_direction;
    let mu_s = (segment.start.dot(sun) / segment.r).clamp(-1.0, 1.0);
    let nu = segment.direction.dot(sun).clamp(-1.0, 1.0);
    let (phase_r, phase_m) = (
        rayleigh(nu),
        if medium.mie {
            medium.atmosphere.mie.phase.eval(nu)
        } else {
            0.0
        },
    );
    let n = out.len();
    let above = medium
        .transmittance
        .segment_column(segment.r, segment.mu, entry, true);
    let mut throughput: Vec<f64> = (0..n)
        .map(|w| (-optical_depth(above, medium.spectra.extinction[w])).exp())
        .collect();
    let mut sun_t = vec![0.0; n];
    let samples = shaft_samples(end - entry, map.grid.cell_m);
    let dt = (end - entry) / samples as f64;
    for k in 0..samples {
        let t = entry + (k as f64 + 0.5) * dt;
        let (r_t, mu_s_t) = point_along(segment.r, segment.mu, mu_s, nu, t);
        let rho = medium.densities(r_t);
        let shadow = 1.0 - map.sun_visible(segment.start + t * segment.direction, sun);
        if shadow > 0.0 {
            medium.sun_transmittance(r_t, mu_s_t, &mut sun_t);
        }
        for w in 0..n {
            let (s_r, s_m, extinction) = medium.coefficients(rho, w);
            let (t_seg, integral) = segment_weight(extinction, dt);
            if shadow > 0.0 {
                let single = sun_t[w] * (s_r * phase_r + s_m * phase_m);
                out[w] += throughput[w] * shadow * single * integral;
            }
            throughput[w] *= t_seg;
        }
    }
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
