//! What `atmos report` compares: the model settings, the models they cover and where the
//! committed report lives.

use atmosphere_core::models::id::ModelId;

use crate::report::measure::Variant;

/// Where the committed report lives.
pub const DEFAULT_OUT: &str = "docs/report";

/// Models the report knows; `--model` accepts these.
pub fn report_models() -> Vec<ModelId> {
    ModelId::ALL
        .into_iter()
        .filter(|m| report_variants().iter().any(|v| v.model == *m))
        .collect()
}

/// The settings the report compares: each model at its paper's values, and the settings
/// that trade accuracy for time around them.
pub fn report_variants() -> Vec<Variant> {
    vec![
        Variant::new(
            ModelId::Riley,
            None,
            &[
                "sphere=false",
                "shared_extinction=false",
                "ozone=false",
                "pieces=1",
            ],
        ),
        Variant::new(ModelId::Riley, None, &["pieces=1"]),
        Variant::new(ModelId::Riley, None, &["pieces=2"]),
        Variant::new(ModelId::Riley, None, &[]),
        Variant::new(ModelId::Nishita, None, &["samples=4"]),
        Variant::new(ModelId::Nishita, None, &["samples=16"]),
        Variant::new(ModelId::Nishita, None, &["samples=64"]),
        Variant::new(ModelId::Nishita, None, &[]),
        Variant::new(ModelId::Oneil, None, &["samples=2"]),
        Variant::new(ModelId::Oneil, None, &[]),
        Variant::new(ModelId::Oneil, None, &["samples=16"]),
        Variant::new(ModelId::Dobashi, Some(1), &[]),
        Variant::new(ModelId::Dobashi, None, &["planes=30"]),
        Variant::new(ModelId::Dobashi, None, &[]),
        Variant::new(ModelId::Dobashi, None, &["planes=400"]),
        Variant::new(ModelId::Hillaire, Some(1), &[]),
        Variant::new(
            ModelId::Hillaire,
            None,
            &["sky_view_samples=10", "ms_samples=4"],
        ),
        Variant::new(ModelId::Hillaire, None, &[]),
        Variant::new(
            ModelId::Hillaire,
            None,
            &["ms_samples=32", "sky_view_samples=60"],
        ),
        Variant::new(ModelId::Hillaire, None, &["ms_order=2"]),
        Variant::new(
            ModelId::Hillaire,
            None,
            &["ms_order=2", "ms_directions=256"],
        ),
        Variant::new(ModelId::Hillaire, None, &["ms_delta=0.45"]),
        Variant::new(
            ModelId::Hillaire,
            None,
            &["ms_delta=0.45", "ms_directions=100"],
        ),
        Variant::new(ModelId::Bruneton, Some(1), &[]),
        Variant::new(ModelId::Bruneton, Some(2), &[]),
        Variant::new(ModelId::Bruneton, None, &[]),
        Variant::new(ModelId::Bruneton, None, &["view_samples=30"]),
        Variant::new(ModelId::Bruneton, None, &["view_samples=100"]),
        Variant::new(ModelId::Bruneton, None, &["nu_by_angle=true"]),
        Variant::new(
            ModelId::Bruneton,
            None,
            &["min_mu_s=-0.35", "nu_by_angle=true"],
        ),
        Variant::new(ModelId::Bruneton, None, &["sun_disk=true"]),
        Variant::new(ModelId::Bruneton, None, &["geometric_mu_s=true"]),
        Variant::new(ModelId::Bruneton, None, &["density_nodes=true"]),
        Variant::new(ModelId::Bruneton, None, &["nu=16", "nu_edge=true"]),
        Variant::new(ModelId::Bruneton, None, &["nu_by_azimuth=true"]),
        Variant::new(ModelId::Bruneton, None, &["mu_zenith=true"]),
        Variant::new(
            ModelId::Bruneton,
            None,
            &[
                "min_mu_s=-0.31",
                "mu_s_knee=true",
                "mu_s=43",
                "geometric_mu_s=true",
            ],
        ),
        Variant::new(
            ModelId::Bruneton,
            None,
            &["r=16", "mu=64", "mu_s=16", "nu=4"],
        ),
        Variant::new(
            ModelId::Bruneton,
            None,
            &[
                "mu_s=86",
                "min_mu_s=-0.31",
                "mu_s_knee=true",
                "nu=16",
                "nu_by_azimuth=true",
                "mu_zenith=true",
                "e_mu_s=512",
                "sphere_zenith=128",
                "sphere_azimuth=64",
                "mie_directions=8",
                "mie_horizon=true",
                "mie_horizon_order_two=true",
                "order_threshold=0.002",
            ],
        ),
    ]
}
