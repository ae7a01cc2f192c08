//! Nishita et al. 1993 as described by Dobashi, Yamamoto and Nishita 2002 (section 5 and
//! appendix A) and O'Neil 2004 ("The Problem"): single scattering integrated along each
//! view ray with N samples, the optical depth from each sample to the sun read from a
//! precomputed table g_l(h, theta_sun).
//!
//! The table stores columns of matter per species (Rayleigh, Mie, ozone) in f64, so one
//! table serves every wavelength; optical depth at a wavelength is the sum of columns times
//! the species' extinctions. See docs/models/nishita.md.

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::options::{ModelOptions, Setting};
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::column::{densities, optical_depth};
use crate::optics::geometry::ray_hits_ground;
use crate::optics::surface_lighting::{SurfaceElement, add_ground_light};
use crate::optics::transmittance_table::TransmittanceTable;
use crate::optics::view_segment::{SegmentEnd, ViewSegment};
use crate::shafts::{ShadowMap, SunVisibility};

/// The settings that trade accuracy for time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NishitaSettings {
    /// Samples along each view ray (equal sub-segments, one sample at each midpoint).
    /// Default 100: the number of sampling planes Dobashi, Yamamoto and Nishita 2002 use
    /// for the sky (Table 1, Fig. 10(a), "100 (sky)"); neither paper states a per-ray
    /// count for Nishita et al. 1993.
    pub view_samples: usize,
    /// Rows of the table g_l: heights from the ground to the top of the atmosphere.
    /// Default 64; the papers do not state a size (see `table_angles`).
    pub table_heights: usize,
    /// Columns of the table g_l: sun zenith angles from 0 to the geometric horizon of the
    /// row's height ([`sun_column`]). Default 256: the papers give no size for g_l, so the
    /// table has the size of the transmittance tables of Bruneton 2017 and Hillaire 2020
    /// (256 x 64), whose error is mostly below that of the default view sampling
    /// (docs/models/nishita.md).
    pub table_angles: usize,
}

impl Default for NishitaSettings {
    fn default() -> Self {
        NishitaSettings {
            view_samples: 100,
            table_heights: 64,
            table_angles: 256,
        }
    }
}

/// `samples`: within what every GPU runs in one loop (well under 65535 trips).
pub const SAMPLES: Setting<usize> = Setting {
    model: "nishita",
    key: "samples",
    range: 1..=4096,
};
/// `table_heights`, `table_angles`: up to 2048 (100 MB of f64 columns at 2048 x 2048).
pub const TABLE_HEIGHTS: Setting<usize> = Setting {
    model: "nishita",
    key: "table_heights",
    range: 2..=2048,
};
pub const TABLE_ANGLES: Setting<usize> = Setting {
    model: "nishita",
    key: "table_angles",
    range: 2..=2048,
};

