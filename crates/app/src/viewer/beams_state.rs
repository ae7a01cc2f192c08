//! Which scene the viewer shows and, for a beams scene, everything the panel edits,
//! without a window: the planet (as before) or a beams scene file (a shipped one or any
//! path), its edits ([`BeamsEdit`]), the fly camera ([`FlyCamera`]) and a manual
//! exposure. The edited file is checked into a scene (light maps and meshes loaded)
//! only when it changed; a scene file that does not load leaves the scene shown as it
//! was and its error in [`BeamsState::message`].

use std::path::Path;

use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::beams::scene_file::SceneFile;

use crate::render::scene::EXPOSURE_EV100;
use crate::viewer::beams_camera::FlyCamera;
use crate::viewer::beams_edit::BeamsEdit;

/// The viewer's scene choice and the beams scene's edits.
#[derive(Debug, Default)]
pub struct BeamsState {
    /// The beams scene loaded, shown while `active`.
    pub edit: Option<BeamsEdit>,
    /// Whether the beams scene is shown (else the planet).
    pub active: bool,
    /// The panel's file path field.
    pub path_field: String,
    pub fly: Option<FlyCamera>,
    /// A manual EV100 in the range of `atmos render --exposure`; metered where `None`.
    pub exposure: Option<f64>,
    /// The last load or check error, shown in the panel.
    pub message: String,
    /// The edited file last checked and its scene or error.
    built: Option<(SceneFile, Result<BeamScene, String>)>,
}

impl BeamsState {
    /// Loads the beams scene at `path` and shows it with the camera of its file; on an
    /// error, the message names it and the scene shown stays.
    pub fn open(&mut self, path: &Path) -> bool {
        match BeamsEdit::load(path) {
            Ok(edit) => {
                let method = self.edit.as_ref().map(|e| (e.method, e.settings.clone()));
                self.edit = Some(edit);
                if let (Some(edit), Some((method, settings))) = (self.edit.as_mut(), method) {
                    edit.method = method;
                    edit.settings = settings;
                }
                self.path_field = path.display().to_string();
                self.fly = None;
                self.built = None;
                self.active = true;
                self.message.clear();
                true
            }
            Err(e) => {
                self.message = format!("cannot load {}: {e}", path.display());
                false
            }
        }
    }

    /// Shows the planet again (the beams scene stays loaded).
    pub fn show_planet(&mut self) {
        self.active = false;
    }

    /// The edited scene with the fly camera at `width` x `height` pixels, and the
    /// method's settings; an error naming the field where an edit is refused.
    pub fn frame_scene(
        &mut self,
        width: u32,
        height: u32,
    ) -> Result<(BeamScene, BeamSettings), String> {
        let Some(edit) = &self.edit else {
            return Err("no beams scene loaded".into());
        };
        if let Some(ev) = self.exposure
            && !(ev.is_finite() && (EXPOSURE_EV100[0]..=EXPOSURE_EV100[1]).contains(&ev))
        {
            return Err(format!(
                "exposure {ev} is outside [{}, {}]",
                EXPOSURE_EV100[0], EXPOSURE_EV100[1]
            ));
        }
        let settings = edit.beam_settings()?;
        let file = edit.edited_file()?;
        if self.built.as_ref().is_none_or(|(f, _)| *f != file) {
            let scene = edit.scene();
            self.built = Some((file, scene));
        }
        let mut scene = match &self.built {
            Some((_, Ok(scene))) => scene.clone(),
            Some((_, Err(e))) => return Err(e.clone()),
            None => return Err("no beams scene loaded".into()),
        };
        let fly = *self
            .fly
            .get_or_insert_with(|| FlyCamera::new(&scene.camera));
        scene.camera = fly.camera(&scene.camera, width, height);
        Ok((scene, settings))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::beams_edit::{SHIPPED_SCENES, scene_list};
    use atmosphere_core::beams::light::LightShape;
    use atmosphere_core::beams::methods::id::BeamMethodId;

    /// An edit that spoils a scene.
    type Spoil = fn(&mut BeamsEdit);

    fn shipped(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(SHIPPED_SCENES)
            .join(name)
    }

    #[test]
    fn the_scene_list_is_the_shipped_toml_files_sorted() {
        let list = scene_list(&shipped(""));
        let names: Vec<String> = list
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            [
                "point_lamp.toml",
                "sphere_spotlight.toml",
                "stage_five_spots.toml",
                "stained_glass_room.toml",
                "teapot_spotlight.toml"
            ]
        );
        assert!(scene_list(Path::new("/nonexistent/beams")).is_empty());
    }

