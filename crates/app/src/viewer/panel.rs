//! The side panel: Sun, Camera, Atmosphere, Model, Image, Camera path and Stats, every
//! control with a tooltip. It edits [`ViewerSettings`] (whose ranges keep every value valid) and asks
//! the app for what it cannot do itself (a screenshot).

use eframe::egui;
use render_wgpu::frame::plan::FramePlan;
use render_wgpu::frame::{MAX_EXAGGERATION, terrain_fits};
use render_wgpu::sky::registry::GPU_MODELS;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::optics::sea_surface::WIND_RANGE_M_S;
use atmosphere_core::sun_position::days_in_month;

use crate::viewer::cloud_panel;
use crate::viewer::exposure::ExposureMode;
use crate::viewer::model_error;
use crate::viewer::optics_panel;
use crate::viewer::path_editor::PathEditor;
use crate::viewer::path_panel;
use crate::viewer::settings::{
    ALTITUDE_RANGE_M, GO_TO, PRESETS, ViewerSettings, altitude_to_slider, slider_to_altitude,
};
use crate::viewer::sun_clock::{self, SPEED_RANGE, SunMode};

/// What the Stats section shows.
#[derive(Debug)]
pub struct Stats<'a> {
    /// Wall time of the last render, ms.
    pub frame_ms: f64,
    /// The longest of the last renders, ms, and its ratio to their median.
    pub longest_ms: Option<(f64, f64)>,
    /// Size of the last rendered image, pixels.
    pub render_size: (u32, u32),
    pub plan: Option<&'a FramePlan>,
    pub table_bytes: u64,
    pub adapter: &'a str,
    /// The rain and ice volumes' tables are being built off the render thread.
    pub optics_building: bool,
}

/// What the user asked of the app this frame.
#[derive(Debug, Default)]
pub struct Actions {
    pub screenshot: bool,
}

/// Shows the panel's sections; `message` is the last report (screenshot path or error).
pub fn show(
    ui: &mut egui::Ui,
    settings: &mut ViewerSettings,
    path: &mut PathEditor,
    stats: &Stats,
    message: &str,
) -> Actions {
    let mut actions = Actions::default();
    egui::ScrollArea::vertical().show(ui, |ui| {
        sun(ui, settings);
        camera(ui, settings);
        atmosphere(ui, settings);
        terrain(ui, settings);
        cloud_panel::show(ui, &mut settings.clouds);
        optics_panel::show(ui, &mut settings.optics, stats.optics_building);
        model(ui, settings);
        actions.screenshot = image(ui, settings);
        path_panel::show(ui, path, settings);
        stats_section(ui, stats);
        if !message.is_empty() {
            ui.separator();
            ui.label(message);
        }
        ui.label("Press H for the keyboard shortcuts.");
    });
    actions
}

fn sun(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    ui.collapsing("Sun", |ui| {
        let mut mode = settings.sun_clock.mode;
        ui.horizontal(|ui| {
            ui.selectable_value(&mut mode, SunMode::Date, "date and time")
                .on_hover_text(
                    "The sun from a UTC date and time and the camera's latitude and longitude \
                     (NOAA/Meeus): flying round the planet crosses day and night",
                );
            ui.selectable_value(&mut mode, SunMode::Angles, "elevation/azimuth")
                .on_hover_text("The sun at a fixed elevation and azimuth wherever the camera is");
        });
        if mode != settings.sun_clock.mode {
            settings.set_sun_mode(mode);
        }
        match mode {
            SunMode::Angles => {
                ui.add(
                    egui::Slider::new(&mut settings.sun_elevation_deg, -20.0..=90.0)
                        .text("elevation °"),
                )
                .on_hover_text("Sun elevation above the horizon at the camera, degrees");
                ui.add(
                    egui::Slider::new(&mut settings.sun_azimuth_deg, -180.0..=180.0)
                        .text("azimuth °"),
                )
                .on_hover_text("Sun azimuth from north towards east at the camera, degrees");
            }
            SunMode::Date => {
                date_and_time(ui, settings);
                match settings.sun_angles_deg() {
                    Ok((elevation, azimuth)) => {
                        ui.label(format!(
                            "elevation {elevation:.2}°, azimuth {:.2}°",
                            azimuth.rem_euclid(360.0)
                        ))
                        .on_hover_text(
                            "The sun at the camera: degrees above the horizon, and from north \
                             towards east",
                        );
                    }
                    Err(e) => {
                        ui.colored_label(egui::Color32::RED, format!("{e:#}"));
                    }
                }
            }
        }
    });
}

