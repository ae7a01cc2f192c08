//! A chunk's triangles, stitched to coarser neighbours without cracks.
//!
//! The `n x n` cells of a chunk are split into two triangles each along alternating
//! diagonals: cell (i, j) along (i, j)-(i+1, j+1) when `i + j` is even, along
//! (i+1, j)-(i, j+1) when odd. Then an odd vertex of an edge, (2k+1, 0) say, belongs to
//! exactly two triangles, which together form the triangle (2k, 0), (2k+2, 0),
//! (2k+1, 1). On an edge that borders a coarser chunk (whose vertices along it are this
//! chunk's even ones), each odd vertex is merged into its even neighbour: one of its two
//! triangles collapses and is dropped, the other becomes (2k, 0), (2k+2, 0), (2k+1, 1).
//! The edge then runs through the coarser chunk's vertices only: no T-junction, no crack,
//! no skirt. The four corners are even, so two stitched edges never meet in a triangle.
//!
//! Vertex (i, j) has index `j (n + 1) + i`. Triangles are counter-clockwise in (u, v),
//! which is counter-clockwise seen from outside the planet (every face basis is
//! right-handed).

use super::chunk_key::Edge;

/// The index of vertex (i, j) of a chunk with `cells` cells along a side.
pub fn vertex_index(cells: u32, i: u32, j: u32) -> u32 {
    j * (cells + 1) + i
}

/// Triangle indices of a chunk of `cells x cells` cells (`cells` even) whose edges
/// flagged in `coarser` (indexed by [`Edge`]) border a coarser chunk.
pub fn stitched_indices(cells: u32, coarser: [bool; 4]) -> Vec<u32> {
    assert!(
        cells >= 2 && cells.is_multiple_of(2),
        "a chunk's cells must be even, got {cells}"
    );
    let n = cells;
    // Odd vertices of stitched edges move to their even neighbour (one step back).
    let merged = |i: u32, j: u32| -> (u32, u32) {
        let v_edge =
            (j == 0 && coarser[Edge::VMin as usize]) || (j == n && coarser[Edge::VMax as usize]);
        let u_edge =
            (i == 0 && coarser[Edge::UMin as usize]) || (i == n && coarser[Edge::UMax as usize]);
        if v_edge && i % 2 == 1 {
            (i - 1, j)
        } else if u_edge && j % 2 == 1 {
            (i, j - 1)
        } else {
            (i, j)
        }
    };
    let mut indices = Vec::with_capacity(6 * (n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let triangles = if (i + j) % 2 == 0 {
                [
                    [(i, j), (i + 1, j), (i + 1, j + 1)],
                    [(i, j), (i + 1, j + 1), (i, j + 1)],
                ]
            } else {
                [
                    [(i, j), (i + 1, j), (i, j + 1)],
                    [(i + 1, j), (i + 1, j + 1), (i, j + 1)],
                ]
            };
            for triangle in triangles {
                let [a, b, c] = triangle.map(|(i, j)| {
                    let (i, j) = merged(i, j);
                    vertex_index(n, i, j)
                });
                if a != b && b != c && c != a {
                    indices.extend([a, b, c]);
                }
            }
        }
    }
    indices
}

#[cfg(test)]
mod tests {
    use std::collections::HashMap;

    use super::*;

    fn uv(cells: u32, index: u32) -> (f64, f64) {
        ((index % (cells + 1)) as f64, (index / (cells + 1)) as f64)
    }

    /// Every mask: triangles counter-clockwise, covering the chunk's square exactly, and
    /// the boundary made of whole coarse segments on stitched edges, unit ones elsewhere.
    #[test]
    fn stitched_triangles_tile_the_chunk() {
        let n = 8;
        for mask in 0..16u32 {
            let coarser = [0, 1, 2, 3].map(|b| mask & (1 << b) != 0);
            let indices = stitched_indices(n, coarser);
            let mut area = 0.0;
            let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
            for t in indices.chunks(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|k| uv(n, k));
                let doubled = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
                assert!(doubled > 0.0, "mask {mask}: clockwise or flat {t:?}");
                area += doubled / 2.0;
                for (p, q) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                    *edges.entry((p, q)).or_default() += 1;
                }
            }
            assert_eq!(area, (n * n) as f64, "mask {mask}");
            // Boundary edges: directed edges without their reverse.
            let boundary: Vec<_> = edges
                .keys()
                .filter(|(p, q)| !edges.contains_key(&(*q, *p)))
                .collect();
            let mut length = 0.0;
            for &&(p, q) in &boundary {
                let (a, b) = (uv(n, p), uv(n, q));
                let step = (b.0 - a.0).abs() + (b.1 - a.1).abs();
                let edge = if a.1 == 0.0 && b.1 == 0.0 {
                    Edge::VMin
                } else if a.1 == n as f64 && b.1 == n as f64 {
                    Edge::VMax
                } else if a.0 == 0.0 && b.0 == 0.0 {
                    Edge::UMin
                } else {
                    assert!(
                        a.0 == n as f64 && b.0 == n as f64,
                        "interior boundary edge {a:?} {b:?}"
                    );
                    Edge::UMax
                };
                let want = if coarser[edge as usize] { 2.0 } else { 1.0 };
                assert_eq!(step, want, "mask {mask} {edge:?} {a:?}-{b:?}");
                length += step;
            }
            assert_eq!(length, 4.0 * n as f64);
        }
    }
}
