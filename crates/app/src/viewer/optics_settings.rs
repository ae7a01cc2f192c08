//! The viewer's rain, cirrus and droplet deck settings (the panel's "Rain and ice"
//! section), kept between runs with the others, and their reading as `atmos render`'s
//! volume flags, which check them (docs/optics-rendering.md, "Settings and their
//! ranges").

use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::scene::{CirrusSettings, DeckSettings, RainShaftSettings};
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use serde::{Deserialize, Serialize};

use crate::render::volume_flags::VolumeFlags;

/// The wavelengths of the viewer's phase tables: half `atmos render`'s, so that a first
/// build keeps the window waiting half as long (docs/optics-rendering.md: 16 change the
/// rain's table by a few per cent from 32).
pub const VIEWER_WAVELENGTHS: usize = 16;
/// Rays per wavelength of the viewer's cirrus: a fifth of `atmos render`'s, for the
/// same reason (fainter rings of noise around the sun show).
pub const VIEWER_CIRRUS_RAYS: usize = 200_000;
/// The viewer's volumes marched for one pixel in 3 x 3 by default, the interactive
/// setting (docs/optics-rendering.md, "Cost").
pub const VIEWER_RESOLUTION_DIVISOR: u32 = 3;

/// The small drops' effective radius offered when they are first turned on, um: the
/// shipped scene's (`assets/scenes/optics/rainbow_small_drops.toml`).
pub const DEFAULT_SMALL_DROP_RADIUS_UM: f64 = 150.0;

/// The panel's rain, cirrus and deck settings; fields missing from older stored
/// settings take their defaults (all off).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct OpticsSettings {
    /// A rain shaft ahead of the camera, placed when it is turned on or changed.
    pub rain: bool,
    /// mm/h, in [0.1, 300].
    pub rain_rate_mm_h: f64,
    /// From the camera to the shaft's axis, m, in [0, 100000].
    pub rain_distance_m: f64,
    /// The shaft's drops are small drops by Lorenz-Mie (supernumerary bows) instead of
    /// Marshall-Palmer rain by geometric optics.
    pub rain_small_drops: bool,
    /// The small drops' effective radius, um, in [50, 600].
    pub rain_small_drop_radius_um: f64,
    /// A cirrus layer of randomly oriented ice columns.
    pub cirrus: bool,
    /// The layer's base above the ground, m, in [1000, 20000].
    pub cirrus_base_m: f64,
    /// Vertical optical depth, in [0, 10].
    pub cirrus_optical_depth: f64,
    /// A deck of cloud droplets (the glory and the cloudbow from above it).
    pub deck: bool,
    /// The deck's base above the ground, m, in [0, 20000].
    pub deck_base_m: f64,
    /// The deck's thickness, m, in [10, 10000].
    pub deck_thickness_m: f64,
    /// The deck's vertical optical depth, in [0, 10].
    pub deck_optical_depth: f64,
    /// The droplets' effective radius, um, in [2, 50].
    pub deck_droplet_radius_um: f64,
    /// How the march counts the light scattered within 1 degree of forward.
    pub forward_peak: ForwardPeak,
    /// Which sky's light the march scatters.
    pub sky_light: SkyLight,
    /// Whether the march adds the sun's light scattered more than once.
    pub multiple_scattering: MultipleScattering,
    /// One pixel in N x N of the volumes marched, the rest upsampled, in [1, 4].
    pub resolution_divisor: u32,
}

impl Default for OpticsSettings {
    fn default() -> OpticsSettings {
        let (rain, cirrus) = (RainShaftSettings::default(), CirrusSettings::default());
        let deck = DeckSettings::default();
        OpticsSettings {
            rain: false,
            rain_rate_mm_h: rain.rain_rate_mm_h,
            rain_distance_m: rain.distance_m,
            rain_small_drops: false,
            rain_small_drop_radius_um: DEFAULT_SMALL_DROP_RADIUS_UM,
            cirrus: false,
            cirrus_base_m: cirrus.base_m,
            cirrus_optical_depth: cirrus.optical_depth,
            deck: false,
            deck_base_m: deck.base_m,
            deck_thickness_m: deck.thickness_m,
            deck_optical_depth: deck.optical_depth,
            deck_droplet_radius_um: deck.droplet_radius_um,
            forward_peak: ForwardPeak::default(),
            sky_light: SkyLight::default(),
            multiple_scattering: MultipleScattering::default(),
            resolution_divisor: VIEWER_RESOLUTION_DIVISOR,
        }
    }
}

