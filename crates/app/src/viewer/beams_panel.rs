//! The side panel's beams sections: "Scene" (the planet or a beams scene: the shipped
//! ones, or any file by path) and, while a beams scene is shown, its method and
//! settings, medium, lights and statistics (`beams_state.rs`, `beams_edit.rs`).

use std::path::{Path, PathBuf};

use atmosphere_core::beams::methods::id::BeamMethodId;
use eframe::egui;
use render_wgpu::shafts::beams::gpu_methods::GPU_BEAM_METHODS;

use crate::render::scene::EXPOSURE_EV100;
use crate::viewer::beams_edit::{DENSITY_RANGE, INTENSITY_RANGE, LightEdit};
use crate::viewer::beams_state::BeamsState;
use crate::viewer::beams_view::BeamsStats;

/// The "Scene" section: the planet, a shipped beams scene of `shipped`, or a file.
pub fn scene_choice(ui: &mut egui::Ui, state: &mut BeamsState, shipped: &[PathBuf]) {
    egui::CollapsingHeader::new("Scene")
        .default_open(true)
        .show(ui, |ui| {
            let current = match (&state.edit, state.active) {
                (Some(edit), true) => file_name(&edit.path),
                _ => "planet".to_string(),
            };
            let mut chosen: Option<Option<PathBuf>> = None;
            egui::ComboBox::from_label("scene")
                .selected_text(current)
                .show_ui(ui, |ui| {
                    if ui.selectable_label(!state.active, "planet").clicked() {
                        chosen = Some(None);
                    }
                    for path in shipped {
                        let shown =
                            state.active && state.edit.as_ref().is_some_and(|e| e.path == *path);
                        if ui.selectable_label(shown, file_name(path)).clicked() {
                            chosen = Some(Some(path.clone()));
                        }
                    }
                })
                .response
                .on_hover_text(
                    "planet: the atmosphere of the other sections; a beams scene: lights through \
                 fog with shadows in the air (docs/beams.md)",
                );
            ui.horizontal(|ui| {
                ui.text_edit_singleline(&mut state.path_field)
                    .on_hover_text("A beams scene file (TOML, docs/beams.md)");
                if ui.button("open").clicked() {
                    chosen = Some(Some(PathBuf::from(state.path_field.trim())));
                }
            });
            match chosen {
                Some(None) => state.show_planet(),
                Some(Some(path)) => {
                    state.open(&path);
                }
                None => {}
            }
            if !state.message.is_empty() {
                ui.colored_label(egui::Color32::LIGHT_RED, &state.message);
            }
        });
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The sections of the beams scene shown: method, medium, lights, exposure, statistics;
/// `error` is the last frame's error, `frame` its wall time (ms) and size.
pub fn show(
    ui: &mut egui::Ui,
    state: &mut BeamsState,
    stats: &BeamsStats,
    error: &str,
    frame: (f64, (u32, u32)),
) {
    let Some(edit) = state.edit.as_mut() else {
        return;
    };
    egui::CollapsingHeader::new("Beam method")
        .default_open(true)
        .show(ui, |ui| {
            egui::ComboBox::from_label("method")
                .selected_text(edit.method.to_string())
                .show_ui(ui, |ui| {
                    for id in GPU_BEAM_METHODS {
                        ui.selectable_value(&mut edit.method, id, id.to_string());
                    }
                })
                .response
                .on_hover_text(method_help(edit.method));
            ui.horizontal(|ui| {
                ui.label("settings");
                ui.text_edit_singleline(&mut edit.settings).on_hover_text(
                    "key=value separated by spaces, e.g. steps=64 (docs/beams/<method>.md)",
                );
            });
        });
    ui.collapsing("Medium", |ui| {
        ui.add(
            egui::Slider::new(&mut edit.density, DENSITY_RANGE[0]..=DENSITY_RANGE[1])
                .logarithmic(true)
                .text("density ×"),
        )
        .on_hover_text("Multiplies the file's scattering and absorption coefficients");
    });
    ui.collapsing("Lights", |ui| {
        for (i, light) in edit.lights.iter_mut().enumerate() {
            ui.collapsing(format!("lights[{i}]: {}", light.kind), |ui| {
                light_widgets(ui, light);
            });
        }
    });
    ui.collapsing("Exposure", |ui| {
        let mut manual = state.exposure.is_some();
        ui.checkbox(&mut manual, "manual EV100")
            .on_hover_text("Off: metered from the image as `atmos render --scene` meters it");
        if manual {
            let ev = state.exposure.get_or_insert(stats.ev100);
            ui.add(egui::Slider::new(ev, EXPOSURE_EV100[0]..=EXPOSURE_EV100[1]).text("EV100"));
        } else {
            state.exposure = None;
            ui.label(format!("metered EV100 {:.2}", stats.ev100));
        }
    });
    egui::CollapsingHeader::new("Beams stats")
        .default_open(true)
        .show(ui, |ui| {
            let (ms, (w, h)) = frame;
            ui.label(format!("frame {ms:.1} ms at {w}x{h}"))
                .on_hover_text("Wall time of the last frame that changed, and its size");
            ui.label(format!("plan: {}", stats.plan)).on_hover_text(
                "The planner (atmosphere-core's beams/plan.rs): a light whose beam stays outside \
             the view, or in a medium that scatters nothing, is skipped",
            );
            ui.label(format!("steps: {}", stats.steps));
            let gpu = stats
                .gpu_ms
                .map_or("no timestamps".into(), |ms| format!("{ms:.1} ms"));
            ui.label(format!(
                "prepared on the CPU in {:.1} ms; GPU {gpu}",
                stats.prepare_ms
            ))
            .on_hover_text(
                "Preparing (plan, shadow maps, planes, tables) runs only when the scene, camera, \
             size, method or settings change; the GPU time is of the method's passes",
            );
        });
    if !error.is_empty() {
        ui.colored_label(egui::Color32::LIGHT_RED, error);
    }
}

fn method_help(id: BeamMethodId) -> &'static str {
    match id {
        BeamMethodId::March => "a ray march with shadow maps per pixel (the modern baseline)",
        BeamMethodId::Planes2000 => {
            "Dobashi, Yamamoto and Nishita 2000: virtual planes with lattice meshes, light \
             maps and shadow maps"
        }
        BeamMethodId::Qtable2002 => {
            "Dobashi et al. 2002: the pre-integrated q(u, v) table with adaptive sub-planes"
        }
        BeamMethodId::Reference => "adaptive quadrature on the CPU (not in the viewer)",
    }
}

