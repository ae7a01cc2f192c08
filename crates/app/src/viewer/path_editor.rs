//! The viewer's camera-path editor, without a window: the keyframes (added from the
//! current view, retimed, deleted), saving and loading path files, and the preview
//! playback whose frame replaces the live view's while it plays or is scrubbed.
//!
//! Every edit is checked by building the whole [`CameraPath`]: an edit that would leave
//! an invalid path is refused with the path's error, and the keyframes stay as they were.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use atmosphere_core::atmosphere::Atmosphere;
use render_wgpu::Frame;

use crate::camera_path::CameraPath;
use crate::camera_path::file::{KeyframeFile, PathHeader};
use crate::viewer::path_capture::keyframe_of;
use crate::viewer::settings::ViewerSettings;

/// Seconds between a new keyframe and the last one.
pub const KEYFRAME_STEP_S: f64 = 5.0;

/// The file a new editor saves to and loads from.
pub const DEFAULT_FILE: &str = "camera_path.toml";

/// The editor's state; see the module documentation.
#[derive(Clone, Debug)]
pub struct PathEditor {
    keyframes: Vec<KeyframeFile>,
    /// The checked path of `keyframes` (none while there are none).
    path: Option<CameraPath>,
    header: PathHeader,
    /// The path file the panel's field names.
    pub file: String,
    /// The time of the next keyframe added, s.
    pub new_time_s: f64,
    /// The playhead, s.
    time_s: f64,
    playing: bool,
    /// Whether the view shows the path (playing or scrubbed) instead of the live camera.
    previewing: bool,
    /// The last edit's outcome (a refusal's reason), for the panel.
    pub message: String,
}

impl Default for PathEditor {
    fn default() -> PathEditor {
        PathEditor {
            keyframes: Vec::new(),
            path: None,
            header: PathHeader::default(),
            file: DEFAULT_FILE.into(),
            new_time_s: 0.0,
            time_s: 0.0,
            playing: false,
            previewing: false,
            message: String::new(),
        }
    }
}

impl PathEditor {
    /// The keyframes as they will be written, in order of time.
    pub fn keyframes(&self) -> &[KeyframeFile] {
        &self.keyframes
    }

    /// The checked path, if there are keyframes.
    pub fn path(&self) -> Option<&CameraPath> {
        self.path.as_ref()
    }

    /// Takes `keyframes` if they make a valid path (sorted by time first).
    fn replace(&mut self, mut keyframes: Vec<KeyframeFile>) -> anyhow::Result<()> {
        keyframes.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        if let Some(pair) = keyframes.windows(2).find(|p| p[0].time_s == p[1].time_s) {
            bail!(
                "two keyframes at time_s {}: each keyframe needs its own time",
                pair[0].time_s
            );
        }
        self.path = if keyframes.is_empty() {
            None
        } else {
            // The origin has no folder: atmosphere files stay as written.
            Some(CameraPath::from_keyframes(
                &self.header,
                &keyframes,
                Path::new("viewer path"),
            )?)
        };
        self.keyframes = keyframes;
        self.time_s = self.time_s.min(self.duration_s());
        Ok(())
    }

    /// Adds a keyframe of the current view at [`new_time_s`](Self::new_time_s); the next
    /// one is then due [`KEYFRAME_STEP_S`] later.
    pub fn add_from_view(&mut self, settings: &ViewerSettings) -> anyhow::Result<()> {
        let key = keyframe_of(settings, self.new_time_s)?;
        let mut keyframes = self.keyframes.clone();
        keyframes.push(key);
        self.replace(keyframes)?;
        self.new_time_s = self.duration_s() + KEYFRAME_STEP_S;
        Ok(())
    }

    /// Moves keyframe `index` (counted from 0) to `time_s`; the list stays in order.
    pub fn set_time(&mut self, index: usize, time_s: f64) -> anyhow::Result<()> {
        let mut keyframes = self.keyframes.clone();
        let n = keyframes.len();
        let key = keyframes
            .get_mut(index)
            .with_context(|| format!("no keyframe {} (there are {n})", index + 1))?;
        key.time_s = time_s;
        self.replace(keyframes)
    }

