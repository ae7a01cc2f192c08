//! Every parser of user input never panics: arbitrary bytes and mutated valid files given
//! to the probe CSV, scene TOML and atmosphere TOML readers, and arbitrary `key=value`
//! items given to every model's settings, end in a value or an error. What they accept
//! lies in the documented ranges.

use std::path::Path;

use atmos::probe::{CSV_LIMITS, read_rays};
use atmos::render::scene::Scene;
use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::limits::{MAX_COEFFICIENT_PER_M, MAX_IRRADIANCE_W_M2_NM};
use atmosphere_core::atmosphere::text_file::{TOML_LIMITS, read_text_from};
use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::methods::method::BeamSettings;
use atmosphere_core::beams::methods::registry::prepare as prepare_beams;
use atmosphere_core::beams::scene::BeamScene;
use atmosphere_core::models::bruneton::settings::BrunetonSettings;
use atmosphere_core::models::dobashi::settings::DobashiSettings;
use atmosphere_core::models::hillaire::HillaireSettings;
use atmosphere_core::models::nishita::NishitaSettings;
use atmosphere_core::models::oneil::OneilSettings;
use atmosphere_core::models::options::ModelOptions;
use proptest::prelude::*;
use proptest::sample::{Index, select};
use proptest::test_runner::FileFailurePersistence;

const EXAMPLE_RAYS: &str = include_str!("../../../assets/probe/example_rays.csv");

const SCENES: [&str; 2] = [
    include_str!("../../../assets/scenes/default.toml"),
    include_str!("../../../assets/scenes/hazy_sunset.toml"),
];

/// Values that break careless number handling.
const NASTY_NUMBERS: [&str; 14] = [
    "0",
    "-0.0",
    "-1",
    "1e-300",
    "1e12",
    "1e300",
    "-1e300",
    "nan",
    "inf",
    "-inf",
    "1.7976931348623157e308",
    "18446744073709551616",
    "4294967296",
    "\"x\"",
];

/// One edit of a text: delete a character, insert one, or replace a number.
#[derive(Clone, Debug)]
enum Edit {
    Delete(Index),
    Insert(Index, char),
    Number(Index, &'static str),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        any::<Index>().prop_map(Edit::Delete),
        (any::<Index>(), any::<char>()).prop_map(|(i, c)| Edit::Insert(i, c)),
        (any::<Index>(), select(&NASTY_NUMBERS[..])).prop_map(|(i, n)| Edit::Number(i, n)),
    ];
    prop::collection::vec(edit, 1..4)
}

