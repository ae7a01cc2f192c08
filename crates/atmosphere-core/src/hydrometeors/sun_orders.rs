//! The sun's light scattered two and more times inside a volume, which single scattering
//! leaves out (about a third of a rain shaft's or a droplet deck's own light). A grid of
//! probes across the volume holds the diffuse radiance L_d(x, w) there, the sun's light
//! scattered one and more times travelling along w, by its first two moments
//!     J(x) = (1 / 4 pi) int L_d dw,     H(x) = (1 / 4 pi) int L_d w dw,
//! per channel, for a sun of unit irradiance (the moments of the Eddington
//! approximation, Joseph, Wiscombe and Weinman 1976, here estimated instead of solved
//! for, so that a finite cylinder is handled like a slab; a grid of a light field's low
//! moments per volume is the way of irradiance volumes and light probes). Between them
//! the radiance is read as a Henyey-Greenstein lobe about H of mean cosine G = |H| / J,
//! L_d(w') = 4 pi J p_HG(w' . H / |H|; G): a medium of albedo 1 scatters it towards w
//! with the convolution of the two lobes, whose Legendre coefficients multiply
//! ([`lobe_table`]). The first two terms alone (J + 3 g_c w . H, exact for a radiance
//! linear in direction) overstate a forward-peaked medium's side light
//! (docs/optics-rendering.md compares the two). Each step of the march adds
//! T_v (1 - e^(-beta dt)) E_sun S(x, w) beside the single scattering (`render.rs`).
//!
//! A probe's moments are a Monte Carlo estimate over directions w stratified across the
//! sphere: the light arriving at x along w comes from collisions on the ray back from x,
//! drawn from e^(-beta t) cut at the volume's edge (weight 1 - T), where the volumes'
//! path tracer (`reference/path.rs`) follows the light scattered towards w (every order,
//! the sun's next-event estimate, the sky left out: its light is `sky_light.rs`'s). The
//! sun is the same everywhere (the march's one value per volume), so the probes depend
//! on the volume, its table and the sun's direction only. Probes sit at cell centres:
//! - shaft: radius rho / R, azimuth from the sun's vertical plane through the axis (0 to
//!   pi: the light is symmetric about that plane), height z / h;
//! - layer: one column on the vertical of its light point, at the fraction
//!   (r^2 - R_b^2) / (R_t^2 - R_b^2) of the shell (a homogeneous shell under a distant
//!   sun is horizontally uniform about the camera);
//!
//! and are read trilinearly between centres, the end cells' values beyond them.

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::channel_phase::{ChannelPhase, between_centres};
use super::reference::path::{UniformSun, VolumePaths, trace_from_cut};
use super::reference::phase::ChannelSampler;
use super::volumes::{Shape, Volume};
use crate::numerics::sampling::{Sampler, mix_seed};
use crate::optics::legendre_series::LegendreSeries;

/// A shaft's probes across its radius, its azimuth and its height.
pub const SHAFT_PROBES: [usize; 3] = [4, 6, 8];
/// A layer's probes across its thickness.
pub const LAYER_PROBES: usize = 16;
/// Directions per probe and channel: cosine strata times azimuth strata, at most; a
/// quarter and a sixteenth of them where the volume is thick ([`probe_strata`]).
pub const PROBE_STRATA: [usize; 2] = [32, 64];
/// A probe's paths are cut after this many collisions (the light of longer paths, deep
/// in an optically thick volume, left out).
pub const PROBE_MAX_SCATTERINGS: u32 = 128;
/// The collisions the probes of one volume may take, about (the strata are cut to keep
/// within it).
pub const PROBE_COLLISION_BUDGET: f64 = 2e7;
const SEED: u64 = 0x0b5e_55ed;
/// The lobe table's G from 0 to [`LOBE_G_MAX`] in equal steps, and its angles alpha from
/// 0 to 180 degrees in equal steps (nodes at both ends).
pub const LOBE_G_STEPS: usize = 32;
pub const LOBE_G_MAX: f64 = 0.9;
pub const LOBE_ANGLES: usize = 91;
/// The Legendre series' degree (G^L below 1e-9 at G = 0.9).
const LOBE_DEGREE: usize = 200;

