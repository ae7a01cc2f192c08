//! The spectral reference: the ground truth every model is measured against.
//!
//! Radiance = single scattering and single ground reflection by converged quadrature
//! ([`single_scattering`]) + all higher orders by Monte Carlo path tracing
//! ([`path_tracer`]) with a reported standard error, refined per ray until it is below
//! the requested fraction of the radiance. f64 throughout. See docs/models/reference.md
//! for why this split, and how convergence is checked.

mod ground_light;
mod guide;
#[cfg(test)]
mod guide_tests;
mod last_event;
mod light_proxy;
mod majorant;
mod path_tracer;
mod scatterer;
mod settings;
mod shadow;
mod single_scattering;
mod sun;
mod towards_light;
#[cfg(test)]
mod twilight_fixture;
mod view_path;

use std::sync::OnceLock;

use glam::DVec3;

use ground_light::{GroundLight, NODE_RAYS};
pub use guide::{DirectionGuide, Guiding};
use last_event::{LastEvent, LastEvents};
pub use light_proxy::LightProxy;
pub use majorant::DensityBounds;
pub use path_tracer::PathTracer;
use scatterer::Scatterer;
pub use settings::{MAX_PATHS, MIN_PATHS, ReferenceSettings, SHARED_GROUND, TOWARDS_LIGHT};
pub use single_scattering::single_scattering;
pub use sun::disk_mean_transmittance;
pub use view_path::{RayEnd, ViewPath};

use crate::atmosphere::Atmosphere;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use crate::numerics::sampling::{Sampler, mix_seed};
use crate::optics::column::{Fineness, optical_depth};
use crate::optics::phase_sampling::PhaseSampler;
use crate::optics::transmittance_table::TransmittanceTable;
use crate::shafts::SunVisibility;

/// Size of the columns table for the sun's transmittance in Monte Carlo events.
const MC_TABLE_SIZE: (usize, usize) = (512, 128);
/// Paths per batch between checks of the standard error.
const BATCH: usize = 256;
/// A standard error below this fraction of the solar irradiance (sr^-1) counts as
/// darkness and is not refined further; far below the ground in nautical twilight.
const DARKNESS: f64 = 1e-14;
/// Paths a node of the ground's shared light (`ground_light.rs`) draws at each
/// wavelength, over all its rays, in units of a ray's `max_paths`: one node stands for
/// every ground ray near the camera.
const GROUND_PATH_FACTOR: usize = 4;

/// The reference model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Reference {
    atmosphere: Atmosphere,
    /// Its `with_mie` is not read: the reference always computes every term.
    base: ModelBase,
    settings: ModelSettings,
    /// The most paths per ray and wavelength.
    max_paths: usize,
    /// How paths are guided where the view ray's last events lie in the umbra.
    guiding: Guiding,
    table: TransmittanceTable,
    bounds: DensityBounds,
    mie_sampler: PhaseSampler,
    /// Per wavelength, the light arriving at each point, built the first time a path at
    /// that wavelength is guided through the umbra.
    light: Vec<OnceLock<Option<LightProxy>>>,
    /// Whether rays ending on the ground in the umbra take the ground's light from
    /// `ground` instead of drawing it themselves.
    shared_ground: bool,
    /// The ground's light of order two and up, by node of mu_s, estimated on first use.
    ground: GroundLight,
}

/// Monte Carlo estimate of orders two and up, at one wavelength.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    pub mean: f64,
    pub std_error: f64,
    pub paths: usize,
}

impl Reference {
    /// Prepares the reference; its own options (`max_paths`) are read from `settings`.
    pub fn prepare(
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
    ) -> Result<Reference, ModelError> {
        let own = ReferenceSettings::from_options(&settings.options)?;
        let (w, h) = MC_TABLE_SIZE;
        Ok(Reference {
            atmosphere: atmosphere.clone(),
            base: ModelBase::new(ModelId::Reference, atmosphere, settings),
            settings: settings.clone(),
            max_paths: own.max_paths,
            guiding: if own.towards_light {
                Guiding::TowardsLitAir
            } else {
                Guiding::Directions
            },
            table: TransmittanceTable::build(atmosphere, w, h),
            bounds: DensityBounds::new(atmosphere),
            mie_sampler: PhaseSampler::new(&atmosphere.mie.phase),
            light: empty_light(settings.wavelengths_nm.len()),
            shared_ground: own.shared_ground,
            ground: GroundLight::default(),
        })
    }

