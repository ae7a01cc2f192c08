//! The volumes rain and ice fill in a planet scene, homogeneous inside (Riley et al.
//! 2004, section 3.2: beta_ex = eta sigma_ex, Eq. 2): a rain shaft, a vertical cylinder
//! of Marshall-Palmer rain standing on the ground, and a cirrus layer, a spherical shell
//! of ice crystals of a vertical optical depth, and a deck of water droplets, a shell
//! like the cirrus. Where a view ray crosses them and how far a ray from a point inside
//! runs before it leaves.

use glam::DVec3;

use super::error::{HydrometeorError, check_range};
use super::mie_droplets::Droplets;
use super::spectral_phase::Particles;
use crate::clouds::layer::shell::Shell;
use crate::optics::mie::marshall_palmer::{MarshallPalmer, RADIUS_RANGE_M};

/// The ranges of a rain shaft's radius and height, m.
pub const SHAFT_RADIUS_RANGE_M: [f64; 2] = [10.0, 50_000.0];
pub const SHAFT_HEIGHT_RANGE_M: [f64; 2] = [100.0, 20_000.0];
/// The ranges of a cirrus layer's base altitude and thickness, m, and its vertical
/// optical depth.
pub const CIRRUS_BASE_RANGE_M: [f64; 2] = [1_000.0, 20_000.0];
pub const CIRRUS_THICKNESS_RANGE_M: [f64; 2] = [10.0, 10_000.0];
pub const CIRRUS_OPTICAL_DEPTH_RANGE: [f64; 2] = [0.0, 10.0];
/// The ranges of a droplet deck's base altitude and thickness, m, and its vertical
/// optical depth.
pub const DECK_BASE_RANGE_M: [f64; 2] = [0.0, 20_000.0];
pub const DECK_THICKNESS_RANGE_M: [f64; 2] = [10.0, 10_000.0];
pub const DECK_OPTICAL_DEPTH_RANGE: [f64; 2] = [0.0, 10.0];
/// Diameters of the rain's extinction integral.
const EXTINCTION_DIAMETERS: usize = 256;

/// Where a volume is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A cylinder whose axis is the vertical `axis` (unit, from the planet's centre)
    /// through the ground at `ground_radius_m`, from the ground (the tangent plane
    /// there) up to `height_m`.
    Shaft {
        axis: DVec3,
        ground_radius_m: f64,
        radius_m: f64,
        height_m: f64,
    },
    /// A spherical shell around the planet's centre.
    Layer(Shell),
}

/// A homogeneous volume of particles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Volume {
    pub shape: Shape,
    /// Extinction coefficient, m^-1 (the particles do not absorb: scattering alike).
    pub extinction_per_m: f64,
    pub particles: Particles,
}

/// Rain's extinction coefficient: sum over drops of Q_ext pi r^2 with Q_ext = 2 (the
/// geometric-optics limit, van de Hulst 1957, section 8.22), m^-1.
pub fn rain_extinction_per_m(rain: &MarshallPalmer) -> f64 {
    let [lo, hi] = RADIUS_RANGE_M;
    let dr = (hi - lo) / EXTINCTION_DIAMETERS as f64;
    (0..EXTINCTION_DIAMETERS)
        .map(|i| {
            let r = lo + dr * (i as f64 + 0.5);
            // n(D) per mm of diameter; dD = 2 dr, in mm.
            rain.density_per_m3_mm(r) * 2.0 * dr * 1e3 * 2.0 * std::f64::consts::PI * r * r
        })
        .sum()
}

impl Volume {
    /// A rain shaft of `rain_rate_mm_h` around the vertical through `ground_point_m`
    /// (on the ground sphere of `ground_radius_m`).
    pub fn rain_shaft(
        ground_point_m: DVec3,
        ground_radius_m: f64,
        radius_m: f64,
        height_m: f64,
        rain_rate_mm_h: f64,
    ) -> Result<Volume, HydrometeorError> {
        let rain = MarshallPalmer::new(rain_rate_mm_h)?;
        check_range(
            "rain shaft radius (m)",
            radius_m,
            SHAFT_RADIUS_RANGE_M,
            "[10, 50000] m",
        )?;
        check_range(
            "rain shaft height (m)",
            height_m,
            SHAFT_HEIGHT_RANGE_M,
            "[100, 20000] m",
        )?;
        let axis = ground_point_m
            .try_normalize()
            .ok_or(HydrometeorError::Setting {
                what: "rain shaft position (length, m)",
                value: ground_point_m.length(),
                range: "(0, infinity)",
            })?;
        Ok(Volume {
            shape: Shape::Shaft {
                axis,
                ground_radius_m,
                radius_m,
                height_m,
            },
            extinction_per_m: rain_extinction_per_m(&rain),
            particles: Particles::Rain { rain_rate_mm_h },
        })
    }

