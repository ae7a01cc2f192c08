//! Stiff and extreme cases give finite, non-negative, bounded and continuous results.

mod common;

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel};
use atmosphere_core::optics::geometry::horizon_mu;
use common::{assert_sane, extreme_atmospheres, extreme_rays, ray};

use atmosphere_core::analysis::stability::venus_like;

fn model(a: &Atmosphere, orders: Option<u32>, target: f64) -> Box<dyn SkyModel> {
    prepare(
        ModelId::Reference,
        a,
        &ModelSettings {
            max_orders: orders,
            target_relative_error: target,
            ..ModelSettings::default()
        },
    )
    .unwrap()
}

#[test]
fn single_scattering_is_finite_and_non_negative_over_extreme_rays() {
    for a in extreme_atmospheres() {
        let m = model(&a, Some(1), 0.01);
        for (what, ray) in extreme_rays(&a, &[None]) {
            assert_sane(&what, &m.radiance(&ray).unwrap());
        }
    }
}

#[test]
fn all_orders_are_finite_and_non_negative_in_extreme_atmospheres() {
    for a in extreme_atmospheres() {
        let m = model(&a, None, 0.05);
        for (altitude, view, sun) in [
            (0.0, 0.0, 30.0),
            (0.0, 89.99, 89.5),
            (10_000.0, 120.0, 100.0),
            (1e7, 179.0, 45.0),
        ] {
            let what = format!("{}: altitude {altitude} view {view} sun {sun}", a.name);
            let result = m.radiance(&ray(&a, altitude, view, sun, 0.0)).unwrap();
            assert_sane(&what, &result);
        }
    }
}

#[test]
fn grazing_optical_depths_pass_a_thousand_without_trouble() {
    let a = venus_like();
    let m = model(&a, Some(1), 0.01);
    let r = a.bottom_radius_m + 10.0;
    let horizon = horizon_mu(r, a.bottom_radius_m).acos().to_degrees();
    let result = m
        .radiance(&ray(&a, 10.0, horizon - 1e-6, 80.0, 0.0))
        .unwrap();
    let tau = -result.transmittance[2].max(f64::MIN_POSITIVE).ln();
    assert!(
        result.transmittance[2] < 1e-300 || tau > 1000.0,
        "optical depth {tau}"
    );
    assert_sane("venus-like: grazing", &result);
}

/// As the sun sets, the radiance falls smoothly: the disk sinks over half a degree and
/// only its visible part lights the air, so there is no step when its centre crosses the
/// horizon.
#[test]
fn radiance_is_continuous_as_the_sun_crosses_the_horizon() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = model(&a, Some(1), 0.01);
    let values: Vec<f64> = (0..=100)
        .map(|i| {
            let sun = 89.5 + 0.01 * i as f64;
            m.radiance(&ray(&a, 0.0, 85.0, sun, 0.0)).unwrap().radiance[0]
        })
        .collect();
    let largest = values.iter().cloned().fold(0.0, f64::max);
    for pair in values.windows(2) {
        let step = (pair[1] - pair[0]).abs() / largest;
        assert!(step < 0.05, "step {step} of the largest value: {values:?}");
    }
}

/// A camera just under, on and just above the top of the atmosphere sees the same.
#[test]
fn radiance_is_continuous_across_the_top_boundary() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = model(&a, Some(1), 0.01);
    let top = a.thickness_m();
    for (view, sun) in [(120.0, 30.0), (100.0, 80.0), (170.0, 95.0)] {
        let at = |altitude: f64| m.radiance(&ray(&a, altitude, view, sun, 45.0)).unwrap();
        let reference = at(top);
        for altitude in [top - 1e-3, top + 1e-3, top + 1.0] {
            let other = at(altitude);
            for w in 0..3 {
                let (x, y) = (reference.radiance[w], other.radiance[w]);
                assert!(
                    (x - y).abs() <= 1e-4 * x.max(1e-12),
                    "view {view} sun {sun} at {altitude}: {x} vs {y}"
                );
                let (x, y) = (reference.transmittance[w], other.transmittance[w]);
                assert!(
                    (x - y).abs() <= 1e-4,
                    "transmittance at {altitude}: {x} vs {y}"
                );
            }
        }
    }
}

/// Rays ever closer to the horizon converge, above it (sky) and below it (ground). Below
/// it the point where the ray meets the ground moves as the square root of the angle to
/// the horizon (1.2 km at 1e-6 degrees, 37 m at 1e-9 degrees from 10 km up), which sets
/// the tolerances.
#[test]
fn radiance_converges_as_rays_graze_the_horizon() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = model(&a, Some(1), 0.01);
    let altitude = 10_000.0;
    let r = a.bottom_radius_m + altitude;
    let horizon = horizon_mu(r, a.bottom_radius_m).acos().to_degrees();
    for side in [-1.0, 1.0] {
        let at = |offset: f64| {
            m.radiance(&ray(&a, altitude, horizon + side * offset, 60.0, 0.0))
                .unwrap()
                .radiance
        };
        let (coarse, fine, finest) = (at(1e-6), at(1e-9), at(1e-12));
        for w in 0..3 {
            assert!(
                (coarse[w] - finest[w]).abs() < 1e-3 * finest[w],
                "side {side}: {coarse:?} {finest:?}"
            );
            assert!(
                (fine[w] - finest[w]).abs() < 1e-4 * finest[w],
                "side {side}: {fine:?} {finest:?}"
            );
        }
    }
}

/// The sweep for one model (one test per model, so that they run in parallel).
fn sweep_passes(id: ModelId) {
    let results = atmosphere_core::analysis::stability::run(id).unwrap();
    let failed: Vec<_> = results.iter().filter(|r| !r.passed).collect();
    assert!(failed.is_empty(), "{id}: {failed:#?}");
}

/// The sweep test of each model. The match is exhaustive, so a model added without a
/// sweep test below does not compile: a check at build time, not a test that runs.
const _: fn(ModelId) -> fn() = |id| match id {
    ModelId::Reference => stability_sweep_reference,
    ModelId::Bruneton => stability_sweep_bruneton,
    ModelId::Dobashi => stability_sweep_dobashi,
    ModelId::Hillaire => stability_sweep_hillaire,
    ModelId::Nishita => stability_sweep_nishita,
    ModelId::Oneil => stability_sweep_oneil,
    ModelId::Riley => stability_sweep_riley,
};

#[test]
fn stability_sweep_reference() {
    sweep_passes(ModelId::Reference);
}

#[test]
fn stability_sweep_bruneton() {
    sweep_passes(ModelId::Bruneton);
}

#[test]
fn stability_sweep_dobashi() {
    sweep_passes(ModelId::Dobashi);
}

#[test]
fn stability_sweep_hillaire() {
    sweep_passes(ModelId::Hillaire);
}

#[test]
fn stability_sweep_nishita() {
    sweep_passes(ModelId::Nishita);
}

#[test]
fn stability_sweep_oneil() {
    sweep_passes(ModelId::Oneil);
}

#[test]
fn stability_sweep_riley() {
    sweep_passes(ModelId::Riley);
}