    /// The path tracer at wavelength index `w`.
    pub fn tracer(&self, w: usize, sun_direction: DVec3) -> PathTracer<'_> {
        PathTracer {
            atmosphere: &self.atmosphere,
            table: &self.table,
            bounds: &self.bounds,
            mie_sampler: &self.mie_sampler,
            extinction: self.base.spectra.extinction[w],
            rayleigh_scattering: self.base.spectra.rayleigh_scattering[w],
            mie_scattering: self.base.spectra.mie_scattering[w],
            solar_irradiance: self.base.spectra.solar_irradiance[w],
            max_orders: self.settings.max_orders,
            sun_direction,
            guide: None,
            light: None,
        }
    }

    /// The light proxy at wavelength index `w`, built on first use from `tracer`.
    fn light_proxy(&self, w: usize, tracer: &PathTracer<'_>) -> Option<&LightProxy> {
        self.light[w]
            .get_or_init(|| {
                LightProxy::new(&self.atmosphere, tracer.sun_direction, |p, d| {
                    tracer.rough_incoming(p, d)
                })
            })
            .as_ref()
    }

    /// Orders two and up along a discretised view ray at wavelength index `w`, refined
    /// until the standard error is below `target` times (`known` + the estimate), with
    /// directions guided towards sunlit air or not (the same expected value). With
    /// `shared_ground=true` and every order, a ray that ends on the ground in the umbra
    /// takes the ground's light from shared nodes (`ground_light.rs`) and draws only its
    /// air's; the error returned is then the two parts' combined.
    pub fn multiple_scattering(
        &self,
        path: &ViewPath,
        sun_direction: DVec3,
        w: usize,
        known: f64,
        guiding: Guiding,
        sampler: &mut Sampler,
    ) -> Result<Estimate, ModelError> {
        let none = Estimate {
            mean: 0.0,
            std_error: 0.0,
            paths: 0,
        };
        if self.settings.max_orders == Some(1) {
            return Ok(none);
        }
        let shared = match path.end {
            RayEnd::Ground(point)
                if self.shared_ground
                    && self.settings.max_orders.is_none()
                    && self.tracer(w, sun_direction).in_umbra(point) =>
            {
                let sky = |ray: &ViewRay, seed: u64| self.sky_from_ground(ray, seed, guiding);
                let g = self.ground.reflected(
                    w,
                    (point, path.direction, sun_direction),
                    (guiding as u8, self.settings.seed),
                    self.atmosphere.bottom_radius_m,
                    &sky,
                )?;
                let ground_mass =
                    (-optical_depth(path.total_column, self.base.spectra.extinction[w])).exp()
                        * self.atmosphere.ground_albedo;
                Some((ground_mass * g.mean, ground_mass * g.std_error))
            }
            _ => None,
        };
        let air = self.draw_last_events(
            path,
            sun_direction,
            w,
            known + shared.map_or(0.0, |s| s.0),
            (guiding, self.max_paths, shared.is_none()),
            sampler,
        );
        Ok(match shared {
            Some((mean, std_error)) => Estimate {
                mean: air.mean + mean,
                std_error: air.std_error.hypot(std_error),
                paths: air.paths,
            },
            None => air,
        })
    }

    /// Orders two and up along `path` from paths drawn from its last events: the nodes
    /// of the view ray and, where `with_ground`, the ground it ends on; at most
    /// `max_paths`, fewer once the standard error is below the target times (`known` +
    /// the estimate).
    fn draw_last_events(
        &self,
        path: &ViewPath,
        sun_direction: DVec3,
        w: usize,
        known: f64,
        (guiding, max_paths, with_ground): (Guiding, usize, bool),
        sampler: &mut Sampler,
    ) -> Estimate {
        let ext = self.base.spectra.extinction[w];
        let (br, bm) = (
            self.base.spectra.rayleigh_scattering[w],
            self.base.spectra.mie_scattering[w],
        );
        let events: Vec<LastEvent> = path
            .nodes
            .iter()
            .map(|n| LastEvent {
                position: n.position,
                scatterer: Scatterer::Air {
                    rayleigh: br * n.densities[0],
                    mie: bm * n.densities[1],
                },
                mass: n.weight
                    * (-optical_depth(n.column_from_camera, ext)).exp()
                    * (br * n.densities[0] + bm * n.densities[1]),
            })
            .chain(match path.end {
                RayEnd::Ground(point) if with_ground => Some(LastEvent {
                    position: point,
                    scatterer: Scatterer::Ground(point.normalize()),
                    mass: (-optical_depth(path.total_column, ext)).exp()
                        * self.atmosphere.ground_albedo,
                }),
                _ => None,
            })
            .collect();
        let unguided = self.tracer(w, sun_direction);
        let Some(last) =
            LastEvents::new(events, path.direction, &unguided, guiding != Guiding::Off)
        else {
            return Estimate {
                mean: 0.0,
                std_error: 0.0,
                paths: 0,
            };
        };
        let light = if guiding == Guiding::TowardsLitAir && last.is_guided() {
            self.light_proxy(w, &unguided)
        } else {
            None
        };
        let darkness = DARKNESS * self.base.spectra.solar_irradiance[w];
        let (mut sum, mut sum_sq, mut n) = (0.0, 0.0, 0usize);
        loop {
            for _ in 0..BATCH {
                let (event, mass_weight, guide) = last.draw(sampler.uniform());
                let tracer = PathTracer {
                    guide,
                    light,
                    ..unguided
                };
                let (direction, weight) =
                    tracer.scatter(event.position, path.direction, event.scatterer, sampler);
                let value = if weight > 0.0 {
                    mass_weight
                        * weight
                        * tracer.incoming_scattered(event.position, direction, 2, sampler)
                } else {
                    0.0
                };
                sum += value;
                sum_sq += value * value;
            }
            n += BATCH;
            let mean = sum / n as f64;
            let variance = ((sum_sq / n as f64) - mean * mean).max(0.0) * n as f64 / (n - 1) as f64;
            let std_error = (variance / n as f64).sqrt();
            let converged = std_error <= self.settings.target_relative_error * (known + mean)
                || std_error <= darkness;
            if n >= max_paths || (n >= MIN_PATHS && converged) {
                return Estimate {
                    mean,
                    std_error,
                    paths: n,
                };
            }
        }
    }

    /// The sky's radiance, every order, along `ray` from a ground point (for the nodes of
    /// `ground_light.rs`), per wavelength: single scattering by quadrature and the
    /// higher orders from `GROUND_PATH_FACTOR` times `max_paths` / `NODE_RAYS` paths.
    fn sky_from_ground(
        &self,
        ray: &ViewRay,
        seed: u64,
        guiding: Guiding,
    ) -> Result<Vec<f64>, ModelError> {
        let path = ViewPath::new(&self.atmosphere, ray, Fineness::VIEW)?;
        let single = single_scattering(
            &self.atmosphere,
            &self.base.spectra,
            &path,
            ray.sun_direction,
            None,
        );
        let paths = (self.max_paths.saturating_mul(GROUND_PATH_FACTOR) / NODE_RAYS).max(MIN_PATHS);
        Ok(single
            .iter()
            .enumerate()
            .map(|(w, l1)| {
                let mut sampler = Sampler::new(mix_seed(&[seed, w as u64]));
                let ms = self.draw_last_events(
                    &path,
                    ray.sun_direction,
                    w,
                    *l1,
                    (guiding, paths, true),
                    &mut sampler,
                );
                l1 + ms.mean
            })
            .collect())
    }
}

