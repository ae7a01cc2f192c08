//! The settings of the hillaire model that trade accuracy for time, as `key=value`
//! options with the paper's values as defaults, each with its range, and the memory its
//! tables take (docs/models/hillaire.md).

use crate::models::error::ModelError;
use crate::models::gpu_loops::check_loop_trips;
use crate::models::hillaire::aerial_perspective::{AerialPerspective, VolumeShape};
use crate::models::hillaire::directions::LatLong;
use crate::models::hillaire::ground::HemisphereQuadrature;
use crate::models::hillaire::moments::{MAX_ORDER, blocks};
use crate::models::hillaire::sky_view::SkyView;
use crate::models::options::{ModelOptions, Setting};
use crate::models::table_budget::{check_table_bytes, product};
use crate::optics::transmittance_table::BRUNETON_TABLE_SIZE;

/// The settings that trade accuracy for time. `Default` gives the paper's sizes and
/// sample counts (section 5 and its published implementation); docs/models/hillaire.md
/// gives the source of each.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HillaireSettings {
    /// Transmittance LUT (mu, r): 256 x 64.
    pub transmittance_size: (usize, usize),
    /// Psi_ms LUT (mu_s, altitude): 32 x 32.
    pub multiple_scattering_size: (usize, usize),
    /// Directions over the sphere per Psi_ms texel, a square number: 64 (8 x 8).
    pub multiple_scattering_directions: usize,
    /// Segments per Psi_ms ray: 20.
    pub multiple_scattering_samples: usize,
    /// Legendre moments about the sun of the multiple-scattering field beyond its mean
    /// (`moments.rs`): 0, the paper's isotropic term; 1 or 2, the anisotropic term.
    pub multiple_scattering_order: usize,
    /// The share f of Mie scattering that orders two and up take as unscattered, the
    /// similarity-scaled medium of `similarity.rs`: 0, the paper's medium.
    pub multiple_scattering_delta: f64,
    /// Sky-view LUT (longitude, latitude): 192 x 108; the latitude count must be even.
    pub sky_view_size: (usize, usize),
    /// Segments per sky-view ray: 30.
    pub sky_view_samples: usize,
    /// Aerial-perspective volume (longitude, latitude, depth slices): 96 x 96 x 32. The
    /// paper's 32 x 32 froxels per slice cover the camera's frustum; 96 x 96 over all
    /// directions is the same angular spacing for a 60 degree field of view.
    pub aerial_size: (usize, usize, usize),
    /// Depth covered by the volume: 32 km.
    pub aerial_range_m: f64,
    /// Segments per slice and direction: 2.
    pub aerial_samples_per_slice: usize,
    /// Segments of the per-pixel march (cameras in space, surfaces beyond the volume):
    /// 30, the sky-view's count (the paper's implementation varies it from 4 to 14 with
    /// the ray's length, for speed on the GPU).
    pub march_samples: usize,
    /// Values of the ground's sky-irradiance table over mu_s: 32 (not in the paper; see
    /// `ground.rs`).
    pub ground_size: usize,
    /// Its hemisphere quadrature: 8-point Gauss-Legendre panels in the zenith cosine (1)
    /// and azimuths over half the circle (8).
    pub ground_zenith_panels: usize,
    pub ground_azimuths: usize,
    /// Views whose per-view tables are kept: 8 (about 7.4 MB each at three wavelengths;
    /// a frame needs one, the stability sweep cycles through five sun elevations).
    pub view_cache: usize,
}

impl Default for HillaireSettings {
    fn default() -> Self {
        HillaireSettings {
            transmittance_size: BRUNETON_TABLE_SIZE,
            multiple_scattering_size: (32, 32),
            multiple_scattering_directions: 64,
            multiple_scattering_samples: 20,
            multiple_scattering_order: 0,
            multiple_scattering_delta: 0.0,
            sky_view_size: (192, 108),
            sky_view_samples: 30,
            aerial_size: (96, 96, 32),
            aerial_range_m: 32_000.0,
            aerial_samples_per_slice: 2,
            march_samples: 30,
            ground_size: 32,
            ground_zenith_panels: 1,
            ground_azimuths: 8,
            view_cache: 8,
        }
    }
}

/// A setting of hillaire's.
const fn setting<T>(key: &'static str, range: std::ops::RangeInclusive<T>) -> Setting<T> {
    Setting {
        model: "hillaire",
        key,
        range,
    }
}

