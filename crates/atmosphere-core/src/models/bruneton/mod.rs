//! Bruneton and Neyret 2008, "Precomputed atmospheric scattering": a
//! transmittance table T(r, mu), a 4D scattering table S(u_r, u_mu, u_mu_s, u_nu) holding
//! every scattering order, and an irradiance table E(r, mu_s); a view ray then costs a
//! few look-ups.
//!
//! Radiance of a view ray from x (the camera, moved to where the ray enters the
//! atmosphere if it is in space) along v with the sun towards s:
//! L = S(x, v, s) - T(x, x_s) S(x_s, v, s) + T(x, x_o) alpha / pi (E_sun + E_sky)(x_o),
//! the second term for rays ending on an object at x_s, the third for rays ending on the
//! ground at x_o (paper Eq. 13-16, with the ground a sphere: no occlusion by terrain).
//! Single Mie scattering is stored separately (the paper's C_M with all three channels,
//! not its proportionality approximation), so that the Mie phase function is applied
//! exactly per ray; single Rayleigh is stored without its phase function, and orders two
//! and up as radiance. The sun disk itself is excluded. Tables hold radiance per unit
//! solar irradiance, so that `update` rebuilds nothing for a new solar spectrum. With
//! light shafts, the single scattering of the shadowed length is taken out (`shafts.rs`,
//! Eq. 17-18). See docs/models/bruneton.md.

pub mod builder;
pub mod channels;
pub mod delta_m;
pub mod mie_quadrature;
pub mod node_placement;
pub mod parameterization;
pub mod precompute;
pub mod settings;
pub mod shafts;
pub mod sphere_integrals;
pub mod sun_disk;
pub mod tables;
pub mod view_integrals;

pub use settings::BrunetonSettings;

use std::f64::consts::PI;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::bruneton::builder::Builder;
use crate::models::bruneton::channels::Channels;
use crate::models::bruneton::delta_m::DeltaM;
use crate::models::bruneton::mie_quadrature::MieQuadrature;
use crate::models::bruneton::parameterization::{Radii, table_position};
use crate::models::bruneton::precompute::{OrderStats, Tables};
use crate::models::bruneton::shafts::{ShaftRay, shadowed_segment};
use crate::models::bruneton::sun_disk::{disk_changed, visible_sun};
use crate::models::bruneton::tables::{DensityTable, Table4};
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::geometry::ray_hits_ground;
use crate::optics::phase::rayleigh;
use crate::optics::surface_lighting::SurfaceElement;
use crate::optics::transmittance_table::TransmittanceTable;
use crate::optics::view_segment::{SegmentEnd, ViewSegment};
use crate::shafts::{ShadowMap, shadowed_length_m};

/// The Bruneton 2008 model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Bruneton {
    atmosphere: Atmosphere,
    /// `with_mie` false when Mie work is pruned (see [`Bruneton::mie_pruned`]).
    base: ModelBase,
    /// [`ModelSettings::max_orders`].
    max_orders: Option<u32>,
    settings: BrunetonSettings,
    radii: Radii,
    transmittance: TransmittanceTable,
    /// One set of tables per three wavelengths (the last set padded by repeating the last
    /// wavelength).
    groups: Vec<Tables>,
    build_seconds: f64,
    /// The terrain's shadow in the air, when light shafts are on (docs/shafts.md).
    shadow: Option<ShadowMap>,
}

impl Bruneton {
    /// Builds the tables with the paper's settings.
    pub fn prepare(
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
    ) -> Result<Bruneton, ModelError> {
        Bruneton::prepare_with(
            atmosphere,
            settings,
            &BrunetonSettings::from_options(&settings.options)?,
        )
    }

