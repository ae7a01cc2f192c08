//! Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere Rendering
//! Technique" (EGSR 2020): no high-dimensional table; a transmittance LUT (256 x 64), a
//! multiple-scattering LUT Psi_ms (32 x 32) from an isotropic approximation of orders two
//! and up, and per view a sky-view LUT (192 x 108) and an aerial-perspective volume
//! (32 slices over 32 km), all filled by short ray marches.
//!
//! A view ray from a camera inside the atmosphere reads the sky-view LUT if it ends in
//! space, the aerial-perspective volume if it ends on the ground or an object within the
//! volume's range, and is ray marched per pixel otherwise (surfaces beyond the volume);
//! a camera in space marches every ray per pixel from where it enters the atmosphere, as
//! the paper does for views from space. Rays that end on the ground add the ground's
//! Lambertian light times the ray's transmittance. See docs/models/hillaire.md.

pub mod aerial_perspective;
pub mod directions;
pub mod ground;
pub mod march;
pub mod medium;
pub mod moments;
pub mod multiple_scattering;
pub mod rows;
pub mod settings;
pub mod shafts;
pub mod similarity;
pub mod sky_view;
pub mod view_cache;

pub use settings::HillaireSettings;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::error::ModelError;
use crate::models::hillaire::aerial_perspective::AerialPerspective;
use crate::models::hillaire::directions::view_angles;
use crate::models::hillaire::ground::GroundIrradiance;
use crate::models::hillaire::march::ViewMarch;
use crate::models::hillaire::medium::Medium;
use crate::models::hillaire::multiple_scattering::MultipleScattering;
use crate::models::hillaire::sky_view::SkyView;
use crate::models::hillaire::view_cache::ViewCache;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::column::optical_depth;
use crate::optics::geometry::ray_hits_ground;
use crate::optics::surface_lighting::{SurfaceElement, add_ground_light};
use crate::optics::transmittance_table::TransmittanceTable;
use crate::optics::view_segment::{SegmentEnd, ViewSegment};
use crate::shafts::ShadowMap;

/// The inputs of the paper's Psi_ms: extinction, scattering (part of the extinction
/// inputs) and the ground's albedo; not the Mie phase function (isotropic there) nor the
/// sun (the table is per unit irradiance).
pub const MULTIPLE_SCATTERING_INPUTS: Inputs = Inputs::EXTINCTION.union(Inputs::GROUND_ALBEDO);
/// The inputs of the ground's sky irradiance, of the per-view tables and of the
/// anisotropic Psi_ms (`ms_order` above 0), whose first scattering has the medium's phase.
pub const VIEW_INPUTS: Inputs = MULTIPLE_SCATTERING_INPUTS.union(Inputs::MIE_PHASE);

/// The inputs of Psi_ms under `settings`.
pub fn multiple_scattering_inputs(settings: &HillaireSettings) -> Inputs {
    if settings.multiple_scattering_order == 0 {
        MULTIPLE_SCATTERING_INPUTS
    } else {
        VIEW_INPUTS
    }
}

/// The Hillaire 2020 model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Hillaire {
    atmosphere: Atmosphere,
    base: ModelBase,
    settings: HillaireSettings,
    /// Orders two and up (the Psi_ms term and the sky's light on the ground); off for
    /// `ModelSettings::max_orders == Some(1)`.
    multiple_on: bool,
    /// The similarity-scaled coefficients of orders two and up (`ms_delta` above 0).
    diffuse: Option<Spectra>,
    transmittance: TransmittanceTable,
    multiple: Option<MultipleScattering>,
    ground: Option<GroundIrradiance>,
    views: ViewCache,
    /// The terrain's shadow in the air, when light shafts are on (`shafts.rs`).
    shadow: Option<ShadowMap>,
}