impl OpticsSettings {
    /// Whether any volume is on.
    pub fn any(&self) -> bool {
        self.rain || self.cirrus || self.deck
    }

    /// The same settings as `atmos render`'s flags.
    pub fn flags(&self) -> VolumeFlags {
        VolumeFlags {
            rain: Some(self.rain),
            rain_rate_mm_h: Some(self.rain_rate_mm_h),
            rain_distance_m: Some(self.rain_distance_m),
            rain_small_drop_radius_um: (self.rain && self.rain_small_drops)
                .then_some(self.rain_small_drop_radius_um),
            cirrus: Some(self.cirrus),
            cirrus_base_m: Some(self.cirrus_base_m),
            cirrus_optical_depth: Some(self.cirrus_optical_depth),
            cirrus_rays: Some(VIEWER_CIRRUS_RAYS),
            deck: Some(self.deck),
            deck_base_m: Some(self.deck_base_m),
            deck_thickness_m: Some(self.deck_thickness_m),
            deck_optical_depth: Some(self.deck_optical_depth),
            deck_droplet_radius_um: Some(self.deck_droplet_radius_um),
            wavelengths: Some(VIEWER_WAVELENGTHS),
            forward_peak: Some(self.forward_peak),
            sky_light: Some(self.sky_light),
            multiple_scattering: Some(self.multiple_scattering),
            resolution_divisor: Some(self.resolution_divisor),
            ..VolumeFlags::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_defaults_are_the_volumes_and_bad_values_are_named() {
        let mut optics = OpticsSettings::default();
        assert!(!optics.any());
        assert_eq!(optics.flags().rain_settings(), None);
        assert_eq!(optics.flags().cirrus_settings(), None);
        optics.rain = true;
        optics.cirrus = true;
        assert_eq!(
            optics.flags().rain_settings(),
            Some(RainShaftSettings::default())
        );
        assert_eq!(
            optics.flags().cirrus_settings(),
            Some(CirrusSettings {
                rays: VIEWER_CIRRUS_RAYS,
                ..CirrusSettings::default()
            })
        );
        optics.cirrus_optical_depth = 20.0;
        let cirrus = optics.flags().cirrus_settings().unwrap();
        let e = cirrus.volume(6_360e3, 20.0).unwrap_err().to_string();
        assert!(e.contains("cirrus optical depth 20"), "{e}");
        // The small drops and the deck are the flags' own settings.
        optics.rain_small_drops = true;
        optics.deck = true;
        let flags = optics.flags();
        assert_eq!(
            flags.rain_settings().unwrap().small_drop_radius_um,
            Some(DEFAULT_SMALL_DROP_RADIUS_UM)
        );
        assert_eq!(flags.deck_settings(), Some(DeckSettings::default()));
        optics.rain = false;
        assert_eq!(optics.flags().rain_small_drop_radius_um, None);
        optics.deck_droplet_radius_um = 60.0;
        let e = optics.flags().deck_settings().unwrap().volume(6_360e3);
        let e = e.unwrap_err().to_string();
        assert!(e.contains("deck droplet radius (um) 60"), "{e}");
        let stored: OpticsSettings = toml::from_str("rain = true").unwrap();
        assert!(stored.rain && !stored.cirrus && !stored.deck && !stored.rain_small_drops);
        assert_eq!(stored.forward_peak, ForwardPeak::Unscattered);
        optics.forward_peak = ForwardPeak::Extinction;
        assert_eq!(optics.flags().forward_peak, Some(ForwardPeak::Extinction));
        assert_eq!(stored.sky_light, SkyLight::Sphere);
        optics.sky_light = SkyLight::Horizontal;
        assert_eq!(optics.flags().sky_light, Some(SkyLight::Horizontal));
        assert_eq!(stored.multiple_scattering, MultipleScattering::Probes);
        assert_eq!(stored.resolution_divisor, VIEWER_RESOLUTION_DIVISOR);
        assert_eq!(optics.flags().divisor().unwrap(), VIEWER_RESOLUTION_DIVISOR);
        optics.multiple_scattering = MultipleScattering::None;
        assert_eq!(
            optics.flags().multiple_scattering,
            Some(MultipleScattering::None)
        );
        assert_eq!(
            stored.rain_rate_mm_h,
            RainShaftSettings::default().rain_rate_mm_h
        );
    }
}
