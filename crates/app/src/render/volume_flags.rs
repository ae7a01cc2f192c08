//! Rain and ice volumes of a scene (`atmos render --rain`, `--cirrus` and their flags,
//! or a scene file's `[volumes]` table): a rain shaft ahead of the camera and a cirrus
//! layer, a deck of cloud droplets below or around the camera, each setting checked against its range with errors naming the flag; and the
//! lit volumes the renderer composites (docs/optics-rendering.md).

use crate::table_cache_dir::table_cache;
use anyhow::{Context, bail};
use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::reduced::check_divisor;
use atmosphere_core::hydrometeors::render::LitVolume;
use atmosphere_core::hydrometeors::scene::{
    CirrusSettings, DEFAULT_WAVELENGTHS, DeckSettings, RainShaftSettings, VolumeOptics, lit_volume,
};
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::spectral_phase::WAVELENGTH_COUNT_RANGE;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::hydrometeors::volumes::Volume;
use atmosphere_core::models::registry::prepare;
use clap::Args;
use render_wgpu::Frame;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;
use serde::{Deserialize, Serialize};

/// The falling plates' tilt spread when `--cirrus-tilt-deg` is not given, degrees.
pub const DEFAULT_PLATES_TILT_DEG: f64 = 1.0;

/// The volume flags; every one optional, the settings' defaults filling the rest.
#[derive(Clone, Debug, Default, PartialEq, Args, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VolumeFlags {
    /// A rain shaft ahead of the camera, Marshall-Palmer drops (the rainbows) [default:
    /// false].
    #[arg(long = "rain", value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub rain: Option<bool>,
    /// Rain rate, mm/h, in [0.1, 300] [default: 5].
    #[arg(long = "rain-rate-mm-h", value_name = "MM_H")]
    pub rain_rate_mm_h: Option<f64>,
    /// Distance from the camera to the shaft's axis, along the view's horizontal
    /// direction, m, in [0, 100000] [default: 3000].
    #[arg(long = "rain-distance-m", value_name = "M")]
    pub rain_distance_m: Option<f64>,
    /// The shaft's radius, m, in [10, 50000] [default: 2000].
    #[arg(long = "rain-radius-m", value_name = "M")]
    pub rain_radius_m: Option<f64>,
    /// The shaft's height above the ground, m, in [100, 20000] [default: 4000].
    #[arg(long = "rain-height-m", value_name = "M")]
    pub rain_height_m: Option<f64>,
    /// Small drops of this effective radius, um, in [50, 600], by Lorenz-Mie (the
    /// supernumerary bows) instead of Marshall-Palmer drops by geometric optics; the
    /// rate still sets the shaft's extinction [default: off].
    #[arg(long = "rain-small-drop-radius-um", value_name = "UM")]
    pub rain_small_drop_radius_um: Option<f64>,
    /// A deck of cloud droplets by Lorenz-Mie, in single scattering (the glory, the
    /// cloudbow) [default: false].
    #[arg(long = "deck", value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub deck: Option<bool>,
    /// The deck's base above the ground, m, in [0, 20000] [default: 1000].
    #[arg(long = "deck-base-m", value_name = "M")]
    pub deck_base_m: Option<f64>,
    /// The deck's thickness, m, in [10, 10000] [default: 500].
    #[arg(long = "deck-thickness-m", value_name = "M")]
    pub deck_thickness_m: Option<f64>,
    /// The deck's vertical optical depth, in [0, 10] [default: 1].
    #[arg(long = "deck-optical-depth", value_name = "TAU")]
    pub deck_optical_depth: Option<f64>,
    /// The deck droplets' effective radius, um, in [2, 50] (lognormal, sigma 0.1)
    /// [default: 10].
    #[arg(long = "deck-droplet-radius-um", value_name = "UM")]
    pub deck_droplet_radius_um: Option<f64>,
    /// A cirrus layer of hexagonal ice columns, randomly oriented (the 22 and 46 degree
    /// halos) [default: false].
    #[arg(long = "cirrus", value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub cirrus: Option<bool>,
    /// The layer's base above the ground, m, in [1000, 20000] [default: 8000].
    #[arg(long = "cirrus-base-m", value_name = "M")]
    pub cirrus_base_m: Option<f64>,
    /// The layer's thickness, m, in [10, 10000] [default: 1000].
    #[arg(long = "cirrus-thickness-m", value_name = "M")]
    pub cirrus_thickness_m: Option<f64>,
    /// The layer's vertical optical depth, in [0, 10] [default: 0.3].
    #[arg(long = "cirrus-optical-depth", value_name = "TAU")]
    pub cirrus_optical_depth: Option<f64>,
    /// The columns' radius (axis to edge) and length, um, each in [1, 10000], the
    /// aspect ratio length / (2 radius) in [0.01, 100] [default: 20 and 80].
    #[arg(long = "cirrus-crystal-radius-um", value_name = "UM")]
    pub cirrus_crystal_radius_um: Option<f64>,
    #[arg(long = "cirrus-crystal-length-um", value_name = "UM")]
    pub cirrus_crystal_length_um: Option<f64>,
    /// Rays traced through the crystals per wavelength, in [1e4, 1e8] (fewer show the
    /// rays' noise as rings around the sun) [default: 1000000].
    #[arg(long = "cirrus-rays", value_name = "N")]
    pub cirrus_rays: Option<usize>,
    /// The crystals are plates falling with their c-axis vertical (sundogs, the
    /// parhelic circle) instead of randomly oriented; the sun must be above the horizon
    /// [default: false].
    #[arg(long = "cirrus-plates", value_name = "BOOL", num_args = 0..=1, default_missing_value = "true")]
    pub cirrus_plates: Option<bool>,
    /// The falling plates' tilt spread (standard deviation of each tilt component),
    /// degrees, in [0, 30] [default: 1].
    #[arg(long = "cirrus-tilt-deg", value_name = "DEG")]
    pub cirrus_tilt_deg: Option<f64>,
    /// Wavelengths the volumes' phase functions are computed at, across 380-720 nm, in
    /// [3, 128] [default: 32].
    #[arg(long = "optics-wavelengths", value_name = "N")]
    pub wavelengths: Option<usize>,
    /// How the volumes' march counts the light its particles scatter within 1 degree
    /// of the forward direction (diffraction): `unscattered`, as light that arrives
    /// unscattered (delta-M: the extinction without it, the phase table truncated), or
    /// `extinction`, as light lost (the whole extinction) [default: unscattered].
    #[arg(long = "optics-forward-peak", value_name = "PEAK", value_enum)]
    pub forward_peak: Option<ForwardPeak>,
    /// The sky's light the volumes scatter: `sphere`, the model's radiance averaged over
    /// every direction around the volume (the sky, the lit ground below), the all-orders
    /// answer in a uniform field; or `horizontal`, the sky's horizontal irradiance over a
    /// black ground, once [default: sphere].
    #[arg(long = "optics-sky-light", value_name = "SKY", value_enum)]
    pub sky_light: Option<SkyLight>,
    /// The sun's light scattered more than once inside the volumes: `probes`, from a
    /// grid of probes of the diffuse light (a Monte Carlo estimate per volume, about a
    /// tenth to a third of a second on the CPU), or `none`, single scattering of the
    /// sun only [default: probes].
    #[arg(long = "optics-multiple-scattering", value_name = "ORDERS", value_enum)]
    pub multiple_scattering: Option<MultipleScattering>,
    /// The volumes marched for one pixel in N x N and upsampled where the rays' paths
    /// through them agree (the rest marched per pixel), 1 to 4 [default: 1].
    #[arg(long = "optics-resolution-divisor", value_name = "N")]
    pub resolution_divisor: Option<u32>,
}

