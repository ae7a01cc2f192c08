//! The sizes and sample counts of the Bruneton tables, from the command line's options.

use std::ops::RangeInclusive;

use crate::models::bruneton::parameterization::{AngleMapping, ScatteringSize};
use crate::models::error::ModelError;
use crate::models::options::{ModelOptions, Setting};
use crate::models::table_budget::{check_table_bytes, product};
use crate::optics::transmittance_table::BRUNETON_TABLE_SIZE;

/// The model's settings. `Default` gives the paper's sizes (section 6) and the sample
/// counts of its published implementation.
#[derive(Clone, Debug, PartialEq)]
pub struct BrunetonSettings {
    /// S over (r, mu, mu_s, nu): 32 x 128 x 32 x 8 in the paper. mu must be even (half
    /// for rays that meet the ground); every size at least 2.
    pub scattering_size: ScatteringSize,
    /// E over (mu_s, r): 64 x 16 in the paper.
    pub irradiance_size: (usize, usize),
    /// T over (mu, r): 256 x 64 (the paper has 256 x 64 too, in another mapping; this is
    /// the shared table of Bruneton 2017's mapping).
    pub transmittance_size: (usize, usize),
    /// Trapezoid intervals along each texel's ray for single scattering and each
    /// Delta S: 50 (INSCATTER_INTEGRAL_SAMPLES of the paper's code); fewer miss the thin
    /// hazy boundary layer. Unlike that code, nodes are spaced quadratically towards the
    /// dense end of climbing and descending rays, where evenly spaced nodes overestimate
    /// Mie scattering on vertical rays.
    pub view_samples: usize,
    /// Those nodes placed at equal steps of half distance, half optical depth along the
    /// ray (`node_placement.rs`) instead of by the crowding rule above: off by default.
    pub density_nodes: bool,
    /// Directions (zenith angle, azimuth) of the sphere integrals for Delta J and
    /// Delta E: 16 x 32 (INSCATTER_SPHERICAL_INTEGRAL_SAMPLES). The zenith angle is
    /// integrated by 8-point Gauss-Legendre panels on each side of the horizon, one pair
    /// of panels per 16 directions.
    pub sphere_samples: (usize, usize),
    /// Stop after an order whose share of all the table's radiance (sum over texels, worst
    /// channel) is below this: 0.02 (on Earth the loop stops after a few orders; those
    /// left out add less than the last one).
    pub order_threshold: f64,
    /// The most orders when `ModelSettings::max_orders` is `None` (a guard for thick
    /// atmospheres whose orders fade slowly): 32.
    pub order_limit: u32,
    /// The sun as a disk of the atmosphere's angular radius where it meets the horizon
    /// (its visible part, dimmed along its centroid's path), rather than a point (the
    /// paper).
    pub sun_disk: bool,
    /// Mie's share of Delta J: 0 for the delta-M form with three Legendre terms from the
    /// moments of the incoming radiance (the default); n (a multiple of 8) for a
    /// quadrature of n x n directions about each texel's view direction with the exact
    /// phase function (`mie_quadrature.rs`).
    pub mie_directions: usize,
    /// That quadrature's directions laid out in the texel's frame, split at the view and
    /// at the horizon (`mie_quadrature.rs`), instead of about the view: off by default.
    pub mie_horizon: bool,
    /// With `mie_horizon`, the texel's frame for order two alone (whose incoming light,
    /// scattered once, holds the sharp band and step at the horizon), the layout about
    /// the view for the later orders: off by default (every order).
    pub mie_horizon_order_two: bool,
}

impl Default for BrunetonSettings {
    fn default() -> Self {
        BrunetonSettings {
            scattering_size: ScatteringSize {
                r: 32,
                mu: 128,
                mu_s: 32,
                nu: 8,
                angles: AngleMapping::PAPER,
            },
            irradiance_size: (64, 16),
            transmittance_size: BRUNETON_TABLE_SIZE,
            view_samples: 50,
            density_nodes: false,
            sphere_samples: (16, 32),
            order_threshold: 0.02,
            order_limit: 32,
            sun_disk: false,
            mie_directions: 0,
            mie_horizon: false,
            mie_horizon_order_two: false,
        }
    }
}

/// A setting of bruneton's.
const fn setting<T>(key: &'static str, range: RangeInclusive<T>) -> Setting<T> {
    Setting {
        model: "bruneton",
        key,
        range,
    }
}

