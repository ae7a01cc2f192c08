//! Dobashi, Yamamoto, Nishita 2002, "Interactive rendering of atmospheric scattering
//! effects using graphics hardware", sections 5.2-5.3 and appendix A: the sky by
//! sampling planes whose segments are read from pre-integrated tables dI_r, dI_m, dg_v over
//! (h, theta_v), the sun's attenuation from g_l(h, theta_sun), the plane interval by the
//! rule of section 4.2.1, sample spheres for cameras far out in space, and multiple
//! scattering as a constant ambient term (not in the paper).
//!
//! - `settings`: what trades accuracy for time, with the paper's values.
//! - `segment`: the integrals of one segment (Eq. 12, A.5-A.6).
//! - `plane_tables`: dI_r, dI_m, dg_v(h, theta_v) and the interval rule.
//! - `sphere_tables`: the sample spheres and their 1D tables.
//! - `trace`: Eq. 12 along a ray, through planes or spheres.
//! - `ambient`: the ambient term and how its value is chosen.
//!
//! See docs/models/dobashi.md for the equations, the settings and the measured errors.

pub mod ambient;
pub mod ambient_build;
pub mod grid;
pub mod plane_tables;
pub mod segment;
pub mod settings;
pub mod sphere_tables;
pub mod trace;

use crate::atmosphere::Atmosphere;
use crate::models::error::ModelError;
use crate::models::id::ModelId;
use crate::models::model_base::ModelBase;
use crate::models::settings::ModelSettings;
use crate::models::sky_model::{RayRadiance, SkyModel, SurfacePoint, ViewRay};
use crate::optics::surface_lighting::SurfaceElement;
use crate::optics::transmittance_table::TransmittanceTable;
use crate::shafts::ShadowMap;

pub use ambient::AmbientTable;
pub use plane_tables::PlaneTables;
pub use settings::DobashiSettings;
pub use sphere_tables::SphereTables;
pub use trace::{Ambient, Terms, Tracer};

/// The dobashi model, prepared for one atmosphere.
#[derive(Debug)]
pub struct Dobashi {
    atmosphere: Atmosphere,
    base: ModelBase,
    settings: DobashiSettings,
    max_orders: Option<u32>,
    sun_table: TransmittanceTable,
    planes: PlaneTables,
    spheres: SphereTables,
    /// `None` for single scattering (`max_orders = Some(1)`).
    ambient: Option<AmbientTable>,
    /// The terrain's shadow in the air, when light shafts are on (docs/shafts.md).
    shadow: Option<ShadowMap>,
}

impl Dobashi {
    /// Prepares every table. Orders two and up (`max_orders` other than `Some(1)`) are the
    /// ambient term.
    pub fn prepare(
        atmosphere: &Atmosphere,
        model_settings: &ModelSettings,
        settings: DobashiSettings,
    ) -> Result<Dobashi, ModelError> {
        let base = ModelBase::checked(ModelId::Dobashi, atmosphere, model_settings)?;
        settings.validate()?;
        settings.check_table_bytes(model_settings.wavelengths_nm.len())?;
        let (spectra, with_mie) = (&base.spectra, base.with_mie);
        let mut model = Dobashi {
            atmosphere: atmosphere.clone(),
            settings,
            max_orders: model_settings.max_orders,
            sun_table: TransmittanceTable::build(
                atmosphere,
                settings.sun_table_angles,
                settings.sun_table_heights,
            ),
            planes: PlaneTables::build(atmosphere, spectra, &settings, with_mie),
            spheres: SphereTables::build(
                atmosphere,
                spectra,
                settings.spheres,
                settings.sphere_table_angles,
                with_mie,
            ),
            base,
            ambient: None,
            shadow: None,
        };
        model.ambient = model.build_ambient()?;
        Ok(model)
    }

    fn build_ambient(&self) -> Result<Option<AmbientTable>, ModelError> {
        if self.max_orders == Some(1) {
            return Ok(None);
        }
        // Orders two and up stay unshadowed (docs/shafts.md).
        let unshadowed = Tracer {
            shadow: None,
            ..self.tracer()
        };
        AmbientTable::build(
            &unshadowed,
            self.settings.ambient_directions,
            self.settings.ambient_sun_angles,
            self.max_orders,
        )
        .map(Some)
    }