impl VolumeFlags {
    /// Whether no field is set (the scene file then has no `[volumes]` table).
    pub fn is_empty(&self) -> bool {
        *self == VolumeFlags::default()
    }

    /// These flags with every field that `flags` sets replaced.
    pub fn overridden_by(self, flags: VolumeFlags) -> VolumeFlags {
        VolumeFlags {
            rain: flags.rain.or(self.rain),
            rain_rate_mm_h: flags.rain_rate_mm_h.or(self.rain_rate_mm_h),
            rain_distance_m: flags.rain_distance_m.or(self.rain_distance_m),
            rain_radius_m: flags.rain_radius_m.or(self.rain_radius_m),
            rain_height_m: flags.rain_height_m.or(self.rain_height_m),
            rain_small_drop_radius_um: flags
                .rain_small_drop_radius_um
                .or(self.rain_small_drop_radius_um),
            deck: flags.deck.or(self.deck),
            deck_base_m: flags.deck_base_m.or(self.deck_base_m),
            deck_thickness_m: flags.deck_thickness_m.or(self.deck_thickness_m),
            deck_optical_depth: flags.deck_optical_depth.or(self.deck_optical_depth),
            deck_droplet_radius_um: flags.deck_droplet_radius_um.or(self.deck_droplet_radius_um),
            cirrus: flags.cirrus.or(self.cirrus),
            cirrus_base_m: flags.cirrus_base_m.or(self.cirrus_base_m),
            cirrus_thickness_m: flags.cirrus_thickness_m.or(self.cirrus_thickness_m),
            cirrus_optical_depth: flags.cirrus_optical_depth.or(self.cirrus_optical_depth),
            cirrus_crystal_radius_um: flags
                .cirrus_crystal_radius_um
                .or(self.cirrus_crystal_radius_um),
            cirrus_crystal_length_um: flags
                .cirrus_crystal_length_um
                .or(self.cirrus_crystal_length_um),
            cirrus_rays: flags.cirrus_rays.or(self.cirrus_rays),
            cirrus_plates: flags.cirrus_plates.or(self.cirrus_plates),
            cirrus_tilt_deg: flags.cirrus_tilt_deg.or(self.cirrus_tilt_deg),
            wavelengths: flags.wavelengths.or(self.wavelengths),
            forward_peak: flags.forward_peak.or(self.forward_peak),
            sky_light: flags.sky_light.or(self.sky_light),
            multiple_scattering: flags.multiple_scattering.or(self.multiple_scattering),
            resolution_divisor: flags.resolution_divisor.or(self.resolution_divisor),
        }
    }

