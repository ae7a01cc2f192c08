//! Phase functions of rain, droplets and ice at many wavelengths across the visible,
//! seen with the sun's disc: what the bows, glories and halos are rendered with. Rain by
//! geometric optics ([`super::drop_rays`]) with the Marshall-Palmer (1948) drops'
//! diffraction; small drops and cloud droplets by Lorenz-Mie ([`super::mie_droplets`]);
//! ice by the ray tracer of `optics/ice/` (randomly oriented hexagonal crystals, the
//! same rays at every wavelength so that the halos' colours are not the rays' noise).
//! Each wavelength is tabulated in bins of [`BIN_DEG`] and averaged over the sun's disc
//! ([`super::sun_disk_blur`]). Falling plates (sundogs) scatter by azimuth too: their
//! tables are over the sky's two angles ([`SKY_GRID`], `optics/ice/sky_table.rs`), the
//! sun's disc in their rays. [`SpectralPhase::build_cached`] keeps the tables in a
//! [`TableCache`] between runs.

use std::f64::consts::PI;

use rayon::prelude::*;

use super::drop_rays::{diffraction_bins, geometric_bins};
use super::error::{HydrometeorError, check_range};
use super::mie_droplets::Droplets;
use super::sun_disk_blur::blur_with_sun_disk;
use crate::optics::ice::crystal::HexagonalPrism;
use crate::optics::ice::orientation::Orientation;
use crate::optics::ice::phase_table::{IcePhaseError, RaySettings, ice_phase_table};
use crate::optics::ice::sky_table::{PlateSky, SkyGrid, plate_sky_table};
use crate::optics::mie::marshall_palmer::{MarshallPalmer, RADIUS_RANGE_M};
use crate::optics::refractive_index::ice::ice_refractive_index;
use crate::optics::refractive_index::water::water_refractive_index;
use crate::table_cache::TableCache;

/// The width of the tables' angle bins, degrees: a fifth of the sun's radius.
pub const BIN_DEG: f64 = 0.05;
/// The wavelengths the tables span, nm.
pub const WAVELENGTH_RANGE_NM: [f64; 2] = [380.0, 720.0];
/// How many wavelengths a table may have.
pub const WAVELENGTH_COUNT_RANGE: [f64; 2] = [3.0, 128.0];
/// Rays traced per wavelength for ice.
pub const ICE_RAYS_RANGE: [f64; 2] = [1e4, 1e8];
/// The sun's angular radius accepted, rad (0: a point).
pub const SUN_RADIUS_RANGE_RAD: [f64; 2] = [0.0, 0.05];
/// The sky's bins of falling plates' tables: half a degree in elevation, a quarter in
/// azimuth (the sundogs' colours span about a degree).
pub const SKY_GRID: SkyGrid = SkyGrid {
    elevation_bin_deg: 0.5,
    azimuth_bin_deg: 0.25,
};
/// Radii of the rain's diffraction average.
const RAIN_DIFFRACTION_RADII: usize = 64;
/// The seed of the ice's rays (the same at every wavelength).
const ICE_SEED: u64 = 14;

/// The particles of a volume.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Particles {
    /// Marshall-Palmer rain of a rate, mm/h.
    Rain { rain_rate_mm_h: f64 },
    /// Randomly oriented hexagonal ice crystals of a radius and length, m, by `rays`
    /// rays per wavelength.
    Ice {
        radius_m: f64,
        length_m: f64,
        rays: usize,
    },
    /// Lognormal water droplets by Lorenz-Mie theory ([`super::mie_droplets`]): small
    /// rain drops (supernumerary bows) or cloud droplets (the glory, the cloudbow).
    Droplets(Droplets),
    /// Hexagonal plates of a radius and length, m, falling with their c-axis vertical
    /// within a tilt spread, lit by the sun at an elevation (degrees), by `rays` rays per
    /// wavelength: a table over the sky's two angles.
    Plates {
        radius_m: f64,
        length_m: f64,
        rays: usize,
        tilt_spread_deg: f64,
        sun_elevation_deg: f64,
    },
}

/// Phase functions at `wavelengths_nm`, each in bins of `bin_deg` from 0 to 180 degrees
/// (values at the bins' centres), sr^-1; or, with `sky`, over its grid of the sky
/// (row-major: elevation rows, azimuth columns).
#[derive(Clone, Debug, PartialEq)]
pub struct SpectralPhase {
    pub wavelengths_nm: Vec<f64>,
    pub bin_deg: f64,
    pub sky: Option<SkyGrid>,
    /// One table per wavelength.
    pub phase: Vec<Vec<f64>>,
}

/// `count` wavelengths at the midpoints of equal intervals of [`WAVELENGTH_RANGE_NM`].
pub fn wavelengths_nm(count: usize) -> Vec<f64> {
    let [lo, hi] = WAVELENGTH_RANGE_NM;
    let step = (hi - lo) / count as f64;
    (0..count).map(|i| lo + step * (i as f64 + 0.5)).collect()
}

