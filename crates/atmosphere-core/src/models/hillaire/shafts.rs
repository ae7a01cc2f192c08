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
//! over the part of the segment below the shadow volume's top only
//! (`shafts::shaft_span_m`): a camera above that top enters it after `T(x, x_entry)`,
//! the difference of two columns of the transmittance table (Bruneton and Neyret 2008,
//! section 4). The part is cut in two samples per cell of the map it spans, at least
//! `MIN_SHAFT_SAMPLES` and at most `SHAFT_SAMPLES` equal segments
//! (`shafts::shaft_samples`). Orders two and up (Psi_ms) stay unshadowed, and so does the
//! similarity scaling's light path: the true medium's transmittances are used.

use crate::models::hillaire::medium::{Medium, point_along, segment_weight};
use crate::optics::column::optical_depth;
use crate::optics::phase::rayleigh;
use crate::optics::view_segment::ViewSegment;
use crate::shafts::{ShadowMap, SunVisibility, segment_span_m, shaft_samples};

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
    if let Some(span) = segment_span_m(segment, map, bottom) {
        let samples = shaft_samples(span.1 - span.0, map.sample_cell_m());
        shadowed_single_over(medium, segment, map, span, samples, out);
    }
}

/// The single scattering per unit solar irradiance (sr^-1) that the sun's invisibility
/// `1 - V` of `visibility` takes out of the part `span` (distances from the segment's
/// start, m) of `segment`, by `samples` equal segments, per wavelength, into `out`; the
/// march of [`shadowed_single`] for any visibility (the terrain's, the cloud's).
pub fn shadowed_single_over(
    medium: &Medium<'_>,
    segment: &ViewSegment,
    visibility: &dyn SunVisibility,
    span: (f64, f64),
    samples: usize,
    out: &mut [f64],
) {
    out.fill(0.0);
    let (entry, end) = span;
    if end <= entry || samples == 0 {
        return;
    }
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
    let dt = (end - entry) / samples as f64;
    for k in 0..samples {
        let t = entry + (k as f64 + 0.5) * dt;
        let (r_t, mu_s_t) = point_along(segment.r, segment.mu, mu_s, nu, t);
        let rho = medium.densities(r_t);
        let shadow = 1.0 - visibility.sun_visible(segment.start + t * segment.direction, sun);
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