    /// The rain shaft's settings when on.
    pub fn rain_settings(&self) -> Option<RainShaftSettings> {
        let d = RainShaftSettings::default();
        (self.rain == Some(true)).then(|| RainShaftSettings {
            distance_m: self.rain_distance_m.unwrap_or(d.distance_m),
            radius_m: self.rain_radius_m.unwrap_or(d.radius_m),
            height_m: self.rain_height_m.unwrap_or(d.height_m),
            rain_rate_mm_h: self.rain_rate_mm_h.unwrap_or(d.rain_rate_mm_h),
            small_drop_radius_um: self.rain_small_drop_radius_um,
        })
    }

    /// The droplet deck's settings when on.
    pub fn deck_settings(&self) -> Option<DeckSettings> {
        let d = DeckSettings::default();
        (self.deck == Some(true)).then(|| DeckSettings {
            base_m: self.deck_base_m.unwrap_or(d.base_m),
            thickness_m: self.deck_thickness_m.unwrap_or(d.thickness_m),
            optical_depth: self.deck_optical_depth.unwrap_or(d.optical_depth),
            droplet_radius_um: self.deck_droplet_radius_um.unwrap_or(d.droplet_radius_um),
        })
    }

    /// The cirrus layer's settings when on.
    pub fn cirrus_settings(&self) -> Option<CirrusSettings> {
        let d = CirrusSettings::default();
        (self.cirrus == Some(true)).then(|| CirrusSettings {
            base_m: self.cirrus_base_m.unwrap_or(d.base_m),
            thickness_m: self.cirrus_thickness_m.unwrap_or(d.thickness_m),
            optical_depth: self.cirrus_optical_depth.unwrap_or(d.optical_depth),
            crystal_radius_um: self.cirrus_crystal_radius_um.unwrap_or(d.crystal_radius_um),
            crystal_length_um: self.cirrus_crystal_length_um.unwrap_or(d.crystal_length_um),
            rays: self.cirrus_rays.unwrap_or(d.rays),
            plates_tilt_deg: (self.cirrus_plates == Some(true))
                .then(|| self.cirrus_tilt_deg.unwrap_or(DEFAULT_PLATES_TILT_DEG)),
        })
    }

    /// The volumes of `frame`, each with its flag, placed and checked but not lit:
    /// quick, so that a bad setting is named before any table is built; errors name the
    /// flag.
    pub fn volumes(&self, frame: &Frame) -> anyhow::Result<Vec<(&'static str, Volume)>> {
        let wavelengths = self.wavelengths.unwrap_or(DEFAULT_WAVELENGTHS);
        let [lo, hi] = WAVELENGTH_COUNT_RANGE;
        if !(lo..=hi).contains(&(wavelengths as f64)) {
            bail!("--optics-wavelengths {wavelengths} must lie in [{lo}, {hi}]");
        }
        if self.cirrus_tilt_deg.is_some() && self.cirrus_plates != Some(true) {
            bail!("--cirrus-tilt-deg is the falling plates' tilt: it needs --cirrus-plates");
        }
        if self.rain_small_drop_radius_um.is_some() && self.rain != Some(true) {
            bail!("--rain-small-drop-radius-um is the rain shaft's drops: it needs --rain");
        }
        let ground = frame.atmosphere.bottom_radius_m;
        let camera = frame.camera_position_m;
        let mut volumes = Vec::new();
        if let Some(rain) = self.rain_settings() {
            let forward = frame.axes()[2];
            let volume = rain.volume(camera, forward, ground);
            volumes.push(("--rain", volume.context("--rain")?));
        }
        if let Some(cirrus) = self.cirrus_settings() {
            let up = camera.normalize();
            let sun_elevation_deg = frame
                .sun_direction
                .dot(up)
                .clamp(-1.0, 1.0)
                .asin()
                .to_degrees();
            let volume = cirrus.volume(ground, sun_elevation_deg);
            volumes.push(("--cirrus", volume.context("--cirrus")?));
        }
        if let Some(deck) = self.deck_settings() {
            volumes.push(("--deck", deck.volume(ground).context("--deck")?));
        }
        Ok(volumes)
    }