    /// A cirrus layer from `base_m` to `base_m + thickness_m` above the ground of
    /// `ground_radius_m`, of vertical optical depth `optical_depth`, of ice crystals
    /// `crystals` ([`Particles::Ice`] or [`Particles::Plates`]).
    pub fn cirrus(
        ground_radius_m: f64,
        base_m: f64,
        thickness_m: f64,
        optical_depth: f64,
        crystals: Particles,
    ) -> Result<Volume, HydrometeorError> {
        check_range(
            "cirrus base (m)",
            base_m,
            CIRRUS_BASE_RANGE_M,
            "[1000, 20000] m",
        )?;
        check_range(
            "cirrus thickness (m)",
            thickness_m,
            CIRRUS_THICKNESS_RANGE_M,
            "[10, 10000] m",
        )?;
        check_range(
            "cirrus optical depth",
            optical_depth,
            CIRRUS_OPTICAL_DEPTH_RANGE,
            "[0, 10]",
        )?;
        crystals.check()?;
        if let Particles::Rain { .. } | Particles::Droplets(_) = crystals {
            return Err(HydrometeorError::Setting {
                what: "cirrus particles (water drops)",
                value: 0.0,
                range: "ice crystals only",
            });
        }
        Ok(Volume {
            shape: Shape::Layer(Shell {
                ground_radius_m,
                base_radius_m: ground_radius_m + base_m,
                top_radius_m: ground_radius_m + base_m + thickness_m,
            }),
            extinction_per_m: optical_depth / thickness_m,
            particles: crystals,
        })
    }

    /// A deck of water droplets (a cloud seen in single scattering: its glory and
    /// cloudbow) from `base_m` to `base_m + thickness_m` above the ground of
    /// `ground_radius_m`, of vertical optical depth `optical_depth`.
    pub fn droplet_deck(
        ground_radius_m: f64,
        base_m: f64,
        thickness_m: f64,
        optical_depth: f64,
        droplets: Droplets,
    ) -> Result<Volume, HydrometeorError> {
        check_range("deck base (m)", base_m, DECK_BASE_RANGE_M, "[0, 20000] m")?;
        check_range(
            "deck thickness (m)",
            thickness_m,
            DECK_THICKNESS_RANGE_M,
            "[10, 10000] m",
        )?;
        check_range(
            "deck optical depth",
            optical_depth,
            DECK_OPTICAL_DEPTH_RANGE,
            "[0, 10]",
        )?;
        droplets.check()?;
        Ok(Volume {
            shape: Shape::Layer(Shell {
                ground_radius_m,
                base_radius_m: ground_radius_m + base_m,
                top_radius_m: ground_radius_m + base_m + thickness_m,
            }),
            extinction_per_m: optical_depth / thickness_m,
            particles: Particles::Droplets(droplets),
        })
    }

    /// The first interval `[t0, t1]` of the ray from `origin` along the unit
    /// `direction` inside the volume, ended at `max_distance_m`; `None` if it misses.
    pub fn segment(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_distance_m: f64,
    ) -> Option<(f64, f64)> {
        match self.shape {
            Shape::Layer(shell) => shell.first_segment(origin, direction, max_distance_m),
            Shape::Shaft { .. } => {
                let (t0, t1) = self.shaft_interval(origin, direction)?;
                let (t0, t1) = (t0.max(0.0), t1.min(max_distance_m));
                (t0 < t1).then_some((t0, t1))
            }
        }
    }

    /// From `point` inside the volume along the unit `direction`: how far to its edge.
    pub fn exit_distance(&self, point: DVec3, direction: DVec3) -> f64 {
        match self.shape {
            Shape::Layer(shell) => shell.exit_distance(point, direction),
            Shape::Shaft { .. } => self
                .shaft_interval(point, direction)
                .map_or(0.0, |(_, t1)| t1.max(0.0)),
        }
    }

    /// The whole line's interval inside the shaft (t may be negative).
    fn shaft_interval(&self, origin: DVec3, direction: DVec3) -> Option<(f64, f64)> {
        let Shape::Shaft {
            axis,
            ground_radius_m,
            radius_m,
            height_m,
        } = self.shape
        else {
            return None;
        };
        let p = origin - axis * ground_radius_m;
        let (pz, dz) = (p.dot(axis), direction.dot(axis));
        let (pr, dr) = (p - axis * pz, direction - axis * dz);
        // Inside the slab 0 <= z <= height.
        let (mut t0, mut t1) = if dz.abs() < 1e-12 {
            if !(0.0..=height_m).contains(&pz) {
                return None;
            }
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            let (a, b) = (-pz / dz, (height_m - pz) / dz);
            (a.min(b), a.max(b))
        };
        // Inside the infinite cylinder: |pr + t dr|^2 <= radius^2.
        let a = dr.length_squared();
        let b = pr.dot(dr);
        let c = pr.length_squared() - radius_m * radius_m;
        if a < 1e-24 {
            if c > 0.0 {
                return None;
            }
        } else {
            let disc = b * b - a * c;
            if disc < 0.0 {
                return None;
            }
            let s = disc.sqrt();
            t0 = t0.max((-b - s) / a);
            t1 = t1.min((-b + s) / a);
        }
        (t0 < t1).then_some((t0, t1))
    }

    /// A point well inside the volume near `camera_m` (for its light): the shaft's
    /// middle, or the layer's middle on the camera's vertical.
    pub fn light_point(&self, camera_m: DVec3) -> DVec3 {
        match self.shape {
            Shape::Shaft {
                axis,
                ground_radius_m,
                height_m,
                ..
            } => axis * (ground_radius_m + 0.5 * height_m),
            Shape::Layer(shell) => {
                camera_m.normalize() * 0.5 * (shell.base_radius_m + shell.top_radius_m)
            }
        }
    }
}
