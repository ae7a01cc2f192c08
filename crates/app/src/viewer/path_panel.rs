//! The side panel's "Camera path" section: the keyframes (time, delete), "add keyframe
//! from the current view", the path file's field with save and load, and the preview's
//! play/pause, timeline and "live view". The state and its checks are [`PathEditor`]'s.

use std::path::Path;

use eframe::egui;

use crate::camera_path::keyframe::TIME_S;
use crate::viewer::path_editor::PathEditor;
use crate::viewer::settings::ViewerSettings;

/// Shows the section; edits go through `editor`, whose refusals are shown in red.
pub fn show(ui: &mut egui::Ui, editor: &mut PathEditor, settings: &ViewerSettings) {
    ui.collapsing("Camera path", |ui| {
        keyframes(ui, editor);
        ui.horizontal(|ui| {
            let clicked = ui
                .button("add keyframe from the current view")
                .on_hover_text(
                    "The camera's place, heading and pitch, the sun (angles, or UTC in date \
                     mode), atmosphere preset, model and settings, exposure and terrain",
                )
                .clicked();
            ui.add(
                egui::DragValue::new(&mut editor.new_time_s)
                    .range(TIME_S[0]..=TIME_S[1])
                    .speed(0.1)
                    .suffix(" s"),
            )
            .on_hover_text("The new keyframe's time");
            if clicked {
                report(editor, |e| e.add_from_view(settings), "keyframe added");
            }
        });
        playback(ui, editor);
        file(ui, editor);
        if editor.message.starts_with("refused") {
            ui.colored_label(egui::Color32::RED, editor.message.as_str());
        } else if !editor.message.is_empty() {
            ui.label(editor.message.as_str());
        }
    });
}

/// The keyframes, each with its time and a delete button.
fn keyframes(ui: &mut egui::Ui, editor: &mut PathEditor) {
    if editor.keyframes().is_empty() {
        ui.label("No keyframes yet.");
        return;
    }
    let mut edit = None;
    egui::Grid::new("keyframes").show(ui, |ui| {
        for (i, key) in editor.keyframes().iter().enumerate() {
            ui.label(format!("{}", i + 1));
            let mut time = key.time_s;
            let changed = ui
                .add(
                    egui::DragValue::new(&mut time)
                        .range(TIME_S[0]..=TIME_S[1])
                        .speed(0.1)
                        .suffix(" s"),
                )
                .on_hover_text("The keyframe's time; the list stays in order of time")
                .changed();
            if changed {
                edit = Some((i, Some(time)));
            }
            if ui.button("delete").clicked() {
                edit = Some((i, None));
            }
            ui.end_row();
        }
    });
    match edit {
        Some((i, Some(time))) => report(editor, |e| e.set_time(i, time), ""),
        Some((i, None)) => report(editor, |e| e.delete(i), "keyframe deleted"),
        None => {}
    }
}

/// Play/pause, the timeline and the way back to the live view.
fn playback(ui: &mut egui::Ui, editor: &mut PathEditor) {
    let duration = editor.duration_s();
    ui.horizontal(|ui| {
        ui.add_enabled_ui(editor.path().is_some(), |ui| {
            let label = if editor.playing() { "pause" } else { "play" };
            if ui
                .button(label)
                .on_hover_text("Preview the path in the view")
                .clicked()
            {
                editor.play_pause();
            }
            if ui
                .add_enabled(editor.previewing(), egui::Button::new("live view"))
                .on_hover_text("Back to the camera you fly")
                .clicked()
            {
                editor.stop_preview();
            }
        });
    });
    let mut time = editor.time_s();
    let scrubbed = ui
        .add_enabled(
            editor.path().is_some(),
            egui::Slider::new(&mut time, 0.0..=duration.max(f64::MIN_POSITIVE)).text("time s"),
        )
        .on_hover_text("Scrub the path: the view shows its frame at this time")
        .changed();
    if scrubbed {
        editor.scrub(time);
    }
}

/// The path file's field, save and load.
fn file(ui: &mut egui::Ui, editor: &mut PathEditor) {
    ui.horizontal(|ui| {
        ui.add(egui::TextEdit::singleline(&mut editor.file).desired_width(140.0))
            .on_hover_text("A camera path file (TOML), as `atmos record` reads");
        if ui.button("save").clicked() {
            let file = editor.file.clone();
            report(
                editor,
                |e| e.save(Path::new(&file)),
                &format!("saved {file}"),
            );
        }
        if ui.button("load").clicked() {
            let file = editor.file.clone();
            report(
                editor,
                |e| e.load(Path::new(&file)),
                &format!("loaded {file}"),
            );
        }
    });
}

/// Runs an edit and keeps its outcome as the editor's message.
fn report(
    editor: &mut PathEditor,
    edit: impl FnOnce(&mut PathEditor) -> anyhow::Result<()>,
    done: &str,
) {
    editor.message = match edit(editor) {
        Ok(()) => done.to_string(),
        Err(e) => format!("refused: {e:#}"),
    };
}
