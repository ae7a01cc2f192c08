//! The settings of the dobashi model that trade accuracy for time, as `key=value` options
//! with the paper's values as defaults where it gives one (docs/models/dobashi.md).

use crate::models::error::ModelError;
use crate::models::options::ModelOptions;

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

impl DobashiSettings {
    /// The settings from `key=value` options (keys as the field names); the defaults
    /// where absent.
    pub fn from_options(options: &ModelOptions) -> Result<DobashiSettings, ModelError> {
        options.read_settings("dobashi", DobashiSettings::validate, |o, d| {
            Ok(DobashiSettings {
                planes: o.count("planes", d.planes)?,
                interval_steps: o.count("interval_steps", d.interval_steps)?,
                table_max: o.number("table_max", d.table_max)?,
                max_planes: o.count("max_planes", d.max_planes)?,
                spheres: o.count("spheres", d.spheres)?,
                table_heights: o.count("table_heights", d.table_heights)?,
                table_angles: o.count("table_angles", d.table_angles)?,
                sphere_table_angles: o.count("sphere_table_angles", d.sphere_table_angles)?,
                sun_table_heights: o.count("sun_table_heights", d.sun_table_heights)?,
                sun_table_angles: o.count("sun_table_angles", d.sun_table_angles)?,
                ambient_directions: o.count("ambient_directions", d.ambient_directions)?,
                ambient_sun_angles: o.count("ambient_sun_angles", d.ambient_sun_angles)?,
            })
        })
    }

    /// Why these settings cannot be used, if they cannot.
    pub fn validate(&self) -> Result<(), ModelError> {
        let bad = |m: String| Err(ModelError::Settings(format!("dobashi: {m}")));
        if self.planes == 0 || self.interval_steps == 0 || self.max_planes == 0 {
            return bad("planes, interval_steps and max_planes must be at least 1".into());
        }
        if !(self.table_max.is_finite() && self.table_max > 0.0) {
            return bad(format!("table_max {} must be > 0", self.table_max));
        }
        if self.spheres < 2 {
            return bad(format!("spheres must be at least 2, got {}", self.spheres));
        }
        if self.table_heights < 2 || self.table_angles < 4 || !self.table_angles.is_multiple_of(2) {
            return bad(format!(
                "plane tables need at least 2 heights and an even number (>= 4) of angles, \
                 got {} x {}",
                self.table_heights, self.table_angles
            ));
        }
        if self.sphere_table_angles < 2 || self.ambient_sun_angles < 2 {
            return bad("sphere_table_angles and ambient_sun_angles must be at least 2".into());
        }
        if self.sun_table_heights < 2 || self.sun_table_angles < 2 {
            return bad("the g_l table must be at least 2 x 2".into());
        }
        if self.ambient_directions == 0 {
            return bad("ambient_directions must be at least 1".into());
        }
        Ok(())
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
