//! What a frame draws while chunk meshes are still being built: every chosen chunk whose
//! mesh is ready, and in place of one that is not, its four children where they are all
//! ready (the camera rising: the finer meshes it just drew) or else its nearest ready
//! ancestor (the camera descending). Never a hole where a ready ancestor exists, never a
//! wait. An ancestor drawn in place of several chosen chunks replaces all of them, so no
//! two drawn chunks overlap. Cover chunks are drawn unstitched: until their chosen chunks
//! arrive, a thin crack may open where a cover meets a chunk of another level.
//! With every mesh ready, the cover is the choice itself, in the same order.

use std::collections::BTreeSet;

use super::chunk_key::ChunkKey;
use super::lod::SelectedChunk;

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
    let unstitched = |key| SelectedChunk {
        key,
        coarser: [false; 4],
    };
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
    let outer: Vec<ChunkKey> = ancestors
        .iter()
        .copied()
        .filter(|&a| !covered(a, true))
        .collect();
    let mut draws: Vec<SelectedChunk> = selected
        .iter()
        .filter(|c| ready(c.key) && !covered(c.key, false))
        .copied()
        .collect();
    draws.extend(
        children
            .into_iter()
            .filter(|&k| !covered(k, false))
            .map(unstitched),
    );
    draws.extend(outer.into_iter().map(unstitched));
    draws
}

#[cfg(test)]
mod tests {
    use std::collections::HashSet;

    use super::super::cube_sphere::Face;
    use super::*;

    fn chosen(keys: &[ChunkKey]) -> Vec<SelectedChunk> {
        keys.iter()
            .map(|&key| SelectedChunk {
                key,
                coarser: [false, true, false, false],
            })
            .collect()
    }

    #[test]
    fn with_every_mesh_ready_the_cover_is_the_choice() {
        let keys = ChunkKey::root(Face(3)).children();
        let selected = chosen(&keys);
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
}
