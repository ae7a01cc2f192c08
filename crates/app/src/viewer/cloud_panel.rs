//! The side panel's "Clouds" section: the cloud layer on or off, its cover, base
//! altitude, thickness, density, method, march quality and form: the volume layer, the
//! cloud spheres or a choice by altitude (`cloud_settings.rs`).

use atmosphere_core::clouds::layer::settings::{
    MAX_BASE_M, MAX_EXTINCTION_PER_M, MAX_THICKNESS_M, MIN_BASE_M, MIN_THICKNESS_M,
};

use eframe::egui;

use crate::viewer::cloud_settings::CloudSettings;

/// The section's widgets over `clouds`.
pub fn show(ui: &mut egui::Ui, clouds: &mut CloudSettings) {
    ui.collapsing("Clouds", |ui| {
        ui.checkbox(&mut clouds.on, "cloud layer").on_hover_text(
            "A layer of cloud around the planet from the cover below, ray marched and \
             composited with the current model's light and aerial perspective",
        );
        ui.add_enabled_ui(clouds.on, |ui| {
            ui.horizontal(|ui| {
                ui.label("cover");
                ui.text_edit_singleline(&mut clouds.cover).on_hover_text(
                    "generated: a global cover with the structure of real weather; or any \
                     equirectangular image, FILE.png[:r|g|b|a], whose channel is the cover",
                );
            });
            ui.add(egui::Slider::new(&mut clouds.base_m, MIN_BASE_M..=MAX_BASE_M).text("base, m"));
            ui.add(
                egui::Slider::new(&mut clouds.thickness_m, MIN_THICKNESS_M..=MAX_THICKNESS_M)
                    .logarithmic(true)
                    .text("thickness, m"),
            );
            ui.add(
                egui::Slider::new(&mut clouds.density_per_m, 0.0..=MAX_EXTINCTION_PER_M)
                    .logarithmic(true)
                    .text("density, 1/m"),
            )
            .on_hover_text("Extinction where the cloud is densest (a cumulus core: about 0.1)");
            egui::ComboBox::from_label("method")
                .selected_text(clouds.method.as_str())
                .show_ui(ui, |ui| {
                    for method in ["riley", "octaves", "eddington", "four-stream"] {
                        ui.selectable_value(&mut clouds.method, method.to_string(), method);
                    }
                })
                .response
                .on_hover_text(
                    "riley: Riley et al. 2004's expected orders of scattering; octaves: \
                     Wrenninge et al. 2013's production approximation; eddington: the \
                     light that diffuses through thick cloud (delta-Eddington slab); \
                     four-stream: the same from a delta-M four-stream slab, closer to the \
                     path tracer, dearer",
                );
            egui::ComboBox::from_label("quality")
                .selected_text(clouds.quality.as_str())
                .show_ui(ui, |ui| {
                    for quality in ["interactive", "offline"] {
                        ui.selectable_value(&mut clouds.quality, quality.to_string(), quality);
                    }
                })
                .response
                .on_hover_text(
                    "interactive: 20 steps at a third of the resolution, the cloud \
                     spheres at a third and the cloud's shadow in the air at a sixth, for \
                     flight; offline: 128 steps and the spheres at \
                     full resolution, for recordings",
                );
            egui::ComboBox::from_label("form")
                .selected_text(clouds.form.as_str())
                .show_ui(ui, |ui| {
                    for form in ["auto", "layer", "spheres"] {
                        ui.selectable_value(&mut clouds.form, form.to_string(), form);
                    }
                })
                .response
                .on_hover_text(
                    "auto: the layer up to 50 km, the cloud spheres from 100 km, blended \
                     between; layer: the volume's march; spheres: Dobashi et al. 2002's \
                     cloud spheres (made anew on the CPU when the sun moves)",
                );
            ui.checkbox(&mut clouds.shafts, "cloud shafts")
                .on_hover_text(
                    "the cloud's shadow in the air below its base (crepuscular rays under a \
                 deck with gaps; every model)",
                );
        });
    });
}