/// The date, the time of day (UTC), the solar time at the camera and the time-lapse.
fn date_and_time(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    let clock = &mut settings.sun_clock;
    let mut time = clock.date_time();
    let mut changed = false;
    ui.horizontal(|ui| {
        changed |= ui
            .add(egui::DragValue::new(&mut time.year).range(1583..=9999))
            .on_hover_text("Year (Gregorian)")
            .changed();
        changed |= ui
            .add(egui::DragValue::new(&mut time.month).range(1..=12))
            .on_hover_text("Month")
            .changed();
        let days = days_in_month(time.year, time.month);
        changed |= ui
            .add(egui::DragValue::new(&mut time.day).range(1..=days))
            .on_hover_text("Day of the month")
            .changed();
        ui.label("date (UTC)");
    });
    let mut hours = time.day_fraction() * 24.0;
    let moved = ui
        .add(
            egui::Slider::new(&mut hours, 0.0..=23.999)
                .text("time UTC")
                .custom_formatter(|h, _| sun_clock::format_hms(h)),
        )
        .on_hover_text("Time of day, Coordinated Universal Time (hours)")
        .changed();
    if moved {
        let seconds = (hours * 3600.0).round();
        time.hour = (seconds / 3600.0) as u32;
        time.minute = (seconds / 60.0 % 60.0) as u32;
        time.second = seconds % 60.0;
    }
    if changed || moved {
        time.day = time.day.min(days_in_month(time.year, time.month));
        if let Err(e) = clock.set_date_time(&time) {
            ui.colored_label(egui::Color32::RED, e.to_string());
        }
    }
    let (latitude, longitude) = settings.camera_lat_lon_deg();
    if let Ok(sun) = settings.sun_clock.sun(latitude, longitude) {
        ui.label(format!(
            "solar time at the camera {}",
            sun_clock::format_hms(sun_clock::solar_time_h(&sun))
        ))
        .on_hover_text(
            "Local apparent solar time at the camera's longitude: 12:00 when the sun is \
             highest (UTC + longitude / 15° per hour + the equation of time)",
        );
    }
    let clock = &mut settings.sun_clock;
    ui.horizontal(|ui| {
        let label = if clock.running { "pause" } else { "play" };
        if ui
            .button(label)
            .on_hover_text("Start or stop the time-lapse")
            .clicked()
        {
            clock.running = !clock.running;
        }
        ui.add(
            egui::Slider::new(&mut clock.speed, SPEED_RANGE.0..=SPEED_RANGE.1)
                .logarithmic(true)
                .text("× real time"),
        )
        .on_hover_text(
            "Time-lapse speed: simulated seconds per real second (1 = real time, \
             10,000 = a day in under 9 s)",
        );
    });
}

fn camera(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    ui.collapsing("Camera", |ui| {
        let radius = settings.bottom_radius_m();
        let altitude = settings.altitude_m(radius);
        ui.label(format!("altitude {}", format_distance(altitude)))
            .on_hover_text("Height of the camera above the ground");
        let mut slider = altitude_to_slider(altitude);
        let (low, high) = (
            altitude_to_slider(ALTITUDE_RANGE_M.0),
            altitude_to_slider(ALTITUDE_RANGE_M.1),
        );
        let response = ui
            .add(
                egui::Slider::new(&mut slider, low..=high)
                    .text("altitude")
                    .custom_formatter(|v, _| format_distance(slider_to_altitude(v))),
            )
            .on_hover_text("Altitude on a logarithmic scale, 1 m to 100,000 km");
        if response.changed() {
            settings.set_altitude(slider_to_altitude(slider), radius);
        }
        let flight = settings.flight();
        let mut heading = flight.heading_rad().to_degrees();
        let mut pitch = flight.pitch_rad().to_degrees();
        let turned = ui
            .add(egui::Slider::new(&mut heading, -180.0..=180.0).text("heading °"))
            .on_hover_text("View direction from north towards east, degrees")
            .changed()
            | ui.add(egui::Slider::new(&mut pitch, -89.0..=89.0).text("pitch °"))
                .on_hover_text("View direction above the horizon, degrees")
                .changed();
        if turned {
            settings.set_heading_pitch(heading, pitch);
        }
        ui.add(egui::Slider::new(&mut settings.vertical_fov_deg, 5.0..=120.0).text("fov °"))
            .on_hover_text("Vertical field of view, degrees");
        let (mut latitude, mut longitude) = settings.camera_lat_lon_deg();
        let jumped = ui
            .horizontal(|ui| {
                let lat = degrees_field(
                    ui,
                    &mut latitude,
                    -90.0..=90.0,
                    "° N",
                    "Latitude of the point below the camera, degrees north (south negative); \
                     edit to jump there at the same altitude",
                );
                let lon = degrees_field(
                    ui,
                    &mut longitude,
                    -180.0..=180.0,
                    "° E",
                    "Longitude of the point below the camera, degrees east of Greenwich (west \
                     negative); edit to jump there at the same altitude",
                );
                lat | lon
            })
            .inner;
        if jumped {
            settings.set_lat_lon_deg(latitude, longitude);
        }
        ui.horizontal_wrapped(|ui| {
            for target in GO_TO {
                let tip = format!(
                    "Go to {} above the ground, looking {:+}° from the horizon",
                    format_distance(target.altitude_m),
                    target.pitch_deg
                );
                if ui.button(target.label).on_hover_text(tip).clicked() {
                    settings.go_to(target, radius);
                }
            }
        });
        if ui
            .button("reset view")
            .on_hover_text(
                "Back to the first view: 3 km above the Alps near the Matterhorn on an \
                 October evening, the sun 5° high (camera, date and time)",
            )
            .clicked()
        {
            settings.reset_view();
        }
    });
}