impl NishitaSettings {
    /// The settings from `key=value` options: `samples`, `table_heights`,
    /// `table_angles`; the defaults where absent.
    pub fn from_options(options: &ModelOptions) -> Result<NishitaSettings, ModelError> {
        options.read_settings("nishita", NishitaSettings::validate, |o, d| {
            Ok(NishitaSettings {
                view_samples: o.count(&SAMPLES, d.view_samples)?,
                table_heights: o.count(&TABLE_HEIGHTS, d.table_heights)?,
                table_angles: o.count(&TABLE_ANGLES, d.table_angles)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        SAMPLES.check(self.view_samples)?;
        TABLE_HEIGHTS.check(self.table_heights)?;
        TABLE_ANGLES.check(self.table_angles)?;
        Ok(())
    }
}

/// The optical-depth table g_l(h, theta_sun) of Dobashi, Yamamoto and Nishita 2002,
/// appendix A.1, as columns of
/// matter (m) from a point at radius r towards a sun whose direction has cosine `mu_sun`
/// with the local zenith. The table is a [`TransmittanceTable`]: the paper's two axes
/// (height, sun angle) with the spacing of Bruneton 2017 (rows at equal steps of
/// sqrt(r^2 - R^2), sun angles at equal steps of the distance to the top, so that the
/// horizon is the last column at every height); the paper gives no spacing, and equal
/// steps of theta_sun are far worse near the horizon (docs/models/nishita.md). `None`
/// when the sun's centre is behind the planet: g_l = 0 (section 5.2).
pub fn sun_column(table: &TransmittanceTable, r: f64, mu_sun: f64) -> Option<[f64; 3]> {
    let bottom = table.mapping.bottom_radius_m;
    let r = r.clamp(bottom, table.mapping.top_radius_m);
    let mu_sun = mu_sun.clamp(-1.0, 1.0);
    if ray_hits_ground(r, mu_sun, bottom) {
        None
    } else {
        Some(table.column(r, mu_sun))
    }
}

/// The Nishita model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Nishita {
    atmosphere: Atmosphere,
    /// `with_mie` false when pruning at zero aerosol: no Mie density or phase is evaluated.
    base: ModelBase,
    settings: NishitaSettings,
    table: TransmittanceTable,
    /// The terrain's shadow in the air, when light shafts are on (docs/shafts.md).
    shadow: Option<ShadowMap>,
}

impl Nishita {
    /// Prepares the model with explicit Nishita settings. Only single scattering is
    /// computed, whatever `model_settings.max_orders` asks for (as in the paper).
    pub fn prepare(
        atmosphere: &Atmosphere,
        model_settings: &ModelSettings,
        settings: NishitaSettings,
    ) -> Result<Nishita, ModelError> {
        let base = ModelBase::checked(ModelId::Nishita, atmosphere, model_settings)?;
        settings.validate()?;
        Ok(Nishita {
            atmosphere: atmosphere.clone(),
            base,
            settings,
            table: TransmittanceTable::build(
                atmosphere,
                settings.table_angles,
                settings.table_heights,
            ),
            shadow: None,
        })
    }

    pub fn settings(&self) -> &NishitaSettings {
        &self.settings
    }

    /// The terrain's shadow the view samples test from now on (`None`: no light shafts):
    /// each sample's single scattering times its sun visibility.
    pub fn set_terrain_shadow(&mut self, shadow: Option<ShadowMap>) {
        self.shadow = shadow;
    }

    pub fn table(&self) -> &TransmittanceTable {
        &self.table
    }
}

impl SkyModel for Nishita {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        std::mem::size_of_val(self.table.columns.as_slice())
    }

    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        let size = (self.settings.table_angles, self.settings.table_heights);
        update.rebuild_columns("g_l", &mut self.table, atmosphere, size);
        Ok(update.rebuilt())
    }

    /// The transmitted sun only (Dobashi, Yamamoto and Nishita 2002, Eq. 11): single scattering has no sky light.
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, surface)?;
        let s = &self.base.spectra;
        let column = (e.sun_cosine > 0.0)
            .then(|| sun_column(&self.table, e.r, e.mu_s))
            .flatten();
        Ok(e.sun_irradiances(&s.solar_irradiance, |w| {
            column.map_or(0.0, |c| (-optical_depth(c, s.extinction[w])).exp())
        }))
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let a = &self.atmosphere;
        let s = &self.base.spectra;
        let n_w = s.wavelengths_nm.len();
        let bottom = a.bottom_radius_m;
        let Some(segment) = ViewSegment::new(a, ray)? else {
            return Ok(RayRadiance::unattenuated(n_w));
        };
        let (start, direction, sun) = (segment.start, segment.direction, segment.sun_direction);
        let (length, on_ground) = (segment.length, segment.end == SegmentEnd::Ground);