/// Whether the march adds the sun's light scattered more than once.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum MultipleScattering {
    /// From the grid of probes ([`SunOrders`]).
    #[default]
    Probes,
    /// Left out: single scattering of the sun only.
    None,
}

impl MultipleScattering {
    /// The setting's name on command lines and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            MultipleScattering::Probes => "probes",
            MultipleScattering::None => "none",
        }
    }
}

/// The probes of a volume's diffuse light from the sun.
#[derive(Clone, Debug, PartialEq)]
pub struct SunOrders {
    /// Probes across radius, azimuth and height (a layer: 1, 1, n).
    pub dims: [usize; 3],
    /// Per probe (radius fastest, then azimuth, then height) and channel: J, H_x, H_y,
    /// H_z (planet-centred axes), for a sun of unit irradiance, sr^-1.
    pub moments: Vec<[[f64; 4]; 3]>,
    /// Per channel, the lobe's light S / J at [`LOBE_G_STEPS`] G (rows) and
    /// [`LOBE_ANGLES`] angles alpha (columns): [`lobe_table`].
    pub lobes: Vec<[f64; 3]>,
}

/// A shaft's axes for the probes' azimuth: the unit vertical, and the unit horizontal
/// towards the sun (`None` with the sun overhead, where every azimuth is alike).
fn shaft_axes(axis: DVec3, sun: DVec3) -> Option<DVec3> {
    let flat = sun - axis * sun.dot(axis);
    (flat.length() >= 1e-6).then(|| flat.normalize())
}

/// Where `x` lies in `volume` as fractions of its grid's three extents (radius, azimuth,
/// height), with the sun towards the unit `sun`.
pub fn grid_fractions(volume: &Volume, sun: DVec3, x: DVec3) -> [f64; 3] {
    match volume.shape {
        Shape::Shaft {
            axis,
            ground_radius_m,
            radius_m,
            height_m,
        } => {
            let p = x - axis * ground_radius_m;
            let z = p.dot(axis);
            let radial = p - axis * z;
            let azimuth = shaft_axes(axis, sun).map_or(0.0, |towards| {
                let across = axis.cross(towards);
                radial.dot(across).abs().atan2(radial.dot(towards)) / PI
            });
            [radial.length() / radius_m, azimuth, z / height_m]
        }
        Shape::Layer(shell) => {
            let base = shell.base_radius_m.powi(2);
            let depth = (x.length_squared() - base) / (shell.top_radius_m.powi(2) - base);
            [0.0, 0.0, depth]
        }
    }
}

/// The probe at cell `(i, j, k)` of `dims` in `volume`, the layer's column through
/// `anchor`.
fn probe_point(
    volume: &Volume,
    sun: DVec3,
    anchor: DVec3,
    dims: [usize; 3],
    [i, j, k]: [usize; 3],
) -> DVec3 {
    let centre = |n: usize, i: usize| (i as f64 + 0.5) / n as f64;
    match volume.shape {
        Shape::Shaft {
            axis,
            ground_radius_m,
            radius_m,
            height_m,
        } => {
            let towards = shaft_axes(axis, sun).unwrap_or_else(|| axis.any_orthonormal_vector());
            let across = axis.cross(towards);
            let azimuth = PI * centre(dims[1], j);
            axis * (ground_radius_m + height_m * centre(dims[2], k))
                + (towards * azimuth.cos() + across * azimuth.sin())
                    * (radius_m * centre(dims[0], i))
        }
        Shape::Layer(shell) => {
            let base = shell.base_radius_m.powi(2);
            let top = shell.top_radius_m.powi(2);
            anchor.normalize() * (base + (top - base) * centre(dims[2], k)).sqrt()
        }
    }
}

/// `i` and the fraction `t` for reading `n` cells at the fraction `f` of their extent,
/// linear between centres (one cell: itself).
fn cell_between(f: f64, n: usize) -> (usize, f64) {
    if n < 2 {
        return (0, 0.0);
    }
    between_centres(f, 1.0 / n as f64, n)
}

