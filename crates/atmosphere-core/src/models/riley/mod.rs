//! Riley et al. 2004, section 4.1: an analytic single-scattering sky. Each species is one
//! exponential; single scattering along a view ray is integrated in closed form (Eq. 15)
//! over a few pieces of the ray.
//!
//! The paper's form ([`RileySettings::PAPER`]) flattens the earth in the camera's tangent
//! frame and dims each species' light by its own extinction only ([`flat`]). The defaults
//! keep the closed form but take the columns of every species along the real ray and
//! towards the sun on the sphere ([`chapman`]), light only the ray's parts outside the
//! planet's shadow ([`shadow`]), dim every species' light by all of them and by ozone,
//! and take the exponent linear over each piece ([`pieces`]). See docs/models/riley.md.

pub mod chapman;
pub mod flat;
pub mod flat_path;
pub mod pieces;
pub mod settings;
pub mod shadow;
pub mod species;
pub mod sphere_path;

pub use flat::{FlatExponential, phi};
pub use settings::RileySettings;
pub use species::{Species, effective_exponential};

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::geometry::ray_hits_ground;
use crate::optics::phase::{PhaseFunction, rayleigh};
use crate::optics::surface_lighting::{SurfaceElement, add_ground_light};
use crate::optics::view_segment::{SegmentEnd, ViewSegment};

use chapman::column_to_top;
use flat::flat_legs;
use flat_path::flat_pieces;
use pieces::{OZONE, SCATTERING, SPECIES, piece_integrals};
use sphere_path::sphere_pieces;

/// Riley et al.'s analytic single-scattering sky, prepared for one atmosphere.
#[derive(Clone, Debug)]
pub struct Riley {
    /// `with_mie` false when pruning at zero aerosol: the Mie terms are skipped.
    base: ModelBase,
    settings: RileySettings,
    bottom_radius_m: f64,
    top_radius_m: f64,
    ground_albedo: f64,
    rayleigh: Species,
    mie: Species,
    /// Absorbs only (albedo 0); used with `ozone=true`.
    ozone: Species,
    mie_phase: PhaseFunction,
}

impl Riley {
    /// Samples the atmosphere at the settings' wavelengths and fits each species' profile
    /// (Rayleigh, Mie, ozone) with one exponential. `max_orders` and the stochastic
    /// settings do not apply: the model is single scattering, in closed form.
    pub fn prepare(
        atmosphere: &Atmosphere,
        settings: &ModelSettings,
        riley: RileySettings,
    ) -> Riley {
        let base = ModelBase::new(ModelId::Riley, atmosphere, settings);
        let thickness = atmosphere.thickness_m();
        let spectra = &base.spectra;
        let rayleigh_s = &spectra.rayleigh_scattering;
        let mie_s = &spectra.mie_scattering;
        let extinction =
            |k: usize| -> Vec<f64> { spectra.extinction.iter().map(|e| e[k]).collect() };
        let no_scattering = vec![0.0; spectra.wavelengths_nm.len()];
        Riley {
            settings: riley,
            bottom_radius_m: atmosphere.bottom_radius_m,
            top_radius_m: atmosphere.top_radius_m,
            ground_albedo: atmosphere.ground_albedo,
            rayleigh: Species::new(
                &atmosphere.rayleigh.density,
                thickness,
                rayleigh_s,
                rayleigh_s,
            ),
            mie: Species::new(&atmosphere.mie.density, thickness, mie_s, &extinction(1)),
            ozone: Species::new(
                &atmosphere.ozone.density,
                thickness,
                &no_scattering,
                &extinction(OZONE),
            ),
            mie_phase: atmosphere.mie.phase.clone(),
            base,
        }
    }

    /// The settings the model was prepared with.
    pub fn settings(&self) -> RileySettings {
        self.settings
    }

    /// The scale heights (Rayleigh, Mie) the model uses, m.
    pub fn scale_heights_m(&self) -> (f64, f64) {
        (self.rayleigh.scale_height_m, self.mie.scale_height_m)
    }

    /// The fitted species (Rayleigh, Mie, ozone) the closed form is evaluated with; Mie is
    /// `None` when its terms are skipped (pruned at zero aerosol), ozone when
    /// `ozone=false`. What the GPU twin, `shaders/sky/riley/pixel.wgsl`, is given.
    pub fn species(&self) -> (&Species, Option<&Species>, Option<&Species>) {
        (
            &self.rayleigh,
            self.base.with_mie.then_some(&self.mie),
            self.settings.ozone.then_some(&self.ozone),
        )
    }

    /// Each species' ground extinction at wavelength `w`, zero for a species left out.
    fn extinctions(&self, w: usize) -> [f64; SPECIES] {
        let (rayleigh, mie, ozone) = self.species();
        [
            rayleigh.extinction[w],
            mie.map_or(0.0, |m| m.extinction[w]),
            ozone.map_or(0.0, |o| o.extinction[w]),
        ]
    }

    fn scale_heights(&self) -> [f64; SPECIES] {
        [
            self.rayleigh.scale_height_m,
            self.mie.scale_height_m,
            self.ozone.scale_height_m,
        ]
    }

