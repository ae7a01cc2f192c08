//! Bruneton and Neyret 2008, "Precomputed atmospheric scattering" (seed 004): a
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
//! solar irradiance, so that `update` rebuilds nothing for a new solar spectrum. See
//! docs/models/bruneton.md.

pub mod parameterization;
pub mod precompute;
pub mod tables;

use std::f64::consts::PI;

use glam::DVec3;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::bruneton::parameterization::{Radii, ScatteringSize, table_position};
use crate::models::bruneton::precompute::{Builder, Channels, DeltaM, OrderStats, Tables};
use crate::models::bruneton::tables::{DensityTable, Table4};
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::options::ModelOptions;
use crate::models::sky_model::{ModelSettings, RayRadiance, SkyModel, ViewRay};
use crate::optics::geometry::ray_hits_ground;
use crate::optics::phase::rayleigh;
use crate::optics::surface_lighting::SurfaceElement;
use crate::optics::transmittance_table::{BRUNETON_TABLE_SIZE, TransmittanceTable};
use crate::optics::view_segment::{SegmentEnd, ViewSegment};

/// The model's settings. `Default` gives the paper's sizes (section 6) and the sample
/// counts of its published implementation.
#[derive(Clone, Debug, PartialEq)]
pub struct BrunetonSettings {
    /// S over (r, mu, mu_s, nu): 32 x 128 x 32 x 8 in the paper. mu must be even (half
    /// for rays that meet the ground); every size at least 2.
    pub scattering_size: ScatteringSize,
    /// E over (mu_s, r): 64 x 16 in the paper.
    pub irradiance_size: (usize, usize),
    /// T over (mu, r): 256 x 64 (the paper has 256 x 64 too, in another mapping; this is
    /// the shared table of Bruneton 2017's mapping).
    pub transmittance_size: (usize, usize),
    /// Trapezoid intervals along each texel's ray for single scattering and each
    /// Delta S: 50 (INSCATTER_INTEGRAL_SAMPLES of the paper's code). 30 saves a third of
    /// the build and costs little on clear days, but misses the thin hazy boundary layer
    /// (docs/report: hazy view 5.1 % against 4.4 %). Unlike that code,
    /// nodes are spaced quadratically towards the dense end of climbing and descending
    /// rays: evenly spaced, vertical rays overestimate Mie scattering by 8 %.
    pub view_samples: usize,
    /// Directions (zenith angle, azimuth) of the sphere integrals for Delta J and
    /// Delta E: 16 x 32 (INSCATTER_SPHERICAL_INTEGRAL_SAMPLES). The zenith angle is
    /// integrated by 8-point Gauss-Legendre panels on each side of the horizon, one pair
    /// of panels per 16 directions.
    pub sphere_samples: (usize, usize),
    /// Stop after an order whose share of all the table's radiance (sum over texels, worst
    /// channel) is below this: 0.02. On Earth order 5 adds 1.1 % and stops the loop; the
    /// orders left out would add about 0.6 %.
    pub order_threshold: f64,
    /// The most orders when `ModelSettings::max_orders` is `None` (a guard for thick
    /// atmospheres whose orders fade slowly): 32.
    pub order_limit: u32,
}

impl Default for BrunetonSettings {
    fn default() -> Self {
        BrunetonSettings {
            scattering_size: ScatteringSize {
                r: 32,
                mu: 128,
                mu_s: 32,
                nu: 8,
            },
            irradiance_size: (64, 16),
            transmittance_size: BRUNETON_TABLE_SIZE,
            view_samples: 50,
            sphere_samples: (16, 32),
            order_threshold: 0.02,
            order_limit: 32,
        }
    }
}

