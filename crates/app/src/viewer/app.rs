//! The eframe app: keyboard and mouse into the flight controller, the side panel, and the
//! sky rendered by the [`Renderer`] on the window's own wgpu device, shown as an egui
//! image the size of the central panel. A frame is rendered only when the size or an
//! input changed, or while tables are still being built: the renderer builds them
//! progressively ([`Renderer::set_progressive`]), so the view stays interactive while
//! they rebuild after a parameter change. While the camera moves it renders at half
//! resolution.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use anyhow::Context;
use eframe::egui;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::{Frame, GpuContext, Renderer};

use crate::cli::ViewArgs;
use crate::viewer::beams_mode::BeamsMode;
use crate::viewer::beams_panel;
use crate::viewer::cloud_settings::CloudSettings;
use crate::viewer::cloud_state::CloudState;
use crate::viewer::exposure::{AutoExposure, ExposureMode};
use crate::viewer::flight::{FlightInput, FlightSettings, FlightState};
use crate::viewer::frame_times::FrameTimes;
use crate::viewer::optics_settings::OpticsSettings;
use crate::viewer::optics_state::OpticsState;
use crate::viewer::panel::{self, Stats};
use crate::viewer::path_editor::PathEditor;
use crate::viewer::screenshot;
use crate::viewer::settings::ViewerSettings;
use crate::viewer::start_view;

/// The largest image rendered, pixels (about 1280x720): more only costs time.
const MAX_PIXELS: f64 = 1280.0 * 720.0;

/// Radians of look per point of mouse drag.
const LOOK_RAD_PER_POINT: f64 = 0.003;

/// The keyboard shortcuts, for the help window.
const SHORTCUTS: &[(&str, &str)] = &[
    ("W / S", "fly forward / back"),
    ("A / D", "fly left / right"),
    ("Q / E", "fly down / up"),
    ("shift", "five times faster"),
    ("drag the image", "look around"),
    ("H", "this help"),
];

/// The viewer; see the module documentation.
pub struct ViewerApp {
    settings: ViewerSettings,
    /// The live camera (with its velocity); `settings` holds its position and view.
    flight: FlightState,
    /// The camera path being edited or previewed.
    path: PathEditor,
    renderer: Renderer,
    render_state: egui_wgpu::RenderState,
    texture: Option<egui::TextureId>,
    /// The last frame rendered, to render again only on change.
    last_frame: Option<Frame>,
    /// The cloud settings of the last frame rendered (the frame does not hold them).
    last_clouds: Option<CloudSettings>,
    clouds: CloudState,
    /// The rain and cirrus of the last frame rendered.
    last_optics: Option<OpticsSettings>,
    optics: OpticsState,
    last_plan: Option<FramePlan>,
    auto_exposure: AutoExposure,
    frame_ms: f64,
    /// The last frames' wall times, for the longest.
    frame_times: FrameTimes,
    adapter: String,
    /// The last report: a screenshot's paths or an error.
    message: String,
    show_help: bool,
    args: ViewArgs,
    frames_shown: u32,
    failure: Arc<Mutex<Option<anyhow::Error>>>,
    /// A beams scene shown instead of the planet, when chosen.
    beams: BeamsMode,
}

