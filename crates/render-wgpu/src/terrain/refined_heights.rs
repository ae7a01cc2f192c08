//! Relief below the data's resolution: the data's height plus deterministic detail down to
//! a few metres, zero-mean over every data cell, then held to the coastline of a finer
//! land/sea mask (docs/terrain.md, "Refinement").
//!
//! In the data's grid coordinates `(s, t)` (columns from 180 deg west, rows from the north
//! pole; data cell `(i, j)` is the square `[i, i + 1] x [j, j + 1]`) the detail is the mixed
//! derivative
//!
//! `D = d2(A P) / ds dt`,  `P(s, t) = sum_k a_k 4^-k N_k(2^k s, 2^k t)`,
//!
//! with `A` the relief amplitude (`relief_amplitude.rs`: a quadratic B-spline, rough in
//! mountains, smooth on plains and the sea floor) and `N_k` gradient noise on a lattice of
//! `2^k` cells per data cell (`detail_noise.rs`), `a_k = roughness^k` the octaves' weights.
//! Gradient noise vanishes at its lattice points, which include every data cell's corners,
//! so `G = A P` is 0 at all corners and the integral of `D` over a data cell is
//! `G(s1, t1) - G(s0, t1) - G(s1, t0) + G(s0, t0) = 0` exactly (the fundamental theorem
//! of calculus, twice): a refined cell averages back to the data's, whatever the octaves.
//! `D = A_st P + A_s P_t + A_t P_s + A P_st` is continuous (`A` has continuous first and
//! mixed derivatives, `N_k` is C2), a pure function of the direction: the same place gets
//! the same height at every level of detail, in every chunk and after a restart.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec3;

use super::coastline::{CoastSettings, constrain_to_coast};
use super::detail_noise::gradient_noise;
use super::geo_grid::lat_lon;
use super::height_field::HeightField;
use super::height_map::HeightMap;
use super::land_mask::LandMask;
use super::relief_amplitude::{AmplitudeSettings, ReliefAmplitude};

/// What the refinement adds, and how the coast holds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefinementSettings {
    /// Octaves: the finest has `2^(octaves - 1)` lattice cells per data cell.
    pub octaves: u32,
    /// Each octave's weight relative to the one before.
    pub roughness: f64,
    /// Picks the noise's gradients.
    pub seed: u64,
    pub amplitude: AmplitudeSettings,
    pub coast: CoastSettings,
}

impl Default for RefinementSettings {
    /// 14 octaves: the finest lattice is 1/8192 of a 10' cell, about 2.3 m.
    fn default() -> RefinementSettings {
        RefinementSettings {
            octaves: 14,
            roughness: 0.55,
            seed: 0x61_74_6D_6F_73,
            amplitude: AmplitudeSettings {
                land_gain: 0.6,
                sea_gain: 0.15,
                land_floor_m: 4.0,
                cap_m: 900.0,
            },
            coast: CoastSettings {
                lift_m: 1.0,
                depth_m: 2.0,
            },
        }
    }
}

/// The data's heights refined below their resolution (see the module documentation).
#[derive(Clone, Debug)]
pub struct RefinedHeights {
    pub data: HeightMap,
    pub mask: Option<LandMask>,
    pub settings: RefinementSettings,
    amplitude: ReliefAmplitude,
}

impl RefinedHeights {
    /// Refines `data`, held to the coastline of `mask` where one is given.
    pub fn new(
        data: HeightMap,
        mask: Option<LandMask>,
        settings: RefinementSettings,
    ) -> RefinedHeights {
        let amplitude = ReliefAmplitude::new(&data, &settings.amplitude);
        RefinedHeights {
            data,
            mask,
            settings,
            amplitude,
        }
    }

    /// The data's grid coordinates `(s, t)` of a latitude and longitude (radians).
    pub fn grid_coordinates(&self, lat_rad: f64, lon_rad: f64) -> (f64, f64) {
        (
            (lon_rad + PI) / TAU * self.data.width as f64,
            (FRAC_PI_2 - lat_rad) / PI * self.data.height as f64,
        )
    }

    /// The detail `D` at grid coordinates `(s, t)`, metres.
    pub fn detail_m(&self, s: f64, t: f64) -> f64 {
        let a = self.amplitude.at(s, t);
        if a.value == 0.0 && a.ds == 0.0 && a.dt == 0.0 && a.dsdt == 0.0 {
            return 0.0;
        }
        let (mut p, mut p_s, mut p_t, mut p_st) = (0.0, 0.0, 0.0, 0.0);
        let mut weight = 1.0;
        for k in 0..self.settings.octaves {
            let scale = (1u64 << k) as f64;
            let period = self.data.width as i64 * (1i64 << k);
            let n = gradient_noise(s * scale, t * scale, period, k, self.settings.seed);
            // a_k 4^-k N_k(2^k s, 2^k t) and its derivatives in s and t.
            let c = weight / (scale * scale);
            p += c * n.value;
            p_s += c * scale * n.dx;
            p_t += c * scale * n.dy;
            p_st += weight * n.dxdy;
            weight *= self.settings.roughness;
        }
        a.dsdt * p + a.ds * p_t + a.dt * p_s + a.value * p_st
    }

    /// The height before the coastline holds it: data plus detail, metres.
    pub fn unconstrained_m(&self, lat_rad: f64, lon_rad: f64) -> f64 {
        let (s, t) = self.grid_coordinates(lat_rad, lon_rad);
        self.data.sample(lat_rad, lon_rad) + self.detail_m(s, t)
    }
}

impl HeightField for RefinedHeights {
    fn height_m(&self, direction: DVec3) -> f64 {
        let (lat, lon) = lat_lon(direction);
        let h = self.unconstrained_m(lat, lon);
        match &self.mask {
            Some(mask) => constrain_to_coast(h, mask.land_fraction(lat, lon), &self.settings.coast),
            None => h,
        }
    }

    /// The data's bound plus the detail's: `|D|` is at most the largest amplitude times
    /// the sum over octaves of the bounds of the noise's terms (a generous bound).
    fn max_abs_height_m(&self) -> f64 {
        // |N_xy| <= 42 and |N_x|, |N_y|, |N| <= 6 on the lattice (fade' <= 15/8).
        let octaves: f64 = (0..self.settings.octaves)
            .map(|k| self.settings.roughness.powi(k as i32) * (42.0 + 3.0 * 6.0))
            .sum();
        self.data.max_abs_height_m() + self.amplitude.max_m() * 4.0 * octaves
    }

    /// The finest octave's lattice spacing along a meridian.
    fn sample_spacing_rad(&self) -> f64 {
        PI / self.data.height as f64 / (1u64 << (self.settings.octaves - 1)) as f64
    }
}