    /// Deletes keyframe `index` (counted from 0).
    pub fn delete(&mut self, index: usize) -> anyhow::Result<()> {
        let mut keyframes = self.keyframes.clone();
        if index >= keyframes.len() {
            bail!("no keyframe {} (there are {})", index + 1, keyframes.len());
        }
        keyframes.remove(index);
        self.replace(keyframes)
    }

    /// Writes the path to `file` as a version-1 path file.
    pub fn save(&self, file: &Path) -> anyhow::Result<()> {
        let path = self
            .path
            .as_ref()
            .context("no keyframes to save: add one from the current view first")?;
        std::fs::write(file, path.to_toml())
            .with_context(|| format!("cannot write camera path {}", file.display()))
    }

    /// Reads a path file (errors name its line and field), replacing the keyframes; its
    /// relative atmosphere files become absolute, so a save elsewhere still finds them.
    pub fn load(&mut self, file: &Path) -> anyhow::Result<()> {
        let path = CameraPath::load(file)?;
        let mut keyframes = path.keyframes().to_vec();
        for key in &mut keyframes {
            if let Some(a) = &mut key.atmosphere
                && Atmosphere::preset(a).is_err()
                && let Ok(absolute) = std::path::absolute(PathBuf::from(&*a))
            {
                *a = absolute.display().to_string();
            }
        }
        self.header = path.header();
        self.keyframes.clear();
        self.replace(keyframes)?;
        self.time_s = 0.0;
        self.new_time_s = self.duration_s() + KEYFRAME_STEP_S;
        Ok(())
    }

    /// The last keyframe's time, s (0 without keyframes).
    pub fn duration_s(&self) -> f64 {
        self.path.as_ref().map_or(0.0, CameraPath::duration_s)
    }