impl BrunetonSettings {
    /// The settings from `key=value` options: `r`, `mu`, `mu_s`, `nu` (S's size),
    /// `view_samples`, `sphere_zenith`, `sphere_azimuth`, `order_threshold`,
    /// `order_limit`; the paper's values where absent.
    pub fn from_options(options: &ModelOptions) -> Result<BrunetonSettings, ModelError> {
        let d = BrunetonSettings::default();
        let mut o = options.reader("bruneton");
        let settings = BrunetonSettings {
            scattering_size: ScatteringSize {
                r: o.count("r", d.scattering_size.r)?,
                mu: o.count("mu", d.scattering_size.mu)?,
                mu_s: o.count("mu_s", d.scattering_size.mu_s)?,
                nu: o.count("nu", d.scattering_size.nu)?,
            },
            view_samples: o.count("view_samples", d.view_samples)?,
            sphere_samples: (
                o.count("sphere_zenith", d.sphere_samples.0)?,
                o.count("sphere_azimuth", d.sphere_samples.1)?,
            ),
            order_threshold: o.number("order_threshold", d.order_threshold)?,
            order_limit: o.count("order_limit", d.order_limit as usize)? as u32,
            ..d
        };
        o.finish()?;
        settings.validate()?;
        Ok(settings)
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let s = self.scattering_size;
        if s.r < 2 || s.mu < 4 || !s.mu.is_multiple_of(2) || s.mu_s < 2 || s.nu < 2 {
            return Err(ModelError::Settings(format!(
                "scattering table size {s:?}: each axis needs 2 texels, mu an even count of 4 or more"
            )));
        }
        if self.irradiance_size.0 < 2 || self.irradiance_size.1 < 2 {
            return Err(ModelError::Settings(
                "irradiance table needs 2 x 2 texels".into(),
            ));
        }
        if self.transmittance_size.0 < 2 || self.transmittance_size.1 < 2 {
            return Err(ModelError::Settings(
                "transmittance table needs 2 x 2 texels".into(),
            ));
        }
        if self.view_samples == 0 || self.sphere_samples.0 == 0 || self.sphere_samples.1 < 2 {
            return Err(ModelError::Settings(
                "sample counts must be positive".into(),
            ));
        }
        if !(self.order_threshold.is_finite() && self.order_threshold >= 0.0) {
            return Err(ModelError::Settings("order threshold must be >= 0".into()));
        }
        if self.order_limit == 0 {
            return Err(ModelError::Settings(
                "order limit must be at least 1".into(),
            ));
        }
        Ok(())
    }
}