impl SunOrders {
    /// The probes of `volume` for the truncated tables of `phase`, the sun towards the
    /// unit `sun`, a layer's column through `anchor`.
    pub fn estimate(
        volume: &Volume,
        phase: &ChannelSampler,
        sun: DVec3,
        anchor: DVec3,
    ) -> SunOrders {
        let dims = match volume.shape {
            Shape::Shaft { .. } => SHAFT_PROBES,
            Shape::Layer(_) => [1, 1, LAYER_PROBES],
        };
        let unit_sun = UniformSun([1.0; 3]);
        let paths = VolumePaths {
            volume,
            phase,
            sun: &unit_sun,
            environment: None,
            sun_direction: sun,
        };
        let probes = dims.iter().product::<usize>();
        let strata = probe_strata(volume, phase, probes);
        let moments = (0..probes)
            .into_par_iter()
            .map(|n| {
                let cell = [n % dims[0], n / dims[0] % dims[1], n / (dims[0] * dims[1])];
                let x = probe_point(volume, sun, anchor, dims, cell);
                let seed = mix_seed(&[SEED, n as u64]);
                std::array::from_fn(|c| probe_moments(&paths, c, x, (seed, strata)))
            })
            .collect();
        SunOrders {
            dims,
            moments,
            lobes: lobe_table(phase.table()),
        }
    }

    /// J, H_x, H_y, H_z per channel at `x` in `volume` (trilinear between the probes).
    pub fn moments_at(&self, volume: &Volume, sun: DVec3, x: DVec3) -> [[f64; 4]; 3] {
        let f = grid_fractions(volume, sun, x);
        let [(i, s), (j, t), (k, u)] = std::array::from_fn(|a| cell_between(f[a], self.dims[a]));
        let mut out = [[0.0; 4]; 3];
        for (dk, wk) in [(0, 1.0 - u), (1, u)] {
            for (dj, wj) in [(0, 1.0 - t), (1, t)] {
                for (di, wi) in [(0, 1.0 - s), (1, s)] {
                    let w = wi * wj * wk;
                    if w == 0.0 {
                        continue;
                    }
                    let index = ((k + dk) * self.dims[1] + j + dj) * self.dims[0] + i + di;
                    for (o, m) in out.iter_mut().zip(&self.moments[index]) {
                        for (a, b) in o.iter_mut().zip(m) {
                            *a += w * b;
                        }
                    }
                }
            }
        }
        out
    }

    /// The light a unit of scattering sends along the unit `toward` at `x`, per channel,
    /// for a sun of unit irradiance: J times the lobe table at G = |H| / J and the angle
    /// between `toward` and H.
    pub fn source(&self, volume: &Volume, sun: DVec3, x: DVec3, toward: DVec3) -> [f64; 3] {
        let m = self.moments_at(volume, sun, x);
        std::array::from_fn(|c| {
            let (j, h) = (m[c][0], DVec3::new(m[c][1], m[c][2], m[c][3]));
            if j <= 0.0 {
                return 0.0;
            }
            let length = h.length();
            let cos = if length > 0.0 {
                toward.dot(h) / length
            } else {
                1.0
            };
            let g = (length / j).min(LOBE_G_MAX) / LOBE_G_MAX * (LOBE_G_STEPS - 1) as f64;
            let a = cos.clamp(-1.0, 1.0).acos() / PI * (LOBE_ANGLES - 1) as f64;
            // Nodes at both ends: a node is a bin of width 1 centred on it.
            let (gi, gt) = between_centres(g + 0.5, 1.0, LOBE_G_STEPS);
            let (ai, at) = between_centres(a + 0.5, 1.0, LOBE_ANGLES);
            let v = |r: usize, k: usize| self.lobes[r * LOBE_ANGLES + k][c];
            let low = v(gi, ai) * (1.0 - at) + v(gi, ai + 1) * at;
            let high = v(gi + 1, ai) * (1.0 - at) + v(gi + 1, ai + 1) * at;
            j * (low * (1.0 - gt) + high * gt).max(0.0)
        })
    }
}