    /// The playhead, s.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    pub fn playing(&self) -> bool {
        self.playing
    }

    pub fn previewing(&self) -> bool {
        self.previewing
    }

    /// Starts playback (from the start when at the end) or pauses it.
    pub fn play_pause(&mut self) {
        if self.path.is_none() {
            return;
        }
        self.playing = !self.playing;
        if self.playing {
            self.previewing = true;
            if self.time_s >= self.duration_s() {
                self.time_s = 0.0;
            }
        }
    }

    /// Shows the path at `time_s` (clamped to the path), paused there.
    pub fn scrub(&mut self, time_s: f64) {
        if self.path.is_some() {
            self.time_s = time_s.clamp(0.0, self.duration_s());
            self.previewing = true;
            self.playing = false;
        }
    }

    /// Back to the live camera: playback stops.
    pub fn stop_preview(&mut self) {
        self.playing = false;
        self.previewing = false;
    }

    /// Advances playback by `dt_s`, pausing at the end; true while it plays.
    pub fn tick(&mut self, dt_s: f64) -> bool {
        if !self.playing {
            return false;
        }
        self.time_s = (self.time_s + dt_s.max(0.0)).min(self.duration_s());
        if self.time_s >= self.duration_s() {
            self.playing = false;
        }
        true
    }

    /// The path's frame at the playhead while previewing, at `width` x `height`; its
    /// terrain never waits for chunk meshes, as every frame of the viewer.
    pub fn preview_frame(&self, width: u32, height: u32) -> Option<anyhow::Result<Frame>> {
        let path = self.path.as_ref().filter(|_| self.previewing)?;
        Some(path.frame_at(self.time_s, width, height).map(|mut frame| {
            if let Some(terrain) = frame.terrain.as_mut() {
                terrain.wait_for_chunks = false;
            }
            frame
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::settings::GO_TO;
    use crate::viewer::sun_clock::SunMode;
    use atmosphere_core::models::id::ModelId;

    /// Two views: the default (sun by date) and one 10 km up over Sydney, sun by angles,
    /// on another preset and model with settings.
    fn two_views() -> (ViewerSettings, ViewerSettings) {
        let first = ViewerSettings::default();
        let mut second = ViewerSettings::default();
        second.set_preset("hazy").unwrap();
        second.go_to(&GO_TO[1], second.bottom_radius_m());
        second.set_lat_lon_deg(-33.9, 151.2);
        second.set_heading_pitch(123.0, -7.5);
        second.set_sun_mode(SunMode::Angles);
        second.sun_elevation_deg = 12.0;
        second.sun_azimuth_deg = -80.0;
        second.aerosol_scale = 2.5;
        second.model = ModelId::Nishita;
        second
            .model_options
            .insert("nishita".into(), "samples=24".into());
        second.exposure_ev100 = 11.5;
        second.vertical_fov_deg = 45.0;
        (first, second)
    }

    fn close(a: glam::DVec3, b: glam::DVec3, relative: f64) -> bool {
        (a - b).length() <= relative * a.length().max(b.length())
    }

    /// The path's frame at a keyframe's time is the view the keyframe was added from.
    fn assert_same_view(path: &Frame, view: &Frame) {
        assert!(
            close(path.camera_position_m, view.camera_position_m, 1e-6),
            "{} vs {}",
            path.camera_position_m,
            view.camera_position_m
        );
        for (a, b) in path.axes().iter().zip(view.axes()) {
            assert!(close(*a, b, 1e-6), "axes {a} vs {b}");
        }
        assert!(close(path.sun_direction, view.sun_direction, 1e-9));
        assert_eq!(path.model, view.model);
        assert_eq!(path.settings, view.settings);
        assert_eq!(path.exposure_ev100, view.exposure_ev100);
        assert_eq!(path.vertical_fov_deg, view.vertical_fov_deg);
        // A path's frames wait for the terrain's meshes, the viewer's do not.
        let waiting = |f: &Frame| {
            f.terrain.map(|t| render_wgpu::frame::TerrainOptions {
                wait_for_chunks: true,
                ..t
            })
        };
        assert_eq!(waiting(path), waiting(view));
        assert_eq!(path.atmosphere, view.atmosphere);
    }

    #[test]
    fn keyframes_from_the_view_give_back_the_view() {
        let (first, second) = two_views();
        let mut editor = PathEditor::default();
        editor.add_from_view(&first).unwrap();
        assert_eq!(editor.new_time_s, KEYFRAME_STEP_S);
        editor.add_from_view(&second).unwrap();
        assert_eq!(editor.keyframes().len(), 2);
        let path = editor.path().unwrap();
        assert_eq!(path.duration_s(), KEYFRAME_STEP_S);
        assert!(editor.keyframes()[0].utc.is_some(), "date mode: utc");
        assert_eq!(editor.keyframes()[1].sun_elevation_deg, Some(12.0));
        for (time, view) in [(0.0, &first), (KEYFRAME_STEP_S, &second)] {
            assert_same_view(
                &path.frame_at(time, 16, 8).unwrap(),
                &view.frame(16, 8).unwrap(),
            );
        }
    }

    #[test]
    fn times_stay_sorted_and_clashes_are_refused() {
        let (first, second) = two_views();
        let mut editor = PathEditor::default();
        editor.add_from_view(&first).unwrap();
        editor.add_from_view(&second).unwrap();
        editor.new_time_s = 2.0;
        editor.add_from_view(&second).unwrap();
        let times = |e: &PathEditor| e.keyframes().iter().map(|k| k.time_s).collect::<Vec<_>>();
        assert_eq!(times(&editor), [0.0, 2.0, 5.0]);
        // Keyframe 1 moves after the others; the list is in order again.
        editor.set_time(0, 7.0).unwrap();
        assert_eq!(times(&editor), [2.0, 5.0, 7.0]);
        assert_eq!(editor.keyframes()[2].utc, first_key(&first).utc);
        let err = editor.set_time(0, 5.0).unwrap_err().to_string();
        assert!(err.contains("two keyframes at time_s 5"), "{err}");
        assert_eq!(times(&editor), [2.0, 5.0, 7.0], "unchanged");
        editor.new_time_s = 7.0;
        assert!(editor.add_from_view(&first).is_err());
        let err = format!("{:#}", editor.set_time(1, -1.0).unwrap_err());
        assert!(err.contains("time_s -1"), "{err}");
        assert!(
            editor
                .set_time(3, 1.0)
                .unwrap_err()
                .to_string()
                .contains("no keyframe 4")
        );
        editor.delete(1).unwrap();
        assert_eq!(times(&editor), [2.0, 7.0]);
        editor.delete(0).unwrap();
        editor.delete(0).unwrap();
        assert!(editor.path().is_none() && editor.keyframes().is_empty());
        assert!(editor.delete(0).is_err());
    }

    fn first_key(view: &ViewerSettings) -> KeyframeFile {
        keyframe_of(view, 0.0).unwrap()
    }

    #[test]
    fn saved_paths_load_with_the_same_keyframes_and_frames() {
        let (first, second) = two_views();
        let mut editor = PathEditor::default();
        editor.add_from_view(&first).unwrap();
        editor.add_from_view(&second).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("p.toml");
        editor.save(&file).unwrap();
        let mut loaded = PathEditor::default();
        loaded.load(&file).unwrap();
        assert_eq!(loaded.keyframes(), editor.keyframes());
        // The file is what `atmos record` reads.
        let read = CameraPath::load(&file).unwrap();
        for t in [0.0, 1.3, 5.0] {
            assert_eq!(
                read.frame_at(t, 8, 4).unwrap(),
                editor.path().unwrap().frame_at(t, 8, 4).unwrap()
            );
        }
        let err = format!(
            "{:#}",
            loaded.load(&dir.path().join("none.toml")).unwrap_err()
        );
        assert!(err.contains("none.toml"), "{err}");
        assert!(PathEditor::default().save(&file).is_err());
    }

    #[test]
    fn shipped_paths_load_and_write_back_unchanged() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/paths");
        for name in ["ascent_alps.toml", "day_at_one_place.toml"] {
            let mut editor = PathEditor::default();
            editor.load(&dir.join(name)).unwrap();
            let shipped = CameraPath::load(&dir.join(name)).unwrap();
            assert_eq!(
                editor.path().unwrap().to_toml(),
                shipped.to_toml(),
                "{name}"
            );
            assert_eq!(editor.path().unwrap().header(), shipped.header());
        }
    }

    #[test]
    fn playback_plays_scrubs_and_stops() {
        let (first, second) = two_views();
        let mut editor = PathEditor::default();
        editor.play_pause();
        assert!(!editor.playing() && editor.preview_frame(4, 2).is_none());
        editor.add_from_view(&first).unwrap();
        editor.add_from_view(&second).unwrap();
        editor.play_pause();
        assert!(editor.playing() && editor.previewing());
        assert!(editor.tick(2.0));
        assert_eq!(editor.time_s(), 2.0);
        let frame = editor.preview_frame(4, 2).unwrap().unwrap();
        let mut expected = editor.path().unwrap().frame_at(2.0, 4, 2).unwrap();
        if let Some(t) = expected.terrain.as_mut() {
            t.wait_for_chunks = false;
        }
        assert_eq!(frame, expected);
        assert!(editor.tick(10.0));
        assert_eq!(editor.time_s(), KEYFRAME_STEP_S);
        assert!(!editor.playing() && !editor.tick(1.0), "paused at the end");
        editor.play_pause();
        assert_eq!(editor.time_s(), 0.0, "from the start again");
        editor.scrub(99.0);
        assert_eq!(editor.time_s(), KEYFRAME_STEP_S);
        editor.stop_preview();
        assert!(editor.preview_frame(4, 2).is_none());
    }
}