impl Hillaire {
    /// Builds the global tables (transmittance, Psi_ms, the ground's sky irradiance);
    /// the per-view tables are built when a view first needs them. Orders two and up
    /// are on unless `model_settings.max_orders` is `Some(1)` (the approximation has no
    /// notion of a finite number of orders above one).
    pub fn prepare(
        atmosphere: &Atmosphere,
        model_settings: &ModelSettings,
        settings: HillaireSettings,
    ) -> Result<Hillaire, ModelError> {
        let base = ModelBase::checked(ModelId::Hillaire, atmosphere, model_settings)?;
        settings.validate()?;
        settings.check_table_bytes(model_settings.wavelengths_nm.len())?;
        let (w, h) = settings.transmittance_size;
        let multiple_on = model_settings.max_orders != Some(1);
        let mut model = Hillaire {
            atmosphere: atmosphere.clone(),
            diffuse: None,
            base,
            settings,
            multiple_on,
            transmittance: TransmittanceTable::build(atmosphere, w, h),
            multiple: None,
            ground: None,
            views: ViewCache::new(settings.view_cache),
            shadow: None,
        };
        model.scale_medium();
        model.build_multiple_scattering();
        model.build_ground_irradiance();
        Ok(model)
    }

    pub fn settings(&self) -> &HillaireSettings {
        &self.settings
    }

    /// The terrain's shadow the view rays see (`None`: no light shafts).
    pub fn terrain_shadow(&self) -> Option<&ShadowMap> {
        self.shadow.as_ref()
    }

    /// The terrain's shadow the view rays see from now on (`None`: no light shafts).
    pub fn set_terrain_shadow(&mut self, shadow: Option<ShadowMap>) {
        self.shadow = shadow;
    }

