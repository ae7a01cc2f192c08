//! Dobashi, Yamamoto and Nishita 2002, Eq. 12 along one view ray, on the CPU:
//!
//! I_v = I_sun (r/π) g_l(0, θ_g) cos θ_g Π_j dg_v(t_j)
//!     + I_sun Σ_k g_l(h_k, θ_k) [F_r dI_r(t_k) + F_m dI_m(t_k)] Π_{j<k} dg_v(t_j),
//!
//! plus the ambient term (module `ambient`). The segments [t_k, t_k+1] are cut by sampling
//! planes (section 5.2) or by sample spheres (section 5.3). On the GPU the planes are
//! perpendicular to the view axis of a virtual camera and a pixel's ray meets them at
//! intervals the paper takes as the constant Delta_t; for a single ray the planes are
//! therefore at t_k = k Delta_t from where the ray starts in the atmosphere (the camera,
//! or where its ray enters the atmosphere), and each segment's dI_r, dI_m, dg_v are read
//! from the tables at the plane's height and the ray's angle there. The last segment
//! ends where the ray leaves the atmosphere (the tables stop there) or, for an object, is
//! cut by the rule of a uniform segment (`Accumulator::add`). g_l and the phase functions
//! are taken at the plane, as in Eq. 12. With light shafts (docs/shafts.md) each
//! segment's single scattering is also multiplied by the sun's visibility past the
//! terrain at its plane (`Tracer::shadow`), the visibility term H of section 4.2.2
//! (Eq. 10) read from a shadow map; the paper's Fig. 10(a) draws the mountains' shafts
//! so, on planes of their own with sub-planes, here the sky's own planes without
//! sub-planes. The ambient term and the ground stay unshadowed.

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::models::dobashi::ambient::AmbientTable;
use crate::models::dobashi::plane_tables::PlaneTables;
use crate::models::dobashi::segment::SegmentValues;
use crate::models::dobashi::sphere_tables::SphereTables;
use crate::models::error::ModelError;
use crate::models::nishita::sun_column;
use crate::models::sky_model::{SurfacePoint, ViewRay};
use crate::optics::column::optical_depth;
use crate::optics::geometry::safe_sqrt;
use crate::optics::surface_lighting::SurfaceElement;
use crate::optics::transmittance_table::TransmittanceTable;
use crate::optics::view_segment::{SegmentEnd, ViewSegment};
use crate::shafts::{ShadowMap, SunVisibility};

/// The ray's light per unit solar irradiance (sr^-1), at each wavelength.
#[derive(Clone, Debug, PartialEq)]
pub struct Terms {
    /// Single scattering and the sunlit ground (Eq. 12).
    pub single: Vec<f64>,
    /// The ambient term: the ambient radiance scattered towards the camera by the
    /// segments and reflected by the ground.
    pub ambient: Vec<f64>,
    /// Π dg_v over the ray.
    pub transmittance: Vec<f64>,
}

/// The ambient radiance a trace uses.
#[derive(Clone, Copy, Debug)]
pub enum Ambient<'a> {
    /// None (single scattering only).
    Off,
    /// One unit at every point: `Terms::ambient` is then the transfer of a uniform,
    /// isotropic radiance field (for building the ambient table).
    Unit,
    /// The model's table, by the local sun angle.
    Table(&'a AmbientTable),
}

/// The prepared tables a trace reads.
#[derive(Clone, Copy, Debug)]
pub struct Tracer<'a> {
    pub atmosphere: &'a Atmosphere,
    pub spectra: &'a Spectra,
    /// g_l(h, θ_sun), as columns of matter.
    pub sun_table: &'a TransmittanceTable,
    pub planes: &'a PlaneTables,
    pub spheres: &'a SphereTables,
    /// Above the atmosphere, cameras that would need more planes use the spheres.
    pub max_planes: usize,
    /// The terrain's shadow each segment's single scattering is tested against at its
    /// start (`None`: no light shafts).
    pub shadow: Option<&'a ShadowMap>,
}

