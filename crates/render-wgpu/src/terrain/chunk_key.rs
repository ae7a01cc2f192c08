//! The address of a terrain chunk: a cell of a face's quadtree.
//!
//! At level `L` a face is cut into `2^L x 2^L` chunks; chunk (x, y) covers face
//! coordinates `u` in `[-1 + 2x / 2^L, -1 + 2(x + 1) / 2^L]` and likewise `v` with `y`.
//! A chunk's mesh has `n x n` cells, so its vertex (i, j) sits at `u = (2g - N) / N` with
//! `g = x n + i` and `N = n 2^L`: a ratio of integers, correctly rounded, so the same
//! point gets the same bits from a chunk and from its coarser neighbour (whose `g` and `N`
//! are both halved), and the opposite value's bits across a face edge (where `u` may
//! become `-u`).

use super::cube_sphere::{Face, across_edge};

/// A chunk: face, level and position in the face's `2^level x 2^level` grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ChunkKey {
    pub face: Face,
    pub level: u8,
    /// Column, along u.
    pub x: u32,
    /// Row, along v.
    pub y: u32,
}

/// A side of a chunk, in its face's coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Edge {
    /// u at its minimum.
    UMin = 0,
    /// u at its maximum.
    UMax = 1,
    /// v at its minimum.
    VMin = 2,
    /// v at its maximum.
    VMax = 3,
}

impl Edge {
    pub const ALL: [Edge; 4] = [Edge::UMin, Edge::UMax, Edge::VMin, Edge::VMax];
}

/// The deepest level a key can hold (vertex coordinates stay exact in f64 up to far
/// beyond it).
pub const MAX_LEVEL: u8 = 30;

impl ChunkKey {
    /// The whole face, level 0.
    pub fn root(face: Face) -> ChunkKey {
        ChunkKey {
            face,
            level: 0,
            x: 0,
            y: 0,
        }
    }

    /// The number of chunks along a face's side at this level.
    pub fn side(self) -> u32 {
        1 << self.level
    }

    /// The chunk containing this one at the level above; a root is its own parent.
    pub fn parent(self) -> ChunkKey {
        if self.level == 0 {
            return self;
        }
        ChunkKey {
            level: self.level - 1,
            x: self.x / 2,
            y: self.y / 2,
            ..self
        }
    }

    /// The four chunks of the level below, in the order (0,0), (1,0), (0,1), (1,1).
    pub fn children(self) -> [ChunkKey; 4] {
        assert!(
            self.level < MAX_LEVEL,
            "chunk level {} is the deepest",
            self.level
        );
        let child = |dx, dy| ChunkKey {
            level: self.level + 1,
            x: 2 * self.x + dx,
            y: 2 * self.y + dy,
            ..self
        };
        [child(0, 0), child(1, 0), child(0, 1), child(1, 1)]
    }

    /// The face coordinate of grid line `g` of `cells` cells per chunk: `(2g - N) / N`,
    /// `N = cells 2^level` (exact dyadic; `g` may run past the chunk for stencils).
    pub fn grid_coordinate(self, cells: u32, g: i64) -> f64 {
        let total = (cells as i64) << self.level;
        (2 * g - total) as f64 / total as f64
    }

    /// Face coordinates (u, v) of vertex (i, j) of a chunk mesh of `cells x cells` cells.
    pub fn vertex_uv(self, cells: u32, i: i64, j: i64) -> (f64, f64) {
        (
            self.grid_coordinate(cells, self.x as i64 * cells as i64 + i),
            self.grid_coordinate(cells, self.y as i64 * cells as i64 + j),
        )
    }

    /// The chunk of the same level across `edge`, on the neighbouring face when the edge
    /// is on the face's border.
    pub fn neighbour(self, edge: Edge) -> ChunkKey {
        let side = self.side();
        let inside = match edge {
            Edge::UMin => (self.x > 0).then(|| (self.x - 1, self.y)),
            Edge::UMax => (self.x + 1 < side).then(|| (self.x + 1, self.y)),
            Edge::VMin => (self.y > 0).then(|| (self.x, self.y - 1)),
            Edge::VMax => (self.y + 1 < side).then(|| (self.x, self.y + 1)),
        };
        if let Some((x, y)) = inside {
            return ChunkKey { x, y, ..self };
        }
        // The middle of the edge (never a corner), carried onto the other face.
        let middle = |k: u32| (2 * k as i64 + 1 - side as i64) as f64 / side as f64;
        let (u, v) = match edge {
            Edge::UMin => (-1.0, middle(self.y)),
            Edge::UMax => (1.0, middle(self.y)),
            Edge::VMin => (middle(self.x), -1.0),
            Edge::VMax => (middle(self.x), 1.0),
        };
        let (face, u2, v2) = across_edge(self.face, u, v);
        // Chunk index of a coordinate: the border's first or last, else the one holding it
        // ((c + 1) side / 2 is k + 1/2 exactly).
        let index = |c: f64| {
            if c == -1.0 {
                0
            } else if c == 1.0 {
                side - 1
            } else {
                ((c + 1.0) * side as f64 / 2.0).floor() as u32
            }
        };
        ChunkKey {
            face,
            level: self.level,
            x: index(u2),
            y: index(v2),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all_keys(level: u8) -> Vec<ChunkKey> {
        let side = 1u32 << level;
        let mut keys = Vec::new();
        for face in Face::ALL {
            for x in 0..side {
                for y in 0..side {
                    keys.push(ChunkKey { face, level, x, y });
                }
            }
        }
        keys
    }

    /// Neighbours are mutual, on the same level, and every chunk has four distinct ones;
    /// each root touches the four faces other than itself and its opposite.
    #[test]
    fn neighbours_are_mutual() {
        for level in 0..4 {
            for key in all_keys(level) {
                let mut seen = Vec::new();
                for edge in Edge::ALL {
                    let n = key.neighbour(edge);
                    assert_eq!(n.level, level);
                    assert!(n.x < n.side() && n.y < n.side());
                    assert!(
                        Edge::ALL.iter().any(|&e| n.neighbour(e) == key),
                        "{key:?} {edge:?} {n:?}"
                    );
                    assert!(!seen.contains(&n));
                    seen.push(n);
                }
            }
        }
    }

    /// Shared edge vertices have bit-identical coordinates from both chunks, across face
    /// borders too, and a chunk's vertices are its parent's where they coincide.
    #[test]
    fn vertex_coordinates_are_exact() {
        use super::super::cube_sphere::direction;
        let cells = 8;
        for key in all_keys(2) {
            let child = key.children()[3];
            for j in 0..=cells as i64 {
                for i in 0..=cells as i64 {
                    if i % 2 == 0 && j % 2 == 0 {
                        let (u, v) = child.vertex_uv(cells, i, j);
                        let (pu, pv) =
                            key.vertex_uv(cells, (cells as i64 + i) / 2, (cells as i64 + j) / 2);
                        assert_eq!((u, v), (pu, pv));
                    }
                }
            }
            // The UMax edge's vertices equal the neighbour's vertices on its facing edge.
            let n = key.neighbour(Edge::UMax);
            let theirs: Vec<_> = (0..=cells as i64)
                .flat_map(|j| (0..=cells as i64).map(move |i| (i, j)))
                .map(|(i, j)| {
                    let (u, v) = n.vertex_uv(cells, i, j);
                    direction(n.face, u, v)
                })
                .collect();
            for j in 0..=cells as i64 {
                let (u, v) = key.vertex_uv(cells, cells as i64, j);
                let p = direction(key.face, u, v);
                assert!(theirs.contains(&p), "{key:?} j={j}");
            }
        }
    }
}
