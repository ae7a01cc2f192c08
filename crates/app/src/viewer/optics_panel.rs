//! The side panel's "Rain and ice" section: a rain shaft ahead of the camera (its rate
//! and distance) and a cirrus layer (its base and optical depth), with the rainbows and
//! halos of their phase functions (`optics_settings.rs`).

use atmosphere_core::hydrometeors::scene::SHAFT_DISTANCE_RANGE_M;
use atmosphere_core::hydrometeors::volumes::{CIRRUS_BASE_RANGE_M, CIRRUS_OPTICAL_DEPTH_RANGE};
use atmosphere_core::optics::mie::marshall_palmer::RAIN_RATE_RANGE_MM_H;
use eframe::egui;

use crate::viewer::optics_settings::OpticsSettings;

/// The section's widgets over `optics`.
pub fn show(ui: &mut egui::Ui, optics: &mut OpticsSettings) {
    ui.collapsing("Rain and ice", |ui| {
        ui.checkbox(&mut optics.rain, "rain shaft").on_hover_text(
            "A shaft of Marshall-Palmer rain ahead of the camera, placed where the view \
             points when it is turned on or changed: rainbows with the sun behind you. \
             The first build of its tables takes seconds; they are cached",
        );
        ui.add_enabled_ui(optics.rain, |ui| {
            let [lo, hi] = RAIN_RATE_RANGE_MM_H;
            ui.add(
                egui::Slider::new(&mut optics.rain_rate_mm_h, lo..=hi)
                    .logarithmic(true)
                    .text("rain rate, mm/h"),
            );
            let [lo, hi] = SHAFT_DISTANCE_RANGE_M;
            ui.add(
                egui::Slider::new(&mut optics.rain_distance_m, lo..=hi)
                    .logarithmic(true)
                    .text("distance, m"),
            );
        });
        ui.checkbox(&mut optics.cirrus, "cirrus").on_hover_text(
            "A layer of randomly oriented ice columns: the 22 and 46 degree halos. The \
             first build of its tables takes tens of seconds; they are cached",
        );
        ui.add_enabled_ui(optics.cirrus, |ui| {
            let [lo, hi] = CIRRUS_BASE_RANGE_M;
            ui.add(egui::Slider::new(&mut optics.cirrus_base_m, lo..=hi).text("base, m"));
            let [lo, hi] = CIRRUS_OPTICAL_DEPTH_RANGE;
            ui.add(
                egui::Slider::new(&mut optics.cirrus_optical_depth, lo..=hi)
                    .logarithmic(true)
                    .text("optical depth"),
            );
        });
    });
}
