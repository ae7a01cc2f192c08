//! Every model's settings have ranges and its tables a memory budget: values outside a
//! range are errors naming the model, the key and the range; tables over the budget are
//! errors naming the settings and the bytes, before anything is allocated; the bytes a
//! model's settings are checked for are the bytes its tables take.

use std::time::{Duration, Instant};

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::ModelSettings;

fn with_options(items: &[&str]) -> ModelSettings {
    ModelSettings {
        options: ModelOptions::parse(items).unwrap(),
        prune: false,
        ..ModelSettings::default()
    }
}

/// The error of preparing `model` with `items`, which must come within a second.
fn error(model: ModelId, settings: &ModelSettings) -> String {
    let earth = Atmosphere::preset("earth").unwrap();
    let start = Instant::now();
    let Err(e) = prepare(model, &earth, settings) else {
        panic!("{model} {} was accepted", settings.options);
    };
    assert!(start.elapsed() < Duration::from_secs(1), "{model}: {e}");
    e.to_string()
}

#[test]
fn values_outside_a_range_name_the_key_and_the_range() {
    for (model, item, range) in [
        (ModelId::Nishita, "samples=1000000000", "1..=4096"),
        (ModelId::Nishita, "table_heights=100000", "2..=2048"),
        (ModelId::Oneil, "table_ray_samples=0", "1..=4096"),
        (ModelId::Bruneton, "r=100000", "2..=256"),
        (ModelId::Bruneton, "order_threshold=NaN", "0..=1"),
        (ModelId::Hillaire, "sky_view_width=1000000", "2..=2048"),
        (ModelId::Hillaire, "ap_range_m=inf", "1..=1000000"),
        (ModelId::Dobashi, "planes=5000", "1..=4096"),
        (ModelId::Dobashi, "ambient_directions=17", "1..=16"),
    ] {
        let e = error(model, &with_options(&[item]));
        assert!(
            e.contains(&format!("{model} setting {item} is outside {range}")),
            "{e}"
        );
    }
}

#[test]
fn tables_over_the_budget_are_refused_before_they_are_built() {
    let big_s = ["r=256", "mu=1024", "mu_s=256", "nu=64"];
    let e = error(ModelId::Bruneton, &with_options(&big_s));
    assert!(
        e.contains("bruneton tables of r=256 x mu=1024 x mu_s=256 x nu=64"),
        "{e}"
    );
    assert!(e.contains("need 154619228160 bytes"), "{e}");
    assert!(e.contains("over the budget of 1073741824 bytes"), "{e}");

    let views = ["ap_width=1024", "ap_height=1024", "ap_slices=256"];
    let e = error(ModelId::Hillaire, &with_options(&views));
    assert!(
        e.contains("hillaire tables of") && e.contains("ap 1024 x 1024 x 256"),
        "{e}"
    );

    let mut many = with_options(&["table_heights=2048", "table_angles=2048"]);
    many.wavelengths_nm = (0..100).map(|i| 400.0 + 3.0 * f64::from(i)).collect();
    let e = error(ModelId::Dobashi, &many);
    assert!(
        e.contains("table_heights=2048 x table_angles=2048") && e.contains("100 wavelengths"),
        "{e}"
    );
}

#[test]
fn gpu_loop_bounds_across_settings_are_checked() {
    let ground = [
        "ground_zenith_panels=16",
        "ground_azimuths=256",
        "sky_view_samples=100",
    ];
    let e = error(ModelId::Hillaire, &with_options(&ground));
    assert!(
        e.contains(
            "ground_zenith_panels=16 x 8 x ground_azimuths=256 / 64 lanes x \
             sky_view_samples=100 = 51200 loop trips in one GPU invocation, over 32768"
        ),
        "{e}"
    );
    let within = [
        "ground_zenith_panels=16",
        "ground_azimuths=256",
        "sky_view_samples=64",
    ];
    let settings = atmosphere_core::models::hillaire::HillaireSettings::from_options(
        &ModelOptions::parse(&within).unwrap(),
    );
    assert!(settings.is_ok(), "{settings:?}");
}

#[test]
fn shared_settings_have_ranges() {
    let s = ModelSettings {
        wavelengths_nm: vec![550.0; 101],
        ..ModelSettings::default()
    };
    assert!(error(ModelId::Riley, &s).contains("101 wavelengths is outside 1..=100"));
    let s = ModelSettings {
        max_orders: Some(1001),
        ..ModelSettings::default()
    };
    assert!(error(ModelId::Reference, &s).contains("orders 1001 is outside 1..=1000"));
    let s = ModelSettings {
        target_relative_error: 0.0,
        ..ModelSettings::default()
    };
    assert!(error(ModelId::Reference, &s).contains("is outside 1e-6..=1"));
}

#[test]
fn the_bytes_checked_are_the_bytes_the_tables_take() {
    let earth = Atmosphere::preset("earth").unwrap();
    let n = 5;
    let settings = |items: &[&str]| ModelSettings {
        wavelengths_nm: vec![450.0, 500.0, 550.0, 600.0, 650.0],
        ..with_options(items)
    };
    let b = ["r=4", "mu=8", "mu_s=4", "nu=2", "order_limit=2"];
    let model = prepare(ModelId::Bruneton, &earth, &settings(&b)).unwrap();
    let expected = atmosphere_core::models::bruneton::settings::BrunetonSettings::from_options(
        &ModelOptions::parse(&b).unwrap(),
    )
    .unwrap()
    .table_bytes(n);
    assert_eq!(model.table_bytes() as u64, expected);

    let d = [
        "table_heights=8",
        "table_angles=16",
        "sphere_table_angles=8",
        "planes=10",
    ];
    let model = prepare(ModelId::Dobashi, &earth, &settings(&d)).unwrap();
    let expected = atmosphere_core::models::dobashi::DobashiSettings::from_options(
        &ModelOptions::parse(&d).unwrap(),
    )
    .unwrap()
    .table_bytes(n);
    assert_eq!(model.table_bytes() as u64, expected);

    let h = [
        "view_cache=1",
        "ap_width=8",
        "ap_height=8",
        "sky_view_width=16",
    ];
    let model = prepare(ModelId::Hillaire, &earth, &settings(&h)).unwrap();
    let expected = atmosphere_core::models::hillaire::HillaireSettings::from_options(
        &ModelOptions::parse(&h).unwrap(),
    )
    .unwrap()
    .table_bytes(n);
    assert_eq!(model.table_bytes() as u64, expected);
}
