//! Mie's quadrature in the texel's frame (`mie_horizon`): a switch of the quadrature,
//! so it needs `mie_directions`.

use atmosphere_core::models::bruneton::BrunetonSettings;
use atmosphere_core::models::options::ModelOptions;

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
}