/// Table sides: 2048 texels at most for 2D tables and 1024 (256 slices) for the aerial
/// volume, within every GPU's texture limits; the memory budget bounds their product.
pub const TRANSMITTANCE_WIDTH: Setting<usize> = setting("transmittance_width", 2..=2048);
pub const TRANSMITTANCE_HEIGHT: Setting<usize> = setting("transmittance_height", 2..=2048);
pub const MS_WIDTH: Setting<usize> = setting("ms_width", 2..=1024);
pub const MS_HEIGHT: Setting<usize> = setting("ms_height", 2..=1024);
pub const SKY_VIEW_WIDTH: Setting<usize> = setting("sky_view_width", 2..=2048);
pub const SKY_VIEW_HEIGHT: Setting<usize> = setting("sky_view_height", 4..=2048);
pub const AP_WIDTH: Setting<usize> = setting("ap_width", 2..=1024);
pub const AP_HEIGHT: Setting<usize> = setting("ap_height", 4..=1024);
pub const AP_SLICES: Setting<usize> = setting("ap_slices", 2..=256);
pub const GROUND_SIZE: Setting<usize> = setting("ground_size", 2..=1024);
/// Sample counts: one GPU invocation's loops run well under 65535 trips in all
/// (ap_slices x ap_samples_per_slice at most 16384; ms_directions / 64 lanes x
/// ms_samples at most 16 x 1024; the ground's table is checked in
/// [`HillaireSettings::validate`]).
pub const MS_DIRECTIONS: Setting<usize> = setting("ms_directions", 1..=1024);
pub const MS_SAMPLES: Setting<usize> = setting("ms_samples", 1..=1024);
/// The anisotropic term's highest Legendre moment (0: the paper's isotropic term).
pub const MS_ORDER: Setting<usize> = setting("ms_order", 0..=MAX_ORDER);
/// The delta fraction of the similarity-scaled medium (0: the paper's medium).
pub const MS_DELTA: Setting<f64> = setting("ms_delta", 0.0..=1.0);
pub const SKY_VIEW_SAMPLES: Setting<usize> = setting("sky_view_samples", 1..=1024);
pub const AP_SAMPLES_PER_SLICE: Setting<usize> = setting("ap_samples_per_slice", 1..=64);
pub const MARCH_SAMPLES: Setting<usize> = setting("march_samples", 1..=1024);
pub const GROUND_ZENITH_PANELS: Setting<usize> = setting("ground_zenith_panels", 1..=16);
pub const GROUND_AZIMUTHS: Setting<usize> = setting("ground_azimuths", 1..=256);
/// The aerial volume's depth: 1 m to 1000 km.
pub const AP_RANGE_M: Setting<f64> = setting("ap_range_m", 1.0..=1.0e6);
/// Views kept: 64 at most (the memory budget counts every kept view).
pub const VIEW_CACHE: Setting<usize> = setting("view_cache", 1..=64);