fn light_widgets(ui: &mut egui::Ui, light: &mut LightEdit) {
    vector(ui, "position, m", &mut light.position_m, 0.1);
    if let Some(direction) = light.direction.as_mut() {
        vector(ui, "direction", direction, 0.01);
    }
    if let Some(cone) = light.cone_deg.as_mut() {
        ui.add(egui::Slider::new(cone, 0.5..=88.5).text("cone half-angle °"));
    }
    ui.add(
        egui::Slider::new(
            &mut light.intensity,
            INTENSITY_RANGE[0]..=INTENSITY_RANGE[1],
        )
        .logarithmic(true)
        .text("intensity ×"),
    )
    .on_hover_text("Multiplies the file's intensity (or irradiance)");
    let mut rgb = light.colour.map(|c| c as f32);
    ui.horizontal(|ui| {
        ui.color_edit_button_rgb(&mut rgb);
        ui.label("colour").on_hover_text(
            "A transmission at 680 (red), 550 (green) and 440 nm (blue), linear between, \
             as a light map's texel",
        );
    });
    light.colour = rgb.map(f64::from);
    ui.horizontal(|ui| {
        ui.label("light map");
        ui.text_edit_singleline(&mut light.light_map)
            .on_hover_text("PNG or JPEG relative to the scene file; empty for none");
    });
}

fn vector(ui: &mut egui::Ui, label: &str, v: &mut [f64; 3], speed: f64) {
    ui.horizontal(|ui| {
        for c in v.iter_mut() {
            ui.add(egui::DragValue::new(c).speed(speed).max_decimals(3));
        }
        ui.label(label);
    });
}