        // Dobashi, Yamamoto and Nishita 2002, Eq. 12 with n equal sub-segments of length
        // dt, each represented by its midpoint (O'Neil 2004: "for each sample ray,
        // calculate the center point").
        let n = self.settings.view_samples;
        let dt = length / n as f64;
        let nu = direction.dot(sun);
        let phase_r = crate::optics::phase::rayleigh(nu);
        let phase_m = if self.base.with_mie {
            a.mie.phase.eval(nu)
        } else {
            0.0
        };
        let mut radiance = vec![0.0; n_w];
        let mut view_column = [0.0; 3];
        for k in 0..n {
            let position = start + direction * ((k as f64 + 0.5) * dt);
            let radius = position.length();
            let altitude = (radius - bottom).max(0.0);
            let rho = if self.base.with_mie {
                densities(a, altitude)
            } else {
                [
                    a.rayleigh.density.density(altitude),
                    0.0,
                    a.ozone.density.density(altitude),
                ]
            };
            // Column from the camera to the midpoint: the previous segments plus half of
            // this one.
            let mut to_sample = view_column;
            for c in 0..3 {
                to_sample[c] += 0.5 * dt * rho[c];
                view_column[c] += dt * rho[c];
            }
            let mu_sun = position.dot(sun) / radius;
            let Some(sun_column) = sun_column(&self.table, radius, mu_sun) else {
                continue;
            };
            let visible = self
                .shadow
                .as_ref()
                .map_or(1.0, |m| m.sun_visible(position, sun));
            let scatter_r = rho[0] * phase_r * visible;
            let scatter_m = rho[1] * phase_m * visible;
            for w in 0..n_w {
                let tau = optical_depth(to_sample, s.extinction[w])
                    + optical_depth(sun_column, s.extinction[w]);
                let j = s.rayleigh_scattering[w] * scatter_r + s.mie_scattering[w] * scatter_m;
                radiance[w] += dt * (-tau).exp() * j * s.solar_irradiance[w];
            }
        }
        let transmittance: Vec<f64> = s
            .extinction
            .iter()
            .map(|e| (-optical_depth(view_column, *e)).exp())
            .collect();

        // Ground: I_e = I_sun r g_l(0, theta_g) cos(theta_g), attenuated by the view ray
        // (Dobashi, Yamamoto and Nishita 2002, Eq. 11-12), with r / pi for a Lambertian albedo in radiance units.
        if on_ground {
            let end = start + direction * length;
            add_ground_light(
                self,
                end,
                sun,
                a.ground_albedo,
                &transmittance,
                &mut radiance,
            )?;
        }
        Ok(RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: vec![0.0; n_w],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::geometry::{distance_to_exit, horizon_mu};

    #[test]
    fn sun_behind_the_planet_gives_no_column() {
        let earth = Atmosphere::preset("earth").unwrap();
        let table = TransmittanceTable::build(&earth, 16, 8);
        let r = earth.bottom_radius_m + 10_000.0;
        let h = horizon_mu(r, earth.bottom_radius_m);
        assert!(sun_column(&table, r, h - 1e-6).is_none());
        assert!(sun_column(&table, r, h + 1e-6).is_some());
        assert!(sun_column(&table, earth.bottom_radius_m, -1e-9).is_none());
        assert!(sun_column(&table, earth.bottom_radius_m, 0.0).is_some());
    }

    /// The default 256 x 64 table gives the sun's transmittance at 440 nm within 3e-4 of
    /// the converged columns at every height and sun angle up to the horizon
    /// (docs/models/nishita.md).
    #[test]
    fn default_table_is_accurate_up_to_the_horizon() {
        let earth = Atmosphere::preset("earth").unwrap();
        let d = NishitaSettings::default();
        let table = TransmittanceTable::build(&earth, d.table_angles, d.table_heights);
        let ext = earth.coefficients(440.0).extinction_per_species();
        let mut worst = 0.0f64;
        for h in [0.0, 150.0, 1_234.0, 7_000.0, 23_456.0, 41_000.0, 59_000.0] {
            let r = earth.bottom_radius_m + h;
            let horizon = horizon_mu(r, earth.bottom_radius_m).acos();
            let mut theta = 0.013;
            while theta < horizon {
                let mu = theta.cos();
                let exact = crate::optics::column::column(
                    &earth,
                    r,
                    mu,
                    distance_to_exit(r, mu, earth.top_radius_m),
                );
                let got = sun_column(&table, r, mu).unwrap();
                let dt = (-optical_depth(got, ext)).exp() - (-optical_depth(exact, ext)).exp();
                worst = worst.max(dt.abs());
                theta += 0.00377;
            }
        }
        assert!(worst < 3e-4, "{worst:e}");
    }

    #[test]
    fn settings_are_checked() {
        let bad = NishitaSettings {
            view_samples: 0,
            ..NishitaSettings::default()
        };
        assert!(bad.validate().is_err());
        let bad = NishitaSettings {
            table_heights: 1,
            ..NishitaSettings::default()
        };
        assert!(bad.validate().is_err());
        assert!(NishitaSettings::default().validate().is_ok());
    }
}
