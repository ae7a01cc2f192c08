//! The side panel's "Rain and ice" section: a rain shaft ahead of the camera (its rate,
//! distance and, as a choice, small drops of a radius), a cirrus layer (its base and
//! optical depth) and a deck of cloud droplets (base, thickness, optical depth, droplet
//! radius), with the rainbows, halos, glories and cloudbows of their phase functions
//! (`optics_settings.rs`), how the march counts their forward peak and which sky's light
//! it scatters, and whether their tables are being built.

use atmosphere_core::hydrometeors::forward_peak::ForwardPeak;
use atmosphere_core::hydrometeors::scene::{
    DECK_DROPLET_RADIUS_RANGE_UM, SHAFT_DISTANCE_RANGE_M, SMALL_DROP_RADIUS_RANGE_UM,
};
use atmosphere_core::hydrometeors::sky_light::SkyLight;
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::hydrometeors::volumes::{
    CIRRUS_BASE_RANGE_M, CIRRUS_OPTICAL_DEPTH_RANGE, DECK_BASE_RANGE_M, DECK_OPTICAL_DEPTH_RANGE,
    DECK_THICKNESS_RANGE_M,
};
use atmosphere_core::optics::mie::marshall_palmer::RAIN_RATE_RANGE_MM_H;
use eframe::egui;

use crate::viewer::optics_settings::OpticsSettings;

/// A slider over `value` within `range`.
fn slider<'a>(value: &'a mut f64, [lo, hi]: [f64; 2], text: &str) -> egui::Slider<'a> {
    egui::Slider::new(value, lo..=hi).text(text)
}

/// The section's widgets over `optics`; `building` while their tables are being built.
pub fn show(ui: &mut egui::Ui, optics: &mut OpticsSettings, building: bool) {
    ui.collapsing("Rain and ice", |ui| {
        if building {
            ui.label("building optics tables...").on_hover_text(
                "The phase tables are built off the render thread (seconds to minutes \
                 the first time, then from the cache); the view shows the volumes made \
                 before until they are ready",
            );
        }
        ui.checkbox(&mut optics.rain, "rain shaft").on_hover_text(
            "A shaft of Marshall-Palmer rain ahead of the camera, placed where the view \
             points when it is turned on or changed: rainbows with the sun behind you. \
             The first build of its tables takes seconds; they are cached",
        );
        ui.add_enabled_ui(optics.rain, |ui| {
            ui.add(
                slider(
                    &mut optics.rain_rate_mm_h,
                    RAIN_RATE_RANGE_MM_H,
                    "rain rate, mm/h",
                )
                .logarithmic(true),
            );
            ui.add(
                slider(
                    &mut optics.rain_distance_m,
                    SHAFT_DISTANCE_RANGE_M,
                    "distance, m",
                )
                .logarithmic(true),
            );
            ui.checkbox(&mut optics.rain_small_drops, "small drops")
                .on_hover_text(
                    "Drops of one effective radius by Lorenz-Mie theory: the supernumerary \
                     bows inside the primary. The first build takes a minute or more",
                );
            ui.add_enabled_ui(optics.rain_small_drops, |ui| {
                ui.add(
                    slider(
                        &mut optics.rain_small_drop_radius_um,
                        SMALL_DROP_RADIUS_RANGE_UM,
                        "drop radius, um",
                    )
                    .logarithmic(true),
                );
            });
        });
        ui.checkbox(&mut optics.cirrus, "cirrus").on_hover_text(
            "A layer of randomly oriented ice columns: the 22 and 46 degree halos. The \
             first build of its tables takes tens of seconds; they are cached",
        );
        ui.add_enabled_ui(optics.cirrus, |ui| {
            ui.add(slider(
                &mut optics.cirrus_base_m,
                CIRRUS_BASE_RANGE_M,
                "base, m",
            ));
            ui.add(
                slider(
                    &mut optics.cirrus_optical_depth,
                    CIRRUS_OPTICAL_DEPTH_RANGE,
                    "optical depth",
                )
                .logarithmic(true),
            );
        });
        ui.checkbox(&mut optics.deck, "droplet deck").on_hover_text(
            "A deck of cloud droplets by Lorenz-Mie theory, in single scattering: from \
             above it, with the sun behind the camera, the glory around the antisolar \
             point and the cloudbow 38 degrees out. The first build takes tens of \
             seconds; they are cached",
        );
        ui.add_enabled_ui(optics.deck, |ui| {
            ui.add(slider(
                &mut optics.deck_base_m,
                DECK_BASE_RANGE_M,
                "deck base, m",
            ));
            ui.add(
                slider(
                    &mut optics.deck_thickness_m,
                    DECK_THICKNESS_RANGE_M,
                    "deck thickness, m",
                )
                .logarithmic(true),
            );
            ui.add(
                slider(
                    &mut optics.deck_optical_depth,
                    DECK_OPTICAL_DEPTH_RANGE,
                    "deck optical depth",
                )
                .logarithmic(true),
            );
            ui.add(slider(
                &mut optics.deck_droplet_radius_um,
                DECK_DROPLET_RADIUS_RANGE_UM,
                "droplet radius, um",
            ));
        });
        ui.horizontal(|ui| {
            ui.label("forward peak:");
            let unscattered = ForwardPeak::Unscattered;
            ui.radio_value(&mut optics.forward_peak, unscattered, unscattered.name())
                .on_hover_text(
                    "The light the drops and crystals scatter within 1 degree of forward \
                     (diffraction) arrives as if unscattered: the volumes' extinction \
                     without it (delta-M). Closer to the path-traced reference",
                );
            let extinction = ForwardPeak::Extinction;
            ui.radio_value(&mut optics.forward_peak, extinction, extinction.name())
                .on_hover_text("That light is lost: the whole extinction (darker volumes)");
        });
        ui.horizontal(|ui| {
            ui.label("sky's light:");
            let sphere = SkyLight::Sphere;
            ui.radio_value(&mut optics.sky_light, sphere, sphere.name())
                .on_hover_text(
                    "The volumes scatter the sky's radiance averaged over every direction \
                     around them (the sky above, the lit ground below): every order of \
                     scattering in a uniform field",
                );
            let horizontal = SkyLight::Horizontal;
            ui.radio_value(&mut optics.sky_light, horizontal, horizontal.name())
                .on_hover_text("The sky's horizontal irradiance over a black ground, once");
        });
        ui.horizontal(|ui| {
            ui.label("sun's higher orders:");
            let probes = MultipleScattering::Probes;
            ui.radio_value(&mut optics.multiple_scattering, probes, probes.name())
                .on_hover_text(
                    "The sun's light scattered two and more times inside the volumes, \
                     from a grid of probes estimated once per volume and sun (a tenth to \
                     a third of a second)",
                );
            let none = MultipleScattering::None;
            ui.radio_value(&mut optics.multiple_scattering, none, none.name())
                .on_hover_text("The sun's light scattered once only (darker thick volumes)");
        });
        ui.add(egui::Slider::new(&mut optics.resolution_divisor, 1..=4).text("resolution divisor"))
            .on_hover_text(
                "The volumes marched for one pixel in N x N and upsampled where the rays' \
             paths through them agree; 1 marches every pixel",
            );
    });
}
