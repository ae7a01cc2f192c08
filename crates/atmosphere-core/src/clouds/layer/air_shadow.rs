//! The cloud layer's shadow in the air under it (crepuscular rays from gaps in a deck),
//! for the hillaire model: its light-shaft march (`models::hillaire::shafts`, after
//! Bruneton and Neyret 2008 section 5, Eq. 17-18, the shadowed part marched) with the
//! sun's visibility at each sample the terrain's times the cloud's transmittance from the
//! frame's sun map (`sun_map.rs`, Dobashi, Yamamoto and Nishita 2002 section 5.4's
//! attenuation ratio):
//!
//! `V(x) = V_terrain(x) T_cloud(x)` below the layer's base, `V_terrain(x)` above it,
//!
//! `dL = sum_k T(x, x_k) (1 - V(x_k)) T_sun(x_k) (sigma_s,R p_R + sigma_s,M p_M) w_k`.
//!
//! Inside the layer the air is left to the layer's compositing (`composite.rs`): the
//! air's light there is attenuated by the cloud's transmittance, and its own shadow is
//! not taken. The march runs over the part of the ray below the higher of the terrain
//! shadow's top and the layer's base (`shafts::shaft_span_m`), as far as the wider of the
//! two maps, with two samples per cell of the finer one, within the shafts' fewest and
//! most samples (`shafts::shaft_samples`).

use glam::DVec3;

use super::sun_map::CloudSunMap;
use crate::models::error::ModelError;
use crate::models::hillaire::Hillaire;
use crate::models::hillaire::medium::Medium;
use crate::models::hillaire::shafts::{shadowed_single, shadowed_single_over};
use crate::models::sky_model::{RayRadiance, SkyModel, ViewRay};
use crate::optics::view_segment::ViewSegment;
use crate::shafts::{ShadowMap, SunVisibility, shaft_samples, shaft_span_m};

/// The sun's visibility from a point of the air past the terrain (when there is a map)
/// and the cloud layer's base.
#[derive(Clone, Copy, Debug)]
pub struct AirShadow<'a> {
    pub terrain: Option<&'a ShadowMap>,
    pub clouds: &'a CloudSunMap,
}

impl SunVisibility for AirShadow<'_> {
    fn sun_visible(&self, point_m: DVec3, sun: DVec3) -> f64 {
        let terrain = self.terrain.map_or(1.0, |m| m.sun_visible(point_m, sun));
        if terrain > 0.0 && point_m.length() < self.clouds.base_radius_m {
            terrain * self.clouds.transmittance(point_m)
        } else {
            terrain
        }
    }
}

impl AirShadow<'_> {
    /// The part of `segment` (distances from its start, m) the march covers over a
    /// ground sphere of radius `bottom_radius_m`, and its samples; `None` when the ray
    /// stays above both the terrain's shadow and the layer's base.
    pub fn span(&self, segment: &ViewSegment, bottom_radius_m: f64) -> Option<((f64, f64), usize)> {
        let clouds = &self.clouds.grid;
        let (mut top, mut width, mut cell) = (
            self.clouds.base_radius_m,
            clouds.cell_m * clouds.size as f64,
            clouds.cell_m,
        );
        if let Some(map) = self.terrain {
            top = top.max(bottom_radius_m + f64::from(map.max_top_m));
            width = width.max(map.width_m());
            cell = cell.min(map.sample_cell_m());
        }
        let span = shaft_span_m(segment.r, segment.mu, segment.length, top, width)?;
        Some((span, shaft_samples(span.1 - span.0, cell)))
    }

    /// The single scattering per unit solar irradiance (sr^-1) that the terrain and the
    /// cloud take out of `segment`, per wavelength, into `out`.
    pub fn shadowed_single(&self, medium: &Medium<'_>, segment: &ViewSegment, out: &mut [f64]) {
        out.fill(0.0);
        if let Some((span, samples)) = self.span(segment, medium.atmosphere.bottom_radius_m) {
            shadowed_single_over(medium, segment, self, span, samples, out);
        }
    }
}

/// The radiance of `ray` in `model` with the cloud of `clouds` shadowing the air below
/// the layer's base as well as the model's terrain map (when it has one): the model's
/// answer with its terrain-only shaft term replaced by [`AirShadow::shadowed_single`]'s.
pub fn radiance_with_cloud_shafts(
    model: &Hillaire,
    ray: &ViewRay,
    clouds: &CloudSunMap,
) -> Result<RayRadiance, ModelError> {
    let mut answer = model.radiance(ray)?;
    let medium = model.medium();
    let Some(segment) = ViewSegment::new(medium.atmosphere, ray)? else {
        return Ok(answer);
    };
    let n = medium.wavelengths();
    let mut terrain_only = vec![0.0; n];
    if let Some(map) = model.terrain_shadow() {
        shadowed_single(&medium, &segment, map, &mut terrain_only);
    }
    let air = AirShadow {
        terrain: model.terrain_shadow(),
        clouds,
    };
    let mut both = vec![0.0; n];
    air.shadowed_single(&medium, &segment, &mut both);
    for (w, l) in answer.radiance.iter_mut().enumerate() {
        let solar = medium.spectra.solar_irradiance[w];
        *l = (*l + (terrain_only[w] - both[w]) * solar).max(0.0);
    }
    Ok(answer)
}
