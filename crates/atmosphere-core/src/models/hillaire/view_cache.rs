//! The per-view tables of Hillaire 2020 (sky-view LUT, aerial-perspective volume) depend
//! on the camera's altitude and the sun's elevation above the camera's horizon; the GPU
//! builds them once per frame. On the CPU they are built on first use for a
//! (camera radius, sun zenith cosine) pair and kept in a small least-recently-used cache,
//! so that the rays of one view share them as the pixels of a frame do.
//!
//! Each table is built inside a once-cell, its rows split over plain scoped threads
//! (`rows::rows_in_parallel`): a rayon-parallel build there could, while waiting for its own
//! tasks, steal another ray of the same view from the caller's pool and re-enter the cell.
//! Threads asking for a table being built wait for it.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, OnceLock};

use crate::atmosphere::Atmosphere;
use crate::models::hillaire::aerial_perspective::AerialPerspective;
use crate::models::hillaire::sky_view::SkyView;

/// The tables of one view, each built when first needed.
#[derive(Debug, Default)]
pub struct ViewTables {
    pub sky_view: OnceLock<SkyView>,
    pub aerial_perspective: OnceLock<AerialPerspective>,
}

/// The view a camera at radius `r` with the sun at zenith cosine `mu_s` belongs to: r to
/// the millimetre (clamped to the atmosphere) and mu_s to 2^-30, so that rounding in the
/// caller's vectors (a sun direction normalised twice) does not make a new view. The
/// per-view tables are built for these values, on the CPU and on the GPU.
pub fn view_key(atmosphere: &Atmosphere, r: f64, mu_s: f64) -> (f64, f64) {
    const MU_S_STEP: f64 = 1.0 / (1u64 << 30) as f64;
    (
        ((r * 1e3).round() * 1e-3).clamp(atmosphere.bottom_radius_m, atmosphere.top_radius_m),
        ((mu_s / MU_S_STEP).round() * MU_S_STEP).clamp(-1.0, 1.0),
    )
}

/// A view's key: the bits of its camera radius and sun cosine.
type ViewKey = (u64, u64);

/// Up to `capacity` views' tables, keyed by the exact camera radius and sun cosine, the
/// most recently used last.
#[derive(Debug)]
pub struct ViewCache {
    capacity: usize,
    entries: Mutex<VecDeque<(ViewKey, Arc<ViewTables>)>>,
}

impl ViewCache {
    pub fn new(capacity: usize) -> ViewCache {
        ViewCache {
            capacity: capacity.max(1),
            entries: Mutex::new(VecDeque::new()),
        }
    }

    /// The tables of the view (r, mu_s), an empty entry if the view is new (the oldest
    /// entry is dropped when the cache is full).
    pub fn get(&self, r: f64, mu_s: f64) -> Arc<ViewTables> {
        let key = (r.to_bits(), mu_s.to_bits());
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(entry) = entries
            .iter()
            .position(|(k, _)| *k == key)
            .and_then(|index| entries.remove(index))
        {
            let tables = Arc::clone(&entry.1);
            entries.push_back(entry);
            return tables;
        }
        if entries.len() >= self.capacity {
            entries.pop_front();
        }
        let tables = Arc::new(ViewTables::default());
        entries.push_back((key, Arc::clone(&tables)));
        tables
    }

    /// Drops every view (the atmosphere changed).
    pub fn clear(&self) {
        self.entries
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clear();
    }

    /// Views held.
    pub fn len(&self) -> usize {
        self.entries.lock().unwrap_or_else(|e| e.into_inner()).len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}
