//! The settings of the dobashi model that trade accuracy for time, as `key=value` options
//! with the paper's values as defaults where it gives one (docs/models/dobashi.md).

use std::ops::RangeInclusive;

use crate::models::error::ModelError;
use crate::models::options::{ModelOptions, Setting};
use crate::models::table_budget::{check_table_bytes, product};

/// What trades accuracy for time in Dobashi, Yamamoto and Nishita 2002 (sections
/// 4.2.1 and 5.2-5.3). `Default` is the paper's choice where it states one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DobashiSettings {
    /// Sampling planes that span the longest view from the ground (the horizontal ray to
    /// the top of the atmosphere, sqrt(R_top^2 - R^2)); this sets the largest plane
    /// interval Delta_max of section 4.2.1. Default 100: Table 1, Fig. 10(a), "100 (sky)".
    pub planes: usize,
    /// Delta_max / Delta_min: the interval rule of section 4.2.1 tries Delta_min, 2
    /// Delta_min, ... up to Delta_max. The paper gives no Delta_min for the sky; 10.
    pub interval_steps: usize,
    /// I_max of section 4.2.1: the interval grows while no value of the tables dI_r, dI_m
    /// exceeds it. Default 1.0 ("usually, I_max is 1.0").
    pub table_max: f64,
    /// A camera above the atmosphere whose view would need more planes than this
    /// ((t_max - t_min) / Delta_t + 1, section 4.2.1) uses sample spheres (section 5.3).
    /// Default 300: the most planes of Table 1 (Figs. 10(c) and 11, the Earth from space
    /// near the surface, drawn with planes).
    pub max_planes: usize,
    /// Sample spheres from the ground to the top of the atmosphere, both included.
    /// Default 10: Table 1, Fig. 10(b), "10 (sample spheres)".
    pub spheres: usize,
    /// Rows (heights) of the plane tables dI_r, dI_m, dg_v(h, theta_v). Not stated in the
    /// paper; 64, as the g_l table.
    pub table_heights: usize,
    /// Columns (view angles) of the plane tables, half for rays that meet the ground and
    /// half for the others (must be even). Not stated; 256, as the g_l table.
    pub table_angles: usize,
    /// Entries of each sample sphere's 1D tables, per kind of segment (to the sphere
    /// below, back to the same sphere, to the sphere above). Not stated; 64.
    pub sphere_table_angles: usize,
    /// Rows (heights) of g_l(h, theta_sun). Not stated; 64 (as nishita).
    pub sun_table_heights: usize,
    /// Columns (sun angles) of g_l. Not stated; 256 (as nishita).
    pub sun_table_angles: usize,
    /// Directions of the ambient term's sphere integral: this many Gauss-Legendre zenith
    /// nodes times this many azimuths. The paper has no multiple scattering; 8 (8 x 8 = 64
    /// directions, as Hillaire 2020's multiple-scattering table).
    pub ambient_directions: usize,
    /// Entries of the ambient term's table over the sun's cosine from -1 to 1. 32, the
    /// sun axis of Hillaire 2020's multiple-scattering table.
    pub ambient_sun_angles: usize,
}

impl Default for DobashiSettings {
    fn default() -> Self {
        DobashiSettings {
            planes: 100,
            interval_steps: 10,
            table_max: 1.0,
            max_planes: 300,
            spheres: 10,
            table_heights: 64,
            table_angles: 256,
            sphere_table_angles: 64,
            sun_table_heights: 64,
            sun_table_angles: 256,
            ambient_directions: 8,
            ambient_sun_angles: 32,
        }
    }
}

/// A setting of dobashi's.
const fn setting<T>(key: &'static str, range: RangeInclusive<T>) -> Setting<T> {
    Setting {
        model: "dobashi",
        key,
        range,
    }
}

/// Planes and sample spheres, each crossing one trip of a GPU loop: on the GPU (which
/// keeps I_max >= 1, so the interval is Delta_max) a ray inside the atmosphere crosses at
/// most 2 x planes planes (from space too), or 3 x spheres segments between sample
/// spheres; both well under the 65535 trips every GPU runs in one invocation.
pub const PLANES: Setting<usize> = setting("planes", 1..=4096);
pub const INTERVAL_STEPS: Setting<usize> = setting("interval_steps", 1..=64);
/// max_planes only chooses between planes and spheres (it bounds no loop): up to 1e9,
/// more than any view needs.
pub const MAX_PLANES: Setting<usize> = setting("max_planes", 1..=1_000_000_000);
pub const SPHERES: Setting<usize> = setting("spheres", 2..=1024);
/// I_max: 1e-6 to 1e6.
pub const TABLE_MAX: Setting<f64> = setting("table_max", 1e-6..=1e6);
/// Table sides: 2048 at most (a texture side every GPU holds); the memory budget bounds
/// their product at many wavelengths.
pub const TABLE_HEIGHTS: Setting<usize> = setting("table_heights", 2..=2048);
pub const TABLE_ANGLES: Setting<usize> = setting("table_angles", 4..=2048);
pub const SPHERE_TABLE_ANGLES: Setting<usize> = setting("sphere_table_angles", 2..=2048);
pub const SUN_TABLE_HEIGHTS: Setting<usize> = setting("sun_table_heights", 2..=2048);
pub const SUN_TABLE_ANGLES: Setting<usize> = setting("sun_table_angles", 2..=2048);
pub const AMBIENT_SUN_ANGLES: Setting<usize> = setting("ambient_sun_angles", 2..=2048);
/// Ambient directions: ambient_directions^2 rays per sun angle, shared by 64 GPU lanes
/// (`shaders/sky/dobashi/ambient.wgsl`), each lane's at most 4 rays of up to `planes`
/// planes.
pub const AMBIENT_DIRECTIONS: Setting<usize> = setting("ambient_directions", 1..=16);