/// The light a medium of table `phase` scatters out of a diffuse radiance shaped as a
/// Henyey-Greenstein lobe of mean cosine G about its flux, L_d(w') = 4 pi J p_HG(w' . h;
/// G) (first moment J G h), towards w at the angle alpha from h, over J: the
/// convolution of the two lobes on the sphere multiplies their Legendre coefficients,
///     S / J = sum_l (2l + 1) chi_l,c G^l P_l(cos alpha),
/// chi_l,c the table's coefficients. Rows G at [`LOBE_G_STEPS`] steps to
/// [`LOBE_G_MAX`], columns alpha at [`LOBE_ANGLES`] steps over 0 to 180 degrees.
pub fn lobe_table(phase: &ChannelPhase) -> Vec<[f64; 3]> {
    let rule = phase.cosine_rule();
    let series: [LegendreSeries; 3] = std::array::from_fn(|c| {
        let values: Vec<f64> = phase.values.iter().map(|v| v[c]).collect();
        LegendreSeries::from_gauss_rule(&rule, &values, LOBE_DEGREE)
    });
    let mut table = Vec::with_capacity(LOBE_G_STEPS * LOBE_ANGLES);
    for r in 0..LOBE_G_STEPS {
        let g = LOBE_G_MAX * r as f64 / (LOBE_G_STEPS - 1) as f64;
        let lobes: [LegendreSeries; 3] = std::array::from_fn(|c| {
            LegendreSeries::from_coefficients(
                series[c]
                    .coefficients()
                    .iter()
                    .enumerate()
                    .map(|(l, chi)| chi * g.powi(l as i32))
                    .collect(),
            )
        });
        for k in 0..LOBE_ANGLES {
            let cos = (PI * k as f64 / (LOBE_ANGLES - 1) as f64).cos();
            table.push(std::array::from_fn(|c| 4.0 * PI * lobes[c].eval(cos)));
        }
    }
    table
}

/// The probes' strata for `volume`: [`PROBE_STRATA`], halved on both axes while the
/// collisions their paths are expected to take pass [`PROBE_COLLISION_BUDGET`] (to a
/// sixteenth at most). A path in a volume of optical size tau (the shaft's radius or
/// height, the layer's thickness, whichever is less, at the least truncated extinction)
/// collides about 1 + tau^2 times before it leaves (a random walk), at most
/// [`PROBE_MAX_SCATTERINGS`].
fn probe_strata(volume: &Volume, phase: &ChannelSampler, probes: usize) -> [usize; 2] {
    let size = match volume.shape {
        Shape::Shaft {
            radius_m, height_m, ..
        } => radius_m.min(height_m),
        Shape::Layer(shell) => shell.top_radius_m - shell.base_radius_m,
    };
    let least_cut = phase.peak.peak_fraction.iter().copied().fold(1.0, f64::min);
    let tau = volume.extinction_per_m * (1.0 - least_cut) * size;
    let collisions = (1.0 + tau * tau).min(f64::from(PROBE_MAX_SCATTERINGS));
    let mut strata = PROBE_STRATA;
    for _ in 0..2 {
        let paths = (strata[0] * strata[1] * probes * 3) as f64;
        if paths * collisions <= PROBE_COLLISION_BUDGET {
            break;
        }
        strata = strata.map(|n| n / 2);
    }
    strata
}

