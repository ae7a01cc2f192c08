//! What a frame draws while chunk meshes are still being built: every chosen chunk whose
//! mesh is ready, and in place of one that is not, its four children where they are all
//! ready (the camera rising: the finer meshes it just drew) or else its nearest ready
//! ancestor (the camera descending). Never a hole where a ready ancestor exists, never a
//! wait. An ancestor drawn in place of several chosen chunks replaces all of them, so no
//! two drawn chunks overlap.
//!
//! The drawn set is then **restricted** as the level of detail's choice is (`lod.rs`):
//! neighbours at most one level apart, so `stitching.rs` closes every seam and the edge
//! vertices morph with the coarser neighbour's factor (`geomorph.rs`) as between chosen
//! chunks. A drawn chunk next to one two or more levels finer is first split where its
//! four children are all ready; where they are not, the finer side is merged into its
//! nearest ready ancestor at most one level finer than the coarse chunk. Each phase only
//! splits or only merges, so both end; the six roots are ready, so a merge always finds
//! an ancestor. Each chunk's coarser edges are those of the drawn set.
//! With every mesh ready, the cover is the choice itself, in the same order.

use std::collections::BTreeSet;

use super::chunk_key::{ChunkKey, Edge};
use super::lod::{SelectedChunk, covering_leaf};

/// Levels below a chosen chunk searched for ready children.
const CHILD_DEPTH: u8 = 2;

/// `key`'s ancestor at `level` (itself at its own level); `None` below its level.
fn ancestor_at(key: ChunkKey, level: u8) -> Option<ChunkKey> {
    let mut k = key;
    while k.level > level {
        k = k.parent();
    }
    (k.level == level).then_some(k)
}

/// Ready descendants covering `key` within `depth` levels, if they cover all of it.
fn ready_descendants(
    key: ChunkKey,
    depth: u8,
    ready: &impl Fn(ChunkKey) -> bool,
    out: &mut Vec<ChunkKey>,
) -> bool {
    if depth == 0 || key.level >= super::chunk_key::MAX_LEVEL {
        return false;
    }
    let start = out.len();
    for child in key.children() {
        if !(ready(child) || ready_descendants(child, depth - 1, ready, out)) {
            out.truncate(start);
            return false;
        }
        if ready(child) {
            out.push(child);
        }
    }
    true
}

/// The chunks to draw for the chosen `selected`, given which meshes are `ready`: the
/// chosen ones where ready, covers elsewhere (see the module documentation).
pub fn cover(selected: &[SelectedChunk], ready: impl Fn(ChunkKey) -> bool) -> Vec<SelectedChunk> {
    let mut ancestors = BTreeSet::new();
    let mut children = Vec::new();
    for chunk in selected.iter().filter(|c| !ready(c.key)) {
        if ready_descendants(chunk.key, CHILD_DEPTH, &ready, &mut children) {
            continue;
        }
        if let Some(a) = (0..chunk.key.level)
            .rev()
            .filter_map(|l| ancestor_at(chunk.key, l))
            .find(|&a| ready(a))
        {
            ancestors.insert(a);
        }
    }
    // An ancestor inside another cover ancestor is drawn by that one.
    let covered = |key: ChunkKey, skip_self: bool| {
        (0..=key.level).any(|l| {
            ancestor_at(key, l).is_some_and(|a| ancestors.contains(&a) && !(skip_self && a == key))
        })
    };
    let mut keys: BTreeSet<ChunkKey> = selected
        .iter()
        .map(|c| c.key)
        .filter(|&k| ready(k) && !covered(k, false))
        .collect();
    keys.extend(children.into_iter().filter(|&k| !covered(k, false)));
    keys.extend(ancestors.iter().copied().filter(|&a| !covered(a, true)));
    restrict_drawn(&mut keys, &ready);
    let stitched = |key: ChunkKey| SelectedChunk {
        key,
        coarser: Edge::ALL.map(|edge| {
            let n = key.neighbour(edge);
            !keys.contains(&n) && n.level > 0 && keys.contains(&n.parent())
        }),
    };
    // The chosen chunks drawn, in their order, then the covers.
    let mut draws: Vec<SelectedChunk> = selected
        .iter()
        .filter(|c| keys.contains(&c.key))
        .map(|c| stitched(c.key))
        .collect();
    let chosen: BTreeSet<ChunkKey> = selected.iter().map(|c| c.key).collect();
    draws.extend(
        keys.iter()
            .filter(|k| !chosen.contains(k))
            .map(|&k| stitched(k)),
    );
    draws
}

