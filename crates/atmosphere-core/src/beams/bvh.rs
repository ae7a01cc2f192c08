//! A bounding volume hierarchy over triangles: boxes split at the median centroid of
//! their longest side, leaves of a few triangles, traversed without recursion through a
//! fixed stack (the form a shader can mirror).

use glam::DVec3;

use crate::beams::triangle::Triangle;

/// Triangles per leaf at most.
const LEAF_SIZE: usize = 4;
/// The traversal stack: depth is about log2(triangles / LEAF_SIZE) + 1, so 64 holds any
/// mesh that fits in memory.
pub const STACK_DEPTH: usize = 64;

/// A node: its box, and either two children (`count == 0`: `first` is the left child,
/// the right one follows it) or `count` triangles from `first`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    pub min: DVec3,
    pub max: DVec3,
    pub first: usize,
    pub count: usize,
}

/// Triangles reordered into leaves, and the nodes over them (the root first).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bvh {
    triangles: Vec<Triangle>,
    nodes: Vec<Node>,
}

impl Bvh {
    /// The hierarchy over `triangles`.
    pub fn new(mut triangles: Vec<Triangle>) -> Bvh {
        let mut nodes = Vec::new();
        if !triangles.is_empty() {
            nodes.push(Node {
                min: DVec3::ZERO,
                max: DVec3::ZERO,
                first: 0,
                count: triangles.len(),
            });
            // Work list of nodes to split, instead of recursion.
            let mut pending = vec![0];
            while let Some(index) = pending.pop() {
                let Node { first, count, .. } = nodes[index];
                let slice = &mut triangles[first..first + count];
                let (min, max) = bounds(slice);
                nodes[index].min = min;
                nodes[index].max = max;
                if count <= LEAF_SIZE {
                    continue;
                }
                let (cmin, cmax) = slice.iter().fold(
                    (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                    |(lo, hi), t| (lo.min(t.centroid()), hi.max(t.centroid())),
                );
                let axis = (cmax - cmin).max_position();
                let half = count / 2;
                slice.select_nth_unstable_by(half, |a, b| {
                    a.centroid()[axis].total_cmp(&b.centroid()[axis])
                });
                let left = nodes.len();
                for (start, n) in [(first, half), (first + half, count - half)] {
                    nodes.push(Node {
                        min: DVec3::ZERO,
                        max: DVec3::ZERO,
                        first: start,
                        count: n,
                    });
                }
                nodes[index].first = left;
                nodes[index].count = 0;
                pending.extend([left, left + 1]);
            }
        }
        Bvh { triangles, nodes }
    }

    /// How many triangles it holds.
    /// The triangles in leaf order (what a GPU traversal uploads with [`Bvh::nodes`]).
    pub fn triangles(&self) -> &[Triangle] {
        &self.triangles
    }

    /// The nodes, the root first.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// True when it holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The box around every triangle, if there is one.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        self.nodes.first().map(|n| (n.min, n.max))
    }

    /// The nearest t in (t_min, t_max) at which the ray meets a triangle; with
    /// `any_hit`, the first found (enough for a shadow ray).
    pub fn hit(
        &self,
        origin: DVec3,
        direction: DVec3,
        t_min: f64,
        t_max: f64,
        any_hit: bool,
    ) -> Option<f64> {
        if self.nodes.is_empty() {
            return None;
        }
        let inv = direction.recip();
        let mut nearest = t_max;
        let mut found = None;
        let mut stack = [0usize; STACK_DEPTH];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = self.nodes[stack[top]];
            if !box_overlaps(node.min, node.max, origin, inv, t_min, nearest) {
                continue;
            }
            if node.count > 0 {
                for triangle in &self.triangles[node.first..node.first + node.count] {
                    if let Some(t) = triangle.hit(origin, direction, t_min, nearest) {
                        nearest = t;
                        found = Some(t);
                        if any_hit {
                            return found;
                        }
                    }
                }
            } else if top + 2 <= STACK_DEPTH {
                stack[top] = node.first;
                stack[top + 1] = node.first + 1;
                top += 2;
            }
        }
        found
    }
}

fn bounds(triangles: &[Triangle]) -> (DVec3, DVec3) {
    triangles.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), t| {
            let (a, b) = t.bounds();
            (lo.min(a), hi.max(b))
        },
    )
}

/// Whether the ray's interval (t_min, t_max) crosses the box (the slab test).
fn box_overlaps(min: DVec3, max: DVec3, origin: DVec3, inv: DVec3, t_min: f64, t_max: f64) -> bool {
    let (a, b) = ((min - origin) * inv, (max - origin) * inv);
    let enter = a.min(b).max_element().max(t_min);
    let exit = a.max(b).min_element().min(t_max);
    enter <= exit
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of small triangles in the plane z = 0.
    fn grid(n: usize) -> Vec<Triangle> {
        let mut out = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let p = DVec3::new(i as f64, j as f64, 0.0);
                out.push(Triangle([p, p + DVec3::X, p + DVec3::Y]));
                out.push(Triangle([
                    p + DVec3::X,
                    p + DVec3::ONE.with_z(0.0),
                    p + DVec3::Y,
                ]));
            }
        }
        out
    }

    #[test]
    fn bvh_finds_what_testing_every_triangle_finds() {
        let triangles = grid(20);
        let bvh = Bvh::new(triangles.clone());
        assert_eq!(bvh.len(), 800);
        let mut hits = 0;
        for k in 0..400 {
            let x = -1.0 + 22.0 * ((k * 37) % 400) as f64 / 400.0;
            let y = -1.0 + 22.0 * ((k * 91) % 400) as f64 / 400.0;
            let origin = DVec3::new(x, y, 5.0 + (k % 7) as f64);
            let direction = DVec3::new(0.1, -0.05, -1.0).normalize();
            let brute = triangles
                .iter()
                .filter_map(|t| t.hit(origin, direction, 0.0, f64::INFINITY))
                .min_by(f64::total_cmp);
            assert_eq!(bvh.hit(origin, direction, 0.0, f64::INFINITY, false), brute);
            assert_eq!(
                bvh.hit(origin, direction, 0.0, f64::INFINITY, true)
                    .is_some(),
                brute.is_some()
            );
            hits += usize::from(brute.is_some());
        }
        assert!(hits > 200 && hits < 400, "{hits}");
    }
}