impl Tracer<'_> {
    /// The number of planes a camera at radius `r` needs to cover the atmosphere it can
    /// see (section 4.2.1: (t_max - t_min) / Delta_t + 1, with t_min and t_max the
    /// distances to the nearest point of the atmosphere and to the farthest, along the ray
    /// that grazes the ground).
    pub fn planes_needed(&self, r: f64) -> f64 {
        let (bottom, top) = (
            self.atmosphere.bottom_radius_m,
            self.atmosphere.top_radius_m,
        );
        let r = r.max(bottom);
        let t_max =
            safe_sqrt((r - bottom) * (r + bottom)) + safe_sqrt((top - bottom) * (top + bottom));
        let t_min = (r - top).max(0.0);
        (t_max - t_min) / self.planes.interval_m + 1.0
    }

    /// Whether a camera at radius `r` renders with sample spheres (section 5.3): it is
    /// above the atmosphere and would need more than `max_planes` planes.
    pub fn uses_spheres(&self, r: f64) -> bool {
        r > self.atmosphere.top_radius_m && self.planes_needed(r) > self.max_planes as f64
    }

    /// Eq. 12 along `ray`.
    pub fn trace(&self, ray: &ViewRay, ambient: Ambient<'_>) -> Result<Terms, ModelError> {
        let n_w = self.spectra.wavelengths_nm.len();
        let Some(segment) = ViewSegment::new(self.atmosphere, ray)? else {
            return Ok(Terms {
                single: vec![0.0; n_w],
                ambient: vec![0.0; n_w],
                transmittance: vec![1.0; n_w],
            });
        };
        let mut acc = Accumulator::new(self, &segment, ambient);
        if self.uses_spheres(ray.origin_m.length()) {
            self.through_spheres(&segment, &mut acc);
        } else {
            self.through_planes(&segment, &mut acc);
        }
        if segment.end == SegmentEnd::Ground {
            let end = segment.end_point();
            let ground = SurfacePoint::facing_up(end, segment.sun_direction);
            let element = SurfaceElement::new(self.atmosphere, &ground)?;
            acc.add_ground(&element);
        }
        Ok(acc.terms)
    }

    /// The light on a surface element per unit solar irradiance (Eq. 11's sunlit ground,
    /// and the ambient term's sky): the sun's transmittance g_l(h, theta_sun) into `sun`
    /// (0 where the sun's centre is behind the planet, section 5.2) and the irradiance of
    /// the ambient radiance on a horizontal element into `sky`: pi psi on the ground, and
    /// above it pi psi times the share of the ground's vertical optical depth that lies
    /// above the element (psi is the radiance arriving at the ground; a peak has less sky
    /// over it, and at the top none). The element's facing weighs both
    /// (`SurfaceElement::irradiance`).
    pub fn element_light(
        &self,
        element: &SurfaceElement,
        ambient: Ambient<'_>,
        sun: &mut [f64],
        sky: &mut [f64],
    ) {
        self.light(element.r, element.mu_s, ambient, sun, sky);
        let above = self.sun_table.column(element.r, 1.0);
        let whole = self.sun_table.column(self.atmosphere.bottom_radius_m, 1.0);
        for (psi, e) in sky.iter_mut().zip(&self.spectra.extinction) {
            let total = optical_depth(whole, *e);
            let share = if total > 0.0 {
                optical_depth(above, *e) / total
            } else {
                1.0
            };
            *psi *= PI * share;
        }
    }

    /// g_l at radius `r` and sun cosine `mu_sun` per wavelength into `sunlight` (0 where
    /// the sun is behind the planet), and the ambient radiance psi into `psi`.
    fn light(
        &self,
        r: f64,
        mu_sun: f64,
        ambient: Ambient<'_>,
        sunlight: &mut [f64],
        psi: &mut [f64],
    ) {
        match sun_column(self.sun_table, r, mu_sun) {
            Some(column) => {
                for (g, e) in sunlight.iter_mut().zip(&self.spectra.extinction) {
                    *g = (-optical_depth(column, *e)).exp();
                }
            }
            None => sunlight.fill(0.0),
        }
        match ambient {
            Ambient::Off => psi.fill(0.0),
            Ambient::Unit => psi.fill(1.0),
            Ambient::Table(table) => table.lookup(mu_sun, psi),
        }
    }

    /// Section 5.2: segments of Delta_t from the start of the segment, the last one cut
    /// where an object ends the ray short (`ViewSegment::cut`).
    fn through_planes(&self, segment: &ViewSegment, acc: &mut Accumulator<'_, '_>) {
        let dt = self.planes.interval_m;
        let n = (segment.length / dt).ceil() as usize;
        for k in 0..n {
            let t = k as f64 * dt;
            let p = segment.start + segment.direction * t;
            let r = p.length();
            let mu = p.dot(segment.direction) / r;
            self.planes.lookup(r, mu, &mut acc.values);
            let mut fraction = 1.0;
            if segment.cut && k + 1 == n {
                let full = self.planes.segment_length(r, mu);
                let remaining = segment.length - t;
                if remaining < full {
                    fraction = remaining / full;
                }
            }
            acc.add(p, fraction);
        }
    }

    /// Section 5.3: segments between crossings of the sample spheres, from the top
    /// sphere where the ray enters the atmosphere, the last one cut where an object ends
    /// the ray short.
    fn through_spheres(&self, segment: &ViewSegment, acc: &mut Accumulator<'_, '_>) {
        let spheres = self.spheres;
        let (mut k, mut mu, mut t) = (spheres.radii_m.len() - 1, segment.mu, 0.0);
        while let Some(step) = spheres.step(k, mu) {
            let remaining = segment.length - t;
            if remaining <= 0.0 {
                break;
            }
            let p = segment.start + segment.direction * t;
            spheres.lookup(k, &step, &mut acc.values);
            if segment.cut && remaining < step.length_m {
                acc.add(p, remaining / step.length_m);
                break;
            }
            acc.add(p, 1.0);
            t += step.length_m;
            (k, mu) = (step.next, step.next_mu);
            if k == 0 {
                break;
            }
        }
    }
}