/// 2 pi (cos a - cos b) for a bin from `a_deg` to `b_deg`.
pub fn bin_solid_angle(a_deg: f64, b_deg: f64) -> f64 {
    2.0 * PI * (a_deg.to_radians().cos() - b_deg.to_radians().cos())
}

/// Weights per bin summing to 1 as a phase function, sr^-1.
fn per_solid_angle(weights: &[f64], bin_deg: f64) -> Vec<f64> {
    weights
        .iter()
        .enumerate()
        .map(|(b, w)| w / bin_solid_angle(b as f64 * bin_deg, (b + 1) as f64 * bin_deg))
        .collect()
}

/// The integral over the sphere of a table in bins of `bin_deg`.
fn integral_of(phase: &[f64], bin_deg: f64) -> f64 {
    phase
        .iter()
        .enumerate()
        .map(|(b, p)| p * bin_solid_angle(b as f64 * bin_deg, (b + 1) as f64 * bin_deg))
        .sum()
}

/// The sky grid of `particles`' tables: [`SKY_GRID`] for falling plates.
fn sky_grid(particles: &Particles) -> Option<SkyGrid> {
    matches!(particles, Particles::Plates { .. }).then_some(SKY_GRID)
}

/// The particles, wavelength count and sun radius checked, by name and range.
fn check_settings(
    particles: &Particles,
    count: usize,
    sun_radius_rad: f64,
) -> Result<(), HydrometeorError> {
    particles.check()?;
    check_range(
        "wavelength count",
        count as f64,
        WAVELENGTH_COUNT_RANGE,
        "[3, 128]",
    )?;
    check_range(
        "sun radius (rad)",
        sun_radius_rad,
        SUN_RADIUS_RANGE_RAD,
        "[0, 0.05]",
    )?;
    Ok(())
}

impl Particles {
    /// The settings checked, by name and range.
    pub fn check(&self) -> Result<(), HydrometeorError> {
        match *self {
            Particles::Rain { rain_rate_mm_h } => {
                MarshallPalmer::new(rain_rate_mm_h)?;
            }
            Particles::Droplets(droplets) => droplets.check()?,
            Particles::Ice {
                radius_m,
                length_m,
                rays,
            }
            | Particles::Plates {
                radius_m,
                length_m,
                rays,
                ..
            } => {
                HexagonalPrism::new(radius_m, length_m)?;
                check_range(
                    "ice rays per wavelength",
                    rays as f64,
                    ICE_RAYS_RANGE,
                    "[1e4, 1e8]",
                )?;
            }
        }
        if let Particles::Plates {
            tilt_spread_deg,
            sun_elevation_deg,
            ..
        } = *self
        {
            Orientation::horizontal_plates(tilt_spread_deg, sun_elevation_deg)
                .map_err(IcePhaseError::from)?;
        }
        Ok(())
    }

    /// Falling plates' table over [`SKY_GRID`] at `wavelength_nm`, seen with a sun of
    /// angular radius `sun_radius_rad`; `None` for other particles.
    fn sky_phase_at(
        &self,
        wavelength_nm: f64,
        sun_radius_rad: f64,
    ) -> Option<Result<Vec<f64>, HydrometeorError>> {
        let Particles::Plates {
            radius_m,
            length_m,
            rays,
            tilt_spread_deg,
            sun_elevation_deg,
        } = *self
        else {
            return None;
        };
        let table = || -> Result<Vec<f64>, HydrometeorError> {
            let crystal = HexagonalPrism::new(radius_m, length_m)?;
            let m = ice_refractive_index(wavelength_nm)
                .map_err(|_| HydrometeorError::RefractiveIndex(wavelength_nm))?;
            let plates = PlateSky {
                tilt_spread_deg,
                sun_elevation_deg,
                sun_radius_rad,
            };
            let settings = RaySettings {
                rays,
                bin_deg: BIN_DEG,
                seed: ICE_SEED,
            };
            let sky = plate_sky_table(
                &crystal,
                m,
                wavelength_nm * 1e-9,
                plates,
                SKY_GRID,
                settings,
            )?;
            Ok(sky.phase)
        };
        Some(table())
    }

