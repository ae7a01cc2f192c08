//! With `sun_disk` the bruneton tables depend on the sun's angular radius (the visible
//! part of the disk at the horizon dims single scattering and the ground's direct light):
//! `update` rebuilds them when it changes, and the answers equal a fresh build's; with
//! the paper's point sun (Bruneton and Neyret 2008) the radius rebuilds nothing.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::bruneton::{Bruneton, BrunetonSettings};
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};

/// Reduced tables (S 8 x 32 x 16 x 8) so that each build takes a fraction of a second.
fn small(sun_disk: bool) -> BrunetonSettings {
    let mut s = BrunetonSettings::default();
    s.scattering_size.r = 8;
    s.scattering_size.mu = 32;
    s.scattering_size.mu_s = 16;
    s.scattering_size.nu = 8;
    s.sun_disk = sun_disk;
    s
}

/// Rays from 2 m near the horizon with the sun's centre on the horizon and half a degree
/// below it, where the disk's visible part decides the sun's light.
fn horizon_rays(a: &Atmosphere) -> Vec<ViewRay> {
    let mut rays = Vec::new();
    for sun_zenith_deg in [90.0, 90.5] {
        for (view_zenith_deg, azimuth_deg) in [(85.0, 10.0), (88.0, 120.0), (60.0, 0.0)] {
            rays.push(
                ViewRay::from_angles(
                    a.bottom_radius_m,
                    2.0,
                    view_zenith_deg,
                    sun_zenith_deg,
                    azimuth_deg,
                    None,
                )
                .unwrap(),
            );
        }
    }
    rays
}

fn radiances(model: &Bruneton, rays: &[ViewRay]) -> Vec<f64> {
    rays.iter()
        .flat_map(|ray| model.radiance(ray).unwrap().radiance)
        .collect()
}

#[test]
fn a_new_sun_radius_rebuilds_the_tables_of_a_disk_sun_and_of_no_point_sun() {
    let a = Atmosphere::preset("earth").unwrap();
    let rays = horizon_rays(&a);
    let settings = ModelSettings::default();
    let mut wider = a.clone();
    wider.sun.angular_radius_rad *= 4.0;
    for sun_disk in [true, false] {
        let mut model = Bruneton::prepare_with(&a, &settings, &small(sun_disk)).unwrap();
        let before = radiances(&model, &rays);
        let rebuilt = model.update(&wider).unwrap();
        let fresh = Bruneton::prepare_with(&wider, &settings, &small(sun_disk)).unwrap();
        let (after, want) = (radiances(&model, &rays), radiances(&fresh, &rays));
        for (x, y) in after.iter().zip(&want) {
            assert!(
                (x - y).abs() <= 1e-12 * y.abs(),
                "sun_disk={sun_disk}: {x} vs {y}"
            );
        }
        if sun_disk {
            assert_eq!(
                rebuilt,
                ["single scattering", "multiple scattering", "irradiance"]
            );
            // The disk's radius matters on these rays: stale tables would be seen.
            let most = before
                .iter()
                .zip(&want)
                .map(|(b, w)| (b / w - 1.0).abs())
                .fold(0.0, f64::max);
            assert!(most > 1e-3, "{most}");
        } else {
            assert!(rebuilt.is_empty(), "{rebuilt:?}");
            assert_eq!(before, after);
        }
    }
}