/// The byte ranges of the numbers in `text`.
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        let part = c.is_ascii_digit() || ".eE+-_".contains(c);
        match (start, part) {
            (None, true) if c.is_ascii_digit() || c == '-' => start = Some(i),
            (Some(s), false) => {
                out.push(s..i);
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// `text` with `edits` applied.
fn mutate(text: &str, edits: &[Edit]) -> String {
    let mut text = text.to_string();
    for edit in edits {
        let chars: Vec<usize> = text.char_indices().map(|(i, _)| i).collect();
        match edit {
            Edit::Delete(i) if !chars.is_empty() => {
                text.remove(chars[i.index(chars.len())]);
            }
            Edit::Insert(i, c) => text.insert(
                chars
                    .get(i.index(chars.len() + 1))
                    .copied()
                    .unwrap_or(text.len()),
                *c,
            ),
            Edit::Number(i, n) => {
                let found = numbers(&text);
                if !found.is_empty() {
                    text.replace_range(found[i.index(found.len())].clone(), n);
                }
            }
            Edit::Delete(_) => {}
        }
    }
    text
}

/// An atmosphere the reader accepted is usable: finite, non-negative coefficients within
/// their bounds, densities in [0, 1], and it reads back from its own TOML.
fn check_accepted(a: &Atmosphere) {
    for nm in [360.0, 440.0, 550.0, 680.0, 830.0] {
        let c = a.coefficients(nm);
        let coefficients = [
            c.rayleigh_scattering_per_m,
            c.mie_scattering_per_m,
            c.mie_extinction_per_m,
            c.ozone_absorption_per_m,
        ];
        for k in coefficients {
            assert!((0.0..=MAX_COEFFICIENT_PER_M).contains(&k), "{nm} nm: {k}");
        }
        let e = c.solar_irradiance_w_m2_nm;
        assert!((0.0..=MAX_IRRADIANCE_W_M2_NM).contains(&e), "{nm} nm: {e}");
    }
    for profile in [&a.rayleigh.density, &a.mie.density, &a.ozone.density] {
        for step in 0..=10 {
            let d = profile.density(a.thickness_m() * f64::from(step) / 10.0);
            assert!((0.0..=1.0).contains(&d), "{d}");
        }
    }
    assert_eq!(&Atmosphere::from_toml(&a.to_toml()).unwrap(), a);
}

fn read_atmosphere(bytes: &[u8]) {
    if let Ok(text) = read_text_from(bytes, "fuzz.toml", TOML_LIMITS)
        && let Ok(a) = Atmosphere::from_toml(&text)
    {
        check_accepted(&a);
    }
}

/// Rays the probe reader accepted start on or above the ground and point somewhere.
fn read_probe(bytes: &[u8]) {
    let radius = 6.36e6;
    if let Ok(text) = read_text_from(bytes, "fuzz.csv", CSV_LIMITS)
        && let Ok(input) = read_rays(&text, "fuzz.csv", radius)
    {
        for row in input.rows {
            let ray = row.ray;
            assert!(ray.origin_m.is_finite() && ray.origin_m.length() >= radius);
            assert!((ray.direction.length() - 1.0).abs() < 1e-9);
            assert!((ray.sun_direction.length() - 1.0).abs() < 1e-9);
            assert_eq!(row.fields.len(), input.header.len());
        }
    }
}

/// A scene the reader accepted and made a frame of is one the renderer takes.
fn read_scene(bytes: &[u8]) {
    if let Ok(text) = read_text_from(bytes, "fuzz.toml", TOML_LIMITS)
        && let Ok(scene) = Scene::parse(&text, Path::new("fuzz.toml"))
        && let Ok(frame) = scene.frame()
    {
        frame.validate().unwrap();
    }
}

/// The shipped beams scenes, read from their folder so that their light maps and mesh
/// load.
const BEAMS_SCENES: [&str; 3] = [
    include_str!("../../../assets/scenes/beams/sphere_spotlight.toml"),
    include_str!("../../../assets/scenes/beams/stage_five_spots.toml"),
    include_str!("../../../assets/scenes/beams/stained_glass_room.toml"),
];

/// A beams scene the reader accepted gives finite, non-negative radiance at its camera's
/// centre from every method that accepts its default settings.
fn read_beams_scene(bytes: &[u8]) {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/beams");
    if let Ok(text) = read_text_from(bytes, "fuzz.toml", TOML_LIMITS)
        && let Ok(scene) = BeamScene::from_toml(&text, "fuzz.toml", &folder)
    {
        let ray = scene.camera.ray(
            0.5 * f64::from(scene.camera.width_px),
            0.5 * f64::from(scene.camera.height_px),
        );
        for (id, options) in [
            (BeamMethodId::Reference, vec![("max_panels", 2000)]),
            (
                BeamMethodId::March,
                vec![("steps", 16), ("shadow_map_px", 16)],
            ),
            (
                BeamMethodId::Planes2000,
                vec![("planes", 8), ("lattice", 4), ("shadow_map_px", 16)],
            ),
            (
                BeamMethodId::Qtable2002,
                vec![
                    ("table_u", 8),
                    ("table_v", 8),
                    ("max_subplanes", 2),
                    ("shadow_map_px", 16),
                ],
            ),
        ] {
            let mut settings = BeamSettings::default();
            for (key, value) in options {
                settings.options.set(key, value);
            }
            if let Ok(method) = prepare_beams(id, &scene, &settings) {
                let l = method.radiance(&ray).unwrap();
                assert!(l.iter().all(|x| x.is_finite() && *x >= 0.0), "{id}: {l:?}");
            }
        }
    }
}

/// Keys every model reads, and some none does.
const KEYS: [&str; 12] = [
    "samples",
    "table_heights",
    "table_angles",
    "ap_range_m",
    "order_threshold",
    "order_limit",
    "table_max",
    "planes",
    "r",
    "mu",
    "view_cache",
    "bogus",
];

fn settings_items() -> impl Strategy<Value = Vec<String>> {
    let value = prop_oneof![select(&NASTY_NUMBERS[..]).prop_map(String::from), ".{0,12}"];
    let item = prop_oneof![
        (select(&KEYS[..]), value).prop_map(|(k, v)| format!("{k}={v}")),
        ".{0,16}",
    ];
    prop::collection::vec(item, 0..4)
}

proptest! {
    // The cases that once failed, kept beside this file, run first every time.
    #![proptest_config(ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "tests/parsers_never_panic.proptest-regressions",
        ))),
        ..ProptestConfig::with_cases(256)
    })]

    #[test]
    fn atmosphere_toml_of_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        read_atmosphere(&bytes);
    }

    #[test]
    fn atmosphere_toml_mutated_from_every_preset(
        preset in select(&["earth", "clear", "hazy", "mars"][..]),
        edits in edits(),
    ) {
        let text = Atmosphere::preset(preset).unwrap().to_toml();
        read_atmosphere(mutate(&text, &edits).as_bytes());
    }

    #[test]
    fn probe_csv_of_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        read_probe(&bytes);
    }

    #[test]
    fn probe_csv_mutated_from_the_example(edits in edits()) {
        read_probe(mutate(EXAMPLE_RAYS, &edits).as_bytes());
    }

    #[test]
    fn scene_toml_of_arbitrary_bytes(bytes in prop::collection::vec(any::<u8>(), 0..512)) {
        read_scene(&bytes);
    }

    #[test]
    fn scene_toml_mutated_from_the_shipped_scenes(
        scene in select(&SCENES[..]),
        edits in edits(),
    ) {
        read_scene(mutate(scene, &edits).as_bytes());
    }

    #[test]
    fn beams_scene_toml_mutated_from_the_shipped_scenes(
        scene in select(&BEAMS_SCENES[..]),
        edits in edits(),
    ) {
        read_beams_scene(mutate(scene, &edits).as_bytes());
    }

    #[test]
    fn model_settings_of_arbitrary_items(items in settings_items()) {
        if let Ok(options) = ModelOptions::parse(&items) {
            let _ = NishitaSettings::from_options(&options);
            let _ = OneilSettings::from_options(&options);
            let _ = HillaireSettings::from_options(&options);
            let _ = BrunetonSettings::from_options(&options);
            let _ = DobashiSettings::from_options(&options);
        }
    }
}

#[test]
fn numbers_are_found_for_mutation() {
    let text = "a = 1.5e3\nb = [-2, 3]\nc = \"x-1\"\n";
    let found: Vec<&str> = numbers(text).into_iter().map(|r| &text[r]).collect();
    assert_eq!(found, ["1.5e3", "-2", "3", "-1"]);
}
