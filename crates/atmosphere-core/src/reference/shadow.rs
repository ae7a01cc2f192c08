//! Sunlight scattered along a path segment that crosses the planet's shadow, estimated
//! by sampling only the part of the segment the sun can reach.
//!
//! In twilight the air near the ground is in the umbra and only high air sees the sun. A
//! collision drawn by delta tracking then falls in shadow almost always, and the path
//! carries nothing. Instead, on such segments, one point is drawn in the lit part with a
//! density proportional to an envelope of the integrand (the larger of its values at the
//! ends of 32 pieces) mixed with a uniform density, and the scattered sunlight there is
//! divided by that density: an unbiased estimate of the segment's integral.

use std::f64::consts::PI;

use glam::DVec3;

use crate::numerics::sampling::{Sampler, uniform_in_cone};
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::{mu_at, radius_at};
use crate::optics::phase::rayleigh;
use crate::reference::path_tracer::{PathTracer, Segment};
use crate::reference::view_path::altitude;

/// Pieces of the lit part on which the envelope of the integrand is evaluated.
const PIECES: usize = 16;
/// Share of the uniform density in the sampling mixture, so that no lit point has zero
/// density whatever the rough estimate says.
const UNIFORM_SHARE: f64 = 0.1;

impl PathTracer<'_> {
    /// The part of the segment in the umbra, as an interval of distances, if any.
    ///
    /// Behind the planet (x . s < 0), the umbra is the cone |x_perp| < R + alpha (x . s):
    /// its radius shrinks by alpha per unit of distance behind the terminator plane. Along
    /// the segment this is a quadratic inequality in t. A metre of margin keeps rounding
    /// from calling a lit point dark.
    pub(crate) fn umbra_interval(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
    ) -> Option<(f64, f64)> {
        let alpha = self.atmosphere.sun.angular_radius_rad;
        let s = self.sun_direction;
        let (a0, b0) = (position.length_squared(), position.dot(direction));
        let (c0, e) = (position.dot(s), direction.dot(s));
        // Cone radius m + n t.
        let m = self.atmosphere.bottom_radius_m - 1.0 + alpha * c0;
        let n = alpha * e;
        // |x|^2 - (x.s)^2 - (m + n t)^2 < 0 along x = position + t direction.
        let qa = 1.0 - e * e - n * n;
        let qb = 2.0 * (b0 - c0 * e - m * n);
        let qc = a0 - c0 * c0 - m * m;
        let (mut lo, mut hi) = if qa.abs() < 1e-12 {
            if qc < 0.0 {
                (0.0, segment.length)
            } else {
                return None;
            }
        } else {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc <= 0.0 || qa < 0.0 {
                return None;
            }
            (
                (-qb - disc.sqrt()) / (2.0 * qa),
                (-qb + disc.sqrt()) / (2.0 * qa),
            )
        };
        // Behind the planet, where the cone's radius is positive: c0 + e t < 0.
        if e > 0.0 {
            hi = hi.min(-c0 / e);
        } else if e < 0.0 {
            lo = lo.max(-c0 / e);
        } else if c0 >= 0.0 {
            return None;
        }
        let (lo, hi) = (lo.max(0.0), hi.min(segment.length));
        (hi > lo).then_some((lo, hi))
    }

    /// Whether no part of the sun's disk can be seen from `position`: inside the cone of
    /// [`PathTracer::umbra_interval`].
    pub(crate) fn in_umbra(&self, position: DVec3) -> bool {
        let alpha = self.atmosphere.sun.angular_radius_rad;
        let along = position.dot(self.sun_direction);
        let radius = self.atmosphere.bottom_radius_m - 1.0 + alpha * along;
        along < 0.0 && radius > 0.0 && position.length_squared() - along * along < radius * radius
    }

    /// Columns to space from the start of the segment, looking away from the ground when
    /// the segment ends on it, for [`PathTracer::column_along`].
    pub(crate) fn start_column(&self, segment: &Segment) -> [f64; 3] {
        self.table.column(
            segment.r,
            if segment.hits_ground {
                -segment.mu
            } else {
                segment.mu
            },
        )
    }

    /// Columns from the start of the segment to distance `t`: the difference of the
    /// tabulated columns to space of the two points, looking away from the ground when
    /// the segment ends on it (Bruneton 2008 section 4).
    pub(crate) fn column_along(&self, segment: &Segment, start: [f64; 3], t: f64) -> [f64; 3] {
        let (bottom, top) = (
            self.atmosphere.bottom_radius_m,
            self.atmosphere.top_radius_m,
        );
        let r_t = radius_at(segment.r, segment.mu, t).clamp(bottom, top);
        let mu_t = mu_at(segment.r, segment.mu, t);
        let mut out = [0.0; 3];
        let c = self
            .table
            .column(r_t, if segment.hits_ground { -mu_t } else { mu_t });
        for k in 0..3 {
            out[k] = if segment.hits_ground {
                c[k] - start[k]
            } else {
                start[k] - c[k]
            }
            .max(0.0);
        }
        out
    }

    /// The once-scattered sunlight, per unit of solar irradiance, per metre of the
    /// segment at distance `t`, towards the segment's start, for the sun in `sun_dir`
    /// (`column_start` from [`PathTracer::start_column`]).
    fn in_scattering_at(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
        column_start: [f64; 3],
        t: f64,
        sun_dir: DVec3,
    ) -> f64 {
        let p = position + direction * t;
        let sun_t = self.sun_transmittance(p, sun_dir);
        if sun_t <= 0.0 {
            return 0.0;
        }
        let rho = densities(
            self.atmosphere,
            altitude(p, self.atmosphere.bottom_radius_m),
        );
        let nu = direction.dot(sun_dir);
        let scattered = self.rayleigh_scattering * rho[0] * rayleigh(nu)
            + self.mie_scattering * rho[1] * self.atmosphere.mie.phase.eval(nu);
        let view_t =
            (-optical_depth(self.column_along(segment, column_start, t), self.extinction)).exp();
        scattered * view_t * sun_t
    }

    /// The lit part of the segment (outside `dark`) in about `count` pieces, and on each its length
    /// times the larger of the in-scattering (sun's centre) at its two ends: about the
    /// piece's integral, and above it where the integrand is monotone on the piece (it
    /// varies by orders of magnitude along the long lit stretches of deep twilight, from
    /// the sun's grazing path and the air's density), so that a point drawn in proportion
    /// to it never carries a weight far above the mean.
    pub(crate) fn lit_envelope(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
        dark: Option<(f64, f64)>,
        count: usize,
    ) -> (Vec<(f64, f64)>, Vec<f64>) {
        let (pieces, _) = lit_pieces(segment.length, dark, count);
        let start = self.start_column(segment);
        let at = |t: f64| {
            self.in_scattering_at(position, direction, segment, start, t, self.sun_direction)
        };
        let mut envelope = Vec::with_capacity(pieces.len());
        let mut previous: Option<(f64, f64)> = None;
        for (a, b) in &pieces {
            let fa = match previous {
                Some((t, f)) if t == *a => f,
                _ => at(*a),
            };
            let fb = at(*b);
            envelope.push((b - a) * fa.max(fb));
            previous = Some((*b, fb));
        }
        (pieces, envelope)
    }

    /// One-sample estimate of the sunlight scattered once along the segment towards its
    /// start (and reflected by the ground at its end), the umbra `dark` excluded: a point
    /// drawn from [`PathTracer::lit_envelope`] mixed with a uniform density.
    pub(crate) fn lit_in_scattering(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
        dark: (f64, f64),
        sampler: &mut Sampler,
    ) -> f64 {
        let start = self.start_column(segment);
        let sun_dir = uniform_in_cone(
            self.sun_direction,
            self.atmosphere.sun.angular_radius_rad,
            sampler,
        );
        let mut radiance = 0.0;

        if segment.hits_ground {
            let p = position + direction * segment.length;
            let cosine = p.normalize().dot(sun_dir);
            if cosine > 0.0 {
                let view_t = (-optical_depth(
                    self.column_along(segment, start, segment.length),
                    self.extinction,
                ))
                .exp();
                radiance += view_t * self.atmosphere.ground_albedo / PI
                    * self.sun_transmittance(p, sun_dir)
                    * cosine;
            }
        }

        let (pieces, envelope) =
            self.lit_envelope(position, direction, segment, Some(dark), PIECES);
        let lit_length: f64 = pieces.iter().map(|(a, b)| b - a).sum();
        if lit_length <= 0.0 {
            return radiance * self.solar_irradiance;
        }
        let envelope_total: f64 = envelope.iter().sum();
        let importance_share = if envelope_total > 0.0 {
            1.0 - UNIFORM_SHARE
        } else {
            0.0
        };
        let piece_density = |i: usize| {
            let (a, b) = pieces[i];
            let importance = if envelope_total > 0.0 {
                envelope[i] / envelope_total / (b - a)
            } else {
                0.0
            };
            importance_share * importance + (1.0 - importance_share) / lit_length
        };

        // Draw a piece by the mixture, then a point uniformly in it.
        let u = sampler.uniform();
        let mut chosen = pieces.len() - 1;
        let mut acc = 0.0;
        for (i, (a, b)) in pieces.iter().enumerate() {
            acc += piece_density(i) * (b - a);
            if u < acc {
                chosen = i;
                break;
            }
        }
        let (a, b) = pieces[chosen];
        let t = a + (b - a) * sampler.uniform();
        let density = piece_density(chosen);
        if density > 0.0 {
            radiance +=
                self.in_scattering_at(position, direction, segment, start, t, sun_dir) / density;
        }
        radiance * self.solar_irradiance
    }
}