/// A coordinate in degrees, dragged or typed to four decimals; true when it changed.
fn degrees_field(
    ui: &mut egui::Ui,
    degrees: &mut f64,
    range: std::ops::RangeInclusive<f64>,
    suffix: &str,
    tip: &str,
) -> bool {
    ui.add(
        egui::DragValue::new(degrees)
            .range(range)
            .speed(0.01)
            .fixed_decimals(4)
            .suffix(suffix),
    )
    .on_hover_text(tip)
    .changed()
}

fn terrain(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    let fits = Atmosphere::preset(&settings.preset).is_ok_and(|a| terrain_fits(&a));
    ui.collapsing("Terrain", |ui| {
        ui.add_enabled(
            fits,
            egui::Checkbox::new(&mut settings.terrain, "Earth terrain"),
        )
        .on_disabled_hover_text(
            "The Earth's relief fits an Earth-sized planet only: this preset's planet is \
             drawn as a smooth sphere",
        )
        .on_hover_text(
            "The Earth's relief (NOAA ETOPO5) and colour (NASA Blue Marble) from assets/earth, \
             lit by the sun and sky of the current model and seen through its air; off: a \
             smooth sphere with the atmosphere's ground albedo",
        );
        ui.add_enabled(
            settings.terrain,
            egui::Checkbox::new(&mut settings.shafts, "Light shafts"),
        )
        .on_hover_text(
            "The mountains' shadows in the air: the sun's visibility past the terrain at \
             the sky model's samples, or their length for bruneton (all but dobashi and \
             riley; docs/shafts.md)",
        );
        ui.add_enabled(
            settings.terrain,
            egui::Slider::new(&mut settings.exaggeration, 1.0..=MAX_EXAGGERATION)
                .logarithmic(true)
                .text("exaggeration"),
        )
        .on_hover_text(
            "Vertical exaggeration of the heights: 1 is true scale; the Earth's relief is \
             0.14 % of its radius, so views from orbit show it better at 10 to 50",
        );
        ui.add_enabled(
            settings.terrain,
            egui::Slider::new(&mut settings.wind_m_s, WIND_RANGE_M_S).text("wind, m/s"),
        )
        .on_hover_text(
            "Wind over the sea: the sun's glint on the water spreads with the waves' slopes, \
             whose mean square grows with the wind (Cox and Munk 1954); 0 is a calm sea",
        );
    });
}

fn atmosphere(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    ui.collapsing("Atmosphere", |ui| {
        let mut preset = settings.preset.clone();
        egui::ComboBox::from_label("preset")
            .selected_text(&preset)
            .show_ui(ui, |ui| {
                for name in PRESETS {
                    ui.selectable_value(&mut preset, name.to_string(), *name);
                }
            })
            .response
            .on_hover_text("Atmosphere preset; resets the values below to the preset's");
        if preset != settings.preset {
            // Presets are known names: this cannot fail, but say so if it does.
            if let Err(e) = settings.set_preset(&preset) {
                ui.colored_label(egui::Color32::RED, e.to_string());
            }
        }
        ui.add(egui::Slider::new(&mut settings.aerosol_scale, 0.0..=10.0).text("aerosol ×"))
            .on_hover_text("Factor on the preset's aerosol (Mie) scattering and extinction");
        ui.add(egui::Slider::new(&mut settings.mie_g, -0.95..=0.95).text("Mie g"))
            .on_hover_text("Asymmetry of the aerosol phase function: 0 isotropic, near 1 forward");
        ui.checkbox(&mut settings.ozone, "ozone")
            .on_hover_text("Ozone absorption on or off");
        ui.add(egui::Slider::new(&mut settings.ground_albedo, 0.0..=1.0).text("ground albedo"))
            .on_hover_text("Lambertian reflectance of the ground");
        if let Err(e) = settings.atmosphere() {
            ui.colored_label(egui::Color32::RED, format!("{e:#}"));
        }
    });
}

