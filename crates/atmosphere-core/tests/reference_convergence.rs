//! The reference's own error statements hold: its quadrature has converged and its
//! Monte Carlo standard errors describe the actual scatter of its results.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::column::Fineness;
use atmosphere_core::reference::{ViewPath, single_scattering};

fn rays(a: &Atmosphere) -> Vec<ViewRay> {
    [
        (0.0, 0.0, 30.0, 0.0),
        (0.0, 89.9, 89.0, 0.0),
        (0.0, 92.0, 60.0, 90.0),
        (1.0, 80.0, 92.0, 180.0),
        (10_000.0, 95.0, 88.0, 20.0),
        (100_000.0, 107.0, 50.0, 0.0),
        (3e7, 179.5, 10.0, 0.0),
    ]
    .into_iter()
    .map(|(h, v, s, az)| ViewRay::from_angles(a.bottom_radius_m, h, v, s, az, None).unwrap())
    .collect()
}

/// Halving the quadrature panels changes single scattering by less than 1e-6, or 3e-5
/// for rays that cross the penumbra of the planet's shadow (the sun's visible fraction
/// has square-root edges there, which Gauss-Legendre resolves only algebraically).
#[test]
fn single_scattering_quadrature_has_converged() {
    let a = Atmosphere::preset("earth").unwrap();
    let spectra = Spectra::new(&a, &[680.0, 550.0, 440.0]);
    for ray in rays(&a) {
        let sun = ray.sun_direction;
        let tolerance = if sun.z < 0.1 { 3e-5 } else { 1e-6 };
        let coarse = single_scattering(
            &a,
            &spectra,
            &ViewPath::new(&a, &ray, Fineness::VIEW).unwrap(),
            sun,
            None,
        );
        let fine = single_scattering(
            &a,
            &spectra,
            &ViewPath::new(&a, &ray, Fineness::VIEW.halved()).unwrap(),
            sun,
            None,
        );
        for w in 0..3 {
            let rel = (coarse[w] - fine[w]).abs() / fine[w].max(1e-30);
            assert!(rel < tolerance, "{ray:?} wavelength {w}: {rel:e}");
        }
    }
}

/// Twenty runs with different seeds scatter as the reported standard error says: the
/// spread of the results is within a factor two of the mean reported error.
#[test]
fn reported_standard_error_matches_the_scatter_between_seeds() {
    let a = Atmosphere::preset("earth").unwrap();
    let ray = ViewRay::from_angles(a.bottom_radius_m, 0.0, 60.0, 70.0, 120.0, None).unwrap();
    let runs = 20;
    let results: Vec<(f64, f64)> = (0..runs)
        .map(|seed| {
            let m = prepare(
                ModelId::Reference,
                &a,
                &ModelSettings {
                    wavelengths_nm: vec![440.0],
                    target_relative_error: 0.01,
                    seed,
                    ..ModelSettings::default()
                },
            )
            .unwrap();
            let r = m.radiance(&ray).unwrap();
            (r.radiance[0], r.radiance_std_error[0])
        })
        .collect();
    let mean = results.iter().map(|r| r.0).sum::<f64>() / runs as f64;
    let spread =
        (results.iter().map(|r| (r.0 - mean).powi(2)).sum::<f64>() / (runs - 1) as f64).sqrt();
    let reported = results.iter().map(|r| r.1).sum::<f64>() / runs as f64;
    assert!(
        spread > 0.5 * reported && spread < 2.0 * reported,
        "spread {spread:e} vs reported {reported:e}"
    );
}

/// Each added order adds light; all orders add more than two.
#[test]
fn orders_add_light() {
    let a = Atmosphere::preset("earth").unwrap();
    let ray = ViewRay::from_angles(a.bottom_radius_m, 0.0, 45.0, 45.0, 90.0, None).unwrap();
    let at = |orders| {
        prepare(
            ModelId::Reference,
            &a,
            &ModelSettings {
                max_orders: orders,
                target_relative_error: 0.003,
                ..ModelSettings::default()
            },
        )
        .unwrap()
        .radiance(&ray)
        .unwrap()
    };
    let (one, two, all) = (at(Some(1)), at(Some(2)), at(None));
    for w in 0..3 {
        let noise = 3.0 * (two.radiance_std_error[w] + all.radiance_std_error[w]);
        assert!(two.radiance[w] > one.radiance[w] * 1.01, "{w}");
        assert!(all.radiance[w] > two.radiance[w] - noise, "{w}");
        // The blue sky owes a good part to multiple scattering (Bruneton 2008, Fig. 7).
        assert!(all.radiance[2] > 1.1 * one.radiance[2]);
    }
}