    /// The medium as the ray marches see it.
    pub fn medium(&self) -> Medium<'_> {
        Medium {
            atmosphere: &self.atmosphere,
            spectra: &self.base.spectra,
            transmittance: &self.transmittance,
            mie: self.base.with_mie,
            diffuse: self.diffuse.as_ref(),
        }
    }

    /// The medium in which Psi_ms is built: the similarity-scaled one with
    /// `ms_delta` above 0, else the true one.
    pub fn multiple_scattering_medium(&self) -> Medium<'_> {
        match &self.diffuse {
            Some(diffuse) => Medium {
                spectra: diffuse,
                diffuse: None,
                ..self.medium()
            },
            None => self.medium(),
        }
    }

    /// The similarity-scaled coefficients of orders two and up, with `ms_delta` above 0
    /// and orders two and up on.
    fn scale_medium(&mut self) {
        let f = self.settings.multiple_scattering_delta;
        self.diffuse =
            (self.multiple_on && f > 0.0).then(|| similarity::scaled(&self.base.spectra, f));
    }

    /// The Psi_ms LUT (none for single scattering).
    pub fn multiple_scattering(&self) -> Option<&MultipleScattering> {
        self.multiple.as_ref()
    }

    /// The ground's sky-irradiance table (none for single scattering).
    pub fn ground_irradiance(&self) -> Option<&GroundIrradiance> {
        self.ground.as_ref()
    }

    /// Runs `f` on the sky-view LUT of a camera at radius `r` with the sun at zenith
    /// cosine `mu_s`, built if this view has none yet.
    pub fn with_sky_view<T>(&self, r: f64, mu_s: f64, f: impl FnOnce(&SkyView) -> T) -> T {
        let tables = self.views.get(r, mu_s);
        f(tables.sky_view.get_or_init(|| {
            SkyView::build(
                &self.medium(),
                self.multiple.as_ref(),
                self.settings.sky_view_grid(),
                r,
                mu_s,
                self.settings.sky_view_samples,
            )
        }))
    }

    /// Runs `f` on the aerial-perspective volume of a camera at radius `r` with the sun at
    /// zenith cosine `mu_s`, built if this view has none yet.
    pub fn with_aerial_perspective<T>(
        &self,
        r: f64,
        mu_s: f64,
        f: impl FnOnce(&AerialPerspective) -> T,
    ) -> T {
        let tables = self.views.get(r, mu_s);
        f(tables.aerial_perspective.get_or_init(|| {
            AerialPerspective::build(
                &self.medium(),
                self.multiple.as_ref(),
                self.settings.volume_shape(),
                r,
                mu_s,
            )
        }))
    }

    /// Views whose tables are held.
    pub fn cached_views(&self) -> usize {
        self.views.len()
    }

    /// Builds Psi_ms (orders two and up on).
    fn build_multiple_scattering(&mut self) {
        let s = self.settings;
        self.multiple = self.multiple_on.then(|| {
            MultipleScattering::build(
                &self.multiple_scattering_medium(),
                s.multiple_scattering_size,
                s.multiple_scattering_directions.isqrt(),
                s.multiple_scattering_samples,
                s.multiple_scattering_order,
            )
        });
    }

    /// Builds the ground's sky irradiance from Psi_ms (orders two and up on).
    fn build_ground_irradiance(&mut self) {
        self.ground = self.multiple.as_ref().map(|multiple| {
            GroundIrradiance::build(
                &self.medium(),
                Some(multiple),
                self.settings.ground_size,
                self.settings.hemisphere(),
            )
        });
    }

    /// The per-pixel march of a segment: radiance per unit solar irradiance and
    /// transmittance.
    fn march(&self, segment: &ViewSegment) -> (Vec<f64>, Vec<f64>) {
        let mu_s =
            (segment.start.dot(segment.sun_direction) / segment.start.length()).clamp(-1.0, 1.0);
        let nu = segment
            .direction
            .dot(segment.sun_direction)
            .clamp(-1.0, 1.0);
        let mut march = ViewMarch::new(
            self.medium(),
            self.multiple.as_ref(),
            segment.r,
            segment.mu,
            mu_s,
            nu,
        );
        march.run(segment.length, self.settings.march_samples);
        (march.radiance, march.throughput)
    }

    /// The view a camera at radius `r` with the sun at zenith cosine `mu_s` belongs to
    /// ([`view_cache::view_key`]).
    pub fn view_key(&self, r: f64, mu_s: f64) -> (f64, f64) {
        view_cache::view_key(&self.atmosphere, r, mu_s)
    }

    /// Radiance per unit solar irradiance and transmittance of a segment whose camera is
    /// inside the atmosphere.
    fn read_tables(&self, segment: &ViewSegment) -> (Vec<f64>, Vec<f64>) {
        let n = self.base.spectra.wavelengths_nm.len();
        let up = segment.start / segment.start.length();
        let (r, mu_s) = self.view_key(segment.r, segment.sun_direction.dot(up));
        let (_, phi) = view_angles(up, segment.direction, segment.sun_direction);
        let ground = ray_hits_ground(segment.r, segment.mu, self.atmosphere.bottom_radius_m);
        let mut radiance = vec![0.0; n];
        if segment.end == SegmentEnd::Space {
            self.with_sky_view(r, mu_s, |sky| {
                sky.lookup(segment.mu, phi, false, &mut radiance);
            });
            let column = self.transmittance.column(segment.r, segment.mu);
            let transmittance = self
                .base
                .spectra
                .extinction
                .iter()
                .map(|e| (-optical_depth(column, *e)).exp())
                .collect();
            return (radiance, transmittance);
        }
        let mut transmittance = vec![1.0; n];
        self.with_aerial_perspective(r, mu_s, |volume| {
            volume.lookup(
                segment.mu,
                phi,
                ground,
                segment.length,
                &mut radiance,
                &mut transmittance,
            );
        });
        (radiance, transmittance)
    }
}

