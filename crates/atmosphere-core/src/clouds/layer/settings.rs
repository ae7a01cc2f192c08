//! The settings of the planet's cloud layer, each with its range: where the layer lies,
//! how dense it is, how its cover is scaled, and how its light is computed.

use std::fmt;
use std::str::FromStr;

use crate::clouds::error::{CloudError, check_range};

/// How the march computes light scattered more than once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerMethod {
    /// Riley et al. 2004 section 4.2: the expected number of scatterings from the sun's
    /// optical depth (Eq. 22), the light's loss with the forward fractions F_n (Eq. 25)
    /// and its angular distribution A_(n+1) towards the eye (Eq. 26).
    Riley,
    /// The production approximation of Wrenninge et al. 2013 ("Oz: the great and
    /// volumetric"): a sum of octaves i with scattering scaled by a^i,
    /// optical depth by b^i and the phase function blended towards isotropy by c^i.
    Octaves,
    /// The sun's beam scattered once (A_1, the beam dimmed as delta-Eddington's scaled
    /// beam) plus the diffuse light of the delta-Eddington slab through the sample
    /// (Joseph, Wiscombe and Weinman 1976; `eddington.rs`): the light that diffuses
    /// through a thick layer, which the other two lose.
    Eddington,
    /// As [`LayerMethod::Eddington`], with the slab solved by delta-M four-stream
    /// discrete ordinates (Liou 1974, Wiscombe 1977; `four_stream.rs`): the forward peak
    /// truncated at the fourth Legendre moment, the diffuse field at four directions
    /// instead of two terms, so the light the source-function technique sends to the
    /// eye loses less of the slab's energy.
    FourStream,
}

impl LayerMethod {
    /// Whether the method takes the light that diffuses through from a slab around each
    /// sample (its diffuse part seen through the delta-scaled medium).
    pub fn is_slab(self) -> bool {
        matches!(self, LayerMethod::Eddington | LayerMethod::FourStream)
    }
}

impl fmt::Display for LayerMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LayerMethod::Riley => "riley",
            LayerMethod::Octaves => "octaves",
            LayerMethod::Eddington => "eddington",
            LayerMethod::FourStream => "four-stream",
        })
    }
}

impl FromStr for LayerMethod {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "riley" => Ok(LayerMethod::Riley),
            "octaves" => Ok(LayerMethod::Octaves),
            "eddington" => Ok(LayerMethod::Eddington),
            "four-stream" => Ok(LayerMethod::FourStream),
            other => Err(CloudError(format!(
                "cloud method {other:?} is not one of riley, octaves, eddington, four-stream"
            ))),
        }
    }
}

/// Where the march's sun light finds the optical depth towards the sun.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SunLight {
    /// A shadow march of `shadow_steps` steps from every view sample towards the sun.
    March,
    /// The frame's sun map (`sun_map.rs`): the optical depth at every view sample read
    /// from the map made once a frame, after Dobashi, Yamamoto and Nishita 2002
    /// section 5.4's attenuation textures rendered from the sun.
    Map,
}

impl fmt::Display for SunLight {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            SunLight::March => "march",
            SunLight::Map => "map",
        })
    }
}

impl FromStr for SunLight {
    type Err = CloudError;

    fn from_str(s: &str) -> Result<Self, CloudError> {
        match s {
            "march" => Ok(SunLight::March),
            "map" => Ok(SunLight::Map),
            other => Err(CloudError(format!(
                "cloud sun_light {other:?} is not one of march, map"
            ))),
        }
    }
}

/// The lowest cloud base accepted, m above the ground.
pub const MIN_BASE_M: f64 = 0.0;
/// The highest cloud base accepted, m: the top of the troposphere's highest cirrus.
pub const MAX_BASE_M: f64 = 20_000.0;
/// The thinnest and thickest layers accepted, m.
pub const MIN_THICKNESS_M: f64 = 10.0;
pub const MAX_THICKNESS_M: f64 = 15_000.0;
/// The densest cloud accepted, m^-1 (a cumulus core is about 0.1).
pub const MAX_EXTINCTION_PER_M: f64 = 1.0;
/// The most view and shadow steps per ray.
pub const MAX_STEPS: u32 = 512;
pub const MAX_SHADOW_STEPS: u32 = 64;
/// The most octaves of [`LayerMethod::Octaves`].
pub const MAX_OCTAVES: u32 = 8;
/// The most octaves of detail noise (the field's own, `profile::DETAIL_OCTAVES`).
pub const MAX_DETAIL_OCTAVES: u32 = super::profile::DETAIL_OCTAVES;
/// The range of the view transmittance at which the march stops.
pub const MIN_STOP_TRANSMITTANCE: f64 = 1e-6;
pub const MAX_STOP_TRANSMITTANCE: f64 = 0.1;
/// The coarsest march: one ray per 4 x 4 pixels.
pub const MAX_RESOLUTION_DIVISOR: u32 = 4;
/// The coarsest march of the cloud's shadow in the air: one ray per 8 x 8 pixels.
pub const MAX_AIR_SHADOW_DIVISOR: u32 = 8;