/// S's axes: up to 256 x 1024 x 256 x 64 texels (r, mu, mu_s, nu); the memory budget
/// bounds their product, the GPU's device limits the store and mu_s x nu (a 3D texture's
/// width).
pub const R: Setting<usize> = setting("r", 2..=256);
pub const MU: Setting<usize> = setting("mu", 4..=1024);
pub const MU_S: Setting<usize> = setting("mu_s", 2..=256);
pub const NU: Setting<usize> = setting("nu", 2..=64);
/// E's sun-angle texels (its axis is linear in mu_s).
pub const E_MU_S: Setting<usize> = setting("e_mu_s", 2..=1024);
/// Sample counts: one GPU invocation's loops run well under 65535 trips in all (the
/// sphere integrals' 2 sides x 8 x ceil(sphere_zenith / 16) zenith nodes x
/// sphere_azimuth / 2 azimuths at most 8192).
pub const VIEW_SAMPLES: Setting<usize> = setting("view_samples", 1..=4096);
pub const SPHERE_ZENITH: Setting<usize> = setting("sphere_zenith", 1..=128);
pub const SPHERE_AZIMUTH: Setting<usize> = setting("sphere_azimuth", 2..=128);
pub const ORDER_THRESHOLD: Setting<f64> = setting("order_threshold", 0.0..=1.0);
/// Orders: 63 at most, as many as the GPU records.
pub const ORDER_LIMIT: Setting<usize> = setting("order_limit", 1..=63);
/// The lowest sun cosine of S and E: from -0.6 (127 deg) to -0.05 (93 deg).
pub const MIN_MU_S: Setting<f64> = setting("min_mu_s", -0.6..=-0.05);
/// Directions of Mie's Delta J quadrature per axis (0: delta-M); the GPU's loop runs
/// their square, or with `mie_horizon` six times it (at most 24576 trips).
pub const MIE_DIRECTIONS: Setting<usize> = setting("mie_directions", 0..=64);
/// Keys of the switches (`true` or `false`).
pub const NU_BY_ANGLE: &str = "nu_by_angle";
pub const SUN_DISK: &str = "sun_disk";
pub const MU_S_KNEE: &str = "mu_s_knee";
pub const GEOMETRIC_MU_S: &str = "geometric_mu_s";
pub const DENSITY_NODES: &str = "density_nodes";
pub const NU_EDGE: &str = "nu_edge";
pub const NU_BY_AZIMUTH: &str = "nu_by_azimuth";
pub const MU_ZENITH: &str = "mu_zenith";
pub const MIE_HORIZON: &str = "mie_horizon";
pub const MIE_HORIZON_ORDER_TWO: &str = "mie_horizon_order_two";

