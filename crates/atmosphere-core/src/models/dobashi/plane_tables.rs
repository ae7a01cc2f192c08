//! The tables of the sampling planes (Dobashi, Yamamoto and Nishita 2002, section 5.2 and appendix A.2): dI_r, dI_m
//! and dg_v of a segment of fixed length Delta_t, as functions of the height h of its
//! start and the angle theta_v of its direction from the local vertical, and the interval
//! rule of section 4.2.1 that chooses Delta_t.
//!
//! The paper gives the axes (h, theta_v) but no spacing. Rows are at equal steps of
//! rho = sqrt(r^2 - R^2) (dense near the ground, where the Mie layer is; Bruneton 2017),
//! and the angle axis is split at the horizon: its first half holds rays that meet the
//! ground, at equal steps of the distance to the ground between its least (straight down)
//! and greatest (the horizon), its second half the others, at equal steps of the distance
//! to the top (Bruneton 2017's transmittance mapping, `transmittance_table`). A segment
//! stops where its ray leaves the atmosphere, so the two halves differ at the horizon and
//! are never interpolated across it; straight up, straight down and the horizon fall on
//! nodes at every height.

use rayon::prelude::*;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::bruneton::parameterization::Radii;
use crate::models::dobashi::grid::Grid;
use crate::models::dobashi::segment::{SegmentValues, integrate};
use crate::models::dobashi::settings::DobashiSettings;
use crate::optics::geometry::{distance_to_entry, distance_to_exit, ray_hits_ground};

/// dI_r, dI_m, dg_v over (h, theta_v) for one interval Delta_t.
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneTables {
    /// Delta_t, the distance between sampling planes, m.
    pub interval_m: f64,
    pub radii: Radii,
    pub scatter_r: Grid,
    /// `None` when pruned (no Mie scattering at any wavelength).
    pub scatter_m: Option<Grid>,
    pub transmittance: Grid,
}

impl PlaneTables {
    /// Every coefficient and profile: the segments' optical depths hold all of them.
    pub const INPUTS: Inputs = Inputs::EXTINCTION;

    /// Chooses Delta_t by the rule of section 4.2.1 and builds the tables for it. The rule:
    /// Delta_t = Delta_min, 2 Delta_min, ... while the largest value of dI_r and dI_m over
    /// the tables and wavelengths stays within I_max (`table_max`), up to Delta_max
    /// (`planes`); at least Delta_min. Since dI_r + dI_m <= 1 - dg_v < 1, with the
    /// paper's I_max = 1 the rule always reaches Delta_max.
    pub fn build(
        atmosphere: &Atmosphere,
        spectra: &Spectra,
        settings: &DobashiSettings,
        with_mie: bool,
    ) -> PlaneTables {
        let radii = Radii {
            bottom_m: atmosphere.bottom_radius_m,
            top_m: atmosphere.top_radius_m,
        };
        let delta_max = radii.horizon_length() / settings.planes as f64;
        let steps = settings.interval_steps;
        let lengths: Vec<f64> = (1..=steps)
            .map(|s| delta_max * s as f64 / steps as f64)
            .collect();
        let (width, height) = (settings.table_angles, settings.table_heights);
        let texel = |index: usize| texel_ray(&radii, width, height, index % width, index / width);

        // One pass to Delta_max, keeping each texel's largest value at every step.
        let passes: Vec<(Vec<f64>, SegmentValues)> = (0..width * height)
            .into_par_iter()
            .map(|index| {
                let (r, mu, clip) = texel(index);
                let mut values = integrate(atmosphere, spectra, r, mu, clip, &lengths, with_mie);
                let maxima = values.iter().map(largest).collect();
                (maxima, values.pop().expect("at least one step"))
            })
            .collect();
        let within = |s: usize| passes.iter().all(|(m, _)| m[s] <= settings.table_max);
        let chosen = (0..steps).take_while(|s| within(*s)).count().max(1);
        let interval_m = lengths[chosen - 1];
        let values: Vec<SegmentValues> = if chosen == steps {
            passes.into_iter().map(|(_, v)| v).collect()
        } else {
            (0..width * height)
                .into_par_iter()
                .map(|index| {
                    let (r, mu, clip) = texel(index);
                    let mut v =
                        integrate(atmosphere, spectra, r, mu, clip, &[interval_m], with_mie);
                    v.pop().expect("one length")
                })
                .collect()
        };

        let n_w = spectra.wavelengths_nm.len();
        let mut scatter_r = Grid::filled(width, height, n_w, 0.0);
        let mut scatter_m = with_mie.then(|| Grid::filled(width, height, n_w, 0.0));
        let mut transmittance = Grid::filled(width, height, n_w, 1.0);
        for (index, v) in values.iter().enumerate() {
            let (i, j) = (index % width, index / width);
            scatter_r.set(i, j, &v.scatter_r);
            if let Some(m) = scatter_m.as_mut() {
                m.set(i, j, &v.scatter_m);
            }
            transmittance.set(i, j, &v.transmittance);
        }
        PlaneTables {
            interval_m,
            radii,
            scatter_r,
            scatter_m,
            transmittance,
        }
    }