/// J, H_x, H_y, H_z of channel `c` at `x` from `strata` directions, one per stratum of
/// the cosine and the azimuth, their sampler seeded by `seed`.
fn probe_moments(
    paths: &VolumePaths,
    c: usize,
    x: DVec3,
    (seed, strata): (u64, [usize; 2]),
) -> [f64; 4] {
    let beta = paths.extinction(c);
    let mut sampler = Sampler::new(mix_seed(&[seed, c as u64]));
    let [m_strata, a_strata] = strata;
    let mut sum = [0.0; 4];
    for m in 0..m_strata {
        for a in 0..a_strata {
            let cos = 1.0 - 2.0 * (m as f64 + sampler.uniform()) / m_strata as f64;
            let phi = 2.0 * PI * (a as f64 + sampler.uniform()) / a_strata as f64;
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let w = DVec3::new(sin * phi.cos(), sin * phi.sin(), cos);
            let edge = paths.volume.exit_distance(x, -w);
            let transmittance = (-beta * edge).exp();
            if transmittance >= 1.0 {
                continue;
            }
            let t = -(1.0 - sampler.uniform() * (1.0 - transmittance)).ln() / beta;
            let y = x - w * t.min(edge);
            let [single, multiple, _] =
                trace_from_cut(paths, c, (y, -w), &mut sampler, PROBE_MAX_SCATTERINGS);
            let light = (single + multiple) * (1.0 - transmittance);
            sum[0] += light;
            sum[1] += light * w.x;
            sum[2] += light * w.y;
            sum[3] += light * w.z;
        }
    }
    sum.map(|s| s / (m_strata * a_strata) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clouds::layer::shell::Shell;

    /// A table of `bins` bins over 0-180 degrees: Henyey-Greenstein of asymmetry `g`.
    fn henyey_greenstein(g: f64, bins: usize) -> ChannelPhase {
        let bin_deg = 180.0 / bins as f64;
        let values = (0..bins)
            .map(|b| {
                let mu = ((b as f64 + 0.5) * bin_deg).to_radians().cos();
                let p = (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * mu).powf(1.5));
                [p; 3]
            })
            .collect();
        ChannelPhase {
            bin_deg,
            sky: None,
            values,
        }
    }

    #[test]
    fn the_lobes_keep_the_light_and_an_isotropic_medium_scatters_j() {
        // (1 / 4 pi) int S / J dw = 1 for every G: the scattered light's mean is J.
        let table = lobe_table(&henyey_greenstein(0.7, 1800));
        for r in [0, 10, LOBE_G_STEPS - 1] {
            let row = &table[r * LOBE_ANGLES..(r + 1) * LOBE_ANGLES];
            let step = PI / (LOBE_ANGLES - 1) as f64;
            // The trapezoid in alpha of S / J sin(alpha) / 2.
            let mean: f64 = row
                .iter()
                .enumerate()
                .map(|(k, v)| {
                    let w = if k == 0 || k == LOBE_ANGLES - 1 {
                        0.5
                    } else {
                        1.0
                    };
                    w * v[1] * (k as f64 * step).sin() * step / 2.0
                })
                .sum();
            assert!((mean - 1.0).abs() < 2e-3, "row {r}: {mean}");
        }
        // Two Henyey-Greenstein lobes convolve into one of the product of their mean
        // cosines: forward, at the largest G, 4 pi p_HG(1; 0.7 G).
        let g = LOBE_G_MAX;
        let product = 0.7 * g;
        let forward = (1.0 + product) / (1.0 - product).powi(2);
        let read = table[(LOBE_G_STEPS - 1) * LOBE_ANGLES][0];
        assert!(
            (read / forward - 1.0).abs() < 1e-3,
            "{read} against {forward}"
        );
        // An isotropic medium sends J every way, whatever the lobe.
        let flat = lobe_table(&henyey_greenstein(0.0, 1800));
        let worst = flat.iter().map(|v| (v[2] - 1.0).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-4, "{worst}");
    }

    #[test]
    fn every_probe_sits_at_its_cells_centre() {
        let ground = 6_360e3;
        let sun = DVec3::new(0.5, 0.3, 0.8).normalize();
        let shaft = Volume::rain_shaft(DVec3::X * ground, ground, 1_000.0, 3_000.0, 5.0).unwrap();
        let layer = Volume {
            shape: Shape::Layer(Shell {
                ground_radius_m: ground,
                base_radius_m: ground + 8_000.0,
                top_radius_m: ground + 9_000.0,
            }),
            ..shaft
        };
        for (volume, dims) in [(shaft, SHAFT_PROBES), (layer, [1, 1, LAYER_PROBES])] {
            for cell in [
                [0, 0, 0],
                [dims[0] - 1, dims[1] - 1, dims[2] - 1],
                [0, 1, 2],
            ] {
                let cell = std::array::from_fn(|a| cell[a].min(dims[a] - 1));
                let x = probe_point(&volume, sun, DVec3::X, dims, cell);
                let f = grid_fractions(&volume, sun, x);
                for a in 0..3 {
                    if dims[a] > 1 {
                        let centre = (cell[a] as f64 + 0.5) / dims[a] as f64;
                        assert!((f[a] - centre).abs() < 1e-9, "{cell:?} axis {a}: {f:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_setting_reads_back_by_name() {
        for setting in [MultipleScattering::Probes, MultipleScattering::None] {
            let text = format!("v = \"{}\"", setting.name());
            let read: std::collections::BTreeMap<String, MultipleScattering> =
                toml::from_str(&text).unwrap();
            assert_eq!(read["v"], setting);
        }
        assert_eq!(MultipleScattering::default(), MultipleScattering::Probes);
    }
}
