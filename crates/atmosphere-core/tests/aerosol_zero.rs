//! At zero aerosol a pruning model does no Mie work (ModelSettings::prune): its
//! `ModelBase::with_mie` is off, and its answers equal the full path's. Table models
//! show it in their memory too (dobashi here; bruneton has its own test in
//! model_bruneton.rs, the build being slow). With aerosol nothing is pruned.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};

fn rays(a: &Atmosphere) -> Vec<ViewRay> {
    [
        (2.0, 60.0, 30.0, 40.0, None),
        (2.0, 89.5, 88.0, 0.0, None),
        (10_000.0, 120.0, 45.0, 90.0, None),
        (1_000.0, 85.0, 60.0, 10.0, Some(20_000.0)),
        (400_000.0, 110.0, 60.0, 90.0, None),
    ]
    .into_iter()
    .map(|(h, v, s, az, d)| ViewRay::from_angles(a.bottom_radius_m, h, v, s, az, d).unwrap())
    .collect()
}

#[test]
fn pruned_models_equal_the_full_path_at_zero_aerosol() {
    let clean = Atmosphere::preset("earth").unwrap().with_aerosol_scale(0.0);
    for id in [
        ModelId::Nishita,
        ModelId::Oneil,
        ModelId::Riley,
        ModelId::Dobashi,
    ] {
        let settings = |prune| ModelSettings {
            prune,
            ..ModelSettings::default()
        };
        let pruned = prepare(id, &clean, &settings(true)).unwrap();
        let full = prepare(id, &clean, &settings(false)).unwrap();
        assert!(!pruned.base().with_mie, "{id}: not pruned");
        assert!(full.base().with_mie, "{id}: pruned without prune");
        if id == ModelId::Dobashi {
            assert!(
                pruned.table_bytes() < full.table_bytes(),
                "{id}: {} bytes pruned, {} in full",
                pruned.table_bytes(),
                full.table_bytes()
            );
        }
        let earth = Atmosphere::preset("earth").unwrap();
        let kept = prepare(id, &earth, &settings(true)).unwrap();
        assert!(kept.base().with_mie, "{id}: pruned with aerosol");
        for ray in rays(&clean) {
            let (a, b) = (pruned.radiance(&ray).unwrap(), full.radiance(&ray).unwrap());
            for (x, y) in a
                .radiance
                .iter()
                .chain(&a.transmittance)
                .zip(b.radiance.iter().chain(&b.transmittance))
            {
                assert!((x - y).abs() <= 1e-14 * y.abs(), "{id} {ray:?}: {x} vs {y}");
            }
            assert!(
                a.radiance.iter().all(|l| *l > 0.0),
                "{id} {ray:?}: no light"
            );
        }
    }
}
