//! The sea as a specular surface (`optics::sea_surface`): the Fresnel reflectance against
//! its closed forms, Cox and Munk's slope variance against their numbers, the glint's
//! energy and peak, the sun separated from each model's irradiance against the model's
//! own transmittance, and a calm sea mirroring each model's sky.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::optics::sea_surface::{
    SeaHit, WATER_REFRACTIVE_INDEX, check_wind, fresnel_reflectance, glint_factor,
    mirror_direction, radiance_with_sea, slope_variance, transmitted_sun,
};
use glam::DVec3;

const MODELS: &[ModelId] = &[
    ModelId::Nishita,
    ModelId::Oneil,
    ModelId::Riley,
    ModelId::Dobashi,
    ModelId::Bruneton,
    ModelId::Hillaire,
];

fn model(id: ModelId, a: &Atmosphere) -> Box<dyn SkyModel> {
    prepare(id, a, &ModelSettings::default()).unwrap()
}

/// A unit vector `elevation_deg` above the horizon of the z axis, at `azimuth_deg` from x.
fn at(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, z) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * z.cos(), e.cos() * z.sin(), e.sin())
}

#[test]
fn fresnel_reflectance_meets_its_closed_forms() {
    let n = WATER_REFRACTIVE_INDEX;
    // Normal incidence: ((n - 1) / (n + 1))^2.
    let normal = ((n - 1.0) / (n + 1.0)).powi(2);
    assert!((fresnel_reflectance(1.0) - normal).abs() < 1e-15);
    assert!((fresnel_reflectance(1.0) - 0.02037).abs() < 1e-5);
    // Brewster's angle, tan = n: r_p vanishes and r_s = -sin(i - t), i + t = 90 deg.
    let i = n.atan();
    let t = std::f64::consts::FRAC_PI_2 - i;
    let brewster = 0.5 * (i - t).sin().powi(2);
    assert!((fresnel_reflectance(i.cos()) - brewster).abs() < 1e-12);
    // Grazing: everything is reflected; and R grows towards grazing.
    assert!((fresnel_reflectance(0.0) - 1.0).abs() < 1e-12);
    let mut last = 0.0;
    for k in (0..=100).rev() {
        let r = fresnel_reflectance(k as f64 / 100.0);
        assert!(r >= last, "{k}: {r} < {last}");
        last = r;
    }
}

#[test]
fn the_slope_variance_is_cox_and_munk_s_and_the_wind_has_a_range() {
    // Cox and Munk 1954: 0.003 on a calm sea, 0.0542 at 10 m/s.
    assert!((slope_variance(0.0) - 0.003).abs() < 1e-15);
    assert!((slope_variance(10.0) - 0.0542).abs() < 1e-12);
    assert!(check_wind(0.0).is_ok() && check_wind(20.0).is_ok());
    for bad in [-1.0, 20.5, f64::NAN, f64::INFINITY] {
        let e = check_wind(bad).unwrap_err();
        assert!(e.contains("wind_m_s") && e.contains("[0, 20]"), "{e}");
    }
}

#[test]
fn the_glint_of_a_sun_overhead_reflects_the_fresnel_share_of_its_light() {
    // The sea's reflected irradiance over the incident, the integral of G cos(theta_v)
    // over the hemisphere, is the Fresnel reflectance averaged over the facets that
    // reflect the sun: close to F(1) for a sun overhead.
    for wind in [0.0, 5.0, 15.0] {
        let sigma2 = slope_variance(wind);
        let (n_theta, n_phi) = (4000, 16);
        let d_theta = std::f64::consts::FRAC_PI_2 / n_theta as f64;
        let mut sum = 0.0;
        for i in 0..n_theta {
            let theta = (i as f64 + 0.5) * d_theta;
            // Isotropic about the vertical: one azimuth stands for all, checked on a few.
            let mut ring = 0.0;
            for j in 0..n_phi {
                let phi = (j as f64 + 0.5) / n_phi as f64 * std::f64::consts::TAU;
                let eye = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                ring += glint_factor(eye, DVec3::Z, DVec3::Z, sigma2);
            }
            sum +=
                ring / n_phi as f64 * theta.cos() * theta.sin() * d_theta * std::f64::consts::TAU;
        }
        let f0 = fresnel_reflectance(1.0);
        assert!(
            (sum / f0 - 1.0).abs() < 0.02,
            "wind {wind}: {sum} against {f0}"
        );
    }
}

#[test]
fn the_glint_of_a_calm_sea_peaks_in_the_sun_s_mirror_direction() {
    // In the sun's vertical plane, a little below its mirror image (1 / cos(theta_v) and
    // the Fresnel reflectance grow towards the horizon, by about 2 sigma^2 cot(e) rad):
    // within 1.5 deg for a sun 30 to 60 deg up. A lower sun's glitter runs to the
    // horizon, where it is brightest.
    let sigma2 = slope_variance(0.0);
    for sun_elevation in [30.0f64, 45.0, 60.0] {
        let sun = at(sun_elevation, 0.0);
        let mut best = (0.0, 0.0, 0.0);
        for e in 1..900 {
            for a in -100..=100 {
                let (elevation, azimuth) = (e as f64 * 0.1, a as f64 * 0.1);
                let g = glint_factor(at(elevation, 180.0 + azimuth), sun, DVec3::Z, sigma2);
                if g > best.0 {
                    best = (g, elevation, azimuth);
                }
            }
        }
        let below = sun_elevation - best.1;
        assert!(
            best.2 == 0.0,
            "sun at {sun_elevation}: peak {} deg aside",
            best.2
        );
        assert!(
            (0.0..=1.5).contains(&below),
            "sun at {sun_elevation}: peak {below} deg below the mirror"
        );
    }
    // Masking keeps the glint finite at grazing views.
    let g = glint_factor(at(0.01, 180.0), at(10.0, 0.0), DVec3::Z, sigma2);
    assert!(g.is_finite() && g < 1e3, "{g}");
}