fn model(ui: &mut egui::Ui, settings: &mut ViewerSettings) {
    ui.collapsing("Model", |ui| {
        egui::ComboBox::from_label("model")
            .selected_text(settings.model.as_str())
            .show_ui(ui, |ui| {
                for id in GPU_MODELS {
                    ui.selectable_value(&mut settings.model, id, id.as_str());
                }
            })
            .response
            .on_hover_text("Scattering model on the GPU (docs/models/); the camera stays");
        let valid = settings.parsed_model_options().is_ok();
        let text = settings
            .model_options
            .entry(settings.model.to_string())
            .or_default();
        let mut edit = egui::TextEdit::singleline(text).hint_text("paper's values");
        if !valid {
            edit = edit.text_color(egui::Color32::RED);
        }
        ui.horizontal(|ui| {
            ui.label("quality");
            ui.add(edit).on_hover_text(
                "The model's accuracy/time settings as key=value items separated by \
                 spaces, e.g. samples=32 (nishita) or ms_samples=40 (hillaire); each \
                 model's keys and the papers' values are in docs/models/. Red: not valid \
                 for this model (the last valid frame stays).",
            );
        });
        if let (Ok(options), Ok((sun_elevation_deg, _))) =
            (settings.parsed_model_options(), settings.sun_angles_deg())
        {
            let at = model_error::Situation {
                preset: &settings.preset,
                altitude_m: settings.altitude_m(settings.bottom_radius_m()),
                sun_zenith_deg: 90.0 - sun_elevation_deg,
            };
            ui.label(model_error::line(settings.model, &options, &at))
                .on_hover_text(
                    "Measured by atmos report (docs/report/): the relative RMS luminance \
                     error against the spectral reference on the report view nearest to \
                     this camera (altitude and sun; a decade of altitude counts as 10° of \
                     sun), and the GPU time of a 1280 x 720 frame of that view on the \
                     report's adapter",
                );
        }
    });
}

/// The Image section; true when a screenshot was asked for.
fn image(ui: &mut egui::Ui, settings: &mut ViewerSettings) -> bool {
    let mut screenshot = false;
    ui.collapsing("Image", |ui| {
        ui.horizontal(|ui| {
            ui.selectable_value(&mut settings.exposure_mode, ExposureMode::Auto, "auto")
                .on_hover_text(
                    "Exposure metered from the frame: EV100 = log2(L × 100 / 12.5) with L the \
                     log-average luminance of the lit pixels (cd/m²), adapting over 0.5 s",
                );
            ui.selectable_value(&mut settings.exposure_mode, ExposureMode::Manual, "manual")
                .on_hover_text("Exposure set by the EV100 slider");
        });
        match settings.exposure_mode {
            ExposureMode::Manual => {
                ui.add(egui::Slider::new(&mut settings.exposure_ev100, 0.0..=20.0).text("EV100"))
                    .on_hover_text("Exposure value at ISO 100: higher is darker (14 for daylight)");
            }
            ExposureMode::Auto => {
                ui.label(format!("EV100 {:.2}", settings.exposure_ev100))
                    .on_hover_text("The automatic exposure value at ISO 100 now");
            }
        }
        screenshot = ui
            .button("screenshot")
            .on_hover_text("Save the view as PNG and EXR (HDR) in the current directory")
            .clicked();
    });
    screenshot
}

fn stats_section(ui: &mut egui::Ui, stats: &Stats) {
    ui.collapsing("Stats", |ui| {
        ui.label(format!(
            "frame {:.1} ms at {}x{}",
            stats.frame_ms, stats.render_size.0, stats.render_size.1
        ))
        .on_hover_text("Wall time of the last render and its size in pixels");
        if let Some((longest, ratio)) = stats.longest_ms {
            ui.label(format!("longest {longest:.1} ms, {ratio:.2} x the median"))
                .on_hover_text(format!(
                    "The longest of the last {} renders against their median: a hitch \
                     while flying (terrain meshes are built off the render thread)",
                    crate::viewer::frame_times::WINDOW
                ));
        }
        if let Some(plan) = stats.plan {
            if let Some(building) = &plan.building {
                ui.label(format!("building {building}")).on_hover_text(
                    "Tables are built over several frames after a change; the image \
                     fills in (single scattering first, then each order) meanwhile",
                );
            }
            ui.label(format!("plan: {plan}")).on_hover_text(
                "The last frame's steps, with GPU times where the adapter has timestamps",
            );
        }
        ui.label(format!(
            "tables {:.1} MiB",
            stats.table_bytes as f64 / (1024.0 * 1024.0)
        ))
        .on_hover_text("GPU memory held by the tables of the models used so far");
        ui.label(format!("adapter: {}", stats.adapter))
            .on_hover_text("The GPU the window and the renderer share");
    });
}

/// "2 m", "10.0 km", "36000 km".
fn format_distance(metres: f64) -> String {
    if metres < 1000.0 {
        format!("{metres:.0} m")
    } else {
        format!("{:.1} km", metres / 1000.0)
    }
}