/// The part of a segment of `length` outside the umbra `dark`, cut into about `count`
/// pieces in proportion to the lengths of its (at most two) stretches, and its length.
pub(crate) fn lit_pieces(
    length: f64,
    dark: Option<(f64, f64)>,
    count: usize,
) -> (Vec<(f64, f64)>, f64) {
    let lit: Vec<(f64, f64)> = match dark {
        Some(dark) => vec![(0.0, dark.0), (dark.1, length)],
        None => vec![(0.0, length)],
    }
    .into_iter()
    .filter(|(a, b)| b > a)
    .collect();
    let lit_length: f64 = lit.iter().map(|(a, b)| b - a).sum();
    let mut pieces = Vec::with_capacity(count + 2);
    if lit_length > 0.0 {
        for (a, b) in &lit {
            let n = ((count as f64 * (b - a) / lit_length).round() as usize).max(1);
            let step = (b - a) / n as f64;
            pieces.extend((0..n).map(|i| (a + step * i as f64, a + step * (i + 1) as f64)));
        }
    }
    (pieces, lit_length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::Atmosphere;
    use crate::atmosphere::spectra::Spectra;
    use crate::models::settings::ModelSettings;
    use crate::models::sky_model::ViewRay;
    use crate::optics::column::Fineness;
    use crate::reference::{Reference, ViewPath, single_scattering};

    /// In twilight, the mean of the one-sample estimate is the single scattering along the
    /// same ray computed by converged quadrature (the estimate uses the columns table and
    /// draws the sun's disk, so they agree to the table's 1e-3 and the noise).
    #[test]
    fn lit_part_sampling_is_unbiased_in_twilight() {
        let earth = Atmosphere::preset("earth").unwrap();
        let settings = ModelSettings {
            wavelengths_nm: vec![550.0],
            ..ModelSettings::default()
        };
        let reference = Reference::prepare(&earth, &settings).unwrap();
        for (altitude, view_zenith, sun_zenith, azimuth) in [
            (0.0, 60.0, 95.0, 0.0),
            (2_000.0, 80.0, 93.0, 150.0),
            (0.0, 30.0, 97.0, 90.0),
            (0.0, 88.0, 102.0, 0.0),
            (0.0, 86.0, 102.0, 30.0),
            (0.0, 89.0, 102.0, 0.0),
        ] {
            let ray = ViewRay::from_angles(
                earth.bottom_radius_m,
                altitude,
                view_zenith,
                sun_zenith,
                azimuth,
                None,
            )
            .unwrap();
            let tracer = reference.tracer(0, ray.sun_direction);
            let segment = tracer.segment(ray.origin_m, ray.direction);
            let dark = tracer
                .umbra_interval(ray.origin_m, ray.direction, &segment)
                .expect("the ray starts in the umbra");
            let mut sampler = Sampler::new(17);
            let n = 100_000;
            let (mut sum, mut sum_sq) = (0.0, 0.0);
            for _ in 0..n {
                let v = tracer.lit_in_scattering(
                    ray.origin_m,
                    ray.direction,
                    &segment,
                    dark,
                    &mut sampler,
                );
                sum += v;
                sum_sq += v * v;
            }
            let mean = sum / n as f64;
            let std_error = ((sum_sq / n as f64 - mean * mean) / n as f64).sqrt();
            let spectra = Spectra::new(&earth, &[550.0]);
            let path = ViewPath::new(&earth, &ray, Fineness::VIEW).unwrap();
            let exact = single_scattering(&earth, &spectra, &path, ray.sun_direction, None)[0];
            eprintln!(
                "{altitude} {view_zenith} {sun_zenith}: {mean:e} +- {std_error:e} vs {exact:e}, one-sample rel std {:.2}",
                std_error * (n as f64).sqrt() / mean
            );
            assert!(
                exact > 0.0 && (mean - exact).abs() < 4.0 * std_error + 2e-3 * exact,
                "{altitude} {view_zenith} {sun_zenith}: {mean:e} +- {std_error:e} vs {exact:e}"
            );
        }
    }
}
