//! The cloud layer's shadow in the air under it (crepuscular rays from gaps in a deck),
//! for every sky model: the light-shaft march (Bruneton and Neyret 2008 section 5,
//! Eq. 17-18, the shadowed part marched; `models::hillaire::shafts`) of the single
//! scattering that the cloud takes from the sun beyond the terrain's shadow, with the
//! cloud's transmittance from the frame's sun map (`sun_map.rs`, Dobashi, Yamamoto and
//! Nishita 2002 section 5.4's attenuation ratio), or for the path-traced reference from
//! the field itself (`direct_shade.rs`; [`CloudShade`]). The sun's visibility at a point x is
//!
//! `V(x) = V_terrain(x) T_cloud(x)` below the layer's base, `V_terrain(x)` above it,
//!
//! so what the cloud adds to the terrain's shadow `1 - V_terrain` is
//! `V_terrain(x) (1 - T_cloud(x))` below the base, and
//!
//! `dL = sum_k T(x, x_k) V_terrain(x_k) (1 - T_cloud(x_k)) T_sun(x_k) (sigma_s,R p_R + sigma_s,M p_M) w_k`
//!
//! is taken out of the model's answer, beside the model's own terrain shafts: a point in
//! both shadows is counted once. The march runs over the part of the ray below the
//! layer's base, as far as the map reaches, with two samples per cell, within the shafts'
//! fewest and most samples (`shafts::shaft_samples`), through the atmosphere's own
//! columns table ([`CloudAirShadow`]), the same for every model.
//!
//! Inside the layer the air is left to the layer's compositing (`composite.rs`): the
//! air's light there is attenuated by the cloud's transmittance, and its own shadow is
//! not taken.

use glam::DVec3;

use super::sun_map::CloudSunMap;
use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::models::error::ModelError;
use crate::models::hillaire::medium::Medium;
use crate::models::hillaire::shafts::shadowed_single_over;
use crate::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use crate::optics::transmittance_table::{BRUNETON_TABLE_SIZE, TransmittanceTable};
use crate::optics::view_segment::ViewSegment;
use crate::shafts::{ShadowMap, SunVisibility, shaft_samples, shaft_span_m};

/// What the cloud's shadow in the air is taken from: the sun's transmittance through the
/// layer from a point below its base, how far along a view ray the shadow is marched
/// and in how many samples. Frames take the frame's sun map ([`CloudSunMap`]); the
/// path-traced reference marches the field itself (`direct_shade.rs`).
pub trait CloudShade: std::fmt::Debug + Sync {
    /// The radius of the layer's base, m.
    fn base_radius_m(&self) -> f64;
    /// The sun's transmittance through the cloud from `point_m` (planet-centred, below
    /// the base) along the unit `sun`.
    fn sun_transmittance(&self, point_m: DVec3, sun: DVec3) -> f64;
    /// How far the shadow reaches along a ray below the base, m (the map's width).
    fn reach_m(&self) -> f64;
    /// The samples of a span `span_m` long.
    fn samples(&self, span_m: f64) -> usize;
}

/// The frame's map: the shadow as far as the map reaches, two samples per cell within
/// the shafts' fewest and most (`shafts::shaft_samples`).
impl CloudShade for CloudSunMap {
    fn base_radius_m(&self) -> f64 {
        self.base_radius_m
    }

    fn sun_transmittance(&self, point_m: DVec3, _sun: DVec3) -> f64 {
        self.transmittance(point_m)
    }

    fn reach_m(&self) -> f64 {
        self.grid.cell_m * self.grid.size as f64
    }

    fn samples(&self, span_m: f64) -> usize {
        shaft_samples(span_m, self.grid.cell_m)
    }
}

/// The sun's visibility from a point of the air past the terrain (when there is a map)
/// and the cloud layer's base.
#[derive(Clone, Copy, Debug)]
pub struct AirShadow<'a> {
    pub terrain: Option<&'a ShadowMap>,
    pub clouds: &'a dyn CloudShade,
}

impl SunVisibility for AirShadow<'_> {
    fn sun_visible(&self, point_m: DVec3, sun: DVec3) -> f64 {
        let terrain = self.terrain.map_or(1.0, |m| m.sun_visible(point_m, sun));
        if terrain > 0.0 && point_m.length() < self.clouds.base_radius_m() {
            terrain * self.clouds.sun_transmittance(point_m, sun)
        } else {
            terrain
        }
    }
}