    /// Builds the tables with chosen settings.
    pub fn prepare_with(
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
        bruneton: &BrunetonSettings,
    ) -> Result<Bruneton, ModelError> {
        let base = ModelBase::checked(ModelId::Bruneton, atmosphere, settings)?;
        bruneton.validate()?;
        bruneton.check_table_bytes(settings.wavelengths_nm.len())?;
        let start = std::time::Instant::now();
        let transmittance = TransmittanceTable::build(
            atmosphere,
            bruneton.transmittance_size.0,
            bruneton.transmittance_size.1,
        );
        let mut model = Bruneton {
            atmosphere: atmosphere.clone(),
            base,
            max_orders: settings.max_orders,
            settings: bruneton.clone(),
            radii: Radii {
                bottom_m: atmosphere.bottom_radius_m,
                top_m: atmosphere.top_radius_m,
            },
            transmittance,
            groups: Vec::new(),
            build_seconds: 0.0,
            shadow: None,
        };
        let densities = DensityTable::new(atmosphere);
        let delta_m = model.delta_m();
        model.groups = model
            .group_wavelengths()
            .into_iter()
            .map(|lambdas| model.builder(&densities, delta_m, lambdas).build())
            .collect();
        model.build_seconds = start.elapsed().as_secs_f64();
        Ok(model)
    }

    /// The terrain's shadow the view rays see from now on (`None`: no light shafts): the
    /// single scattering of the shadowed length taken out (`shafts.rs`).
    pub fn set_terrain_shadow(&mut self, shadow: Option<ShadowMap>) {
        self.shadow = shadow;
    }

    /// The wavelengths of each group of three (the last padded by repeating the last).
    fn group_wavelengths(&self) -> Vec<[f64; 3]> {
        self.base
            .spectra
            .wavelengths_nm
            .chunks(3)
            .map(|chunk| [0, 1, 2].map(|k| *chunk.get(k).unwrap_or(&chunk[chunk.len() - 1])))
            .collect()
    }

    /// True when Mie work is left out: pruning is on and the aerosol neither scatters
    /// nor absorbs at any of the model's wavelengths.
    pub fn mie_pruned(&self) -> bool {
        !self.base.with_mie
    }

    /// The delta-M form of the Mie phase function for the order step; `None` when Mie
    /// work is pruned.
    fn delta_m(&self) -> Option<DeltaM> {
        (!self.mie_pruned()).then(|| DeltaM::new(&self.atmosphere.mie.phase))
    }

    /// The table builder of one group of wavelengths.
    fn builder<'a>(
        &'a self,
        densities: &'a DensityTable,
        delta_m: Option<DeltaM>,
        lambdas: [f64; 3],
    ) -> Builder<'a> {
        let channels = Channels::new(&self.atmosphere, lambdas);
        Builder {
            atmosphere: &self.atmosphere,
            settings: &self.settings,
            radii: self.radii,
            transmittance: &self.transmittance,
            densities,
            channels,
            sun_transmittances: channels.transmittances(&self.transmittance),
            delta_m,
            mie_quadrature: (delta_m.is_some() && self.settings.mie_directions > 0).then(|| {
                MieQuadrature::new(
                    &self.atmosphere.mie.phase,
                    self.settings.mie_directions,
                    self.settings.mie_horizon,
                )
            }),
            max_orders: self.max_orders.unwrap_or(self.settings.order_limit),
        }
    }

    /// The orders computed for the first three wavelengths, with their share and time.
    pub fn orders(&self) -> &[OrderStats] {
        &self.groups[0].orders
    }

    /// Wall time of the whole build, seconds.
    pub fn build_seconds(&self) -> f64 {
        self.build_seconds
    }

    /// The tables of each group of three wavelengths.
    pub fn tables(&self) -> &[Tables] {
        &self.groups
    }

    /// S(x, v, s) of one group per unit solar irradiance: all orders, phase functions
    /// applied (paper section 4, "Angular precision": C* and C_M).
    fn scattered(tables: &Tables, p: &[(usize, f64); 4], nu: f64, mie_phase: f64) -> [f64; 3] {
        let a = tables.single_rayleigh.at_position(p);
        let c = tables.multiple.at_position(p);
        let pr = rayleigh(nu);
        let mut l = [0, 1, 2].map(|k| pr * a[k] + c[k]);
        if let Some(mie) = &tables.single_mie {
            let b = mie.at_position(p);
            for k in 0..3 {
                l[k] += mie_phase * b[k];
            }
        }
        l
    }
}

