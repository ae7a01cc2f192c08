//! Mie's quadrature in the texel's frame (`mie_horizon`): a switch of the quadrature,
//! so it needs `mie_directions`; `mie_horizon_order_two` narrows it to order two, whose
//! incoming light (scattered once) holds the horizon's sharp band and step.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::{Bruneton, BrunetonSettings};
use atmosphere_core::models::options::ModelOptions;
use atmosphere_core::models::sky_model::ModelSettings;

#[test]
fn mie_horizon_is_a_switch_of_the_mie_quadrature() {
    let parse = |o: &[&str]| BrunetonSettings::from_options(&ModelOptions::parse(o).unwrap());
    assert!(
        parse(&["mie_directions=8", "mie_horizon=true"])
            .unwrap()
            .mie_horizon
    );
    assert!(!parse(&["mie_directions=8"]).unwrap().mie_horizon);
    let e = parse(&["mie_horizon=true"]).unwrap_err().to_string();
    assert!(
        e.contains("mie_horizon=true") && e.contains("mie_directions"),
        "{e}"
    );
    let order_two = [
        "mie_directions=8",
        "mie_horizon=true",
        "mie_horizon_order_two=true",
    ];
    assert!(parse(&order_two).unwrap().mie_horizon_order_two);
    let e = parse(&["mie_directions=8", "mie_horizon_order_two=true"])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mie_horizon_order_two=true") && e.contains("mie_horizon=true"),
        "{e}"
    );
}

/// The multiple part of reduced hazy tables built to `orders` with `options`.
fn multiple(orders: u32, options: &[&str]) -> Vec<[f32; 3]> {
    let mut items = vec!["r=8", "mu=32", "mu_s=8", "nu=4", "mie_directions=8"];
    items.extend(options);
    let settings = ModelSettings {
        max_orders: Some(orders),
        options: ModelOptions::parse(&items).unwrap(),
        ..ModelSettings::default()
    };
    let model = Bruneton::prepare(&Atmosphere::preset("hazy").unwrap(), &settings).unwrap();
    model.tables()[0].multiple.data.clone()
}

/// Largest difference between two tables relative to the larger table's largest value.
fn difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
    let scale = a
        .iter()
        .chain(b)
        .flatten()
        .fold(0.0f32, |m, v| m.max(v.abs()));
    let worst = a
        .iter()
        .zip(b)
        .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).abs()))
        .fold(0.0f32, f32::max);
    worst / scale
}

#[test]
fn order_two_alone_takes_the_horizon_frame_and_later_orders_the_view_layout() {
    let all = ["mie_horizon=true"];
    let two = ["mie_horizon=true", "mie_horizon_order_two=true"];
    // To order two the two settings build the same tables, unlike the layout about the
    // view.
    let all_to_two = multiple(2, &all);
    assert_eq!(all_to_two, multiple(2, &two));
    assert!(difference(&all_to_two, &multiple(2, &[])) > 1e-3);
    // Order three's Delta J comes from order two's light about the view with
    // `mie_horizon_order_two`: the tables part from those of every order in the frame,
    // and from those of the view layout, which differ already in order two.
    let (all, two, view) = (multiple(3, &all), multiple(3, &two), multiple(3, &[]));
    assert!(difference(&all, &two) > 1e-3, "{}", difference(&all, &two));
    assert!(
        difference(&two, &view) > 1e-3,
        "{}",
        difference(&two, &view)
    );
}