/// One less the share of the sun that the cloud hides beyond the terrain's shadow,
/// `1 - V_terrain (1 - T_cloud)` below the base: the march's `1 - V` is then the
/// cloud's part of the shadow alone.
struct CloudPart<'a>(AirShadow<'a>);

impl SunVisibility for CloudPart<'_> {
    fn sun_visible(&self, point_m: DVec3, sun: DVec3) -> f64 {
        let AirShadow { terrain, clouds } = self.0;
        if point_m.length() >= clouds.base_radius_m() {
            return 1.0;
        }
        let terrain = terrain.map_or(1.0, |m| m.sun_visible(point_m, sun));
        1.0 - terrain * (1.0 - clouds.sun_transmittance(point_m, sun))
    }
}

impl AirShadow<'_> {
    /// The part of `segment` (distances from its start, m) below the layer's base as far
    /// as the shade reaches, and its samples; `None` when the ray stays above the base.
    pub fn span(&self, segment: &ViewSegment) -> Option<((f64, f64), usize)> {
        let (top, reach) = (self.clouds.base_radius_m(), self.clouds.reach_m());
        let span = shaft_span_m(segment.r, segment.mu, segment.length, top, reach)?;
        Some((span, self.clouds.samples(span.1 - span.0)))
    }

    /// The far end of [`AirShadow::span`] where the span holds any air
    /// (`air_shadow_upsample::SpanEnd`).
    pub fn span_end(&self, segment: &ViewSegment) -> Option<f64> {
        self.span(segment)
            .filter(|((start, end), _)| end > start)
            .map(|((_, end), _)| end)
    }

    /// The single scattering per unit solar irradiance (sr^-1) that the cloud takes out
    /// of `segment` beyond the terrain's shadow, per wavelength, into `out`.
    pub fn cloud_single(&self, medium: &Medium<'_>, segment: &ViewSegment, out: &mut [f64]) {
        out.fill(0.0);
        if let Some((span, samples)) = self.span(segment) {
            shadowed_single_over(medium, segment, &CloudPart(*self), span, samples, out);
        }
    }
}

/// The medium the cloud's shadow in the air is marched through, whichever model draws
/// the sky: the atmosphere's coefficients at the model's wavelengths and a columns table
/// of its own, of the GPU pass's size.
#[derive(Clone, Debug)]
pub struct CloudAirShadow {
    atmosphere: Atmosphere,
    spectra: Spectra,
    table: TransmittanceTable,
}

impl CloudAirShadow {
    /// The columns table's size (sun angles, radii), as the GPU pass's
    /// (render-wgpu's `clouds/air_shadow_pass.rs`).
    pub const TABLE_SIZE: (usize, usize) = BRUNETON_TABLE_SIZE;

    /// The medium of `atmosphere` at `model`'s wavelengths.
    pub fn new(atmosphere: &Atmosphere, model: &dyn SkyModel) -> CloudAirShadow {
        let (width, height) = CloudAirShadow::TABLE_SIZE;
        CloudAirShadow {
            atmosphere: atmosphere.clone(),
            spectra: model.spectra().clone(),
            table: TransmittanceTable::build(atmosphere, width, height),
        }
    }

    /// The medium as the march sees it.
    pub fn medium(&self) -> Medium<'_> {
        Medium {
            atmosphere: &self.atmosphere,
            spectra: &self.spectra,
            transmittance: &self.table,
            mie: true,
            diffuse: None,
        }
    }

    /// The radiance of `ray` in `model` with the cloud of `air` shadowing the air below
    /// the layer's base: the model's answer (with its own terrain shafts, when it has
    /// them, from the map `air.terrain` should be) less the cloud's part of the shadow,
    /// [`AirShadow::cloud_single`] times the solar irradiance, at least 0.
    pub fn radiance(
        &self,
        model: &dyn SkyModel,
        ray: &ViewRay,
        air: &AirShadow<'_>,
    ) -> Result<RayRadiance, ModelError> {
        let mut answer = model.radiance(ray)?;
        let Some(segment) = ViewSegment::new(&self.atmosphere, ray)? else {
            return Ok(answer);
        };
        let mut lost = vec![0.0; self.spectra.wavelengths_nm.len()];
        air.cloud_single(&self.medium(), &segment, &mut lost);
        let solar = &self.spectra.solar_irradiance;
        for (w, l) in answer.radiance.iter_mut().enumerate() {
            *l = (*l - lost[w] * solar[w]).max(0.0);
        }
        Ok(answer)
    }
}
