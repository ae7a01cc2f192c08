//! Chunk meshes built off the render thread: a requested mesh is built on rayon's pool
//! and handed back through a channel, so the frame that asks for it never waits.

use std::collections::HashSet;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};

use super::chunk_key::ChunkKey;
use super::chunk_mesh::ChunkMesh;
use super::height_field::HeightField;
use super::lod::SelectedChunk;
use super::surface::TerrainSurface;

/// The most meshes requested and not yet handed back: a camera that moves on leaves few
/// stale requests behind.
pub const MAX_IN_FLIGHT: usize = 64;

/// Builds chunk meshes on other threads; see the module documentation.
#[derive(Debug)]
pub struct ChunkWorker {
    sender: Sender<(u64, ChunkMesh)>,
    receiver: Receiver<(u64, ChunkMesh)>,
    in_flight: HashSet<ChunkKey>,
    /// Counts resets: meshes of an earlier surface are dropped when they arrive.
    generation: u64,
}

impl Default for ChunkWorker {
    fn default() -> Self {
        let (sender, receiver) = channel();
        ChunkWorker {
            sender,
            receiver,
            in_flight: HashSet::new(),
            generation: 0,
        }
    }
}

impl ChunkWorker {
    /// Forgets every request (the surface changed).
    pub fn reset(&mut self) {
        self.generation += 1;
        self.in_flight.clear();
    }

    /// Whether `key`'s mesh is being built.
    pub fn is_building(&self, key: ChunkKey) -> bool {
        self.in_flight.contains(&key)
    }

    /// How many meshes are being built.
    pub fn pending(&self) -> usize {
        self.in_flight.len()
    }

    /// Asks for `chunk`'s mesh of `cells` cells on `surface`; false when
    /// [`MAX_IN_FLIGHT`] meshes are already being built (ask again next frame).
    pub fn request<H: HeightField + Send + Sync + 'static>(
        &mut self,
        surface: &Arc<TerrainSurface<H>>,
        chunk: SelectedChunk,
        cells: u32,
    ) -> bool {
        if self.in_flight.contains(&chunk.key) {
            return true;
        }
        if self.in_flight.len() >= MAX_IN_FLIGHT {
            return false;
        }
        self.in_flight.insert(chunk.key);
        let (surface, sender, generation) =
            (Arc::clone(surface), self.sender.clone(), self.generation);
        rayon::spawn(move || {
            // The receiver lives as long as the worker; a dropped one wants nothing more.
            let _ = sender.send((generation, ChunkMesh::build(&surface, &chunk, cells)));
        });
        true
    }

    /// The meshes finished since the last call, of the current surface.
    pub fn finished(&mut self) -> Vec<ChunkMesh> {
        let mut meshes = Vec::new();
        while let Ok((generation, mesh)) = self.receiver.try_recv() {
            if generation == self.generation && self.in_flight.remove(&mesh.key) {
                meshes.push(mesh);
            }
        }
        meshes
    }
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use glam::DVec3;

    use super::super::cube_sphere::Face;
    use super::*;

    struct Ripples;

    impl HeightField for Ripples {
        fn height_m(&self, d: DVec3) -> f64 {
            900.0 * (40.0 * d.x).sin() * (30.0 * d.y + d.z).cos()
        }
        fn max_abs_height_m(&self) -> f64 {
            900.0
        }
        fn sample_spacing_rad(&self) -> f64 {
            1e-4
        }
    }

    fn chunk(key: ChunkKey) -> SelectedChunk {
        SelectedChunk {
            key,
            coarser: [false; 4],
        }
    }

    /// Waits at most a minute for every request.
    fn drain(worker: &mut ChunkWorker) -> Vec<ChunkMesh> {
        let start = Instant::now();
        let mut meshes = Vec::new();
        while worker.pending() > 0 {
            assert!(start.elapsed() < Duration::from_secs(60), "worker stalled");
            meshes.extend(worker.finished());
            std::thread::sleep(Duration::from_millis(5));
        }
        meshes
    }

    #[test]
    fn meshes_built_off_thread_equal_those_built_in_place() {
        let surface = Arc::new(TerrainSurface::new(Ripples, 6.36e6));
        let keys: Vec<ChunkKey> = ChunkKey::root(Face(1)).children().to_vec();
        let mut worker = ChunkWorker::default();
        for &key in &keys {
            assert!(worker.request(&surface, chunk(key), 8));
            assert!(worker.is_building(key));
        }
        let meshes = drain(&mut worker);
        assert_eq!(meshes.len(), keys.len());
        for mesh in meshes {
            let direct = ChunkMesh::build(&surface, &chunk(mesh.key), 8);
            assert_eq!(mesh.positions, direct.positions);
            assert_eq!(mesh.normals, direct.normals);
            assert_eq!(mesh.morph_offsets, direct.morph_offsets);
            assert_eq!(mesh.morph_normals, direct.morph_normals);
        }
    }

    #[test]
    fn requests_are_capped_and_a_reset_drops_stale_meshes() {
        let surface = Arc::new(TerrainSurface::new(Ripples, 6.36e6));
        let mut worker = ChunkWorker::default();
        let mut keys = vec![ChunkKey::root(Face(0))];
        while keys.len() <= MAX_IN_FLIGHT {
            keys = keys.iter().flat_map(|k| k.children()).collect();
        }
        let accepted = keys
            .iter()
            .filter(|&&k| worker.request(&surface, chunk(k), 4))
            .count();
        assert_eq!(accepted, MAX_IN_FLIGHT);
        worker.reset();
        assert_eq!(worker.pending(), 0);
        std::thread::sleep(Duration::from_millis(200));
        assert!(worker.finished().is_empty());
    }
}
