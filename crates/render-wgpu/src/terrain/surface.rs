//! The rendered surface: a height field on a sphere, with vertical exaggeration and the
//! sea surface.
//!
//! A point in direction `d` (unit, planet-fixed) lies at `d (R + k h'(d))` with `R` the
//! reference radius (the atmosphere's bottom radius, so the ground meets the sky models),
//! `k` the vertical exaggeration and `h'` the height, raised to 0 over the oceans when
//! `sea_surface` is on (the colour map shows the sea; the bathymetry is kept for later
//! use). `k = 1` is true scale; the Earth's relief is 0.14 % of its radius, so views from
//! orbit often use `k` of 10 to 50 to show it. Normals come from the chunk meshes
//! (`chunk_mesh.rs`).

use atmosphere_core::shafts::Relief;
use glam::DVec3;

use super::height_field::HeightField;

/// A height field placed on a sphere.
#[derive(Clone, Debug)]
pub struct TerrainSurface<H> {
    pub heights: H,
    /// Reference radius `R`, metres.
    pub radius_m: f64,
    /// Vertical exaggeration `k` (1 = true scale).
    pub exaggeration: f64,
    /// Heights below 0 are drawn at 0 (the sea surface).
    pub sea_surface: bool,
}

impl<H: HeightField> TerrainSurface<H> {
    /// A true-scale surface with the sea surface drawn.
    pub fn new(heights: H, radius_m: f64) -> TerrainSurface<H> {
        TerrainSurface {
            heights,
            radius_m,
            exaggeration: 1.0,
            sea_surface: true,
        }
    }

    /// The drawn elevation above the reference sphere, metres: `k h'(d)`.
    pub fn elevation_m(&self, direction: DVec3) -> f64 {
        self.elevation_of_height(self.heights.height_m(direction))
    }

    /// The drawn elevation of a height `height_m` of the field, metres.
    pub fn elevation_of_height(&self, height_m: f64) -> f64 {
        self.exaggeration
            * if self.sea_surface {
                height_m.max(0.0)
            } else {
                height_m
            }
    }

    /// The surface point in a direction (unit), planet-centred, metres.
    pub fn position_m(&self, direction: DVec3) -> DVec3 {
        direction * (self.radius_m + self.elevation_m(direction))
    }

    /// A bound on `|elevation_m|`.
    pub fn elevation_bound_m(&self) -> f64 {
        self.exaggeration.abs() * self.heights.max_abs_height_m()
    }
}

/// The drawn relief, as the terrain's shadow in the air sees it (docs/shafts.md).
impl<H: HeightField> Relief for TerrainSurface<H> {
    fn elevation_m(&self, direction: DVec3) -> f64 {
        TerrainSurface::elevation_m(self, direction)
    }

    fn elevation_bound_m(&self) -> f64 {
        self.elevation_bound_m()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tilted plane seen locally: h = g * R * (d . e) around the equator at lon 0.
    struct Ramp {
        gradient: f64,
        radius_m: f64,
    }

    impl HeightField for Ramp {
        fn height_m(&self, d: DVec3) -> f64 {
            self.gradient * self.radius_m * d.y
        }
        fn max_abs_height_m(&self) -> f64 {
            self.gradient * self.radius_m
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-4
        }
    }

    #[test]
    fn exaggeration_scales_heights_and_the_sea_surface_is_flat() {
        let radius_m = 6.36e6;
        let mut surface = TerrainSurface::new(
            Ramp {
                gradient: 0.1,
                radius_m,
            },
            radius_m,
        );
        surface.sea_surface = false;
        surface.exaggeration = 3.0;
        assert_eq!(surface.position_m(DVec3::Y), DVec3::Y * radius_m * 1.3);
        assert!((surface.elevation_bound_m() - 0.3 * radius_m).abs() < 1e-6);
        assert_eq!(surface.position_m(-DVec3::Y), -DVec3::Y * radius_m * 0.7);
        // Below sea level the sea surface is flat at the reference radius.
        surface.sea_surface = true;
        assert_eq!(surface.position_m(-DVec3::Y), -DVec3::Y * radius_m);
    }
}
