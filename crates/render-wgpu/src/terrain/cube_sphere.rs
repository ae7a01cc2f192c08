//! The cube sphere: six faces of a cube, each with coordinates (u, v) in [-1, 1]^2,
//! mapped onto the unit sphere.
//!
//! Tangent-adjusted cube: a face coordinate `u` is first warped to the cube coordinate
//! `a = tan(u * pi / 4)` and the cube point `n + a r + b t` (face normal `n`, right `r`,
//! up `t`) is normalised. Equal steps in `u` are equal angles seen from the centre along
//! the face's axes, so cells differ in area by at most a factor of about 1.4 across a
//! face, where the plain normalised cube's differ by about 5.2 (cells at a face centre
//! against those at its corners).
//!
//! Exactness, which the crack-free seams rely on: the warp is odd by construction
//! (`w(-u) = -w(u)` bit for bit) and exact at the edges (`w(+-1) = +-1`), and a cube point
//! is assembled by placing `+-1`, `+-a` and `+-b` in its components (no arithmetic), so
//! the same point on the edge between two faces gets the same bits from either face when
//! its coordinates are the same dyadic fractions (see `chunk_key.rs`).
//!
//! Frame: planet-fixed, x towards latitude 0 longitude 0, y towards latitude 0 longitude
//! 90 deg east, z towards the north pole (the frame of `atmosphere_core::sun_position`).
//! Every face basis is right-handed (`r x t = n`), so (u, v) increasing counter-clockwise
//! is seen from outside the planet.

use std::f64::consts::FRAC_PI_4;

use glam::DVec3;

/// One of the six faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Face(pub u8);

/// A signed coordinate axis: `axis` 0, 1, 2 for x, y, z, and a sign.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SignedAxis {
    pub axis: usize,
    pub negative: bool,
}

const fn axis(axis: usize, negative: bool) -> SignedAxis {
    SignedAxis { axis, negative }
}

/// Normal, right (direction of increasing u) and up (increasing v) of each face.
const FACES: [[SignedAxis; 3]; 6] = [
    [axis(0, false), axis(1, false), axis(2, false)], // +X
    [axis(0, true), axis(1, true), axis(2, false)],   // -X
    [axis(1, false), axis(0, true), axis(2, false)],  // +Y
    [axis(1, true), axis(0, false), axis(2, false)],  // -Y
    [axis(2, false), axis(1, false), axis(0, true)],  // +Z (north pole)
    [axis(2, true), axis(1, false), axis(0, false)],  // -Z (south pole)
];

impl Face {
    /// All six faces, in order.
    pub const ALL: [Face; 6] = [Face(0), Face(1), Face(2), Face(3), Face(4), Face(5)];

    /// The face's outward normal, right (u) and up (v) axes.
    pub fn basis(self) -> [SignedAxis; 3] {
        FACES[self.0 as usize]
    }

    /// The face whose normal is `axis`.
    pub fn with_normal(axis: SignedAxis) -> Face {
        Face(
            FACES
                .iter()
                .position(|f| f[0] == axis)
                .expect("every signed axis is a face") as u8,
        )
    }
}

impl SignedAxis {
    /// The axis as a unit vector.
    pub fn vector(self) -> DVec3 {
        let mut v = [0.0; 3];
        v[self.axis] = if self.negative { -1.0 } else { 1.0 };
        DVec3::from_array(v)
    }

    /// The component of `p` along this axis (exact: a sign flip at most).
    pub fn component(self, p: DVec3) -> f64 {
        let c = p.to_array()[self.axis];
        if self.negative { -c } else { c }
    }

    /// The opposite axis.
    pub fn flipped(self) -> SignedAxis {
        axis(self.axis, !self.negative)
    }
}

/// The tangent warp from a face coordinate in [-1, 1] to a cube coordinate in [-1, 1]:
/// `tan(u pi / 4)`, odd and exact at +-1 by construction.
pub fn warp(u: f64) -> f64 {
    if u.abs() == 1.0 {
        return u;
    }
    let w = (u.abs() * FRAC_PI_4).tan();
    if u < 0.0 { -w } else { w }
}

/// The inverse of [`warp`]: `atan(a) * 4 / pi`.
pub fn unwarp(a: f64) -> f64 {
    if a.abs() == 1.0 {
        return a;
    }
    a.atan() / FRAC_PI_4
}

/// The point `n + a r + b t` on the cube of half-size 1, for cube coordinates (a, b) (not
/// warped). Components are placed, not computed, and negative zeros become positive, so a
/// point shared by two faces has the same bits from both.
pub fn cube_point(face: Face, a: f64, b: f64) -> DVec3 {
    let [n, r, t] = face.basis();
    let mut p = [0.0; 3];
    p[n.axis] = if n.negative { -1.0 } else { 1.0 };
    p[r.axis] = if r.negative { -a } else { a };
    p[t.axis] = if t.negative { -b } else { b };
    DVec3::from_array(p.map(|c| c + 0.0))
}

/// The unit direction of face coordinates (u, v) in [-1, 1]^2 (tangent-adjusted). Values
/// slightly outside [-1, 1] are allowed (they continue the face's plane onto its
/// neighbour), which the normals' stencils use.
pub fn direction(face: Face, u: f64, v: f64) -> DVec3 {
    cube_point(face, warp(u), warp(v)).normalize()
}

