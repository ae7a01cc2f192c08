//! The proxy geometry of half-angle slicing (Kniss et al. 2002): each slice's plane cut
//! by the volume's box, a convex polygon of 3 to 6 corners, as a fan of triangles with
//! positions relative to the camera.

use atmosphere_core::clouds::volume::half_angle::HalfAngle;
use glam::DVec3;

/// The box's 12 edges as pairs of corner indices (bit 0: x, bit 1: y, bit 2: z).
const EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];

/// The triangles of every slice, 3 vertices each, relative to `camera_m`, and for slice k
/// the range of its vertices.
pub fn slice_triangles(
    slices: &HalfAngle,
    corners: &[DVec3; 8],
    camera_m: DVec3,
) -> (Vec<[f32; 3]>, Vec<std::ops::Range<u32>>) {
    let mut vertices = Vec::new();
    let mut ranges = Vec::with_capacity(slices.slices as usize);
    for k in 0..slices.slices {
        let start = vertices.len() as u32;
        let offset = slices.offset_m(k);
        let mut points: Vec<DVec3> = EDGES
            .iter()
            .filter_map(|&(a, b)| {
                let (da, db) = (
                    corners[a].dot(slices.half) - offset,
                    corners[b].dot(slices.half) - offset,
                );
                (da * db < 0.0).then(|| corners[a] + (corners[b] - corners[a]) * (da / (da - db)))
            })
            .collect();
        if points.len() >= 3 {
            let centre = points.iter().copied().sum::<DVec3>() / points.len() as f64;
            let (e_u, e_v) = slices.half.any_orthonormal_pair();
            let angle = |p: &DVec3| (p - centre).dot(e_v).atan2((p - centre).dot(e_u));
            points.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
            for i in 1..points.len() - 1 {
                for p in [points[0], points[i], points[i + 1]] {
                    vertices.push((p - camera_m).as_vec3().to_array());
                }
            }
        }
        ranges.push(start..vertices.len() as u32);
    }
    (vertices, ranges)
}