impl HillaireSettings {
    /// The settings from `key=value` options (keys in docs/models/hillaire.md); the
    /// defaults where absent.
    pub fn from_options(options: &ModelOptions) -> Result<HillaireSettings, ModelError> {
        options.read_settings("hillaire", HillaireSettings::validate, |o, d| {
            Ok(HillaireSettings {
                transmittance_size: (
                    o.count(&TRANSMITTANCE_WIDTH, d.transmittance_size.0)?,
                    o.count(&TRANSMITTANCE_HEIGHT, d.transmittance_size.1)?,
                ),
                multiple_scattering_size: (
                    o.count(&MS_WIDTH, d.multiple_scattering_size.0)?,
                    o.count(&MS_HEIGHT, d.multiple_scattering_size.1)?,
                ),
                multiple_scattering_directions: o
                    .count(&MS_DIRECTIONS, d.multiple_scattering_directions)?,
                multiple_scattering_samples: o.count(&MS_SAMPLES, d.multiple_scattering_samples)?,
                multiple_scattering_order: o.count(&MS_ORDER, d.multiple_scattering_order)?,
                multiple_scattering_delta: o.number(&MS_DELTA, d.multiple_scattering_delta)?,
                sky_view_size: (
                    o.count(&SKY_VIEW_WIDTH, d.sky_view_size.0)?,
                    o.count(&SKY_VIEW_HEIGHT, d.sky_view_size.1)?,
                ),
                sky_view_samples: o.count(&SKY_VIEW_SAMPLES, d.sky_view_samples)?,
                aerial_size: (
                    o.count(&AP_WIDTH, d.aerial_size.0)?,
                    o.count(&AP_HEIGHT, d.aerial_size.1)?,
                    o.count(&AP_SLICES, d.aerial_size.2)?,
                ),
                aerial_range_m: o.number(&AP_RANGE_M, d.aerial_range_m)?,
                aerial_samples_per_slice: o
                    .count(&AP_SAMPLES_PER_SLICE, d.aerial_samples_per_slice)?,
                march_samples: o.count(&MARCH_SAMPLES, d.march_samples)?,
                ground_size: o.count(&GROUND_SIZE, d.ground_size)?,
                ground_zenith_panels: o.count(&GROUND_ZENITH_PANELS, d.ground_zenith_panels)?,
                ground_azimuths: o.count(&GROUND_AZIMUTHS, d.ground_azimuths)?,
                view_cache: o.count(&VIEW_CACHE, d.view_cache)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let (aw, ah, slices) = self.aerial_size;
        for (setting, value) in [
            (TRANSMITTANCE_WIDTH, self.transmittance_size.0),
            (TRANSMITTANCE_HEIGHT, self.transmittance_size.1),
            (MS_WIDTH, self.multiple_scattering_size.0),
            (MS_HEIGHT, self.multiple_scattering_size.1),
            (MS_DIRECTIONS, self.multiple_scattering_directions),
            (MS_SAMPLES, self.multiple_scattering_samples),
            (MS_ORDER, self.multiple_scattering_order),
            (SKY_VIEW_WIDTH, self.sky_view_size.0),
            (SKY_VIEW_HEIGHT, self.sky_view_size.1),
            (SKY_VIEW_SAMPLES, self.sky_view_samples),
            (AP_WIDTH, aw),
            (AP_HEIGHT, ah),
            (AP_SLICES, slices),
            (AP_SAMPLES_PER_SLICE, self.aerial_samples_per_slice),
            (MARCH_SAMPLES, self.march_samples),
            (GROUND_SIZE, self.ground_size),
            (GROUND_ZENITH_PANELS, self.ground_zenith_panels),
            (GROUND_AZIMUTHS, self.ground_azimuths),
            (VIEW_CACHE, self.view_cache),
        ] {
            setting.check(value)?;
        }
        AP_RANGE_M.check(self.aerial_range_m)?;
        MS_DELTA.check(self.multiple_scattering_delta)?;
        let bad = |m: String| Err(ModelError::Settings(format!("hillaire: {m}")));
        let root = self.multiple_scattering_directions.isqrt();
        if root * root != self.multiple_scattering_directions {
            return bad(format!(
                "ms_directions {} must be a square number",
                self.multiple_scattering_directions
            ));
        }
        if self.multiple_scattering_delta > 0.0 && self.multiple_scattering_order != 0 {
            return bad(format!(
                "ms_delta={} scales the paper's isotropic term and needs ms_order=0, not {}",
                self.multiple_scattering_delta, self.multiple_scattering_order
            ));
        }
        for (key, h) in [("sky_view_height", self.sky_view_size.1), ("ap_height", ah)] {
            if !h.is_multiple_of(2) {
                return bad(format!("{key} {h} must be even"));
            }
        }
        // The ground's table: 64 GPU lanes share the hemisphere's rays, each marched
        // with sky_view_samples segments.
        let (panels, azimuths) = (self.ground_zenith_panels, self.ground_azimuths);
        check_loop_trips(
            "hillaire",
            &format!(
                "ground_zenith_panels={panels} x 8 x ground_azimuths={azimuths} / 64 lanes x \
                 sky_view_samples={}",
                self.sky_view_samples
            ),
            (panels * 8 * azimuths).div_ceil(64) * self.sky_view_samples,
        )
    }

    /// Bytes of the tables these settings make at `wavelengths` wavelengths: the
    /// transmittance (f64 columns), Psi_ms (a block per moment) and the ground's table, and `view_cache`
    /// times a view's sky-view LUT and aerial volume.
    pub fn table_bytes(&self, wavelengths: usize) -> u64 {
        let (tw, th) = self.transmittance_size;
        let (mw, mh) = self.multiple_scattering_size;
        let global = product(&[tw, th, 24])
            + product(&[
                mw,
                mh,
                blocks(self.multiple_scattering_order),
                wavelengths,
                4,
            ])
            + product(&[self.ground_size, wavelengths, 4]);
        let view = SkyView::bytes_for(self.sky_view_grid(), wavelengths) as u64
            + AerialPerspective::bytes_for(self.volume_shape(), wavelengths) as u64;
        global + self.view_cache as u64 * view
    }

    /// Nothing, or an error when the tables at `wavelengths` wavelengths are over the
    /// memory budget.
    pub fn check_table_bytes(&self, wavelengths: usize) -> Result<(), ModelError> {
        let (aw, ah, slices) = self.aerial_size;
        let (sw, sh) = self.sky_view_size;
        check_table_bytes(
            "hillaire",
            &format!(
                "sky_view {sw} x {sh}, ap {aw} x {ah} x {slices}, view_cache={}, \
                 {wavelengths} wavelengths",
                self.view_cache
            ),
            self.table_bytes(wavelengths),
        )
    }

    pub fn sky_view_grid(&self) -> LatLong {
        LatLong {
            width: self.sky_view_size.0,
            height: self.sky_view_size.1,
        }
    }

    pub fn volume_shape(&self) -> VolumeShape {
        VolumeShape {
            grid: LatLong {
                width: self.aerial_size.0,
                height: self.aerial_size.1,
            },
            slices: self.aerial_size.2,
            range_m: self.aerial_range_m,
            samples_per_slice: self.aerial_samples_per_slice,
        }
    }

    pub fn hemisphere(&self) -> HemisphereQuadrature {
        HemisphereQuadrature {
            zenith_panels: self.ground_zenith_panels,
            azimuths: self.ground_azimuths,
            samples: self.sky_view_samples,
        }
    }
}