impl SkyModel for Reference {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        std::mem::size_of_val(self.table.columns.as_slice()) + self.mie_sampler.bytes()
    }

    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        update.rebuild_columns("transmittance", &mut self.table, atmosphere, MC_TABLE_SIZE);
        update.rebuild(
            Inputs::MIE_PHASE,
            "mie phase sampler",
            &mut self.mie_sampler,
            || PhaseSampler::new(&atmosphere.mie.phase),
        );
        self.bounds = DensityBounds::new(atmosphere);
        // Rebuilt on first use: they depend on every optical property and the albedo.
        self.light = empty_light(self.light.len());
        self.ground = GroundLight::default();
        Ok(update.rebuilt())
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        self.radiance_shadowed(ray, None)
    }
}

impl Reference {
    /// The radiance of `ray` with the terrain's shadow `shadow` in the air: its single
    /// scattering sees the sun through it at every quadrature node; the higher orders,
    /// by Monte Carlo, are left unshadowed (docs/shafts.md).
    pub fn radiance_shadowed(
        &self,
        ray: &ViewRay,
        shadow: Option<&dyn SunVisibility>,
    ) -> Result<RayRadiance, ModelError> {
        let path = ViewPath::new(&self.atmosphere, ray, Fineness::VIEW)?;
        let sun = ray.sun_direction.normalize();
        let single = single_scattering(&self.atmosphere, &self.base.spectra, &path, sun, shadow);
        let transmittance = self
            .base
            .spectra
            .extinction
            .iter()
            .map(|e| (-optical_depth(path.total_column, *e)).exp())
            .collect();
        let seed = mix_seed(&[
            self.settings.seed,
            ray.origin_m.x.to_bits(),
            ray.origin_m.y.to_bits(),
            ray.origin_m.z.to_bits(),
            ray.direction.x.to_bits(),
            ray.direction.y.to_bits(),
            ray.direction.z.to_bits(),
            ray.sun_direction.x.to_bits(),
            ray.sun_direction.y.to_bits(),
            ray.sun_direction.z.to_bits(),
            ray.max_distance_m.unwrap_or(-1.0).to_bits(),
        ]);
        let mut radiance = Vec::with_capacity(single.len());
        let mut std_error = Vec::with_capacity(single.len());
        for (w, l1) in single.iter().enumerate() {
            let mut sampler = Sampler::new(mix_seed(&[seed, w as u64]));
            let ms = self.multiple_scattering(&path, sun, w, *l1, self.guiding, &mut sampler)?;
            radiance.push(l1 + ms.mean);
            std_error.push(ms.std_error);
        }
        Ok(RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: std_error,
        })
    }
}

/// One unbuilt light proxy per wavelength.
fn empty_light(wavelengths: usize) -> Vec<OnceLock<Option<LightProxy>>> {
    (0..wavelengths).map(|_| OnceLock::new()).collect()
}
