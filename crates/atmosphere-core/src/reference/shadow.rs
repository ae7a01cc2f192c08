//! Sunlight scattered along a path segment that crosses the planet's shadow, estimated
//! by sampling only the part of the segment the sun can reach.
//!
//! In twilight the air near the ground is in the umbra and only high air sees the sun. A
//! collision drawn by delta tracking then falls in shadow almost always, and the path
//! carries nothing. Instead, on such segments, one point is drawn in the lit part with a
//! density proportional to a rough estimate of the integrand (scattering coefficient times
//! transmittances, on 8 pieces) mixed with a uniform density, and the scattered sunlight
//! there is divided by that density: an unbiased estimate of the segment's integral.

use std::f64::consts::PI;

use glam::DVec3;

use crate::numerics::sampling::{Sampler, uniform_in_cone};
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::{mu_at, radius_at};
use crate::optics::phase::rayleigh;
use crate::reference::path_tracer::{PathTracer, Segment};
use crate::reference::view_path::altitude;

/// Pieces of the lit part on which the rough integrand is evaluated.
const PIECES: usize = 8;
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

    /// Columns from the start of the segment to distance `t`: the difference of the
    /// tabulated columns to space of the two points, looking away from the ground when
    /// the segment ends on it (Bruneton 2008 section 4).
    fn column_along(&self, segment: &Segment, start: [f64; 3], t: f64) -> [f64; 3] {
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

    /// One-sample estimate of the sunlight scattered once along the segment towards its
    /// start (and reflected by the ground at its end), the umbra `dark` excluded.
    pub(crate) fn lit_in_scattering(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
        dark: (f64, f64),
        sampler: &mut Sampler,
    ) -> f64 {
        let bottom = self.atmosphere.bottom_radius_m;
        let start = self.table.column(
            segment.r,
            if segment.hits_ground {
                -segment.mu
            } else {
                segment.mu
            },
        );
        let transmittance_to =
            |t: f64| (-optical_depth(self.column_along(segment, start, t), self.extinction)).exp();
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
                radiance += transmittance_to(segment.length) * self.atmosphere.ground_albedo / PI
                    * self.sun_transmittance(p, sun_dir)
                    * cosine;
            }
        }

        let lit: Vec<(f64, f64)> = [(0.0, dark.0), (dark.1, segment.length)]
            .into_iter()
            .filter(|(a, b)| b > a)
            .collect();
        let lit_length: f64 = lit.iter().map(|(a, b)| b - a).sum();
        if lit_length <= 0.0 {
            return radiance * self.solar_irradiance;
        }
        // Pieces of the lit part and the rough integrand on each (sun's centre).
        let mut pieces = Vec::with_capacity(PIECES + 2);
        for (a, b) in &lit {
            let n = ((PIECES as f64 * (b - a) / lit_length).round() as usize).max(1);
            let step = (b - a) / n as f64;
            pieces.extend((0..n).map(|i| (a + step * i as f64, a + step * (i + 1) as f64)));
        }
        let rough: Vec<f64> = pieces
            .iter()
            .map(|(a, b)| {
                let mid = 0.5 * (a + b);
                let p = position + direction * mid;
                let rho = densities(self.atmosphere, altitude(p, bottom));
                (b - a)
                    * (self.rayleigh_scattering * rho[0] + self.mie_scattering * rho[1])
                    * transmittance_to(mid)
                    * self.sun_transmittance(p, self.sun_direction)
            })
            .collect();
        let rough_total: f64 = rough.iter().sum();
        let importance_share = if rough_total > 0.0 {
            1.0 - UNIFORM_SHARE
        } else {
            0.0
        };

        // Draw a piece by the mixture, then a point uniformly in it.
        let u = sampler.uniform();
        let mut chosen = pieces.len() - 1;
        let mut acc = 0.0;
        for (i, ((a, b), w)) in pieces.iter().zip(&rough).enumerate() {
            let importance = if rough_total > 0.0 {
                w / rough_total
            } else {
                0.0
            };
            acc += importance_share * importance + (1.0 - importance_share) * (b - a) / lit_length;
            if u < acc {
                chosen = i;
                break;
            }
        }
        let (a, b) = pieces[chosen];
        let t = a + (b - a) * sampler.uniform();
        let importance = if rough_total > 0.0 {
            rough[chosen] / rough_total / (b - a)
        } else {
            0.0
        };
        let density = importance_share * importance + (1.0 - importance_share) / lit_length;

        let p = position + direction * t;
        let rho = densities(self.atmosphere, altitude(p, bottom));
        let sun_t = self.sun_transmittance(p, sun_dir);
        if sun_t > 0.0 && density > 0.0 {
            let nu = direction.dot(sun_dir);
            let scattered = self.rayleigh_scattering * rho[0] * rayleigh(nu)
                + self.mie_scattering * rho[1] * self.atmosphere.mie.phase.eval(nu);
            radiance += transmittance_to(t) * scattered * sun_t / density;
        }
        radiance * self.solar_irradiance
    }
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
            let exact = single_scattering(&earth, &spectra, &path, ray.sun_direction)[0];
            eprintln!(
                "{altitude} {view_zenith} {sun_zenith}: {mean:e} +- {std_error:e} vs {exact:e}"
            );
            assert!(
                exact > 0.0 && (mean - exact).abs() < 4.0 * std_error + 2e-3 * exact,
                "{altitude} {view_zenith} {sun_zenith}: {mean:e} +- {std_error:e} vs {exact:e}"
            );
        }
    }
}