impl SkyModel for Hillaire {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    /// The global tables plus the per-view tables of one view.
    fn table_bytes(&self) -> usize {
        let n = self.base.spectra.wavelengths_nm.len();
        std::mem::size_of_val(self.transmittance.columns.as_slice())
            + self.multiple.as_ref().map_or(0, MultipleScattering::bytes)
            + self.ground.as_ref().map_or(0, GroundIrradiance::bytes)
            + SkyView::bytes_for(self.settings.sky_view_grid(), n)
            + AerialPerspective::bytes_for(self.settings.volume_shape(), n)
    }

    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        let changed = update.changed;
        let size = self.settings.transmittance_size;
        update.rebuild_columns("transmittance", &mut self.transmittance, atmosphere, size);
        self.scale_medium();
        if self.multiple_on && changed.intersects(multiple_scattering_inputs(&self.settings)) {
            self.build_multiple_scattering();
            update.mark(&["multiple scattering"]);
        }
        if self.multiple_on && changed.intersects(VIEW_INPUTS) {
            self.build_ground_irradiance();
            update.mark(&["ground irradiance"]);
        }
        if changed.intersects(VIEW_INPUTS) {
            self.views.clear();
            update.mark(&["sky view and aerial perspective"]);
        }
        Ok(update.rebuilt())
    }

    /// The transmitted sun from the transmittance LUT (zero where the planet hides the
    /// sun) and the sky's irradiance E_sky (`ground.rs`; none for single scattering): the
    /// paper's lit planet surface (section 5). The sky-irradiance table is tabulated on
    /// the ground only, over mu_s: an element higher up reads it at its own mu_s, times
    /// the share of the ground's vertical optical depth that lies above the element (the
    /// sky over a peak is thinner; at the top there is none).
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, surface)?;
        let n = self.base.spectra.wavelengths_nm.len();
        let mut sun = vec![0.0; n];
        self.medium().sun_transmittance(e.r, e.mu_s, &mut sun);
        let mut sky = vec![0.0; n];
        if let Some(ground) = &self.ground {
            ground.lookup(e.mu_s, &mut sky);
        }
        let above = self.transmittance.column(e.r, 1.0);
        let whole = self
            .transmittance
            .column(self.atmosphere.bottom_radius_m, 1.0);
        Ok((0..n)
            .map(|w| {
                let extinction = self.base.spectra.extinction[w];
                let total = optical_depth(whole, extinction);
                let share = if total > 0.0 {
                    optical_depth(above, extinction) / total
                } else {
                    1.0
                };
                let solar = self.base.spectra.solar_irradiance[w];
                e.irradiance(solar, sun[w], solar * sky[w] * share)
            })
            .collect())
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let n = self.base.spectra.wavelengths_nm.len();
        let Some(segment) = ViewSegment::new(&self.atmosphere, ray)? else {
            return Ok(RayRadiance::unattenuated(n));
        };
        let inside = ray.origin_m.length() <= self.atmosphere.top_radius_m;
        let (mut radiance, transmittance) = if inside
            && (segment.end == SegmentEnd::Space || segment.length <= self.settings.aerial_range_m)
        {
            self.read_tables(&segment)
        } else {
            self.march(&segment)
        };
        if let Some(map) = &self.shadow {
            let mut lost = vec![0.0; n];
            shafts::shadowed_single(&self.medium(), &segment, map, &mut lost);
            radiance.iter_mut().zip(&lost).for_each(|(l, d)| *l -= d);
        }
        for (l, e) in radiance.iter_mut().zip(&self.base.spectra.solar_irradiance) {
            *l *= e;
        }
        // The ground lit as a surface element facing up at the ray's end.
        if segment.end == SegmentEnd::Ground {
            let end = segment.end_point();
            let (sun, albedo) = (segment.sun_direction, self.atmosphere.ground_albedo);
            add_ground_light(self, end, sun, albedo, &transmittance, &mut radiance)?;
        }
        Ok(RayRadiance {
            radiance: radiance.iter().map(|l| l.max(0.0)).collect(),
            transmittance: transmittance.iter().map(|t| t.clamp(0.0, 1.0)).collect(),
            radiance_std_error: vec![0.0; n],
        })
    }
}