    /// The tables as a [`Tracer`].
    pub fn tracer(&self) -> Tracer<'_> {
        Tracer {
            atmosphere: &self.atmosphere,
            spectra: &self.base.spectra,
            sun_table: &self.sun_table,
            planes: &self.planes,
            spheres: &self.spheres,
            max_planes: self.settings.max_planes,
            shadow: self.shadow.as_ref(),
        }
    }

    /// The terrain's shadow the sampling planes test from now on (`None`: no light
    /// shafts): each segment's single scattering times the sun's visibility at its plane
    /// (Dobashi, Yamamoto and Nishita 2002, Fig. 10(a)); the ambient term stays
    /// unshadowed.
    pub fn set_terrain_shadow(&mut self, shadow: Option<ShadowMap>) {
        self.shadow = shadow;
    }

    pub fn settings(&self) -> &DobashiSettings {
        &self.settings
    }

    pub fn planes(&self) -> &PlaneTables {
        &self.planes
    }

    pub fn spheres(&self) -> &SphereTables {
        &self.spheres
    }

    pub fn ambient(&self) -> Option<&AmbientTable> {
        self.ambient.as_ref()
    }

    /// The ambient radiance the model's traces use: its table, or none.
    fn ambient_radiance(&self) -> Ambient<'_> {
        match &self.ambient {
            Some(table) => Ambient::Table(table),
            None => Ambient::Off,
        }
    }
}

impl SkyModel for Dobashi {
    fn base(&self) -> &ModelBase {
        &self.base
    }

    fn table_bytes(&self) -> usize {
        std::mem::size_of_val(self.sun_table.columns.as_slice())
            + self.planes.bytes()
            + self.spheres.bytes()
            + self.ambient.as_ref().map_or(0, AmbientTable::bytes)
    }

    fn update(&mut self, atmosphere: &Atmosphere) -> Result<Vec<&'static str>, ModelError> {
        let mut update = self.base.adopt(&mut self.atmosphere, atmosphere)?;
        let changed = update.changed;
        let (spectra, with_mie) = (&self.base.spectra, self.base.with_mie);
        let mie_switched = with_mie != self.planes.scatter_m.is_some();
        let size = (
            self.settings.sun_table_angles,
            self.settings.sun_table_heights,
        );
        update.rebuild_columns("g_l", &mut self.sun_table, atmosphere, size);
        let segments = changed.intersects(PlaneTables::INPUTS) || mie_switched;
        if segments {
            self.planes = PlaneTables::build(atmosphere, spectra, &self.settings, with_mie);
            self.spheres = SphereTables::build(
                atmosphere,
                spectra,
                self.settings.spheres,
                self.settings.sphere_table_angles,
                with_mie,
            );
            update.mark(&["dI_r", "dg_v", "sphere dI_r", "sphere dg_v"]);
            if with_mie {
                update.mark(&["dI_m", "sphere dI_m"]);
            }
        }
        if self.max_orders != Some(1) && (segments || changed.intersects(AmbientTable::INPUTS)) {
            self.ambient = self.build_ambient()?;
            update.mark(&["ambient"]);
        }
        Ok(update.rebuilt())
    }

    /// The transmitted sun g_l (Eq. 11) and the ambient term's sky, pi psi on a
    /// horizontal element, psi read at the element's sun angle (`Tracer::element_light`);
    /// no sky for single scattering.
    fn surface_irradiance(&self, surface: &SurfacePoint) -> Result<Vec<f64>, ModelError> {
        let e = SurfaceElement::new(&self.atmosphere, surface)?;
        let n_w = self.base.spectra.wavelengths_nm.len();
        let (mut sun, mut sky) = (vec![0.0; n_w], vec![0.0; n_w]);
        self.tracer()
            .element_light(&e, self.ambient_radiance(), &mut sun, &mut sky);
        Ok((0..n_w)
            .map(|w| {
                let solar = self.base.spectra.solar_irradiance[w];
                e.irradiance(solar, sun[w], solar * sky[w])
            })
            .collect())
    }

    fn radiance(&self, ray: &ViewRay) -> Result<RayRadiance, ModelError> {
        let ambient = self.ambient_radiance();
        let terms = self.tracer().trace(ray, ambient)?;
        let radiance = (0..terms.single.len())
            .map(|w| self.base.spectra.solar_irradiance[w] * (terms.single[w] + terms.ambient[w]))
            .collect();
        Ok(RayRadiance {
            radiance,
            radiance_std_error: vec![0.0; terms.single.len()],
            transmittance: terms.transmittance,
        })
    }
}
