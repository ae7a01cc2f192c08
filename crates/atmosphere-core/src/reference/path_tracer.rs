//! Orders two and up by Monte Carlo path tracing: from a point, follow light backwards
//! through the atmosphere, choosing each next event by delta tracking (Woodcock), with
//! next-event estimation of the sun's disk at every event. The only approximation is the
//! columns table used for the sun's transmittance at each event (bilinear on a fine
//! grid, about 1e-4 relative), far below the Monte Carlo error.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::numerics::sampling::{Sampler, cosine_weighted, direction_around, uniform_in_cone};
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground};
use crate::optics::phase::rayleigh;
use crate::optics::phase_sampling::{PhaseSampler, sample_rayleigh};
use crate::optics::transmittance_table::TransmittanceTable;
use crate::reference::guide::DirectionGuide;
use crate::reference::light_proxy::LightProxy;
use crate::reference::majorant::DensityBounds;
use crate::reference::scatterer::Scatterer;
use crate::reference::view_path::altitude;

/// Scattering order from which Russian roulette may end a path.
const ROULETTE_FROM_ORDER: u32 = 8;

/// Everything a path needs at one wavelength.
#[derive(Debug)]
pub struct PathTracer<'a> {
    pub atmosphere: &'a Atmosphere,
    pub table: &'a TransmittanceTable,
    pub bounds: &'a DensityBounds,
    pub mie_sampler: &'a PhaseSampler,
    /// Extinction per species at this wavelength (m^-1 at density 1).
    pub extinction: [f64; 3],
    pub rayleigh_scattering: f64,
    pub mie_scattering: f64,
    pub solar_irradiance: f64,
    pub max_orders: Option<u32>,
    pub sun_direction: DVec3,
    /// Directions towards sunlit air, mixed into the drawing of directions at events in
    /// the umbra (`guide.rs`); `None` draws from the phase function (or cosine) alone.
    pub guide: Option<&'a DirectionGuide>,
    /// The light arriving at each point, by which the next events of paths in the umbra
    /// are drawn towards it (`towards_light.rs`); `None` draws them by delta tracking.
    pub light: Option<&'a LightProxy>,
}

/// Pieces of each direction's lit part on which the guide's radiance is estimated.
const GUIDE_PIECES: usize = 8;

/// Probability of drawing from the guide rather than from the phase function (or cosine)
/// at an event in the umbra: the weight of a direction is then at most 1 / (1 - share)
/// times the phase function's own.
const GUIDE_SHARE: f64 = 0.7;

/// Where a ray from a point inside the atmosphere next interacts.
pub(crate) enum Event {
    Scatter {
        position: DVec3,
        densities: [f64; 3],
        albedo: f64,
    },
    Ground(DVec3),
    Escape,
}

/// A straight stretch of a path, from a point to the ground or to space.
pub(crate) struct Segment {
    pub r: f64,
    pub mu: f64,
    pub length: f64,
    pub hits_ground: bool,
}

