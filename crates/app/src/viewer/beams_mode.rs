//! The viewer while it shows a beams scene: the fly camera driven by the keys and the
//! mouse ([`FlyCamera`]), the frame rendered by [`BeamsView`] at the panel's size
//! (halved on each side while moving, as the planet view is) and shown as an egui
//! texture, and its PNG for `atmos view --frames N --screenshot`.

use std::path::{Path, PathBuf};
use std::time::Instant;

use eframe::egui;
use render_wgpu::GpuContext;

use crate::files::write_atomically;
use crate::render::image_files::png_of_size;
use crate::viewer::beams_edit::{SHIPPED_SCENES, scene_list};
use crate::viewer::beams_state::BeamsState;
use crate::viewer::beams_view::{BeamsPixels, BeamsView};
use crate::viewer::flight::FlightInput;

/// The beams scene's state, renderer and shown image.
#[derive(Default)]
pub struct BeamsMode {
    pub state: BeamsState,
    pub view: BeamsView,
    /// The shipped scenes, listed once.
    pub shipped: Vec<PathBuf>,
    texture: Option<egui::TextureHandle>,
    /// The frame shown.
    pub shown: Option<BeamsPixels>,
    /// Wall time of the last frame that changed, ms.
    pub frame_ms: f64,
    /// The last frame's error, shown in the panel.
    pub error: String,
}

impl std::fmt::Debug for BeamsMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BeamsMode")
            .field("state", &self.state)
            .finish_non_exhaustive()
    }
}

impl BeamsMode {
    /// With the shipped scenes listed from the working directory.
    pub fn new() -> BeamsMode {
        BeamsMode {
            shipped: scene_list(Path::new(SHIPPED_SCENES)),
            ..BeamsMode::default()
        }
    }

    /// Moves the camera by `input` over `dt` s; whether it moved.
    pub fn fly(&mut self, input: &FlightInput, dt: f64) -> bool {
        self.state.fly.as_mut().is_some_and(|f| f.step(input, dt))
    }

    /// Renders the frame at `size` where anything changed and paints it into `rect`.
    pub fn paint(
        &mut self,
        ui: &mut egui::Ui,
        gpu: &GpuContext,
        size: (u32, u32),
        rect: egui::Rect,
    ) {
        let start = Instant::now();
        let rendered = self
            .state
            .frame_scene(size.0, size.1)
            .map_err(anyhow::Error::msg)
            .and_then(|(scene, settings)| {
                let method = self.state.edit.as_ref().map(|e| e.method);
                let method = method.ok_or_else(|| anyhow::anyhow!("no beams scene loaded"))?;
                self.view
                    .render(gpu, &scene, method, &settings, self.state.exposure)
            });
        match rendered {
            Ok(Some(pixels)) => {
                self.frame_ms = start.elapsed().as_secs_f64() * 1e3;
                self.error.clear();
                let (w, h) = pixels.size;
                let image = egui::ColorImage::from_rgba_unmultiplied(
                    [w as usize, h as usize],
                    pixels.pixels.as_flattened(),
                );
                match &mut self.texture {
                    Some(texture) => texture.set(image, egui::TextureOptions::LINEAR),
                    None => {
                        self.texture = Some(ui.ctx().load_texture(
                            "beams",
                            image,
                            egui::TextureOptions::LINEAR,
                        ))
                    }
                }
                self.shown = Some(pixels);
            }
            Ok(None) => self.error.clear(),
            Err(e) => self.error = format!("cannot render: {e:#}"),
        }
        if let Some(texture) = &self.texture {
            let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
            ui.painter()
                .image(texture.id(), rect, uv, egui::Color32::WHITE);
        }
    }

    /// The last frame's method, plan, steps and times in one line.
    pub fn summary(&self) -> String {
        let stats = &self.view.stats;
        let method = self.state.edit.as_ref().map(|e| e.method.to_string());
        let (w, h) = self.shown.as_ref().map_or((0, 0), |p| p.size);
        let gpu = stats
            .gpu_ms
            .map_or("no timestamps".into(), |ms| format!("{ms:.1} ms"));
        format!(
            "beams {} at {w}x{h}: plan {}; steps: {}; prepared in {:.1} ms, GPU {gpu}, \
             frame {:.1} ms",
            method.unwrap_or_default(),
            stats.plan,
            stats.steps,
            stats.prepare_ms,
            self.frame_ms
        )
    }

    /// The frame shown as a PNG at `path`.
    pub fn save_png(&self, path: &Path) -> anyhow::Result<()> {
        let Some(shown) = &self.shown else {
            anyhow::bail!("no beams frame rendered yet");
        };
        let scene = self
            .state
            .edit
            .as_ref()
            .map(|e| (e.path.display().to_string(), e.method.to_string()))
            .unwrap_or_default();
        let text = [
            ("atmos:beams_scene", scene.0),
            ("atmos:beam_method", scene.1),
            ("atmos:exposure_ev100", self.view.stats.ev100.to_string()),
        ];
        write_atomically(path, &png_of_size(shown.size, &shown.pixels, &text, &[])?)
    }
}