    /// The phase function at `wavelength_nm` in bins of `bin_deg`, before the sun's disc.
    fn phase_at(&self, wavelength_nm: f64, bin_deg: f64) -> Result<Vec<f64>, HydrometeorError> {
        let bins = (180.0 / bin_deg).round() as usize;
        let wavelength_m = wavelength_nm * 1e-9;
        match *self {
            Particles::Rain { rain_rate_mm_h } => {
                let rain = MarshallPalmer::new(rain_rate_mm_h)?;
                let n = water_refractive_index(wavelength_nm)
                    .map_err(|_| HydrometeorError::RefractiveIndex(wavelength_nm))?
                    .re;
                let geometric = geometric_bins(n, bins, bin_deg);
                let [lo, hi] = RADIUS_RANGE_M;
                let dr = (hi - lo) / RAIN_DIFFRACTION_RADII as f64;
                let discs: Vec<(f64, f64)> = (0..RAIN_DIFFRACTION_RADII)
                    .map(|i| {
                        let r = lo + dr * (i as f64 + 0.5);
                        let weight = rain.density_per_m3_mm(r) * r * r;
                        (weight, 2.0 * PI * r / wavelength_m)
                    })
                    .collect();
                let diffraction = diffraction_bins(&discs, bins, bin_deg);
                let total = 1.0 + geometric.iter().sum::<f64>();
                let weights: Vec<f64> = geometric
                    .iter()
                    .zip(&diffraction)
                    .map(|(g, d)| (g + d) / total)
                    .collect();
                Ok(per_solid_angle(&weights, bin_deg))
            }
            Particles::Droplets(droplets) => {
                let m = water_refractive_index(wavelength_nm)
                    .map_err(|_| HydrometeorError::RefractiveIndex(wavelength_nm))?;
                droplets.phase_bins(m, wavelength_m, bin_deg)
            }
            Particles::Ice {
                radius_m,
                length_m,
                rays,
            }
            | Particles::Plates {
                radius_m,
                length_m,
                rays,
                ..
            } => {
                let crystal = HexagonalPrism::new(radius_m, length_m)?;
                let m = ice_refractive_index(wavelength_nm)
                    .map_err(|_| HydrometeorError::RefractiveIndex(wavelength_nm))?;
                let settings = RaySettings {
                    rays,
                    bin_deg,
                    seed: ICE_SEED,
                };
                let table =
                    ice_phase_table(&crystal, m, wavelength_m, Orientation::Random, settings)?;
                Ok(table.phase)
            }
        }
    }
}

impl SpectralPhase {
    /// The phase functions of `particles` at `count` wavelengths ([`wavelengths_nm`]),
    /// averaged over a sun of angular radius `sun_radius_rad`.
    pub fn build(
        particles: &Particles,
        count: usize,
        sun_radius_rad: f64,
    ) -> Result<SpectralPhase, HydrometeorError> {
        check_settings(particles, count, sun_radius_rad)?;
        let wavelengths = wavelengths_nm(count);
        let phase = wavelengths
            .par_iter()
            .map(|&l| {
                if let Some(sky) = particles.sky_phase_at(l, sun_radius_rad) {
                    return sky;
                }
                let p = particles.phase_at(l, BIN_DEG)?;
                if sun_radius_rad == 0.0 {
                    return Ok(p);
                }
                // The disc's mean keeps the integral but for the forward peak's few
                // bins, which linear interpolation between centres cannot hold: the
                // table is scaled back to unit integral.
                let blurred = blur_with_sun_disk(&p, BIN_DEG, sun_radius_rad);
                let integral = integral_of(&blurred, BIN_DEG);
                Ok(blurred.iter().map(|v| v / integral).collect())
            })
            .collect::<Result<Vec<_>, HydrometeorError>>()?;
        Ok(SpectralPhase {
            wavelengths_nm: wavelengths,
            bin_deg: BIN_DEG,
            sky: sky_grid(particles),
            phase,
        })
    }

    /// [`SpectralPhase::build`] through `cache`, keyed by the particles, the wavelengths,
    /// the sun's radius, the bins and the methods' fixed settings.
    pub fn build_cached(
        particles: &Particles,
        count: usize,
        sun_radius_rad: f64,
        cache: &TableCache,
    ) -> Result<SpectralPhase, HydrometeorError> {
        check_settings(particles, count, sun_radius_rad)?;
        let key = format!(
            "{particles:?} wavelengths={count} sun_radius_rad={sun_radius_rad:?} \
             bin_deg={BIN_DEG:?} sky={:?} rain_diffraction_radii={RAIN_DIFFRACTION_RADII} \
             ice_seed={ICE_SEED}",
            sky_grid(particles)
        );
        let phase = cache.load_or_build("spectral-phase", &key, || {
            SpectralPhase::build(particles, count, sun_radius_rad).map(|t| t.phase)
        })?;
        let sky = sky_grid(particles);
        let bins = sky.map_or((180.0 / BIN_DEG).round() as usize, |g| {
            g.elevation_bins() * g.azimuth_bins()
        });
        if phase.len() != count || phase.iter().any(|p| p.len() != bins) {
            return SpectralPhase::build(particles, count, sun_radius_rad);
        }
        Ok(SpectralPhase {
            wavelengths_nm: wavelengths_nm(count),
            bin_deg: BIN_DEG,
            sky,
            phase,
        })
    }

    /// The integral over the sphere of wavelength `w`'s table by angle (bins times their
    /// solid angles).
    pub fn integral(&self, w: usize) -> f64 {
        integral_of(&self.phase[w], self.bin_deg)
    }

    /// Wavelength `w`'s value at `angle_deg` in a table by angle, linear between bin
    /// centres.
    pub fn value_at(&self, w: usize, angle_deg: f64) -> f64 {
        let p = &self.phase[w];
        let x = (angle_deg / self.bin_deg - 0.5).clamp(0.0, (p.len() - 1) as f64);
        let i = (x.floor() as usize).min(p.len() - 2);
        let t = x - i as f64;
        p[i] * (1.0 - t) + p[i + 1] * t
    }
}