impl SkyModel for Bruneton {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        let table4 = |t: &Table4| std::mem::size_of_val(t.data.as_slice());
        std::mem::size_of_val(self.transmittance.columns.as_slice())
            + self
                .groups
                .iter()
                .map(|g| {
                    table4(&g.single_rayleigh)
                        + g.single_mie.as_ref().map_or(0, table4)
                        + table4(&g.multiple)
                        + std::mem::size_of_val(g.irradiance.data.as_slice())
                })
                .sum::<usize>()
    }

    /// Rebuilds what depends on what changed: the transmittance table holds columns of
    /// matter ([`Inputs::COLUMNS`]); single scattering depends on extinction and
    /// scattering but not on the phase functions (applied per ray) nor the ground;
    /// orders two and up and the irradiance table also on the ground albedo and the Mie
    /// phase function (unless Mie is pruned). Tables are per unit solar irradiance, so
    /// the solar spectrum rebuilds nothing; the sun's angular radius rebuilds single
    /// scattering and what follows it when the tables hold the sun as a disk
    /// ([`disk_changed`]).
    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let was_pruned = self.mie_pruned();
        let disk = disk_changed(self.settings.sun_disk, &self.atmosphere, atmosphere);
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        let changed = update.changed;
        self.radii = Radii {
            bottom_m: atmosphere.bottom_radius_m,
            top_m: atmosphere.top_radius_m,
        };
        let size = self.settings.transmittance_size;
        update.rebuild_columns("transmittance", &mut self.transmittance, atmosphere, size);
        let single = changed.intersects(Inputs::EXTINCTION) || disk;
        let multiple = single
            || changed.intersects(Inputs::GROUND_ALBEDO)
            || (changed.intersects(Inputs::MIE_PHASE) && !was_pruned);
        if multiple {
            let densities = DensityTable::new(atmosphere);
            let delta_m = self.delta_m();
            let old = std::mem::take(&mut self.groups);
            let groups = old
                .into_iter()
                .zip(self.group_wavelengths())
                .map(|(tables, lambdas)| {
                    let builder = self.builder(&densities, delta_m, lambdas);
                    if single {
                        builder.build()
                    } else {
                        let first = tables.orders[0];
                        builder.multiple_orders(tables.single_rayleigh, tables.single_mie, first)
                    }
                })
                .collect();
            self.groups = groups;
            if single {
                update.mark(&["single scattering"]);
            }
            update.mark(&["multiple scattering", "irradiance"]);
        }
        Ok(update.rebuilt())
    }

    /// The transmitted sun T(x, s) from the transmittance table (zero where the planet
    /// hides the sun's centre) and the sky's irradiance E[L](r, mu_s) from the irradiance
    /// table (section 4, Eq. 15: the irradiance on a horizontal element at radius r, from
    /// every order), at the element's radius and sun angle: the paper's ground term
    /// (Eq. 16) for any element.
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, surface)?;
        let n = self.base.spectra.wavelengths_nm.len();
        // The sun's visible fraction and the column along the path that dims it.
        let sun = if self.settings.sun_disk {
            visible_sun(
                e.r,
                e.mu_s,
                self.radii.bottom_m,
                self.atmosphere.sun.angular_radius_rad,
            )
        } else {
            (!ray_hits_ground(e.r, e.mu_s, self.radii.bottom_m)).then_some((1.0, e.mu_s))
        };
        let column_sun = sun.map(|(fraction, mu)| (fraction, self.transmittance.column(e.r, mu)));
        let mut out = Vec::with_capacity(n);
        for (g, tables) in self.groups.iter().enumerate() {
            let sky = tables.irradiance.lookup(e.r, e.mu_s);
            let sun_t = column_sun.map_or([0.0; 3], |(fraction, c)| {
                tables.channels.transmittance(c).map(|t| fraction * t)
            });
            for k in 0..3 {
                if 3 * g + k < n {
                    let solar = self.base.spectra.solar_irradiance[3 * g + k];
                    out.push(e.irradiance(solar, sun_t[k], solar * sky[k]));
                }
            }
        }
        Ok(out)
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.base.spectra.wavelengths_nm.len();
        let Some(segment) = ViewSegment::new(&self.atmosphere, ray)? else {
            return Ok(RayRadiance::unattenuated(n));
        };
        let (bottom, top) = (self.radii.bottom_m, self.radii.top_m);
        let (x, direction, sun) = (segment.start, segment.direction, segment.sun_direction);
        let (r, mu, length) = (segment.r, segment.mu, segment.length);
        let mu_s = (x.dot(sun) / x.length()).clamp(-1.0, 1.0);
        let nu = direction.dot(sun).clamp(-1.0, 1.0);
        // The half of the mu axis: that of the whole ray, also when an object ends it
        // before the ground.
        let ground = ray_hits_ground(r, mu, bottom);
        // The aerial perspective S(x) - T(x, x_o) S(x_o) (section 4, Eq. 3) for an object
        // that cuts the ray short; one beyond the ground ends the ray there, where S(x_o)
        // looks into the ground along a ray of length 0 and is zero.
        let object = segment.cut.then_some(length);
        let column = self.transmittance.segment_column(r, mu, length, ground);
        let mie_phase = if self.groups[0].single_mie.is_some() {
            self.atmosphere.mie.phase.eval(nu)
        } else {
            0.0
        };
        let size = self.groups[0].single_rayleigh.size;
        let p = table_position(&self.radii, &size, r, mu, mu_s, nu, ground);
        let end = object.map(|d| {
            let r_d = crate::optics::geometry::radius_at(r, mu, d).clamp(bottom, top);
            let mu_d = ((r * mu + d) / r_d).clamp(-1.0, 1.0);
            let mu_s_d = ((r * mu_s + d * nu) / r_d).clamp(-1.0, 1.0);
            table_position(&self.radii, &size, r_d, mu_d, mu_s_d, nu, ground)
        });
        // The ground's irradiance at the ray's end, the element facing up there.
        let ground_light = match segment.end {
            SegmentEnd::Ground => {
                let point = segment.end_point();
                Some(self.surface_irradiance(&SurfacePoint::facing_up(point, sun))?)
            }
            _ => None,
        };
        // Light shafts: the shadowed length as one segment (Eq. 17-18).
        let shadowed = self
            .shadow
            .as_ref()
            .map(|m| shadowed_length_m(&segment, m, bottom))
            .filter(|l| *l > 0.0)
            .map(|l| shadowed_segment(&segment, l));
        let shaft_ray = ShaftRay {
            radii: &self.radii,
            transmittance: &self.transmittance,
            segment: &segment,
            mu_s,
            nu,
            ground,
            mie_phase,
        };
        let mut radiance = Vec::with_capacity(n);
        let mut transmittance = Vec::with_capacity(n);
        for (g, tables) in self.groups.iter().enumerate() {
            let solar =
                [0, 1, 2].map(|k| self.base.spectra.solar_irradiance[(3 * g + k).min(n - 1)]);
            let mut l = Self::scattered(tables, &p, nu, mie_phase);
            let t = tables.channels.transmittance(column);
            if let Some(q) = &end {
                let l_end = Self::scattered(tables, q, nu, mie_phase);
                for k in 0..3 {
                    l[k] -= t[k] * l_end[k];
                }
            }
            if let Some(part) = shadowed {
                let lost = shaft_ray.single_taken_out(tables, part);
                for k in 0..3 {
                    l[k] -= lost[k];
                }
            }
            for k in 0..3 {
                if 3 * g + k < n {
                    let ground = ground_light.as_ref().map_or(0.0, |e| {
                        t[k] * self.atmosphere.ground_albedo / PI * e[3 * g + k]
                    });
                    radiance.push((solar[k] * l[k] + ground).max(0.0));
                    transmittance.push(t[k].clamp(0.0, 1.0));
                }
            }
        }
        Ok(RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: vec![0.0; n],
        })
    }
}