    /// The divisor the volumes are marched at (1 by default), checked; the error names
    /// the flag.
    pub fn divisor(&self) -> anyhow::Result<u32> {
        check_divisor(self.resolution_divisor.unwrap_or(1)).context("--optics-resolution-divisor")
    }

    /// The volumes of `frame` ([`VolumeFlags::volumes`]), lit by its model on the CPU
    /// with their phase tables (from the table cache, or built: seconds to minutes);
    /// errors name the flag.
    pub fn lit_volumes(&self, frame: &Frame) -> anyhow::Result<Vec<LitVolume>> {
        let volumes = self.volumes(frame)?;
        if volumes.is_empty() {
            return Ok(Vec::new());
        }
        let model = prepare(frame.model, &frame.atmosphere, &frame.settings)?;
        let view = (frame.camera_position_m, frame.sun_direction);
        let optics = VolumeOptics {
            wavelengths: self.wavelengths.unwrap_or(DEFAULT_WAVELENGTHS),
            sun_radius_rad: frame.atmosphere.sun.angular_radius_rad,
            forward_peak: self.forward_peak.unwrap_or_default(),
            sky_light: self.sky_light.unwrap_or_default(),
            multiple_scattering: self.multiple_scattering.unwrap_or_default(),
        };
        let cache = table_cache();
        volumes
            .into_iter()
            .map(|(flag, volume)| {
                lit_volume(
                    model.as_ref(),
                    volume,
                    view,
                    optics,
                    RGB_WAVELENGTHS_NM,
                    &cache,
                )
                .context(flag)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_forward_peak_sky_light_and_orders_read_from_a_scene_file_and_bad_ones_are_named() {
        let text = "rain = true\nforward_peak = \"extinction\"\nsky_light = \"horizontal\"\n\
                    multiple_scattering = \"none\"";
        let flags: VolumeFlags = toml::from_str(text).unwrap();
        assert_eq!(flags.forward_peak, Some(ForwardPeak::Extinction));
        assert_eq!(flags.sky_light, Some(SkyLight::Horizontal));
        assert_eq!(flags.multiple_scattering, Some(MultipleScattering::None));
        let flags = flags.overridden_by(VolumeFlags {
            forward_peak: Some(ForwardPeak::Unscattered),
            ..VolumeFlags::default()
        });
        assert_eq!(flags.forward_peak, Some(ForwardPeak::Unscattered));
        let e = toml::from_str::<VolumeFlags>("forward_peak = \"lost\"")
            .unwrap_err()
            .to_string();
        assert!(e.contains("lost") && e.contains("unscattered"), "{e}");
        let e = toml::from_str::<VolumeFlags>("sky_light = \"dome\"")
            .unwrap_err()
            .to_string();
        assert!(e.contains("dome") && e.contains("sphere"), "{e}");
        let e = toml::from_str::<VolumeFlags>("multiple_scattering = \"many\"")
            .unwrap_err()
            .to_string();
        assert!(e.contains("many") && e.contains("probes"), "{e}");
        let flags: VolumeFlags = toml::from_str("resolution_divisor = 3").unwrap();
        assert_eq!(flags.divisor().unwrap(), 3);
        assert_eq!(VolumeFlags::default().divisor().unwrap(), 1);
        let e = VolumeFlags {
            resolution_divisor: Some(9),
            ..VolumeFlags::default()
        }
        .divisor()
        .unwrap_err();
        let e = format!("{e:#}");
        assert!(
            e.contains("--optics-resolution-divisor") && e.contains('9'),
            "{e}"
        );
    }
}
