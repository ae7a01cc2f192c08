//! A rain shaft, a cirrus layer and a droplet deck as a scene gives them (command-line flags, scene
//! files, the viewer), each setting with its range: placed around the camera, made into
//! volumes, given phase tables at the frame's wavelengths and lit by a sky model.

use glam::DVec3;

use super::channel_phase::ChannelPhase;
use super::error::{HydrometeorError, check_range};
use super::forward_peak::{ForwardPeak, truncated};
use super::mie_droplets::Droplets;
use super::reference::phase::ChannelSampler;
use super::render::{LitVolume, light_of};
use super::sky_light::SkyLight;
use super::spectral_phase::{Particles, SpectralPhase};
use super::sun_orders::{MultipleScattering, SunOrders};
use super::volumes::Volume;
use crate::models::sky_model::SkyModel;
use crate::table_cache::TableCache;

/// The range of the shaft's distance from the camera, m.
pub const SHAFT_DISTANCE_RANGE_M: [f64; 2] = [0.0, 100_000.0];
/// Wavelengths the phase tables are built at by default: doubling them changes the
/// rain's table by less than 1 % (docs/optics-rendering.md).
pub const DEFAULT_WAVELENGTHS: usize = 32;
/// The range of small rain drops' effective radius, um (supernumerary bows).
pub const SMALL_DROP_RADIUS_RANGE_UM: [f64; 2] = [50.0, 600.0];
/// Small drops: a narrow lognormal, and the radii of its average. The rays reflected
/// outside a drop and those of its bows interfere in a ripple of a few units of size
/// parameter, which a coarse regular rule in r samples at pseudo-random phases: each
/// wavelength's table then jitters from the next and the colour integral over the
/// wavelengths settles slowly; 64 radii average the ripple out (docs/optics-rendering.md,
/// "Wavelengths and cost").
pub const SMALL_DROP_SIGMA: f64 = 0.05;
pub const SMALL_DROP_RADII: usize = 64;
/// The range of a deck's droplet effective radius, um.
pub const DECK_DROPLET_RADIUS_RANGE_UM: [f64; 2] = [2.0, 50.0];
/// Cloud droplets: a lognormal of sigma 0.1, and the radii of its average (about four
/// per unit of size parameter at 380 nm for 10 um, so that the sharp resonances of the
/// glory's swings with size average out: with fewer, each wavelength's table jitters
/// from the next as the rule hits or misses them).
pub const DECK_SIGMA: f64 = 0.1;
pub const DECK_RADII: usize = 512;

/// A rain shaft standing `distance_m` from the camera along a horizontal direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RainShaftSettings {
    pub distance_m: f64,
    pub radius_m: f64,
    pub height_m: f64,
    pub rain_rate_mm_h: f64,
    /// Small drops of this effective radius, um, by Lorenz-Mie (supernumerary bows)
    /// instead of Marshall-Palmer drops by geometric optics; the rate still sets the
    /// shaft's extinction.
    pub small_drop_radius_um: Option<f64>,
}

/// A deck of cloud droplets (the glory, the cloudbow), a shell around the planet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeckSettings {
    pub base_m: f64,
    pub thickness_m: f64,
    pub optical_depth: f64,
    pub droplet_radius_um: f64,
}

impl Default for DeckSettings {
    fn default() -> Self {
        DeckSettings {
            base_m: 1_000.0,
            thickness_m: 500.0,
            optical_depth: 1.0,
            droplet_radius_um: 10.0,
        }
    }
}

impl DeckSettings {
    /// The deck over ground of radius `ground_radius_m`.
    pub fn volume(&self, ground_radius_m: f64) -> Result<Volume, HydrometeorError> {
        check_range(
            "deck droplet radius (um)",
            self.droplet_radius_um,
            DECK_DROPLET_RADIUS_RANGE_UM,
            "[2, 50] um",
        )?;
        Volume::droplet_deck(
            ground_radius_m,
            self.base_m,
            self.thickness_m,
            self.optical_depth,
            Droplets {
                effective_radius_m: self.droplet_radius_um * 1e-6,
                sigma: DECK_SIGMA,
                radii: DECK_RADII,
            },
        )
    }
}

impl Default for RainShaftSettings {
    fn default() -> Self {
        RainShaftSettings {
            distance_m: 3_000.0,
            radius_m: 2_000.0,
            height_m: 4_000.0,
            rain_rate_mm_h: 5.0,
            small_drop_radius_um: None,
        }
    }
}

/// A cirrus layer of hexagonal ice crystals: randomly oriented, or, with
/// `plates_tilt_deg`, plates falling with their c-axis vertical within that tilt spread
/// (sundogs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CirrusSettings {
    pub base_m: f64,
    pub thickness_m: f64,
    pub optical_depth: f64,
    pub crystal_radius_um: f64,
    pub crystal_length_um: f64,
    /// Rays traced per wavelength.
    pub rays: usize,
    /// The falling plates' tilt spread, degrees; `None`: random orientations.
    pub plates_tilt_deg: Option<f64>,
}

impl Default for CirrusSettings {
    fn default() -> Self {
        CirrusSettings {
            base_m: 8_000.0,
            thickness_m: 1_000.0,
            optical_depth: 0.3,
            crystal_radius_um: 20.0,
            crystal_length_um: 80.0,
            rays: 1_000_000,
            plates_tilt_deg: None,
        }
    }
}