    #[test]
    fn an_unedited_scene_is_the_files_with_the_views_size() {
        let path = shipped("stage_five_spots.toml");
        let mut state = BeamsState::default();
        assert!(state.open(&path));
        assert!(state.active);
        let (scene, settings) = state.frame_scene(64, 36).unwrap();
        let mut file = BeamScene::load(&path).unwrap();
        file.camera.width_px = 64;
        file.camera.height_px = 36;
        assert_eq!(scene, file);
        assert_eq!(settings.wavelengths_nm, [680.0, 550.0, 440.0]);
    }

    #[test]
    fn light_and_medium_edits_reach_the_scene() {
        let mut state = BeamsState::default();
        assert!(state.open(&shipped("sphere_spotlight.toml")));
        let base = state.frame_scene(64, 36).unwrap().0;
        let edit = state.edit.as_mut().unwrap();
        edit.density = 2.0;
        edit.lights[0].position_m = [1.0, 18.0, -2.0];
        edit.lights[0].cone_deg = Some(10.0);
        edit.lights[0].intensity = 3.0;
        edit.lights[0].colour = [1.0, 0.5, 0.0];
        edit.method = BeamMethodId::Qtable2002;
        edit.settings = "epsilon=1".into();
        let (scene, settings) = state.frame_scene(64, 36).unwrap();
        for l in [680.0, 550.0, 440.0] {
            let (s0, s1) = (
                &base.medium.scattering_per_m,
                &scene.medium.scattering_per_m,
            );
            assert!((s1.at(l) - 2.0 * s0.at(l)).abs() <= 1e-12 * s0.at(l));
            let (a0, a1) = (
                &base.medium.absorption_per_m,
                &scene.medium.absorption_per_m,
            );
            assert!((a1.at(l) - 2.0 * a0.at(l)).abs() <= 1e-12 * a0.at(l));
        }
        // The colour is a transmission of 1 at 680 nm, 0.5 at 550 nm and 0 at 440 nm.
        let (e0, e1) = (&base.lights[0].emission, &scene.lights[0].emission);
        for (l, tint) in [(680.0, 1.0), (550.0, 0.5), (440.0, 0.0), (615.0, 0.75)] {
            assert!(
                (e1.at(l) - 3.0 * tint * e0.at(l)).abs() <= 1e-9 * e0.at(l),
                "{l}"
            );
        }
        let LightShape::Spot {
            position_m,
            cos_cone,
            ..
        } = scene.lights[0].shape
        else {
            panic!("the sphere scene's light is a spot");
        };
        assert_eq!(position_m.to_array(), [1.0, 18.0, -2.0]);
        assert!((cos_cone - 10f64.to_radians().cos()).abs() < 1e-12);
        let items: Vec<(&str, &str)> = settings.options.items().collect();
        assert_eq!(items, [("epsilon", "1")]);
    }

    #[test]
    fn bad_edits_and_files_are_named_and_never_panic() {
        let mut state = BeamsState::default();
        assert!(!state.open(Path::new("/nonexistent/scene.toml")));
        assert!(
            state.message.contains("/nonexistent/scene.toml"),
            "{}",
            state.message
        );
        assert!(!state.active);
        assert!(state.frame_scene(64, 36).is_err());
        assert!(state.open(&shipped("sphere_spotlight.toml")));
        let cases: [(&str, Spoil); 6] = [
            ("lights[0].cone_deg", |e| e.lights[0].cone_deg = Some(95.0)),
            ("lights[0].light_map", |e| {
                e.lights[0].light_map = "missing.png".into()
            }),
            ("lights[0] intensity", |e| e.lights[0].intensity = f64::NAN),
            ("lights[0] colour", |e| e.lights[0].colour = [2.0, 1.0, 1.0]),
            ("medium density", |e| e.density = -1.0),
            ("lights[0].direction", |e| {
                e.lights[0].direction = Some([0.0; 3])
            }),
        ];
        for (field, spoil) in cases {
            let mut bad = BeamsState::default();
            assert!(bad.open(&shipped("sphere_spotlight.toml")));
            spoil(bad.edit.as_mut().unwrap());
            let error = bad.frame_scene(64, 36).unwrap_err();
            assert!(error.contains(field), "{field}: {error}");
        }
        state.exposure = Some(1e3);
        assert!(
            state
                .frame_scene(64, 36)
                .unwrap_err()
                .contains("exposure 1000")
        );
        state.exposure = None;
        state.edit.as_mut().unwrap().settings = "steps".into();
        assert!(state.frame_scene(64, 36).unwrap_err().contains("steps"));
    }
}