    /// Bytes of the tables.
    pub fn bytes(&self) -> usize {
        self.scatter_r.bytes()
            + self.scatter_m.as_ref().map_or(0, Grid::bytes)
            + self.transmittance.bytes()
    }

    /// The table coordinates (x, y) of a segment from (r, mu).
    fn coordinates(&self, r: f64, mu: f64) -> (f64, f64) {
        let half = self.scatter_r.width / 2;
        let (bottom, top) = (self.radii.bottom_m, self.radii.top_m);
        let r = r.clamp(bottom, top);
        let rho = self.radii.rho(r);
        let ground = ray_hits_ground(r, mu, bottom);
        let (d, d_min, d_max) = if ground {
            (
                distance_to_entry(r, mu, bottom).unwrap_or(0.0),
                r - bottom,
                rho,
            )
        } else {
            let h = self.radii.horizon_length();
            (distance_to_exit(r, mu, top), top - r, rho + h)
        };
        let unit = if d_max > d_min {
            ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let x = unit * (half - 1) as f64 + if ground { 0.0 } else { half as f64 };
        (x, self.radii.u_r(r) * (self.scatter_r.height - 1) as f64)
    }

    /// dI_r, dI_m (zero when pruned) and dg_v of the segment of length Delta_t from
    /// (r, mu), or up to where its ray leaves the atmosphere.
    pub fn lookup(&self, r: f64, mu: f64, out: &mut SegmentValues) {
        let (x, y) = self.coordinates(r, mu);
        self.scatter_r.sample(x, y, &mut out.scatter_r);
        match &self.scatter_m {
            Some(m) => m.sample(x, y, &mut out.scatter_m),
            None => out.scatter_m.fill(0.0),
        }
        self.transmittance.sample(x, y, &mut out.transmittance);
    }

    /// The length of the segment the table holds for (r, mu): Delta_t, or less where the
    /// ray leaves the atmosphere first.
    pub fn segment_length(&self, r: f64, mu: f64) -> f64 {
        let (bottom, top) = (self.radii.bottom_m, self.radii.top_m);
        let r = r.clamp(bottom, top);
        let exit = if ray_hits_ground(r, mu, bottom) {
            distance_to_entry(r, mu, bottom).unwrap_or(0.0)
        } else {
            distance_to_exit(r, mu, top)
        };
        exit.min(self.interval_m)
    }
}

/// The ray of node (i, j): radius, direction cosine, and the distance to where it leaves
/// the atmosphere (the ground in the first half of the columns, the top in the second).
fn texel_ray(radii: &Radii, width: usize, height: usize, i: usize, j: usize) -> (f64, f64, f64) {
    let half = width / 2;
    let r = radii.r_from_u(j as f64 / (height - 1) as f64);
    let rho = radii.rho(r);
    let h = radii.horizon_length();
    let ground = i < half;
    let x = (i % half) as f64 / (half - 1) as f64;
    let (d_min, d_max) = if ground {
        (r - radii.bottom_m, rho)
    } else {
        (radii.top_m - r, rho + h)
    };
    let d = d_min + x * (d_max - d_min).max(0.0);
    if d <= 0.0 {
        return (r, if ground { -1.0 } else { 1.0 }, 0.0);
    }
    // R^2 = r^2 + d^2 + 2 r mu d towards the ground; R_top^2 likewise towards the top.
    let mu = if ground {
        -(rho * rho + d * d) / (2.0 * r * d)
    } else {
        (h * h - rho * rho - d * d) / (2.0 * r * d)
    };
    (r, mu.clamp(-1.0, 1.0), d)
}

/// The largest dI_r or dI_m over the wavelengths.
fn largest(v: &SegmentValues) -> f64 {
    v.scatter_r
        .iter()
        .chain(&v.scatter_m)
        .cloned()
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(planes: usize, table_max: f64) -> DobashiSettings {
        DobashiSettings {
            planes,
            table_max,
            table_heights: 8,
            table_angles: 16,
            ..DobashiSettings::default()
        }
    }

    /// Section 4.2.1: with I_max = 1 the interval reaches Delta_max; with I_max at half
    /// the largest value at Delta_max it stops at the multiple s Delta_min whose table is
    /// within I_max while the segments of (s + 1) Delta_min, integrated afresh, are not.
    #[test]
    fn interval_rule_stops_below_table_max() {
        let a = crate::atmosphere::presets::earth();
        let spectra = Spectra::new(&a, &[680.0, 550.0, 440.0]);
        let max_of = |t: &PlaneTables| t.scatter_r.data.iter().cloned().fold(0.0f32, f32::max);
        let full = PlaneTables::build(&a, &spectra, &small(100, 1.0), true);
        let delta_max = (a.top_radius_m.powi(2) - a.bottom_radius_m.powi(2)).sqrt() / 100.0;
        assert!((full.interval_m / delta_max - 1.0).abs() < 1e-12);
        let limit = 0.5 * max_of(&full) as f64;
        let limited = PlaneTables::build(&a, &spectra, &small(100, limit), true);
        let step = delta_max / 10.0;
        let s = (limited.interval_m / step).round() as usize;
        assert!((1..10).contains(&s), "{}", limited.interval_m);
        assert!((limited.interval_m / (s as f64 * step) - 1.0).abs() < 1e-12);
        assert!(max_of(&limited) as f64 <= limit * (1.0 + 1e-6));
        let longer = (0..16 * 8)
            .map(|index| {
                let (r, mu, clip) = texel_ray(&limited.radii, 16, 8, index % 16, index / 16);
                let v = integrate(&a, &spectra, r, mu, clip, &[(s + 1) as f64 * step], true);
                largest(&v[0])
            })
            .fold(0.0, f64::max);
        assert!(longer > limit, "{longer} vs {limit}");
    }

    /// Every node of the default table holds the segment integrated afresh at its own
    /// ray, within f32 rounding.
    #[test]
    fn nodes_hold_their_segments() {
        let a = crate::atmosphere::presets::earth();
        let spectra = Spectra::new(&a, &[440.0]);
        let s = small(100, 1.0);
        let t = PlaneTables::build(&a, &spectra, &s, true);
        for (i, j) in [(0, 3), (3, 2), (7, 5), (8, 1), (9, 4), (12, 7), (15, 3)] {
            let (r, mu, clip) = texel_ray(&t.radii, 16, 8, i, j);
            let v = &integrate(&a, &spectra, r, mu, clip, &[t.interval_m], true)[0];
            let mut got = SegmentValues {
                scatter_r: vec![0.0],
                scatter_m: vec![0.0],
                transmittance: vec![0.0],
            };
            t.lookup(r, mu, &mut got);
            assert!(
                (got.scatter_r[0] - v.scatter_r[0]).abs() <= 1e-6 * v.scatter_r[0] + 1e-12,
                "({i}, {j}): {} vs {}",
                got.scatter_r[0],
                v.scatter_r[0]
            );
            assert!((got.transmittance[0] - v.transmittance[0]).abs() < 1e-6);
        }
    }
}
