//! The level of detail's choice ([`select_chunks`]) made off the render thread: a frame
//! hands the selector its camera and draws the newest finished choice, never waiting for
//! one. One thread chooses; a camera that arrives while it works replaces any camera still
//! queued, so the next choice is for the newest camera. With the choice comes the order
//! in which its meshes are wanted (coarsest level first, then nearest to its camera), so
//! the frame computes no bounding sphere either.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};

use glam::DVec3;

use super::chunk_key::ChunkKey;
use super::cube_sphere::Face;
use super::lod::{InvalidLodSettings, LodSettings, LodView, SelectedChunk, select_chunks};

/// The drawn elevation above the reference sphere of a unit direction, metres
/// (`TerrainSurface::elevation_m`), shared with the selector's thread.
pub type Elevation = Arc<dyn Fn(DVec3) -> f64 + Send + Sync>;

/// What a choice depends on: the level of detail's settings, the camera and the surface.
#[derive(Clone)]
pub struct SelectionRequest {
    pub settings: LodSettings,
    pub view: LodView,
    pub elevation: Elevation,
}

impl std::fmt::Debug for SelectionRequest {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SelectionRequest")
            .field("settings", &self.settings)
            .field("view", &self.view)
            .finish_non_exhaustive()
    }
}

/// A finished choice.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The camera it was made for.
    pub view: LodView,
    /// The chosen chunks, as [`select_chunks`] returns them.
    pub chunks: Vec<SelectedChunk>,
    /// The same chunks, coarsest level first, then nearest to `view`'s camera: the
    /// order in which their meshes are asked for.
    pub build_order: Vec<SelectedChunk>,
}

impl Selection {
    /// The choice for `request`, made on the calling thread.
    pub fn make(request: &SelectionRequest) -> Result<Selection, InvalidLodSettings> {
        let elevation = |d| (request.elevation)(d);
        let chunks = select_chunks(&request.settings, &request.view, elevation)?;
        let camera = request.view.camera_m;
        let mut keyed: Vec<(u8, f64, SelectedChunk)> = chunks
            .iter()
            .map(|c| {
                let centre = request.settings.bounding_sphere(c.key, &elevation).0;
                (c.key.level, (centre - camera).length(), *c)
            })
            .collect();
        keyed.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        Ok(Selection {
            view: request.view,
            chunks,
            build_order: keyed.into_iter().map(|(_, _, c)| c).collect(),
        })
    }

    /// The six faces ([`root_chunks`]), what a frame draws before the first choice
    /// arrives.
    pub fn roots(view: LodView) -> Selection {
        let chunks = root_chunks();
        Selection {
            view,
            build_order: chunks.clone(),
            chunks,
        }
    }
}

/// The six faces of the cube sphere as chunks: the coarsest choice.
pub fn root_chunks() -> Vec<SelectedChunk> {
    Face::ALL
        .iter()
        .map(|&f| SelectedChunk {
            key: ChunkKey::root(f),
            coarser: [false; 4],
        })
        .collect()
}

/// A choice and how many requests it answers (those it superseded, and its own).
type Answer = (usize, Result<Selection, InvalidLodSettings>);

/// Makes choices on its own thread; see the module documentation.
pub struct ChunkSelector {
    requests: Sender<SelectionRequest>,
    answers: Receiver<Answer>,
    in_flight: usize,
    /// The camera and settings of the last request sent: an unchanged camera asks for
    /// nothing.
    last_sent: Option<(LodSettings, LodView)>,
    latest: Option<Arc<Selection>>,
}

impl std::fmt::Debug for ChunkSelector {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ChunkSelector")
            .field("in_flight", &self.in_flight)
            .field("last_sent", &self.last_sent)
            .finish_non_exhaustive()
    }
}

impl Default for ChunkSelector {
    fn default() -> Self {
        let (requests, inbox) = channel::<SelectionRequest>();
        let (outbox, answers) = channel::<Answer>();
        // The thread ends when the selector, and with it the request channel, is dropped.
        std::thread::Builder::new()
            .name("terrain chunk selection".into())
            .spawn(move || {
                while let Ok(mut request) = inbox.recv() {
                    let mut answered = 1;
                    while let Ok(newer) = inbox.try_recv() {
                        request = newer;
                        answered += 1;
                    }
                    if outbox.send((answered, Selection::make(&request))).is_err() {
                        break;
                    }
                }
            })
            .expect("the operating system starts a thread");
        ChunkSelector {
            requests,
            answers,
            in_flight: 0,
            last_sent: None,
            latest: None,
        }
    }
}

impl ChunkSelector {
    /// Takes the choices finished since the last call (keeping the newest), then asks for
    /// one for `request` unless its camera and settings are those last asked for.
    /// Never waits. An error is that of the newest finished choice (settings out of range).
    pub fn update(&mut self, request: SelectionRequest) -> Result<(), InvalidLodSettings> {
        let mut failure = None;
        while let Ok((answered, result)) = self.answers.try_recv() {
            self.in_flight -= answered;
            match result {
                Ok(selection) => {
                    self.latest = Some(Arc::new(selection));
                    failure = None;
                }
                Err(e) => failure = Some(e),
            }
        }
        if let Some(e) = failure {
            return Err(e);
        }
        let wanted = (request.settings, request.view);
        if self.last_sent != Some(wanted) && self.requests.send(request).is_ok() {
            self.last_sent = Some(wanted);
            self.in_flight += 1;
        }
        Ok(())
    }