/// Splits, then merges, the drawn `keys` until no two neighbours are two or more levels
/// apart, drawing only `ready` chunks (see the module documentation).
fn restrict_drawn(keys: &mut BTreeSet<ChunkKey>, ready: &impl Fn(ChunkKey) -> bool) {
    for merge in [false, true] {
        loop {
            let mut changed = false;
            let snapshot: Vec<ChunkKey> = keys.iter().copied().collect();
            for fine in snapshot {
                if !keys.contains(&fine) {
                    continue;
                }
                let Some(coarse) = Edge::ALL
                    .iter()
                    .filter_map(|&e| covering_leaf(keys, fine.neighbour(e)))
                    .find(|c| c.level + 1 < fine.level)
                else {
                    continue;
                };
                if !merge {
                    let split = coarse.children();
                    if split.iter().all(|&c| ready(c)) {
                        keys.remove(&coarse);
                        keys.extend(split);
                        changed = true;
                    }
                } else if let Some(q) = (0..=coarse.level + 1)
                    .rev()
                    .filter_map(|l| ancestor_at(fine, l))
                    .find(|&a| ready(a))
                {
                    keys.retain(|&k| ancestor_at(k, q.level) != Some(q));
                    keys.insert(q);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use glam::DVec3;

    use super::super::cube_sphere::{Face, direction};
    use super::super::lod::{LodSettings, LodView, select_chunks};
    use super::*;

    fn chosen(keys: &[ChunkKey]) -> Vec<SelectedChunk> {
        keys.iter()
            .map(|&key| SelectedChunk {
                key,
                coarser: [false, true, false, false],
            })
            .collect()
    }

    /// A choice of the level of detail, with its coarser edges.
    #[test]
    fn with_every_mesh_ready_the_cover_is_the_choice() {
        let r = 6.36e6;
        let view = LodView::new(
            DVec3::new(0.3, -0.8, 0.5).normalize() * (r + 900.0),
            720.0,
            1.0,
        );
        let settings = LodSettings {
            cells: 8,
            max_level: 9,
            ..LodSettings::new(r)
        };
        let selected = select_chunks(&settings, &view, |_| 0.0).unwrap();
        assert!(selected.iter().any(|c| c.coarser.iter().any(|&b| b)));
        assert_eq!(cover(&selected, |_| true), selected);
    }

    #[test]
    fn a_missing_chunk_is_covered_by_its_nearest_ready_ancestor_alone() {
        let root = ChunkKey::root(Face(2));
        let [a, b, c, d] = root.children();
        let fine = a.children();
        // Chosen: a's four children and b, c, d; only the root and b are ready.
        let mut keys = fine.to_vec();
        keys.extend([b, c, d]);
        let ready: HashSet<ChunkKey> = [root, b, fine[0]].into();
        let draws = cover(&chosen(&keys), |k| ready.contains(&k));
        // The root covers everything: nothing else may overlap it.
        assert_eq!(draws.len(), 1, "{draws:?}");
        assert_eq!(draws[0].key, root);
        assert_eq!(draws[0].coarser, [false; 4]);
    }

    #[test]
    fn a_missing_chunk_is_covered_by_its_ready_children() {
        let root = ChunkKey::root(Face(4));
        let [a, b, c, d] = root.children();
        let mut ready: HashSet<ChunkKey> = a.children().into();
        ready.extend([b, c, d]);
        let draws = cover(&chosen(&[a, b, c, d]), |k| ready.contains(&k));
        let drawn: HashSet<ChunkKey> = draws.iter().map(|c| c.key).collect();
        assert_eq!(drawn, ready);
    }

    #[test]
    fn nothing_ready_draws_nothing() {
        let keys = ChunkKey::root(Face(0)).children();
        assert!(cover(&chosen(&keys), |_| false).is_empty());
    }

    /// The chosen chunks, those whose meshes were drawn before, and which chosen meshes
    /// are ready besides.
    type Scenario<'a> = (
        &'a [SelectedChunk],
        &'a [SelectedChunk],
        &'a dyn Fn(ChunkKey) -> bool,
    );

    /// `draws` tile the planet once, neighbours at most one level apart, with the coarser
    /// edges flagged where they are (the level of detail's own invariants).
    fn assert_restricted_partition(draws: &[SelectedChunk]) {
        let area: f64 = draws
            .iter()
            .map(|c| 4.0 / (c.key.side() as f64).powi(2))
            .sum();
        assert!((area - 24.0).abs() < 1e-9, "{area}");
        let keys: BTreeSet<ChunkKey> = draws.iter().map(|c| c.key).collect();
        assert_eq!(keys.len(), draws.len(), "a chunk drawn twice");
        for c in draws {
            for edge in Edge::ALL {
                match covering_leaf(&keys, c.key.neighbour(edge)) {
                    Some(n) => {
                        assert!(c.key.level <= n.level + 1, "{:?} next to {n:?}", c.key);
                        assert_eq!(c.coarser[edge as usize], n.level < c.key.level);
                    }
                    None => assert!(!c.coarser[edge as usize]),
                }
            }
        }
    }

    /// The camera descending (the meshes of a view from 2,000 km ready, the choice from
    /// 500 m) and climbing (from 500 m to 50 km), with a third of the chosen meshes ready,
    /// and descending with the chosen meshes ready on one side of a plane through the
    /// camera (fine chunks next to coarse covers, which the restriction must mend): the
    /// drawn set holds covers next to chunks of other levels, and is restricted.
    #[test]
    fn covers_are_restricted_and_stitched_to_their_neighbours() {
        const R: f64 = 6.36e6;
        let settings = LodSettings {
            cells: 8,
            max_error_px: 40.0,
            max_level: 9,
            ..LodSettings::new(R)
        };
        let up = DVec3::new(1.0, 1.0, 1.02).normalize();
        let choose = |altitude_m: f64| {
            let view = LodView::new(up * (R + altitude_m), 1080.0, 1.0);
            select_chunks(&settings, &view, |_| 0.0).unwrap()
        };
        let (near, middle, far) = (choose(500.0), choose(50_000.0), choose(2e6));
        let across = up.cross(DVec3::Z).normalize();
        let one_side = |k: ChunkKey| {
            let (u, v) = k.vertex_uv(8, 4, 4);
            direction(k.face, u, v).dot(across) > 0.0
        };
        let third = |k: ChunkKey| (k.x + k.y).is_multiple_of(3);
        let scenarios: [Scenario; 3] = [
            (&near, &far, &third),
            (&middle, &near, &third),
            (&near, &far, &one_side),
        ];
        for (chosen, before, also_ready) in scenarios {
            let ready: HashSet<ChunkKey> = before
                .iter()
                .map(|c| c.key)
                .chain(chosen.iter().map(|c| c.key).filter(|&k| also_ready(k)))
                .chain(Face::ALL.map(ChunkKey::root))
                .collect();
            let draws = cover(chosen, |k| ready.contains(&k));
            assert!(draws.iter().all(|c| ready.contains(&c.key)));
            assert_restricted_partition(&draws);
            let chosen_keys: HashSet<ChunkKey> = chosen.iter().map(|c| c.key).collect();
            let keys: BTreeSet<ChunkKey> = draws.iter().map(|c| c.key).collect();
            let cover_by_other_level = draws.iter().any(|c| {
                !chosen_keys.contains(&c.key)
                    && Edge::ALL.iter().any(|&e| {
                        covering_leaf(&keys, c.key.neighbour(e))
                            .is_none_or(|n| n.level != c.key.level)
                    })
            });
            assert!(
                cover_by_other_level,
                "no cover meets a chunk of another level"
            );
        }
    }
}