impl DobashiSettings {
    /// The settings from `key=value` options (keys as the field names); the defaults
    /// where absent.
    pub fn from_options(options: &ModelOptions) -> Result<DobashiSettings, ModelError> {
        options.read_settings("dobashi", DobashiSettings::validate, |o, d| {
            Ok(DobashiSettings {
                planes: o.count(&PLANES, d.planes)?,
                interval_steps: o.count(&INTERVAL_STEPS, d.interval_steps)?,
                table_max: o.number(&TABLE_MAX, d.table_max)?,
                max_planes: o.count(&MAX_PLANES, d.max_planes)?,
                spheres: o.count(&SPHERES, d.spheres)?,
                table_heights: o.count(&TABLE_HEIGHTS, d.table_heights)?,
                table_angles: o.count(&TABLE_ANGLES, d.table_angles)?,
                sphere_table_angles: o.count(&SPHERE_TABLE_ANGLES, d.sphere_table_angles)?,
                sun_table_heights: o.count(&SUN_TABLE_HEIGHTS, d.sun_table_heights)?,
                sun_table_angles: o.count(&SUN_TABLE_ANGLES, d.sun_table_angles)?,
                ambient_directions: o.count(&AMBIENT_DIRECTIONS, d.ambient_directions)?,
                ambient_sun_angles: o.count(&AMBIENT_SUN_ANGLES, d.ambient_sun_angles)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        for (setting, value) in [
            (PLANES, self.planes),
            (INTERVAL_STEPS, self.interval_steps),
            (MAX_PLANES, self.max_planes),
            (SPHERES, self.spheres),
            (TABLE_HEIGHTS, self.table_heights),
            (TABLE_ANGLES, self.table_angles),
            (SPHERE_TABLE_ANGLES, self.sphere_table_angles),
            (SUN_TABLE_HEIGHTS, self.sun_table_heights),
            (SUN_TABLE_ANGLES, self.sun_table_angles),
            (AMBIENT_DIRECTIONS, self.ambient_directions),
            (AMBIENT_SUN_ANGLES, self.ambient_sun_angles),
        ] {
            setting.check(value)?;
        }
        TABLE_MAX.check(self.table_max)?;
        let bad = |m: String| Err(ModelError::Settings(format!("dobashi: {m}")));
        if !self.table_angles.is_multiple_of(2) {
            return bad(format!(
                "table_angles {} must be even (half the rays meet the ground)",
                self.table_angles
            ));
        }
        Ok(())
    }

    /// Bytes of the tables these settings make at `wavelengths` wavelengths: g_l (f64
    /// columns) and, in f32 per wavelength, the plane and sphere tables (dI_r, dI_m,
    /// dg_v) and the ambient table.
    pub fn table_bytes(&self, wavelengths: usize) -> u64 {
        product(&[self.sun_table_heights, self.sun_table_angles, 24])
            + product(&[3, self.table_heights, self.table_angles, wavelengths, 4])
            + product(&[
                3,
                3 * self.spheres,
                self.sphere_table_angles,
                wavelengths,
                4,
            ])
            + product(&[self.ambient_sun_angles, wavelengths, 4])
    }

    /// Nothing, or an error when the tables at `wavelengths` wavelengths are over the
    /// memory budget.
    pub fn check_table_bytes(&self, wavelengths: usize) -> Result<(), ModelError> {
        check_table_bytes(
            "dobashi",
            &format!(
                "table_heights={} x table_angles={}, spheres={} x sphere_table_angles={} at \
                 {wavelengths} wavelengths",
                self.table_heights, self.table_angles, self.spheres, self.sphere_table_angles
            ),
            self.table_bytes(wavelengths),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_are_read_and_checked() {
        let o = ModelOptions::parse(&["planes=50", "table_max=0.5"]).unwrap();
        let s = DobashiSettings::from_options(&o).unwrap();
        assert_eq!(s.planes, 50);
        assert_eq!(s.table_max, 0.5);
        assert_eq!(s.spheres, 10);
        for bad in [
            "planes=0",
            "table_angles=7",
            "spheres=1",
            "table_max=-1",
            "orders=2",
        ] {
            let o = ModelOptions::parse(&[bad]).unwrap();
            assert!(DobashiSettings::from_options(&o).is_err(), "{bad}");
        }
        assert!(DobashiSettings::default().validate().is_ok());
    }
}