impl std::fmt::Debug for ViewerApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ViewerApp")
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl ViewerApp {
    /// The app on eframe's wgpu device, with the settings of the last run (not with
    /// `--frames`). `failure` receives an error the app cannot show (batch screenshots).
    pub fn new(
        cc: &eframe::CreationContext<'_>,
        args: ViewArgs,
        failure: Arc<Mutex<Option<anyhow::Error>>>,
    ) -> anyhow::Result<ViewerApp> {
        let render_state = cc
            .wgpu_render_state
            .clone()
            .context("eframe made no wgpu device")?;
        let gpu = GpuContext::from_existing(
            render_state.instance.clone(),
            render_state.adapter.clone(),
            render_state.device.clone(),
            render_state.queue.clone(),
        );
        let adapter = gpu.adapter_summary();
        let stored = match (args.frames, cc.storage) {
            (None, Some(storage)) => eframe::get_value::<ViewerSettings>(storage, eframe::APP_KEY),
            _ => None,
        };
        // Settings of another version that no longer make a frame are dropped.
        let mut settings = stored
            .filter(|s| s.frame(1, 1).is_ok() && Renderer::check_model(s.model).is_ok())
            .unwrap_or_default();
        start_view::apply(&args.start, &mut settings)?;
        let mut renderer = Renderer::new(gpu)?;
        renderer.set_earth_data(args.earth_data.source()?);
        // Batch screenshots (`--frames`) show complete tables in every frame.
        renderer.set_progressive(args.frames.is_none());
        let mut path = PathEditor::default();
        if let Some(file) = &args.path {
            path.load(file)?;
            path.file = file.display().to_string();
            path.play_pause();
        }
        let mut beams = BeamsMode::new();
        if let Some(file) = &args.beams_scene {
            if !beams.state.open(file) {
                anyhow::bail!("--beams-scene: {}", beams.state.message);
            }
            let method =
                crate::render::beams::gpu_method("--beams-method", args.beams_method.as_deref())?;
            if let Some(edit) = beams.state.edit.as_mut() {
                edit.method = method;
                edit.settings = args.beams_set.join(" ");
            }
        }
        Ok(ViewerApp {
            beams,
            path,
            flight: settings.flight(),
            settings,
            renderer,
            render_state,
            texture: None,
            last_frame: None,
            last_clouds: None,
            clouds: CloudState::default(),
            last_optics: None,
            optics: OpticsState::default(),
            last_plan: None,
            auto_exposure: AutoExposure::default(),
            frame_ms: 0.0,
            frame_times: FrameTimes::default(),
            adapter,
            message: String::new(),
            show_help: false,
            args,
            frames_shown: 0,
            failure,
        })
    }

    /// WASD/QE/shift as a flight input (none while a text field has the keyboard).
    fn keys(ctx: &egui::Context) -> FlightInput {
        if ctx.egui_wants_keyboard_input() {
            return FlightInput::default();
        }
        ctx.input(|i| {
            let axis = |plus, minus| {
                f64::from(u8::from(i.key_down(plus))) - f64::from(u8::from(i.key_down(minus)))
            };
            FlightInput {
                forward: axis(egui::Key::W, egui::Key::S),
                right: axis(egui::Key::D, egui::Key::A),
                up: axis(egui::Key::E, egui::Key::Q),
                boost: i.modifiers.shift,
                ..FlightInput::default()
            }
        })
    }

    /// Whether the renderer is still building: the last frame's tables, terrain meshes
    /// being built or covered, or the terrain's chunks being chosen (more of them next
    /// frame).
    fn renderer_building(&self) -> bool {
        self.last_plan
            .as_ref()
            .is_some_and(|p| p.building.is_some())
            || self
                .renderer
                .terrain_progress()
                .is_some_and(|t| t.covered > 0 || t.building > 0 || t.selecting)
    }

    /// Whether the renderer is building or the rain and ice volumes' tables are being
    /// built on their worker thread (the window repaints to look for them).
    fn building(&self) -> bool {
        self.renderer_building() || self.optics.building()
    }

    /// Renders `frame` if it differs from the last one, the renderer is building, or
    /// the volumes' tables have just been swapped in, and points the egui texture at
    /// it.
    fn render(&mut self, frame: Frame) -> anyhow::Result<()> {
        // A pending build of the volumes is looked for every frame; the image is drawn
        // again only when its volumes arrive.
        let swapped = self.optics.building()
            && self
                .optics
                .apply(&mut self.renderer, &frame, &self.settings.optics)?;
        if self.last_frame.as_ref() == Some(&frame)
            && self.last_clouds.as_ref() == Some(&self.settings.clouds)
            && self.last_optics.as_ref() == Some(&self.settings.optics)
            && !swapped
            && !self.renderer_building()
        {
            return Ok(());
        }
        let start = Instant::now();
        self.clouds
            .apply(&mut self.renderer, &frame, &self.settings.clouds)?;
        self.last_clouds = Some(self.settings.clouds.clone());
        self.optics
            .apply(&mut self.renderer, &frame, &self.settings.optics)?;
        self.last_optics = Some(self.settings.optics.clone());
        let plan = self.renderer.render(&frame)?;
        self.frame_ms = start.elapsed().as_secs_f64() * 1e3;
        self.frame_times.push(self.frame_ms);
        self.last_plan = Some(plan);
        self.last_frame = Some(frame);
        if self.settings.exposure_mode == ExposureMode::Auto {
            self.auto_exposure.meter(self.renderer.average_luminance()?);
        }
        let view = self
            .renderer
            .ldr_texture()
            .context("the renderer kept no image")?
            .create_view(&Default::default());
        let device = &self.render_state.device;
        let mut egui_renderer = self.render_state.renderer.write();
        match self.texture {
            Some(id) => egui_renderer.update_egui_texture_from_wgpu_texture(
                device,
                &view,
                wgpu::FilterMode::Linear,
                id,
            ),
            None => {
                self.texture = Some(egui_renderer.register_native_texture(
                    device,
                    &view,
                    wgpu::FilterMode::Linear,
                ))
            }
        }
        Ok(())
    }

    /// With `--frames N`: after the N-th displayed frame, the screenshot and close.
    fn count_frame(&mut self, ctx: &egui::Context) {
        let Some(frames) = self.args.frames else {
            return;
        };
        self.frames_shown += 1;
        if self.frames_shown < frames {
            ctx.request_repaint();
            return;
        }
        if self.frames_shown > frames {
            return; // closing
        }
        if let Some(path) = &self.args.screenshot {
            let saved = if self.beams.state.active {
                self.beams.save_png(path)
            } else if let Some(frame) = &self.last_frame {
                screenshot::save_png(&self.renderer, frame, path)
            } else {
                Err(anyhow::anyhow!("nothing rendered"))
            };
            match saved.with_context(|| format!("cannot save the screenshot {}", path.display())) {
                Ok(()) => {
                    if self.beams.state.active {
                        eprintln!("atmos view: {}", self.beams.summary());
                    }
                    eprintln!("atmos view: saved {}", path.display())
                }
                Err(e) => {
                    if let Ok(mut failure) = self.failure.lock() {
                        *failure = Some(e);
                    }
                }
            }
        }
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }

    fn help(&mut self, ctx: &egui::Context) {
        egui::Window::new("Keyboard shortcuts")
            .open(&mut self.show_help)
            .show(ctx, |ui| {
                egui::Grid::new("shortcuts").show(ui, |ui| {
                    for (key, what) in SHORTCUTS {
                        ui.strong(*key);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
    }
}

/// The render size for a panel of `points` at `pixels_per_point`: the panel's pixels,
/// at most [`MAX_PIXELS`], halved on each side while moving.
fn render_size(points: egui::Vec2, pixels_per_point: f32, moving: bool) -> (u32, u32) {
    let (w, h) = (
        f64::from(points.x * pixels_per_point).max(1.0),
        f64::from(points.y * pixels_per_point).max(1.0),
    );
    let mut scale = (MAX_PIXELS / (w * h)).sqrt().min(1.0);
    if moving {
        scale *= 0.5;
    }
    let side = |v: f64| ((v * scale).round() as u32).clamp(1, render_wgpu::frame::MAX_SIDE_PX);
    (side(w), side(h))
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        if !ctx.egui_wants_keyboard_input() && ctx.input(|i| i.key_pressed(egui::Key::H)) {
            self.show_help = !self.show_help;
        }
        let mut input = Self::keys(&ctx);
        let dt = f64::from(ctx.input(|i| i.stable_dt)).min(0.1);

        self.settings.set_flight(&self.flight);
        let before = self.settings.clone();
        let stats = Stats {
            frame_ms: self.frame_ms,
            longest_ms: self.frame_times.longest(),
            render_size: self
                .last_frame
                .as_ref()
                .map_or((0, 0), |f| (f.width, f.height)),
            plan: self.last_plan.as_ref(),
            table_bytes: self.renderer.table_bytes(),
            adapter: &self.adapter,
            optics_building: self.optics.building(),
        };
        let beams = &mut self.beams;
        let actions = egui::Panel::left("settings")
            .default_size(320.0)
            .show(ui, |ui| {
                beams_panel::scene_choice(ui, &mut beams.state, &beams.shipped);
                if beams.state.active {
                    let size = beams.shown.as_ref().map_or((0, 0), |p| p.size);
                    let frame = (beams.frame_ms, size);
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        beams_panel::show(
                            ui,
                            &mut beams.state,
                            &beams.view.stats,
                            &beams.error,
                            frame,
                        );
                    });
                    panel::Actions::default()
                } else {
                    panel::show(
                        ui,
                        &mut self.settings,
                        &mut self.path,
                        &stats,
                        &self.message,
                    )
                }
            })
            .inner;
        if self.settings.camera_position_m != before.camera_position_m
            || self.settings.camera_forward != before.camera_forward
        {
            // A jump of the view from the panel: the exposure meets the new view at once.
            self.flight = self.settings.flight();
            self.auto_exposure.reset();
        }

        egui::CentralPanel::default().show(ui, |ui| {
            let size = ui.available_size();
            let (rect, response) = ui.allocate_exact_size(size, egui::Sense::drag());
            let drag = response.drag_delta();
            input.yaw_rad = f64::from(drag.x) * LOOK_RAD_PER_POINT;
            input.pitch_rad = -f64::from(drag.y) * LOOK_RAD_PER_POINT;
            if self.beams.state.active {
                let moving = self.beams.fly(&input, dt) || response.dragged();
                let size = render_size(size, ctx.pixels_per_point(), moving);
                self.beams.paint(ui, self.renderer.gpu(), size, rect);
                if moving {
                    ctx.request_repaint();
                }
                return;
            }
            let radius = self.settings.bottom_radius_m();
            // The camera stays above the terrain drawn (the renderer's heights; none before
            // its first frame with terrain, or with terrain off).
            let renderer = &self.renderer;
            let terrain = self.settings.terrain;
            self.flight
                .step(&FlightSettings::new(radius), &input, dt, |d| {
                    terrain
                        .then(|| renderer.terrain_elevation_m(d))
                        .flatten()
                        .unwrap_or(0.0)
                });
            self.settings.set_flight(&self.flight);
            let moving = self.flight.velocity_m_s.length() > 1e-3 || response.dragged();
            // The time-lapse and the exposure's adaptation animate while they change.
            let mut animating = self.settings.sun_clock.tick(dt) | self.path.tick(dt);
            if self.settings.exposure_mode == ExposureMode::Auto {
                animating |= self
                    .auto_exposure
                    .apply(dt, &mut self.settings.exposure_ev100);
            }
            let (width, height) = render_size(size, ctx.pixels_per_point(), moving);
            // A camera path's frame replaces the live view's while it plays or is scrubbed.
            let rendered = self
                .path
                .preview_frame(width, height)
                .unwrap_or_else(|| self.settings.frame(width, height))
                .and_then(|mut frame| {
                    // Batch screenshots (`--frames`) wait for every terrain mesh, as
                    // offline renders do; the live view never waits.
                    if let Some(terrain) = frame.terrain.as_mut() {
                        terrain.wait_for_chunks = self.args.frames.is_some();
                    }
                    self.render(frame)
                });
            if let Err(e) = rendered {
                self.message = format!("cannot render: {e:#}");
            }
            if let Some(id) = self.texture {
                let uv = egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0));
                ui.painter().image(id, rect, uv, egui::Color32::WHITE);
            }
            if moving || animating || self.building() {
                ctx.request_repaint();
            }
        });
        if actions.screenshot {
            self.message = match &self.last_frame {
                Some(frame) => match screenshot::save_pair(&self.renderer, frame, &self.settings) {
                    Ok((png, exr)) => format!("saved {} and {}", png.display(), exr.display()),
                    Err(e) => format!("cannot save the screenshot: {e:#}"),
                },
                None => "nothing rendered yet".into(),
            };
        }
        self.help(&ctx);
        self.count_frame(&ctx);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.args.frames.is_none() {
            self.settings.set_flight(&self.flight);
            eframe::set_value(storage, eframe::APP_KEY, &self.settings);
        }
    }

    fn persist_egui_memory(&self) -> bool {
        self.args.frames.is_none()
    }
}