#[test]
fn a_mirror_below_the_horizon_is_laid_on_it() {
    let point = DVec3::new(0.0, 0.0, 6.36e6);
    let m = mirror_direction(point, at(-10.0, 0.0), DVec3::Z);
    assert!((m - at(10.0, 0.0)).length() < 1e-12);
    // A normal tilted 8 deg away from the camera turns a ray 10 deg down below the
    // horizon.
    let tilted = at(82.0, 0.0);
    assert!(at(-10.0, 0.0).dot(tilted) < 0.0);
    let m = mirror_direction(point, at(-10.0, 0.0), tilted);
    assert!(m.z.abs() < 1e-12 && (m.length() - 1.0).abs() < 1e-12);
}

#[test]
fn the_sun_separated_from_each_model_s_irradiance_is_its_transmitted_sun() {
    let a = Atmosphere::preset("earth").unwrap();
    let point = DVec3::new(0.0, 0.0, a.bottom_radius_m);
    for &id in MODELS {
        let m = model(id, &a);
        for elevation in [60.0, 20.0, 5.0] {
            let sun = at(elevation, 30.0);
            let separated = transmitted_sun(m.as_ref(), point, sun).unwrap();
            let to_sun = m
                .radiance(&ViewRay {
                    origin_m: point,
                    direction: sun,
                    sun_direction: sun,
                    max_distance_m: None,
                })
                .unwrap();
            for (w, e) in m.solar_irradiance_w_m2_nm().iter().enumerate() {
                let expected = e * to_sun.transmittance[w];
                let error = (separated[w] - expected).abs() / expected;
                assert!(
                    error < 0.02,
                    "{id} sun at {elevation}: {} against {expected}",
                    separated[w]
                );
            }
        }
        // The sun below the horizon: none.
        let set = transmitted_sun(m.as_ref(), point, at(-5.0, 0.0)).unwrap();
        assert!(set.iter().all(|&e| e.abs() < 1e-9), "{id}: {set:?}");
    }
}

#[test]
fn a_calm_sea_mirrors_each_model_s_sky_times_the_fresnel_reflectance() {
    // A camera 2 m above a black sea looks 10 deg down, the sun behind it (no glint): the
    // water adds F times the sky the model sees from the sea along the mirror direction,
    // which is the sky the camera sees 10 deg up, 2 m higher.
    let a = Atmosphere::preset("earth").unwrap();
    let bottom = a.bottom_radius_m;
    let camera = DVec3::new(0.0, 0.0, bottom + 2.0);
    let sun = at(25.0, 180.0);
    let down = at(-10.0, 0.0);
    let distance_m = 2.0 / 10f64.to_radians().sin();
    for &id in MODELS {
        let m = model(id, &a);
        let n = m.wavelengths_nm().len();
        let ray = ViewRay {
            origin_m: camera,
            direction: down,
            sun_direction: sun,
            max_distance_m: None,
        };
        let hit = SeaHit {
            distance_m,
            normal: DVec3::Z,
            body_albedo: vec![0.0; n],
            slope_variance: slope_variance(0.0),
        };
        let sea = radiance_with_sea(m.as_ref(), &a, &ray, &hit).unwrap();
        let path = m
            .radiance(&ViewRay {
                max_distance_m: Some(distance_m),
                ..ray
            })
            .unwrap();
        let sky = m
            .radiance(&ViewRay {
                direction: at(10.0, 0.0),
                ..ray
            })
            .unwrap();
        let f = fresnel_reflectance(10f64.to_radians().sin());
        for w in 0..n {
            let reflected = sea.radiance[w] - path.radiance[w];
            let expected = path.transmittance[w] * f * sky.radiance[w];
            let error = (reflected - expected).abs() / expected;
            assert!(error < 0.02, "{id} at {w}: {reflected} against {expected}");
        }
    }
}

#[test]
fn bad_sea_hits_are_named() {
    let a = Atmosphere::preset("earth").unwrap();
    let m = model(ModelId::Nishita, &a);
    let ray = ViewRay {
        origin_m: DVec3::new(0.0, 0.0, a.bottom_radius_m + 10.0),
        direction: at(-30.0, 0.0),
        sun_direction: DVec3::Z,
        max_distance_m: None,
    };
    let hit = SeaHit {
        distance_m: 20.0,
        normal: DVec3::Z,
        body_albedo: vec![0.05; 3],
        slope_variance: slope_variance(5.0),
    };
    let err = |h: SeaHit| {
        radiance_with_sea(m.as_ref(), &a, &ray, &h)
            .unwrap_err()
            .to_string()
    };
    assert!(
        err(SeaHit {
            distance_m: -1.0,
            ..hit.clone()
        })
        .contains("distance")
    );
    assert!(
        err(SeaHit {
            body_albedo: vec![0.1],
            ..hit.clone()
        })
        .contains("albedos")
    );
    assert!(
        err(SeaHit {
            normal: DVec3::ZERO,
            ..hit.clone()
        })
        .contains("normal")
    );
    assert!(radiance_with_sea(m.as_ref(), &a, &ray, &hit).is_ok());
}