impl RainShaftSettings {
    /// The shaft around the vertical through the ground `distance_m` from `camera_m`
    /// along `horizontal` (any direction: its part along the vertical is removed).
    pub fn volume(
        &self,
        camera_m: DVec3,
        horizontal: DVec3,
        ground_radius_m: f64,
    ) -> Result<Volume, HydrometeorError> {
        check_range(
            "rain shaft distance (m)",
            self.distance_m,
            SHAFT_DISTANCE_RANGE_M,
            "[0, 100000] m",
        )?;
        let up = camera_m.normalize();
        let along = (horizontal - up * horizontal.dot(up))
            .try_normalize()
            .unwrap_or_else(|| up.any_orthonormal_vector());
        let foot = (camera_m + along * self.distance_m).normalize() * ground_radius_m;
        let mut shaft = Volume::rain_shaft(
            foot,
            ground_radius_m,
            self.radius_m,
            self.height_m,
            self.rain_rate_mm_h,
        )?;
        if let Some(radius_um) = self.small_drop_radius_um {
            check_range(
                "small drop radius (um)",
                radius_um,
                SMALL_DROP_RADIUS_RANGE_UM,
                "[50, 600] um",
            )?;
            shaft.particles = Particles::Droplets(Droplets {
                effective_radius_m: radius_um * 1e-6,
                sigma: SMALL_DROP_SIGMA,
                radii: SMALL_DROP_RADII,
            });
        }
        Ok(shaft)
    }
}

impl CirrusSettings {
    /// The crystals, falling plates lit by the sun at `sun_elevation_deg`.
    pub fn particles(&self, sun_elevation_deg: f64) -> Particles {
        let (radius_m, length_m) = (self.crystal_radius_um * 1e-6, self.crystal_length_um * 1e-6);
        match self.plates_tilt_deg {
            None => Particles::Ice {
                radius_m,
                length_m,
                rays: self.rays,
            },
            Some(tilt_spread_deg) => Particles::Plates {
                radius_m,
                length_m,
                rays: self.rays,
                tilt_spread_deg,
                sun_elevation_deg,
            },
        }
    }

    /// The layer over ground of radius `ground_radius_m`, the sun at `sun_elevation_deg`
    /// above the camera's horizon (it matters to falling plates only).
    pub fn volume(
        &self,
        ground_radius_m: f64,
        sun_elevation_deg: f64,
    ) -> Result<Volume, HydrometeorError> {
        Volume::cirrus(
            ground_radius_m,
            self.base_m,
            self.thickness_m,
            self.optical_depth,
            self.particles(sun_elevation_deg),
        )
    }
}

/// What a volume's table is made with (its wavelengths across 380-720 nm, the sun's
/// angular radius it is seen with, 0 for a point sun), how the march counts its forward
/// peak, which sky's light it scatters and whether it adds the sun's light scattered
/// more than once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeOptics {
    pub wavelengths: usize,
    pub sun_radius_rad: f64,
    pub forward_peak: ForwardPeak,
    pub sky_light: SkyLight,
    pub multiple_scattering: MultipleScattering,
}

impl VolumeOptics {
    /// A table of `wavelengths` seen with a sun of `sun_radius_rad`, the forward peak and
    /// the sky's light as the march takes them by default.
    pub fn new(wavelengths: usize, sun_radius_rad: f64) -> VolumeOptics {
        VolumeOptics {
            wavelengths,
            sun_radius_rad,
            forward_peak: ForwardPeak::default(),
            sky_light: SkyLight::default(),
            multiple_scattering: MultipleScattering::default(),
        }
    }
}

/// `volume` with its phase table made as `table` says (kept in `cache`), reduced to
/// `channels_nm` and truncated for its forward peak, lit by `model` from the camera
/// `view.0` with the sun towards `view.1`, with the probes of the sun's light scattered
/// more than once where `table` asks for them (not for falling plates: their table over
/// the sky has no scattering angle to draw paths by).
pub fn lit_volume(
    model: &dyn SkyModel,
    volume: Volume,
    view: (DVec3, DVec3),
    table: VolumeOptics,
    channels_nm: [f64; 3],
    cache: &TableCache,
) -> Result<LitVolume, HydrometeorError> {
    let spectral = SpectralPhase::build_cached(
        &volume.particles,
        table.wavelengths,
        table.sun_radius_rad,
        cache,
    )?;
    let channels = ChannelPhase::new(&spectral, channels_nm)?;
    let light = light_of(model, &volume, view, table.sky_light)
        .map_err(|e| HydrometeorError::Model(e.to_string()))?;
    let orders = match table.multiple_scattering {
        MultipleScattering::Probes if channels.sky.is_none() => Some(SunOrders::estimate(
            &volume,
            &ChannelSampler::new(&channels)?,
            light.sun_direction,
            volume.light_point(view.0),
        )),
        _ => None,
    };
    let (phase, peak_fraction) = truncated(channels, table.forward_peak);
    Ok(LitVolume {
        volume,
        phase,
        peak_fraction,
        light,
        orders,
    })
}