    fn answer(&self, radiance: Vec<f64>, transmittance: Vec<f64>) -> RayRadiance {
        let n = radiance.len();
        RayRadiance {
            radiance,
            transmittance,
            radiance_std_error: vec![0.0; n],
        }
    }
}

impl SkyModel for Riley {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        0
    }

    /// No tables: the fitted coefficients are recomputed, which costs microseconds.
    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        atmosphere.validate()?;
        let settings = ModelSettings {
            wavelengths_nm: self.base.spectra.wavelengths_nm.clone(),
            prune: self.base.prune,
            ..ModelSettings::default()
        };
        *self = Riley::prepare(atmosphere, &settings, self.settings);
        Ok(Vec::new())
    }

    /// The transmitted sun only (single scattering has no sky light): the sun's optical
    /// depth from the element, summed over the species, is on the sphere the Chapman
    /// column up to the top ([`chapman::column_to_top`], none where the ground hides the
    /// sun) and on
    /// the flat earth Eq. (12) in the element's own tangent frame, beta H exp(-y / H) / l
    /// with l = mu_s (none for l <= 0, the flat ground's horizon).
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let (bottom, top) = (self.bottom_radius_m, self.top_radius_m);
        let e = SurfaceElement::new_within(bottom, top, surface)?;
        let y = e.r - bottom;
        let heights = self.scale_heights();
        let lit = if self.settings.sphere {
            !ray_hits_ground(e.r, e.mu_s, bottom)
        } else {
            e.mu_s > 0.0
        };
        let columns: [f64; SPECIES] = std::array::from_fn(|k| {
            if !lit {
                0.0
            } else if self.settings.sphere {
                column_to_top(y, e.mu_s, heights[k], bottom, top - bottom)
            } else {
                heights[k] * (-y / heights[k]).exp() / e.mu_s
            }
        });
        Ok(e.sun_irradiances(&self.base.spectra.solar_irradiance, |w| {
            if e.sun_cosine > 0.0 && lit {
                let ext = self.extinctions(w);
                let tau: f64 = (0..SPECIES).map(|k| ext[k] * columns[k]).sum();
                (-tau).exp()
            } else {
                0.0
            }
        }))
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.base.spectra.wavelengths_nm.len();
        let (bottom, top) = (self.bottom_radius_m, self.top_radius_m);
        let Some(segment) = ViewSegment::new_within(bottom, top, ray)? else {
            return Ok(self.answer(vec![0.0; n], vec![1.0; n]));
        };
        let (direction, sun) = (segment.direction, segment.sun_direction);
        let heights = self.scale_heights();
        let pieces = self.settings.pieces;
        let ray_pieces = if self.settings.sphere {
            sphere_pieces(&segment, (bottom, top), heights, pieces)
        } else {
            let zenith = segment.start / segment.start.length();
            let (y0, p) = (segment.r - bottom, segment.mu);
            let l = sun.dot(zenith).clamp(-1.0, 1.0);
            let (mut legs, _) = flat_legs(y0, segment.r, p, bottom, top);
            if segment.end == SegmentEnd::Object {
                // Keep the legs up to the object.
                let mut remaining = segment.length;
                legs.retain_mut(|leg| {
                    let keep = remaining > 0.0;
                    leg.length_m = leg.length_m.min(remaining);
                    remaining -= leg.length_m;
                    keep
                });
            }
            flat_pieces(&legs, l, heights, pieces)
        };
        let nu = direction.dot(sun);
        let phase_r = rayleigh(nu);
        let phase_m = if self.base.with_mie {
            self.mie_phase.eval(nu)
        } else {
            0.0
        };
        let mut radiance = vec![0.0; n];
        let mut transmittance = vec![1.0; n];
        for w in 0..n {
            let extinction = self.extinctions(w);
            let weights: [f64; SCATTERING] = [
                self.rayleigh.albedo[w] * phase_r,
                self.mie.albedo[w] * phase_m,
            ];
            let mut integral = 0.0;
            for part in &ray_pieces.parts {
                for piece in part.windows(2) {
                    let light = piece_integrals(
                        &piece[0],
                        &piece[1],
                        &extinction,
                        self.settings.shared_extinction,
                    );
                    integral += weights[0] * light[0] + weights[1] * light[1];
                }
            }
            radiance[w] = self.base.spectra.solar_irradiance[w] * integral;
            let depth: f64 = (0..SPECIES)
                .filter(|&k| extinction[k] > 0.0)
                .map(|k| extinction[k] * ray_pieces.end_view[k])
                .sum();
            transmittance[w] = (-depth).exp();
        }
        if segment.end == SegmentEnd::Ground {
            // The Lambertian ground lit by the transmitted sun, as any surface element
            // facing up at the ray's end.
            let end = segment.end_point();
            let albedo = self.ground_albedo;
            add_ground_light(self, end, sun, albedo, &transmittance, &mut radiance)?;
        }
        Ok(self.answer(radiance, transmittance))
    }
}
