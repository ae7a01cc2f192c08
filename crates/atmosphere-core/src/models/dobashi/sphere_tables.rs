//! The sample spheres of Dobashi, Yamamoto and Nishita 2002, section 5.3 (Fig. 7, appendix A.2): for a camera far
//! out in space the view ray is cut where it crosses spheres concentric with the planet,
//! and dI'_r, dI'_m, dg'_v of the segment from sphere k to the next crossing depend only on
//! the direction at sphere k, so each sphere has 1D tables.
//!
//! From sphere k a ray goes on to one of three crossings, which are the three kinds of
//! segment: down to sphere k - 1 (the ground for k = 1), along a chord back to sphere k
//! (descending but missing sphere k - 1), or up to sphere k + 1. The kinds meet at
//! discontinuities of the segment's end, so each has its own row of entries, indexed by the
//! segment's length (equal steps between its shortest and longest); the table of all
//! spheres is one 2D grid of 3 rows per sphere. The paper does not place the spheres; here
//! they split the vertical column of air (Rayleigh density) into equal parts, so that each
//! layer scatters about as much light (section 5.3 leaves h_k free).

use rayon::prelude::*;

use crate::atmosphere::Atmosphere;
use crate::atmosphere::spectra::Spectra;
use crate::atmosphere::table_inputs::Inputs;
use crate::models::dobashi::grid::Grid;
use crate::models::dobashi::segment::{SegmentValues, integrate};
use crate::optics::column::column;
use crate::optics::geometry::{
    discriminant, distance_to_entry, distance_to_exit, ray_hits_ground, safe_sqrt,
};

/// The kind of a segment from a sample sphere: its row within the sphere's three.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Down = 0,
    Chord = 1,
    Up = 2,
}

/// One segment of a ray between two crossings of sample spheres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    pub kind: Kind,
    pub length_m: f64,
    /// The sphere where the segment ends and the ray's direction cosine there.
    pub next: usize,
    pub next_mu: f64,
}

/// dI'_r, dI'_m, dg'_v of every sample sphere.
#[derive(Clone, Debug, PartialEq)]
pub struct SphereTables {
    /// Radii of the spheres, from the ground (sphere 0) to the top of the atmosphere.
    pub radii_m: Vec<f64>,
    /// `entries` x (3 rows per sphere).
    pub scatter_r: Grid,
    /// `None` when pruned.
    pub scatter_m: Option<Grid>,
    pub transmittance: Grid,
}

impl SphereTables {
    /// Every coefficient and profile, as the plane tables.
    pub const INPUTS: Inputs = Inputs::EXTINCTION;

    /// Places `spheres` spheres and builds `entries` entries per sphere and kind.
    pub fn build(
        atmosphere: &Atmosphere,
        spectra: &Spectra,
        spheres: usize,
        entries: usize,
        with_mie: bool,
    ) -> SphereTables {
        let radii_m: Vec<f64> = sphere_heights(atmosphere, spheres)
            .into_iter()
            .map(|h| atmosphere.bottom_radius_m + h)
            .collect();
        let n_w = spectra.wavelengths_nm.len();
        let rows = 3 * spheres;
        let mut tables = SphereTables {
            radii_m,
            scatter_r: Grid::filled(entries, rows, n_w, 0.0),
            scatter_m: with_mie.then(|| Grid::filled(entries, rows, n_w, 0.0)),
            transmittance: Grid::filled(entries, rows, n_w, 1.0),
        };
        let kinds = [Kind::Down, Kind::Chord, Kind::Up];
        let values: Vec<Option<SegmentValues>> = (0..entries * rows)
            .into_par_iter()
            .map(|index| {
                let (i, row) = (index % entries, index / entries);
                let (k, kind) = (row / 3, kinds[row % 3]);
                let (d_min, d_max) = tables.length_range(k, kind)?;
                let d = d_min + (d_max - d_min) * i as f64 / (entries - 1) as f64;
                let mu = tables.mu_of(k, kind, d);
                let mut v = integrate(
                    atmosphere,
                    spectra,
                    tables.radii_m[k],
                    mu,
                    d,
                    &[d],
                    with_mie,
                );
                v.pop()
            })
            .collect();
        for (index, v) in values.iter().enumerate() {
            if let Some(v) = v {
                let (i, row) = (index % entries, index / entries);
                tables.scatter_r.set(i, row, &v.scatter_r);
                if let Some(m) = tables.scatter_m.as_mut() {
                    m.set(i, row, &v.scatter_m);
                }
                tables.transmittance.set(i, row, &v.transmittance);
            }
        }
        tables
    }