/// The cloud layer's settings. Every field has a range ([`LayerSettings::check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerSettings {
    /// Altitude of the layer's base above the ground, m, in [0, 20000].
    pub base_m: f64,
    /// Thickness of the layer, m, in [10, 15000].
    pub thickness_m: f64,
    /// Extinction where the density is 1, m^-1, in [0, 1].
    pub extinction_per_m: f64,
    /// Single-scattering albedo of the droplets, in [0, 1].
    pub albedo: f64,
    /// Factor on the cover before it is clamped to 1, in [0, 4].
    pub coverage_scale: f64,
    /// Size of the detail noise's cells, m, in [50, 1e5].
    pub detail_scale_m: f64,
    /// How deep the detail noise carves the cover, in [0, 1].
    pub detail_strength: f64,
    pub method: LayerMethod,
    /// View steps per ray through the layer, in [1, 512].
    pub steps: u32,
    /// Where the sun's optical depth at a view sample comes from: its own shadow march
    /// or the frame's sun map.
    pub sun_light: SunLight,
    /// Shadow steps towards the sun per view step, in [1, 64]; with the sun map, the
    /// equal parts its optical depth is cut into for Riley's walk (Eq. 25).
    pub shadow_steps: u32,
    /// Riley et al. 2004's back-scattering term xi (Eq. 26), sr^-1, in [0, 1].
    pub backscatter_xi: f64,
    /// Octaves of [`LayerMethod::Octaves`], in [1, 8].
    pub octaves: u32,
    /// Octaves of detail noise in the density the view march reads, in [1, 3].
    pub detail_octaves: u32,
    /// Octaves of detail noise in the density the sun's shadow march reads, in [0, 3]
    /// (0: the noise's mean; the light sees a smoother cloud than the eye).
    pub shadow_octaves: u32,
    /// The view transmittance below which the march stops, in [1e-6, 0.1].
    pub min_transmittance: f64,
    /// The march's resolution is the image's divided by this in each direction, the
    /// rest interpolated (`upsample.rs`), in [1, 4].
    pub resolution_divisor: u32,
    /// The same for the march of the cloud's shadow in the air below the base
    /// (`air_shadow_upsample.rs`), in [1, 8]: the beams are smoother than the cloud.
    pub air_shadow_divisor: u32,
}

impl Default for LayerSettings {
    fn default() -> Self {
        LayerSettings {
            base_m: 1500.0,
            thickness_m: 1500.0,
            extinction_per_m: 0.04,
            albedo: 1.0,
            coverage_scale: 1.0,
            detail_scale_m: 2000.0,
            detail_strength: 0.5,
            method: LayerMethod::Riley,
            steps: 48,
            sun_light: SunLight::March,
            shadow_steps: 8,
            backscatter_xi: 0.05,
            octaves: 4,
            detail_octaves: MAX_DETAIL_OCTAVES,
            shadow_octaves: MAX_DETAIL_OCTAVES,
            min_transmittance: 1e-4,
            resolution_divisor: 1,
            air_shadow_divisor: 1,
        }
    }
}

impl LayerSettings {
    /// `Ok` when every field lies in its range, else an error naming the first that does
    /// not, with its value and range.
    pub fn check(&self) -> Result<(), CloudError> {
        check_range("cloud base_m", self.base_m, MIN_BASE_M, MAX_BASE_M)?;
        check_range(
            "cloud thickness_m",
            self.thickness_m,
            MIN_THICKNESS_M,
            MAX_THICKNESS_M,
        )?;
        check_range(
            "cloud extinction_per_m",
            self.extinction_per_m,
            0.0,
            MAX_EXTINCTION_PER_M,
        )?;
        check_range("cloud albedo", self.albedo, 0.0, 1.0)?;
        check_range("cloud coverage_scale", self.coverage_scale, 0.0, 4.0)?;
        check_range("cloud detail_scale_m", self.detail_scale_m, 50.0, 1e5)?;
        check_range("cloud detail_strength", self.detail_strength, 0.0, 1.0)?;
        check_count("cloud steps", self.steps, MAX_STEPS)?;
        check_count("cloud shadow_steps", self.shadow_steps, MAX_SHADOW_STEPS)?;
        check_range("cloud backscatter_xi", self.backscatter_xi, 0.0, 1.0)?;
        check_count("cloud octaves", self.octaves, MAX_OCTAVES)?;
        check_count(
            "cloud detail_octaves",
            self.detail_octaves,
            MAX_DETAIL_OCTAVES,
        )?;
        if self.shadow_octaves > MAX_DETAIL_OCTAVES {
            return Err(CloudError(format!(
                "cloud shadow_octaves = {} must lie in [0, {MAX_DETAIL_OCTAVES}]",
                self.shadow_octaves
            )));
        }
        check_range(
            "cloud min_transmittance",
            self.min_transmittance,
            MIN_STOP_TRANSMITTANCE,
            MAX_STOP_TRANSMITTANCE,
        )?;
        check_count(
            "cloud resolution_divisor",
            self.resolution_divisor,
            MAX_RESOLUTION_DIVISOR,
        )?;
        check_count(
            "cloud air_shadow_divisor",
            self.air_shadow_divisor,
            MAX_AIR_SHADOW_DIVISOR,
        )
    }

    /// Radius of the layer's base and top on a planet of `bottom_radius_m`.
    pub fn radii_m(&self, bottom_radius_m: f64) -> (f64, f64) {
        let base = bottom_radius_m + self.base_m;
        (base, base + self.thickness_m)
    }
}

fn check_count(what: &str, value: u32, max: u32) -> Result<(), CloudError> {
    if (1..=max).contains(&value) {
        Ok(())
    } else {
        Err(CloudError(format!(
            "{what} = {value} must lie in [1, {max}]"
        )))
    }
}