/// For face coordinates on an edge of `face` (`|u| = 1`, or else `|v| = 1`), the face
/// across that edge and the same point's coordinates on it. Exact: the coordinates are
/// permuted and sign-flipped (the warp commutes with both), so dyadic coordinates stay
/// the same dyadic fractions. At a corner the edge of `u` is crossed.
pub fn across_edge(face: Face, u: f64, v: f64) -> (Face, f64, f64) {
    let [_, r, t] = face.basis();
    let edge = if u.abs() == 1.0 {
        if u < 0.0 { r.flipped() } else { r }
    } else {
        assert!(v.abs() == 1.0, "({u}, {v}) is not on an edge of {face:?}");
        if v < 0.0 { t.flipped() } else { t }
    };
    let other = Face::with_normal(edge);
    // The coordinates as a permutation carrier: the "cube point" of the unwarped values.
    let p = cube_point(face, u, v);
    let [_, r2, t2] = other.basis();
    (other, r2.component(p) + 0.0, t2.component(p) + 0.0)
}

/// The face and face coordinates (u, v) of a direction (need not be unit): the face of the
/// largest component (ties go to the lower face index), then the inverse warp.
pub fn face_coordinates(direction: DVec3) -> (Face, f64, f64) {
    let c = direction.to_array();
    let mut major = 0;
    for i in 1..3 {
        if c[i].abs() > c[major].abs() {
            major = i;
        }
    }
    let face = Face::with_normal(axis(major, c[major] < 0.0));
    let [n, r, t] = face.basis();
    let depth = n.component(direction);
    (
        face,
        unwarp(r.component(direction) / depth),
        unwarp(t.component(direction) / depth),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_bases_are_right_handed_and_cover_the_axes() {
        let mut normals = Vec::new();
        for face in Face::ALL {
            let [n, r, t] = face.basis();
            assert_eq!(r.vector().cross(t.vector()), n.vector(), "{face:?}");
            assert_eq!(Face::with_normal(n), face);
            normals.push(n.vector());
        }
        for (i, a) in normals.iter().enumerate() {
            for b in &normals[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }

    #[test]
    fn warp_is_odd_exact_at_the_edges_and_inverted() {
        assert_eq!(warp(1.0), 1.0);
        assert_eq!(warp(-1.0), -1.0);
        assert_eq!(warp(0.0), 0.0);
        for k in 0..=64 {
            let u = k as f64 / 64.0;
            assert_eq!(warp(-u), -warp(u));
            assert!((unwarp(warp(u)) - u).abs() < 1e-15, "{u}");
        }
    }

    /// (face, u, v) -> direction -> (face, u, v) on a grid inside every face, and
    /// direction -> (face, u, v) -> direction everywhere, faces' edges included.
    #[test]
    fn round_trips() {
        for face in Face::ALL {
            for i in 0..=16 {
                for j in 0..=16 {
                    let (u, v) = (i as f64 / 8.0 - 1.0, j as f64 / 8.0 - 1.0);
                    let d = direction(face, u, v);
                    assert!((d.length() - 1.0).abs() < 1e-15);
                    let (f2, u2, v2) = face_coordinates(d);
                    if u.abs() < 1.0 && v.abs() < 1.0 {
                        assert_eq!(f2, face);
                        assert!((u2 - u).abs() < 1e-14 && (v2 - v).abs() < 1e-14);
                    }
                    assert!((direction(f2, u2, v2) - d).length() < 1e-15);
                }
            }
        }
        // The north pole is the centre of +Z; longitude 90 east on the equator is +Y's.
        assert_eq!(face_coordinates(DVec3::Z), (Face(4), 0.0, 0.0));
        assert_eq!(face_coordinates(DVec3::Y), (Face(2), 0.0, 0.0));
    }

    /// A point on the edge between two faces has the same bits from both faces, and
    /// crossing back returns the starting coordinates.
    #[test]
    fn shared_edges_are_bitwise_equal() {
        for face in Face::ALL {
            for k in 0..=32 {
                let s = (2 * k - 32) as f64 / 32.0;
                for (u, v) in [(1.0, s), (-1.0, s), (s, 1.0), (s, -1.0)] {
                    let (other, u2, v2) = across_edge(face, u, v);
                    assert_ne!(other, face);
                    assert_eq!(direction(other, u2, v2), direction(face, u, v));
                    if s.abs() < 1.0 {
                        assert_eq!(across_edge(other, u2, v2), (face, u, v));
                    }
                }
            }
        }
    }

    /// The tangent warp's cells differ in solid angle by less than 1.5x across a face.
    #[test]
    fn tangent_cells_are_nearly_uniform() {
        let n = 32;
        let area = |i: usize, j: usize| {
            let c = |a: usize, b: usize| {
                direction(
                    Face(0),
                    2.0 * a as f64 / n as f64 - 1.0,
                    2.0 * b as f64 / n as f64 - 1.0,
                )
            };
            let (p0, p1, p2, p3) = (c(i, j), c(i + 1, j), c(i + 1, j + 1), c(i, j + 1));
            0.5 * ((p1 - p0).cross(p3 - p0).length() + (p1 - p2).cross(p3 - p2).length())
        };
        let (centre, corner) = (area(n / 2, n / 2), area(0, 0));
        assert!(
            centre / corner < 1.5 && corner / centre < 1.5,
            "{centre} {corner}"
        );
    }
}