impl PathTracer<'_> {
    /// A rough estimate of the sunlight scattered once towards `position` from `direction`
    /// (the lit part of the ray's envelope, the ground at its end, for the sun's centre), in
    /// units of the solar irradiance.
    pub(crate) fn rough_incoming(&self, position: DVec3, direction: DVec3) -> f64 {
        let segment = self.segment(position, direction);
        let dark = self.umbra_interval(position, direction, &segment);
        let (_, envelope) = self.lit_envelope(position, direction, &segment, dark, GUIDE_PIECES);
        let mut value: f64 = envelope.iter().sum();
        if segment.hits_ground {
            let p = position + direction * segment.length;
            let cosine = p.normalize().dot(self.sun_direction);
            if cosine > 0.0 {
                let start = self.start_column(&segment);
                let view_t = (-optical_depth(
                    self.column_along(&segment, start, segment.length),
                    self.extinction,
                ))
                .exp();
                value += view_t * self.atmosphere.ground_albedo / PI
                    * cosine
                    * self.sun_transmittance(p, self.sun_direction);
            }
        }
        value
    }

    /// An estimate of the radiance arriving at `position` from `direction` made of light
    /// scattered at least once (no direct sunlight), where the first event met along
    /// `direction` is of scattering order `first_order`.
    ///
    /// Each event's next place is drawn by delta tracking (from the umbra, with a light
    /// proxy, from a mixture towards the light: `towards_light.rs`), and a new direction
    /// from the phase function or, on the ground, the cosine. The sunlight scattered once more on
    /// each segment is estimated by next-event estimation of the sun's disk at that event,
    /// or, on segments that cross the planet's umbra, by sampling their lit part
    /// (`shadow.rs`).
    pub fn incoming_scattered(
        &self,
        position: DVec3,
        direction: DVec3,
        first_order: u32,
        sampler: &mut Sampler,
    ) -> f64 {
        let mut radiance = 0.0;
        let mut throughput = 1.0;
        let mut position = position;
        let mut direction = direction;
        let mut order = first_order;
        loop {
            if self.max_orders.is_some_and(|max| order > max) {
                return radiance;
            }
            let segment = self.segment(position, direction);
            let umbra = self.umbra_interval(position, direction, &segment);
            if let Some(dark) = umbra {
                radiance += throughput
                    * self.lit_in_scattering(position, direction, &segment, dark, sampler);
            }
            let at_event = umbra.is_none();
            let last = self.max_orders.is_some_and(|max| order >= max);
            if last && !at_event {
                return radiance;
            }
            let (event, event_weight) =
                self.next_event_towards_light(position, direction, &segment, sampler);
            throughput *= event_weight;
            match event {
                Event::Escape => return radiance,
                Event::Scatter {
                    position: p,
                    densities: rho,
                    albedo,
                } => {
                    throughput *= albedo;
                    let sr = self.rayleigh_scattering * rho[0];
                    let sm = self.mie_scattering * rho[1];
                    if at_event {
                        let sun_dir = uniform_in_cone(
                            self.sun_direction,
                            self.atmosphere.sun.angular_radius_rad,
                            sampler,
                        );
                        let sun_t = self.sun_transmittance(p, sun_dir);
                        if sun_t > 0.0 {
                            let nu = direction.dot(sun_dir);
                            let phase = (sr * rayleigh(nu)
                                + sm * self.atmosphere.mie.phase.eval(nu))
                                / (sr + sm);
                            radiance += throughput * phase * self.solar_irradiance * sun_t;
                        }
                    }
                    if last {
                        return radiance;
                    }
                    let scatterer = Scatterer::Air {
                        rayleigh: sr,
                        mie: sm,
                    };
                    let (next, weight) = self.scatter(p, direction, scatterer, sampler);
                    throughput *= weight;
                    direction = next;
                    position = p;
                }
                Event::Ground(p) => {
                    let normal = p.normalize();
                    let albedo = self.atmosphere.ground_albedo;
                    if at_event {
                        let sun_dir = uniform_in_cone(
                            self.sun_direction,
                            self.atmosphere.sun.angular_radius_rad,
                            sampler,
                        );
                        let cosine = normal.dot(sun_dir);
                        if cosine > 0.0 {
                            radiance += throughput * albedo / PI
                                * self.solar_irradiance
                                * self.sun_transmittance(p, sun_dir)
                                * cosine;
                        }
                    }
                    if last {
                        return radiance;
                    }
                    let (next, weight) =
                        self.scatter(p, direction, Scatterer::Ground(normal), sampler);
                    throughput *= albedo * weight;
                    direction = next;
                    position = p;
                }
            }
            if throughput == 0.0 {
                return radiance;
            }
            order += 1;
            if order >= ROULETTE_FROM_ORDER {
                let survive = throughput.min(0.95);
                if sampler.uniform() >= survive {
                    return radiance;
                }
                throughput /= survive;
            }
        }
    }

    /// The direction light arrived from before it scattered at `position` into
    /// `outgoing` (the direction the path came along, traced backwards), and its weight:
    /// the phase function (or cosine / pi) over the density it was drawn with. In the
    /// umbra, with a guide, the density is the mixture of the guide and the phase
    /// function (balance heuristic, `guide.rs`); elsewhere the phase function alone.
    pub(crate) fn scatter(
        &self,
        position: DVec3,
        outgoing: DVec3,
        scatterer: Scatterer,
        sampler: &mut Sampler,
    ) -> (DVec3, f64) {
        let Some(guide) = self.guide.filter(|_| self.in_umbra(position)) else {
            return self.scatter_by_phase(outgoing, scatterer, sampler);
        };
        let direction = if sampler.uniform() < GUIDE_SHARE {
            guide.sample(sampler)
        } else {
            self.scatter_by_phase(outgoing, scatterer, sampler).0
        };
        let (value, phase_pdf) = match scatterer {
            Scatterer::Air {
                rayleigh: sr,
                mie: sm,
            } if sr + sm > 0.0 => {
                let nu = outgoing.dot(direction);
                let phase_r = sr * rayleigh(nu);
                (
                    (phase_r + sm * self.atmosphere.mie.phase.eval(nu)) / (sr + sm),
                    (phase_r + sm * self.mie_sampler.pdf(nu)) / (sr + sm),
                )
            }
            Scatterer::Air { .. } => (0.0, 0.0),
            Scatterer::Ground(normal) => {
                let cosine = normal.dot(direction).max(0.0) / PI;
                (cosine, cosine)
            }
        };
        let pdf = GUIDE_SHARE * guide.pdf(direction) + (1.0 - GUIDE_SHARE) * phase_pdf;
        (direction, if pdf > 0.0 { value / pdf } else { 0.0 })
    }

    /// A direction drawn from the phase function (the Rayleigh or the Mie part in
    /// proportion to their scattering coefficients) or, on the ground, the cosine, and
    /// its weight.
    fn scatter_by_phase(
        &self,
        outgoing: DVec3,
        scatterer: Scatterer,
        sampler: &mut Sampler,
    ) -> (DVec3, f64) {
        match scatterer {
            Scatterer::Air {
                rayleigh: sr,
                mie: sm,
            } => {
                let (nu, weight) = if sampler.uniform() * (sr + sm) < sr {
                    (sample_rayleigh(sampler.uniform()), 1.0)
                } else {
                    self.mie_sampler.sample(sampler)
                };
                let phi = 2.0 * PI * sampler.uniform();
                (direction_around(outgoing, nu, phi), weight)
            }
            Scatterer::Ground(normal) => (cosine_weighted(normal, sampler), 1.0),
        }
    }

    pub(crate) fn segment(&self, position: DVec3, direction: DVec3) -> Segment {
        let bottom = self.atmosphere.bottom_radius_m;
        let top = self.atmosphere.top_radius_m;
        let r = position.length().clamp(bottom, top);
        let mu = (position.dot(direction) / position.length()).clamp(-1.0, 1.0);
        let hits_ground = ray_hits_ground(r, mu, bottom);
        let length = if hits_ground {
            distance_to_entry(r, mu, bottom).unwrap_or(0.0)
        } else {
            distance_to_exit(r, mu, top)
        };
        Segment {
            r,
            mu,
            length,
            hits_ground,
        }
    }

    /// Transmittance from `position` to space towards `sun_dir`; zero behind the ground.
    pub(crate) fn sun_transmittance(&self, position: DVec3, sun_dir: DVec3) -> f64 {
        let bottom = self.atmosphere.bottom_radius_m;
        let r = position
            .length()
            .clamp(bottom, self.atmosphere.top_radius_m);
        let mu = (sun_dir.dot(position) / position.length()).clamp(-1.0, 1.0);
        if ray_hits_ground(r, mu, bottom) {
            return 0.0;
        }
        (-optical_depth(self.table.column(r, mu), self.extinction)).exp()
    }

    /// Delta tracking along the segment to the next real collision, the ground, or space.
    pub(crate) fn next_event(
        &self,
        position: DVec3,
        direction: DVec3,
        segment: &Segment,
        sampler: &mut Sampler,
    ) -> Event {
        let bottom = self.atmosphere.bottom_radius_m;
        let (r, mu) = (segment.r, segment.mu);
        // Lowest altitude on the segment: the start, the ground, or the tangent point.
        let lowest = if mu >= 0.0 {
            r - bottom
        } else if segment.hits_ground {
            0.0
        } else {
            r * (1.0 - mu * mu).sqrt() - bottom
        };
        let bound = self.bounds.above(lowest.max(0.0));
        let majorant = self.extinction[0] * bound[0]
            + self.extinction[1] * bound[1]
            + self.extinction[2] * bound[2];
        if majorant > 0.0 {
            let mut t = 0.0;
            loop {
                t -= (1.0 - sampler.uniform()).ln() / majorant;
                if t >= segment.length {
                    break;
                }
                let p = position + direction * t;
                let rho = densities(self.atmosphere, altitude(p, bottom));
                let extinction = self.extinction[0] * rho[0]
                    + self.extinction[1] * rho[1]
                    + self.extinction[2] * rho[2];
                if sampler.uniform() * majorant < extinction {
                    let scattering =
                        self.rayleigh_scattering * rho[0] + self.mie_scattering * rho[1];
                    return Event::Scatter {
                        position: p,
                        densities: rho,
                        albedo: scattering / extinction,
                    };
                }
            }
        }
        if segment.hits_ground {
            let p = position + direction * segment.length;
            Event::Ground(p * (bottom / p.length()))
        } else {
            Event::Escape
        }
    }
}
