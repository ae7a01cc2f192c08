//! A hexagonal prism of ice: its eight faces as planes n . x = h (outward normals), its
//! areas, and where a ray meets it.

use glam::DVec3;
use thiserror::Error;

/// The range of length / (2 radius): plates to 0.01, columns to 100.
pub const ASPECT_RATIO_RANGE: [f64; 2] = [0.01, 100.0];

/// The range of radius and length, m: 1 um to 10 mm (geometric optics holds for crystals
/// many wavelengths across; docs/particles.md says where it stops).
pub const SIZE_RANGE_M: [f64; 2] = [1e-6, 1e-2];

#[derive(Clone, Debug, Error, PartialEq)]
pub enum CrystalError {
    #[error("crystal {what} {value} m is outside [1e-6, 1e-2] m")]
    Size { what: &'static str, value: f64 },
    #[error(
        "crystal aspect ratio length / (2 radius) = {0} is outside [0.01, 100] (plates to \
         columns)"
    )]
    AspectRatio(f64),
}

/// A hexagonal prism centred on the origin, c-axis along z.
#[derive(Clone, Debug, PartialEq)]
pub struct HexagonalPrism {
    pub radius_m: f64,
    pub length_m: f64,
    /// Outward unit normals and offsets: six prism faces, then the two basal faces.
    faces: [(DVec3, f64); 8],
}

impl HexagonalPrism {
    pub fn new(radius_m: f64, length_m: f64) -> Result<HexagonalPrism, CrystalError> {
        let [lo, hi] = SIZE_RANGE_M;
        for (what, value) in [("radius", radius_m), ("length", length_m)] {
            if !(lo..=hi).contains(&value) {
                return Err(CrystalError::Size { what, value });
            }
        }
        let aspect = length_m / (2.0 * radius_m);
        // Rounding in the quotient must not refuse the ends themselves.
        let [lo, hi] = ASPECT_RATIO_RANGE.map(|a| a * (1.0 + 1e-12 * a.signum()));
        if !(lo * (1.0 - 2e-12)..=hi).contains(&aspect) {
            return Err(CrystalError::AspectRatio(aspect));
        }
        let apothem = radius_m * 3f64.sqrt() / 2.0;
        let mut faces = [(DVec3::Z, 0.5 * length_m); 8];
        for (j, face) in faces.iter_mut().take(6).enumerate() {
            let phi = (60.0 * j as f64).to_radians();
            *face = (DVec3::new(phi.cos(), phi.sin(), 0.0), apothem);
        }
        faces[7] = (DVec3::NEG_Z, 0.5 * length_m);
        Ok(HexagonalPrism {
            radius_m,
            length_m,
            faces,
        })
    }

    /// The radius of the sphere around the crystal.
    pub fn bounding_radius_m(&self) -> f64 {
        self.radius_m.hypot(0.5 * self.length_m)
    }

    /// The area of each face, in the order of the faces.
    fn face_area_m2(&self, face: usize) -> f64 {
        if face < 6 {
            self.radius_m * self.length_m
        } else {
            1.5 * 3f64.sqrt() * self.radius_m * self.radius_m
        }
    }

    /// The whole surface: by Cauchy's theorem four times the projected area averaged
    /// over random orientations.
    pub fn surface_area_m2(&self) -> f64 {
        (0..8).map(|f| self.face_area_m2(f)).sum()
    }

    /// The area projected on a plane normal to `direction`: half the sum over faces of
    /// area times |n . direction| (a convex body).
    pub fn projected_area_m2(&self, direction: DVec3) -> f64 {
        0.5 * (0..8)
            .map(|f| self.face_area_m2(f) * self.faces[f].0.dot(direction).abs())
            .sum::<f64>()
    }

    /// Where a ray from outside enters: the distance along `direction` and the face's
    /// outward normal, or None when it misses.
    pub fn entry(&self, origin: DVec3, direction: DVec3) -> Option<(f64, DVec3)> {
        let (mut t_in, mut t_out, mut normal) = (f64::NEG_INFINITY, f64::INFINITY, DVec3::ZERO);
        for &(n, h) in &self.faces {
            let along = n.dot(direction);
            let gap = h - n.dot(origin);
            if along < 0.0 {
                let t = gap / along;
                if t > t_in {
                    (t_in, normal) = (t, n);
                }
            } else if along > 0.0 {
                t_out = t_out.min(gap / along);
            } else if gap < 0.0 {
                return None;
            }
        }
        (t_in <= t_out && t_in > 0.0).then_some((t_in, normal))
    }

    /// Where a ray inside leaves: the distance to the nearest face ahead and its normal.
    pub fn exit(&self, origin: DVec3, direction: DVec3) -> (f64, DVec3) {
        let mut best = (f64::INFINITY, DVec3::Z);
        for &(n, h) in &self.faces {
            let along = n.dot(direction);
            if along > 0.0 {
                let t = ((h - n.dot(origin)) / along).max(0.0);
                if t < best.0 {
                    best = (t, n);
                }
            }
        }
        best
    }
}
