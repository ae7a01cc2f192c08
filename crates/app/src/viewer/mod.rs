//! The interactive viewer (issue 5): a window (eframe, on the window's wgpu device) with
//! the rendered sky in the middle and a side panel of settings. `atmos` with no arguments
//! and `atmos view` open it.
//!
//! One idea per file: [`settings`] (the panel's state and its [`Frame`](render_wgpu::Frame),
//! no window), [`panel`] (the side panel's widgets), [`app`] (the eframe app: input,
//! rendering, the image), [`screenshot`] (PNG and EXR files of the view), [`flight`]
//! (the flight controller), [`sun_clock`] (the sun by angles or by UTC date and time, and
//! the time-lapse), [`exposure`] (manual and automatic exposure) and [`default_view`]
//! (the view a first start and "reset view" show); [`model_error`] (the model panel's
//! measured error and GPU cost, from the report); [`path_capture`] (a camera-path
//! keyframe of the view), [`path_editor`] (the keyframes, path files and playback) and
//! [`path_panel`] (the panel's "Camera path" section); [`cloud_settings`],
//! [`cloud_panel`] and [`cloud_state`] (the cloud layer's settings, its panel section,
//! and what the renderer is given for it); [`optics_settings`], [`optics_panel`] and
//! [`optics_state`] (the rain shaft and cirrus layer, alike); [`beams_edit`],
//! [`beams_state`], [`beams_camera`], [`beams_view`], [`beams_mode`] and [`beams_panel`]
//! (a beams scene instead of the planet: the file and its edits, the scene choice, the
//! fly camera, the frame rendered, the view's part of the app, and the panel's sections).

pub mod app;
pub mod beams_camera;
pub mod beams_edit;
pub mod beams_mode;
pub mod beams_panel;
pub mod beams_state;
pub mod beams_view;
pub mod cloud_panel;
pub mod cloud_settings;
pub mod cloud_state;
pub mod default_view;
pub mod exposure;
pub mod flight;
pub mod frame_times;
pub mod model_error;
pub mod optics_panel;
pub mod optics_settings;
pub mod optics_state;
pub mod panel;
pub mod path_capture;
pub mod path_editor;
pub mod path_panel;
pub mod screenshot;
pub mod settings;
pub mod start_view;
pub mod sun_clock;

use std::sync::{Arc, Mutex};

use anyhow::bail;
use render_wgpu::gpu::adapter_choice::choose_adapter;

use crate::cli::ViewArgs;

/// What to run instead when there is no display.
const HEADLESS_HINT: &str = "without a display, render images with:\n  \
     atmos render --scene assets/scenes/default.toml --out sky.png";

/// Opens the viewer window and runs it until it is closed (or, with `--frames`, until
/// that many frames are shown). Without a display, an error saying so.
pub fn run(args: &ViewArgs) -> anyhow::Result<()> {
    // Bad flags are named before any window opens.
    start_view::apply(&args.start, &mut settings::ViewerSettings::default())?;
    args.earth_data.source()?;
    if let Some(path) = &args.path {
        crate::camera_path::CameraPath::load(path)?;
    }
    if let Some(path) = &args.beams_scene {
        crate::render::beams::gpu_method("--beams-method", args.beams_method.as_deref())?;
        let mut edit =
            beams_edit::BeamsEdit::load(path).map_err(|e| anyhow::anyhow!("--beams-scene: {e}"))?;
        edit.settings = args.beams_set.join(" ");
        edit.beam_settings()
            .map_err(|e| anyhow::anyhow!("--beams-set: {e}"))?;
    }
    let has_display = ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()));
    if cfg!(target_os = "linux") && !has_display {
        bail!(
            "the viewer needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set; \
             {HEADLESS_HINT}"
        );
    }
    let batch = args.frames.is_some();
    let defaults = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    let backends = defaults.instance_descriptor.backends;
    // The adapter as headless rendering chooses it: one that can run every pass.
    let choose = move |adapters: &[wgpu::Adapter], surface: Option<&wgpu::Surface<'_>>| {
        choose_adapter(adapters, backends, surface).map_err(|e| e.to_string())
    };
    let wgpu_setup = egui_wgpu::WgpuSetupCreateNew {
        native_adapter_selector: Some(Arc::new(choose)),
        device_descriptor: Arc::new(render_wgpu::gpu::context::device_descriptor),
        ..defaults
    };
    let options = eframe::NativeOptions {
        viewport: eframe::egui::ViewportBuilder::default()
            .with_title("atmos")
            .with_inner_size([1280.0, 760.0]),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: wgpu_setup.into(),
            ..Default::default()
        },
        persist_window: !batch,
        ..Default::default()
    };
    // The app's own failure (a screenshot it could not write), kept for after the loop.
    let failure = Arc::new(Mutex::new(None));
    let app_failure = Arc::clone(&failure);
    let args = args.clone();
    let result = eframe::run_native(
        "atmos",
        options,
        Box::new(move |cc| Ok(Box::new(app::ViewerApp::new(cc, args, app_failure)?))),
    );
    match result {
        // No adapter can run atmos: headless rendering would not help either.
        Err(eframe::Error::Wgpu(egui_wgpu::WgpuError::CustomNativeAdapterSelectionError(e))) => {
            bail!("cannot open the viewer window: {e}")
        }
        Err(e) => bail!("cannot open the viewer window ({e}); {HEADLESS_HINT}"),
        Ok(()) => {}
    }
    match failure.lock().map(|mut f| f.take()) {
        Ok(Some(e)) => Err(e),
        _ => Ok(()),
    }
}