/// The sums of Eq. 12 as the segments come, camera side first.
struct Accumulator<'t, 'a> {
    tracer: &'t Tracer<'a>,
    ambient: Ambient<'a>,
    sun: DVec3,
    phase_r: f64,
    phase_m: f64,
    /// The current segment's table values (filled by the caller before `add`).
    values: SegmentValues,
    sunlight: Vec<f64>,
    psi: Vec<f64>,
    terms: Terms,
}

impl<'t, 'a> Accumulator<'t, 'a> {
    fn new(tracer: &'t Tracer<'a>, segment: &ViewSegment, ambient: Ambient<'a>) -> Self {
        let n_w = tracer.spectra.wavelengths_nm.len();
        let nu = segment.direction.dot(segment.sun_direction);
        Accumulator {
            tracer,
            ambient,
            sun: segment.sun_direction,
            phase_r: crate::optics::phase::rayleigh(nu),
            phase_m: tracer.atmosphere.mie.phase.eval(nu),
            values: SegmentValues {
                scatter_r: vec![0.0; n_w],
                scatter_m: vec![0.0; n_w],
                transmittance: vec![1.0; n_w],
            },
            sunlight: vec![0.0; n_w],
            psi: vec![0.0; n_w],
            terms: Terms {
                single: vec![0.0; n_w],
                ambient: vec![0.0; n_w],
                transmittance: vec![1.0; n_w],
            },
        }
    }

    /// g_l at `p` per wavelength into `sunlight` (0 where the sun is behind the planet,
    /// section 5.2), and the ambient radiance into `psi`.
    fn light_at(&mut self, p: DVec3) {
        let r = p.length();
        let mu_sun = (p.dot(self.sun) / r).clamp(-1.0, 1.0);
        self.tracer
            .light(r, mu_sun, self.ambient, &mut self.sunlight, &mut self.psi);
    }

    /// The sun's visibility past the terrain at `p` (1 without light shafts).
    fn visible_at(&self, p: DVec3) -> f64 {
        self.tracer
            .shadow
            .map_or(1.0, |map| map.sun_visible(p, self.sun))
    }

    /// Adds the segment starting at `p` whose values are in `self.values`, or its first
    /// `fraction` (0 < fraction < 1) when an object cuts it: the segment is taken as
    /// uniform, so dg_v becomes dg_v^fraction and dI becomes
    /// dI (1 - dg_v^fraction) / (1 - dg_v), both exact for a uniform segment. The
    /// single scattering is seen through the sun's visibility at `p`.
    fn add(&mut self, p: DVec3, fraction: f64) {
        if fraction <= 0.0 {
            return;
        }
        self.light_at(p);
        let visible = self.visible_at(p);
        let v = &self.values;
        for w in 0..self.sunlight.len() {
            let (mut s_r, mut s_m, mut g_v) = (v.scatter_r[w], v.scatter_m[w], v.transmittance[w]);
            if fraction < 1.0 {
                let tau = -g_v.max(0.0).ln();
                let ratio = if tau > 1e-9 {
                    (-fraction * tau).exp_m1() / (-tau).exp_m1()
                } else {
                    fraction
                };
                s_r *= ratio;
                s_m *= ratio;
                g_v = (-fraction * tau).exp();
            }
            let t = self.terms.transmittance[w];
            self.terms.single[w] +=
                t * visible * self.sunlight[w] * (self.phase_r * s_r + self.phase_m * s_m);
            self.terms.ambient[w] += t * self.psi[w] * (s_r + s_m);
            self.terms.transmittance[w] = t * g_v;
        }
    }

    /// The ground at the end of the ray, the element facing up there: I_e = I_sun (r/π)
    /// g_l(0, θ_g) cos θ_g (Eq. 11; r/π for a Lambertian albedo in radiance), and the
    /// ambient radiance from the sky hemisphere reflected, (r/π) π ψ, both seen through
    /// Π dg_v.
    fn add_ground(&mut self, element: &SurfaceElement) {
        let albedo = self.tracer.atmosphere.ground_albedo;
        self.tracer
            .element_light(element, self.ambient, &mut self.sunlight, &mut self.psi);
        for w in 0..self.sunlight.len() {
            let t = self.terms.transmittance[w];
            self.terms.single[w] +=
                t * albedo / PI * element.irradiance(1.0, self.sunlight[w], 0.0);
            self.terms.ambient[w] += t * albedo / PI * element.irradiance(0.0, 0.0, self.psi[w]);
        }
    }
}