    /// Forgets the last request, so the next [`ChunkSelector::update`] asks again (the
    /// surface changed).
    pub fn reset(&mut self) {
        self.last_sent = None;
    }

    /// The newest finished choice; `None` before the first.
    pub fn latest(&self) -> Option<Arc<Selection>> {
        self.latest.clone()
    }

    /// Whether a choice is being made.
    pub fn is_selecting(&self) -> bool {
        self.in_flight > 0
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::time::{Duration, Instant};

    use super::*;

    const R: f64 = 6.36e6;

    fn hills(d: DVec3) -> f64 {
        2000.0 * (1.0 + (20.0 * d.x).sin() * (17.0 * d.y + 0.5 * d.z).cos())
    }

    fn request(altitude_m: f64, elevation: Elevation) -> SelectionRequest {
        let at = DVec3::new(0.3, -0.8, 0.5).normalize();
        SelectionRequest {
            settings: LodSettings::new(R),
            view: LodView::new(at * (R + 4000.0 + altitude_m), 720.0, 1.0),
            elevation,
        }
    }

    /// Calls `update` (a frame) until no choice is in flight; at most a minute.
    fn settle(selector: &mut ChunkSelector, request: &SelectionRequest) {
        let start = Instant::now();
        while selector.is_selecting() {
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "selector stalled"
            );
            std::thread::sleep(Duration::from_millis(2));
            selector.update(request.clone()).unwrap();
        }
    }

    #[test]
    fn a_choice_made_off_thread_equals_the_inline_choice() {
        let mut selector = ChunkSelector::default();
        for altitude_m in [2.0, 3000.0, 4e5] {
            let request = request(altitude_m, Arc::new(hills));
            selector.update(request.clone()).unwrap();
            settle(&mut selector, &request);
            let inline =
                select_chunks(&request.settings, &request.view, hills).expect("valid settings");
            let chosen = selector.latest().expect("a finished choice");
            assert_eq!(chosen.view, request.view);
            assert_eq!(chosen.chunks, inline, "{altitude_m} m");
            // The build order holds the same chunks, coarsest first.
            let mut reordered = chosen.build_order.clone();
            reordered.sort_by_key(|c| c.key);
            assert_eq!(reordered, inline);
            assert!(
                chosen
                    .build_order
                    .windows(2)
                    .all(|w| w[0].key.level <= w[1].key.level)
            );
        }
    }

    /// A choice held back until the test lets it go: frames go on without it, and the
    /// choice that arrives is for the newest camera.
    #[test]
    fn frames_never_wait_for_a_slow_choice() {
        let open = Arc::new(AtomicBool::new(false));
        let gate = Arc::clone(&open);
        let gated: Elevation = Arc::new(move |d| {
            while !gate.load(Ordering::Acquire) {
                std::thread::sleep(Duration::from_millis(1));
            }
            hills(d)
        });
        let mut selector = ChunkSelector::default();
        let cameras = [2.0, 50.0, 900.0].map(|a| request(a, Arc::clone(&gated)));
        let mut frames_while_selecting = 0;
        for frame in 0..30 {
            selector
                .update(cameras[(frame / 10).min(2)].clone())
                .unwrap();
            assert!(selector.latest().is_none(), "the gate is closed");
            frames_while_selecting += usize::from(selector.is_selecting());
        }
        assert_eq!(frames_while_selecting, 30);
        // The first camera is being chosen; the second was replaced by the third.
        open.store(true, Ordering::Release);
        settle(&mut selector, &cameras[2]);
        let chosen = selector.latest().unwrap();
        assert_eq!(chosen.view, cameras[2].view);
        let inline = select_chunks(&cameras[2].settings, &cameras[2].view, hills).unwrap();
        assert_eq!(chosen.chunks, inline);
    }

    #[test]
    fn an_unchanged_camera_asks_for_nothing_and_bad_settings_are_an_error() {
        let mut selector = ChunkSelector::default();
        let request = request(10.0, Arc::new(hills));
        selector.update(request.clone()).unwrap();
        settle(&mut selector, &request);
        selector.update(request.clone()).unwrap();
        assert!(!selector.is_selecting(), "the same camera asked again");
        selector.reset();
        selector.update(request.clone()).unwrap();
        assert!(selector.is_selecting(), "a reset asks again");
        settle(&mut selector, &request);

        let mut bad = request.clone();
        bad.settings.max_error_px = -1.0;
        selector.update(bad.clone()).unwrap();
        let start = Instant::now();
        let error = loop {
            assert!(start.elapsed() < Duration::from_secs(60), "no answer");
            std::thread::sleep(Duration::from_millis(2));
            if let Err(e) = selector.update(bad.clone()) {
                break e;
            }
        };
        assert!(error.to_string().contains("max_error_px: -1"), "{error}");
    }

    #[test]
    fn the_roots_cover_the_planet() {
        let roots = Selection::roots(request(1.0, Arc::new(hills)).view);
        assert_eq!(roots.chunks.len(), 6);
        assert!(roots.chunks.iter().all(|c| c.key.level == 0));
    }
}