    /// Bytes of the tables.
    pub fn bytes(&self) -> usize {
        self.scatter_r.bytes()
            + self.scatter_m.as_ref().map_or(0, Grid::bytes)
            + self.transmittance.bytes()
    }

    /// The shortest and longest segment of a kind from sphere k; `None` for the kinds
    /// that do not exist (nothing below the ground, nothing above the top).
    fn length_range(&self, k: usize, kind: Kind) -> Option<(f64, f64)> {
        let r = self.radii_m[k];
        let chord_to = |other: f64| safe_sqrt((r - other).abs() * (r + other));
        match kind {
            Kind::Down if k > 0 => {
                let below = self.radii_m[k - 1];
                Some((r - below, chord_to(below)))
            }
            Kind::Chord if k > 0 => Some((0.0, 2.0 * chord_to(self.radii_m[k - 1]))),
            Kind::Up if k + 1 < self.radii_m.len() => {
                let above = self.radii_m[k + 1];
                Some((above - r, chord_to(above)))
            }
            _ => None,
        }
    }

    /// The direction cosine at sphere k of the segment of a kind and length d.
    fn mu_of(&self, k: usize, kind: Kind, d: f64) -> f64 {
        let r = self.radii_m[k];
        let towards = |other: f64| {
            if d <= 0.0 {
                return if other < r { -1.0 } else { 1.0 };
            }
            // other^2 = r^2 + d^2 + 2 r mu d.
            (((other - r) * (other + r) - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        };
        match kind {
            Kind::Down => towards(self.radii_m[k - 1]),
            Kind::Chord => (-d / (2.0 * r)).clamp(-1.0, 0.0),
            Kind::Up => towards(self.radii_m[k + 1]),
        }
    }

    /// The segment from sphere k along a ray whose direction cosine there is mu; `None`
    /// when the ray leaves the top sphere into space. Sphere 0 is the ground: a ray that
    /// reaches it ends there.
    pub fn step(&self, k: usize, mu: f64) -> Option<Step> {
        let r = self.radii_m[k];
        if mu < 0.0 && k > 0 {
            let below = self.radii_m[k - 1];
            let hits = if k == 1 {
                ray_hits_ground(r, mu, below)
            } else {
                discriminant(r, mu, below) >= 0.0
            };
            if hits {
                let d = distance_to_entry(r, mu, below).unwrap_or(0.0);
                return Some(Step {
                    kind: Kind::Down,
                    length_m: d,
                    next: k - 1,
                    next_mu: ((r * mu + d) / below).clamp(-1.0, 1.0),
                });
            }
            return Some(Step {
                kind: Kind::Chord,
                length_m: -2.0 * r * mu,
                next: k,
                next_mu: -mu,
            });
        }
        if k + 1 >= self.radii_m.len() {
            return None;
        }
        let above = self.radii_m[k + 1];
        let d = distance_to_exit(r, mu.max(0.0), above);
        Some(Step {
            kind: Kind::Up,
            length_m: d,
            next: k + 1,
            next_mu: ((r * mu.max(0.0) + d) / above).clamp(-1.0, 1.0),
        })
    }

    /// dI'_r, dI'_m (zero when pruned) and dg'_v of a segment from sphere `k`.
    pub fn lookup(&self, k: usize, step: &Step, out: &mut SegmentValues) {
        let (d_min, d_max) = self
            .length_range(k, step.kind)
            .expect("steps only take segments that exist");
        let x = if d_max > d_min {
            (step.length_m - d_min) / (d_max - d_min) * (self.scatter_r.width - 1) as f64
        } else {
            0.0
        };
        let y = (3 * k + step.kind as usize) as f64;
        self.scatter_r.sample(x, y, &mut out.scatter_r);
        match &self.scatter_m {
            Some(m) => m.sample(x, y, &mut out.scatter_m),
            None => out.scatter_m.fill(0.0),
        }
        self.transmittance.sample(x, y, &mut out.transmittance);
    }
}

/// Heights of `n` spheres from the ground to the top that split the vertical Rayleigh
/// column into equal parts (equal steps in height if there is no Rayleigh density).
pub fn sphere_heights(atmosphere: &Atmosphere, n: usize) -> Vec<f64> {
    let thickness = atmosphere.thickness_m();
    let below = |h: f64| column(atmosphere, atmosphere.bottom_radius_m, 1.0, h)[0];
    let total = below(thickness);
    (0..n)
        .map(|k| {
            let fraction = k as f64 / (n - 1) as f64;
            if k == 0 || k == n - 1 || total <= 0.0 {
                return fraction * thickness;
            }
            let (mut lo, mut hi) = (0.0, thickness);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if below(mid) < fraction * total {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// exp(-h / 8 km): h_k = -H ln(1 - k / (n - 1) (1 - exp(-Z / H))).
    #[test]
    fn spheres_split_the_air_column_equally() {
        let a = crate::atmosphere::presets::earth();
        let h = sphere_heights(&a, 10);
        let z = a.thickness_m();
        for (k, got) in h.iter().enumerate() {
            let f = k as f64 / 9.0 * (1.0 - (-z / 8_000.0f64).exp());
            let exact = -8_000.0 * (1.0 - f).ln();
            assert!((got - exact).abs() < 1e-3, "{k}: {got} vs {exact}");
        }
    }

    /// Walking a ray from the top sphere by steps reaches the ground where geometry says,
    /// and a ray missing the planet leaves at the top after the tangent point; every
    /// step's entry reproduces the segment integrated afresh.
    #[test]
    fn steps_follow_the_ray_and_tables_hold_the_segments() {
        let a = crate::atmosphere::presets::earth();
        let spectra = Spectra::new(&a, &[550.0]);
        let t = SphereTables::build(&a, &spectra, 6, 32, true);
        let top = a.top_radius_m;
        for mu in [-1.0, -0.5, -0.13, -0.1, -0.02] {
            let (mut k, mut m, mut travelled) = (5, mu, 0.0);
            while let Some(step) = t.step(k, m) {
                let mut got = SegmentValues {
                    scatter_r: vec![0.0],
                    scatter_m: vec![0.0],
                    transmittance: vec![0.0],
                };
                t.lookup(k, &step, &mut got);
                let v = &integrate(
                    &a,
                    &spectra,
                    t.radii_m[k],
                    m,
                    step.length_m,
                    &[step.length_m],
                    true,
                )[0];
                let err = (got.transmittance[0] - v.transmittance[0]).abs();
                assert!(err < 2e-3, "mu {mu}, sphere {k}: dg_v off by {err}");
                travelled += step.length_m;
                (k, m) = (step.next, step.next_mu);
                if k == 0 {
                    break;
                }
            }
            let expected = if ray_hits_ground(top, mu, a.bottom_radius_m) {
                assert_eq!(k, 0, "mu {mu}");
                distance_to_entry(top, mu, a.bottom_radius_m).unwrap()
            } else {
                assert_eq!(k, 5, "mu {mu}");
                distance_to_exit(top, mu, top)
            };
            assert!(
                (travelled - expected).abs() < 1e-3,
                "mu {mu}: {travelled} vs {expected}"
            );
        }
    }
}