impl BrunetonSettings {
    /// The settings from `key=value` options: `r`, `mu`, `mu_s`, `nu` (S's size),
    /// `e_mu_s` (E's sun angles), `view_samples`, `sphere_zenith`, `sphere_azimuth`,
    /// `order_threshold`, `order_limit`, `min_mu_s`, `nu_by_angle`, `mu_s_knee`,
    /// `sun_disk`, `mie_directions`, `mie_horizon`, `mie_horizon_order_two`,
    /// `geometric_mu_s`, `density_nodes`,
    /// `nu_edge`, `nu_by_azimuth`, `mu_zenith`; the paper's values where absent.
    pub fn from_options(options: &ModelOptions) -> Result<BrunetonSettings, ModelError> {
        options.read_settings("bruneton", BrunetonSettings::validate, |o, d| {
            Ok(BrunetonSettings {
                scattering_size: ScatteringSize {
                    r: o.count(&R, d.scattering_size.r)?,
                    mu: o.count(&MU, d.scattering_size.mu)?,
                    mu_s: o.count(&MU_S, d.scattering_size.mu_s)?,
                    nu: o.count(&NU, d.scattering_size.nu)?,
                    angles: AngleMapping {
                        min_mu_s: o.number(&MIN_MU_S, d.scattering_size.angles.min_mu_s)?,
                        nu_by_angle: o.flag(NU_BY_ANGLE, d.scattering_size.angles.nu_by_angle)?,
                        mu_s_knee: o.flag(MU_S_KNEE, d.scattering_size.angles.mu_s_knee)?,
                        geometric_mu_s: o
                            .flag(GEOMETRIC_MU_S, d.scattering_size.angles.geometric_mu_s)?,
                        nu_edge: o.flag(NU_EDGE, d.scattering_size.angles.nu_edge)?,
                        nu_by_azimuth: o
                            .flag(NU_BY_AZIMUTH, d.scattering_size.angles.nu_by_azimuth)?,
                        mu_zenith: o.flag(MU_ZENITH, d.scattering_size.angles.mu_zenith)?,
                    },
                },
                irradiance_size: (o.count(&E_MU_S, d.irradiance_size.0)?, d.irradiance_size.1),
                view_samples: o.count(&VIEW_SAMPLES, d.view_samples)?,
                density_nodes: o.flag(DENSITY_NODES, d.density_nodes)?,
                sphere_samples: (
                    o.count(&SPHERE_ZENITH, d.sphere_samples.0)?,
                    o.count(&SPHERE_AZIMUTH, d.sphere_samples.1)?,
                ),
                order_threshold: o.number(&ORDER_THRESHOLD, d.order_threshold)?,
                order_limit: o.count(&ORDER_LIMIT, d.order_limit as usize)? as u32,
                sun_disk: o.flag(SUN_DISK, d.sun_disk)?,
                mie_directions: o.count(&MIE_DIRECTIONS, d.mie_directions)?,
                mie_horizon: o.flag(MIE_HORIZON, d.mie_horizon)?,
                mie_horizon_order_two: o.flag(MIE_HORIZON_ORDER_TWO, d.mie_horizon_order_two)?,
                ..d
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let s = self.scattering_size;
        for (setting, value) in [
            (R, s.r),
            (MU, s.mu),
            (MU_S, s.mu_s),
            (NU, s.nu),
            (E_MU_S, self.irradiance_size.0),
            (VIEW_SAMPLES, self.view_samples),
            (SPHERE_ZENITH, self.sphere_samples.0),
            (SPHERE_AZIMUTH, self.sphere_samples.1),
            (ORDER_LIMIT, self.order_limit as usize),
            (MIE_DIRECTIONS, self.mie_directions),
        ] {
            setting.check(value)?;
        }
        ORDER_THRESHOLD.check(self.order_threshold)?;
        MIN_MU_S.check(s.angles.min_mu_s)?;
        if !s.mu.is_multiple_of(2) {
            return Err(ModelError::Settings(format!(
                "bruneton setting mu={} must be even (half the rays meet the ground)",
                s.mu
            )));
        }
        if s.angles.nu_by_azimuth && (s.angles.nu_by_angle || s.angles.nu_edge) {
            return Err(ModelError::Settings(
                "bruneton setting nu_by_azimuth=true replaces nu_by_angle and nu_edge \
                 (its texels span only the directions their mu and mu_s allow): set those \
                 false"
                    .to_string(),
            ));
        }
        if self.mie_horizon && self.mie_directions == 0 {
            return Err(ModelError::Settings(
                "bruneton setting mie_horizon=true lays out the directions of Mie's \
                 quadrature: set mie_directions to a multiple of 8 too"
                    .to_string(),
            ));
        }
        if self.mie_horizon_order_two && !self.mie_horizon {
            return Err(ModelError::Settings(
                "bruneton setting mie_horizon_order_two=true narrows mie_horizon to order \
                 two: set mie_horizon=true too"
                    .to_string(),
            ));
        }
        if !self.mie_directions.is_multiple_of(8) {
            return Err(ModelError::Settings(format!(
                "bruneton setting mie_directions={} must be 0 or a multiple of 8",
                self.mie_directions
            )));
        }
        let two = |(a, b): (usize, usize)| (2..=2048).contains(&a) && (2..=2048).contains(&b);
        if !two(self.irradiance_size) || !two(self.transmittance_size) {
            return Err(ModelError::Settings(format!(
                "bruneton irradiance table {:?} and transmittance table {:?}: each side 2..=2048",
                self.irradiance_size, self.transmittance_size
            )));
        }
        Ok(())
    }

    /// Bytes of the tables these settings make at `wavelengths` wavelengths: the
    /// transmittance (f64 columns) and, per group of three wavelengths, single Rayleigh,
    /// single Mie and multiple scattering and the irradiance, in f32.
    pub fn table_bytes(&self, wavelengths: usize) -> u64 {
        let (tw, th) = self.transmittance_size;
        let (ew, eh) = self.irradiance_size;
        let group = product(&[3, self.scattering_size.texels(), 12]) + product(&[ew, eh, 12]);
        product(&[tw, th, 24]) + wavelengths.div_ceil(3) as u64 * group
    }

    /// Nothing, or an error when the tables at `wavelengths` wavelengths are over the
    /// memory budget.
    pub fn check_table_bytes(&self, wavelengths: usize) -> Result<(), ModelError> {
        let s = self.scattering_size;
        check_table_bytes(
            "bruneton",
            &format!(
                "r={} x mu={} x mu_s={} x nu={} at {wavelengths} wavelengths",
                s.r, s.mu, s.mu_s, s.nu
            ),
            self.table_bytes(wavelengths),
        )
    }
}