/// The Bruneton 2008 model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Bruneton {
    atmosphere: Atmosphere,
    model_settings: ModelSettings,
    settings: BrunetonSettings,
    radii: Radii,
    wavelengths_nm: Vec<f64>,
    solar_irradiance: Vec<f64>,
    transmittance: TransmittanceTable,
    /// One set of tables per three wavelengths (the last set padded by repeating the last
    /// wavelength).
    groups: Vec<Tables>,
    build_seconds: f64,
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
        atmosphere.validate()?;
        settings.validate()?;
        bruneton.validate()?;
        let start = std::time::Instant::now();
        let transmittance = TransmittanceTable::build(
            atmosphere,
            bruneton.transmittance_size.0,
            bruneton.transmittance_size.1,
        );
        let mut model = Bruneton {
            atmosphere: atmosphere.clone(),
            model_settings: settings.clone(),
            settings: bruneton.clone(),
            radii: Radii {
                bottom_m: atmosphere.bottom_radius_m,
                top_m: atmosphere.top_radius_m,
            },
            wavelengths_nm: settings.wavelengths_nm.clone(),
            solar_irradiance: solar_irradiance(atmosphere, &settings.wavelengths_nm),
            transmittance,
            groups: Vec::new(),
            build_seconds: 0.0,
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

    /// The wavelengths of each group of three (the last padded by repeating the last).
    fn group_wavelengths(&self) -> Vec<[f64; 3]> {
        self.wavelengths_nm
            .chunks(3)
            .map(|chunk| [0, 1, 2].map(|k| *chunk.get(k).unwrap_or(&chunk[chunk.len() - 1])))
            .collect()
    }

    /// True when Mie work is left out: pruning is on and the aerosol neither scatters
    /// nor absorbs at any of the model's wavelengths.
    pub fn mie_pruned(&self) -> bool {
        !Spectra::new(&self.atmosphere, &self.wavelengths_nm).needs_mie(self.model_settings.prune)
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
            max_orders: self
                .model_settings
                .max_orders
                .unwrap_or(self.settings.order_limit),
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

    /// Columns of matter from (r, mu) over distance d, from the transmittance table.
    fn segment_column(&self, r: f64, mu: f64, d: f64, ground: bool) -> [f64; 3] {
        let r_d = crate::optics::geometry::radius_at(r, mu, d)
            .clamp(self.radii.bottom_m, self.radii.top_m);
        let mu_d = ((r * mu + d) / r_d).clamp(-1.0, 1.0);
        let (a, b) = if ground {
            (
                self.transmittance.column(r_d, -mu_d),
                self.transmittance.column(r, -mu),
            )
        } else {
            (
                self.transmittance.column(r, mu),
                self.transmittance.column(r_d, mu_d),
            )
        };
        [0, 1, 2].map(|k| (a[k] - b[k]).max(0.0))
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
    fn id(&self) -> ModelId {
        ModelId::Bruneton
    }

    fn wavelengths_nm(&self) -> &[f64] {
        &self.wavelengths_nm
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
    /// the sun ([`Inputs::SUN`]) rebuilds nothing.
    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        atmosphere.validate()?;
        let changed = Inputs::changed(&self.atmosphere, atmosphere);
        let was_pruned = self.mie_pruned();
        self.atmosphere = atmosphere.clone();
        self.solar_irradiance = solar_irradiance(atmosphere, &self.wavelengths_nm);
        self.radii = Radii {
            bottom_m: atmosphere.bottom_radius_m,
            top_m: atmosphere.top_radius_m,
        };
        let mut rebuilt = Vec::new();
        if changed.intersects(Inputs::COLUMNS) {
            self.transmittance = TransmittanceTable::build(
                atmosphere,
                self.settings.transmittance_size.0,
                self.settings.transmittance_size.1,
            );
            rebuilt.push("transmittance");
        }
        let single = changed.intersects(Inputs::EXTINCTION);
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
                rebuilt.push("single scattering");
            }
            rebuilt.extend(["multiple scattering", "irradiance"]);
        }
        Ok(rebuilt)
    }

    fn solar_irradiance_w_m2_nm(&self) -> &[f64] {
        &self.solar_irradiance
    }

    /// The transmitted sun T(x, s) from the transmittance table (zero where the planet
    /// hides the sun's centre) and the sky's irradiance E[L](r, mu_s) from the irradiance
    /// table (section 4, Eq. 15: the irradiance on a horizontal element at radius r, from
    /// every order), at the element's radius and sun angle: the paper's ground term
    /// (Eq. 16) for any element.
    fn surface_irradiance(
        &self,
        point_m: DVec3,
        normal: DVec3,
        sun_direction: DVec3,
    ) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, point_m, normal, sun_direction)?;
        let n = self.wavelengths_nm.len();
        let column_sun = (!ray_hits_ground(e.r, e.mu_s, self.radii.bottom_m))
            .then(|| self.transmittance.column(e.r, e.mu_s));
        let mut out = Vec::with_capacity(n);
        for (g, tables) in self.groups.iter().enumerate() {
            let sky = tables.irradiance.lookup(e.r, e.mu_s);
            let sun_t = column_sun.map_or([0.0; 3], |c| tables.channels.transmittance(c));
            for k in 0..3 {
                if 3 * g + k < n {
                    let solar = self.solar_irradiance[3 * g + k];
                    out.push(e.irradiance(solar, sun_t[k], solar * sky[k]));
                }
            }
        }
        Ok(out)
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.wavelengths_nm.len();
        let Some(segment) = ViewSegment::new(&self.atmosphere, ray)? else {
            return Ok(RayRadiance {
                radiance: vec![0.0; n],
                transmittance: vec![1.0; n],
                radiance_std_error: vec![0.0; n],
            });
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
        let column = self.segment_column(r, mu, length, ground);
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
                Some(self.surface_irradiance(point, point, sun)?)
            }
            _ => None,
        };
        let mut radiance = Vec::with_capacity(n);
        let mut transmittance = Vec::with_capacity(n);
        for (g, tables) in self.groups.iter().enumerate() {
            let solar = [0, 1, 2].map(|k| self.solar_irradiance[(3 * g + k).min(n - 1)]);
            let mut l = Self::scattered(tables, &p, nu, mie_phase);
            let t = tables.channels.transmittance(column);
            if let Some(q) = &end {
                let l_end = Self::scattered(tables, q, nu, mie_phase);
                for k in 0..3 {
                    l[k] -= t[k] * l_end[k];
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

/// The solar irradiance at the top of the atmosphere at each wavelength.
fn solar_irradiance(atmosphere: &Atmosphere, wavelengths_nm: &[f64]) -> Vec<f64> {
    wavelengths_nm
        .iter()
        .map(|l| atmosphere.sun.irradiance_w_m2_nm.at(*l))
        .collect()
}
