//! The sundogs scene on the CPU twin (`hydrometeors/render.rs` over the nishita model's
//! sky): a cirrus of falling plates with the sun 20 degrees up shows, along the sun's
//! elevation, a sundog at the azimuth where the projected 60 degree prism deviates
//! least (Bravais's effective index), red on its inner edge, far brighter than the sky
//! above it; the sky angles the tables are read by; the sun below the horizon refused.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::hydrometeors::channel_phase::sky_angles_deg;
use atmosphere_core::hydrometeors::render::composite;
use atmosphere_core::hydrometeors::scene::{CirrusSettings, VolumeOptics, lit_volume};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::ViewRay;
use atmosphere_core::optics::refractive_index::ice::ice_refractive_index;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;

const FRAME_NM: [f64; 3] = [680.0, 550.0, 440.0];
const SUN_ELEVATION_DEG: f64 = 20.0;

/// A unit direction at `elevation_deg` and `azimuth_deg` from the -Y azimuth, X up.
fn direction(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::X * e.sin() + (-DVec3::Y * a.cos() + DVec3::Z * a.sin()) * e.cos()
}

/// Bravais's (1847) effective index n' = sqrt(n^2 - sin^2 e) / cos e of a ray climbing
/// at e through a prism with vertical edges; the sundog's azimuth from the sun is the
/// least deviation 2 asin(n' sin 30 deg) - 60 deg (Tape 1994, chapter 4).
fn parhelion_azimuth_deg(n: f64, e_deg: f64) -> f64 {
    let e = e_deg.to_radians();
    let effective = (n * n - e.sin().powi(2)).sqrt() / e.cos();
    (2.0 * (effective * 0.5).asin()).to_degrees() - 60.0
}

#[test]
fn the_sundog_lies_beside_the_sun_at_the_prisms_least_projected_deviation() {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let model = prepare(ModelId::Nishita, &atmosphere, &Default::default()).unwrap();
    let camera = DVec3::X * (atmosphere.bottom_radius_m + 2.0);
    let sun = direction(SUN_ELEVATION_DEG, 0.0);
    let volume = CirrusSettings {
        crystal_radius_um: 50.0,
        crystal_length_um: 20.0,
        rays: 200_000,
        plates_tilt_deg: Some(0.5),
        ..CirrusSettings::default()
    }
    .volume(atmosphere.bottom_radius_m, SUN_ELEVATION_DEG)
    .unwrap();
    let lit = [lit_volume(
        model.as_ref(),
        volume,
        (camera, sun),
        VolumeOptics::new(8, 0.004675),
        FRAME_NM,
        &TableCache::off(),
    )
    .unwrap()];
    let spectra = Spectra::new(&atmosphere, &FRAME_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let pixel = |elevation: f64, azimuth: f64| {
        let d = direction(elevation, azimuth);
        let ray = ViewRay {
            origin_m: camera,
            direction: d,
            sun_direction: sun,
            max_distance_m: None,
        };
        let full = model.radiance(&ray).unwrap().radiance;
        let full: [f64; 3] = std::array::from_fn(|c| full[c]);
        composite(
            &atmosphere,
            &extinction,
            &lit,
            camera,
            d,
            f64::INFINITY,
            full,
        )
    };
    let row: Vec<(f64, [f64; 3])> = (0..=400)
        .map(|k| {
            let azimuth = 15.0 + 0.05 * f64::from(k);
            (azimuth, pixel(SUN_ELEVATION_DEG, azimuth))
        })
        .collect();
    let peak = |c: usize| {
        row.iter().fold(
            (0.0, f64::MIN),
            |b, (a, v)| if v[c] > b.1 { (*a, v[c]) } else { b },
        )
    };
    let n = ice_refractive_index(550.0).unwrap().re;
    let want = parhelion_azimuth_deg(n, SUN_ELEVATION_DEG);
    let (green, brightest) = peak(1);
    eprintln!("sundog: green peak at azimuth {green:.2} deg, closed form {want:.3} deg");
    assert!((green - want).abs() <= 0.3, "{green} against {want}");
    // Red on the inner edge (ice bends red least).
    let (red, blue) = (peak(0).0, peak(2).0);
    assert!(red < blue, "red {red}, blue {blue}");
    // Far brighter than the sky 10 degrees above it.
    let above = pixel(SUN_ELEVATION_DEG + 10.0, green)[1];
    assert!(brightest > 3.0 * above, "sundog {brightest}, above {above}");
}

#[test]
fn the_sky_angles_are_the_elevation_and_the_azimuth_from_the_sun() {
    let (up, sun) = (DVec3::X, direction(SUN_ELEVATION_DEG, 0.0));
    for (e, a) in [(20.0, 24.7), (-30.0, 170.0), (0.0, 0.0), (85.0, 90.0)] {
        let (elevation, azimuth) = sky_angles_deg(direction(e, a), sun, up);
        assert!((elevation - e).abs() < 1e-9 && (azimuth - a).abs() < 1e-9);
        // Either side of the sun's vertical alike.
        let (_, mirrored) = sky_angles_deg(direction(e, -a), sun, up);
        assert!((mirrored - a).abs() < 1e-9);
    }
    // Straight up: azimuth 0, not NaN.
    assert_eq!(sky_angles_deg(up, sun, up), (90.0, 0.0));
}

#[test]
fn falling_plates_with_the_sun_below_the_horizon_are_refused_by_name() {
    let plates = CirrusSettings {
        plates_tilt_deg: Some(1.0),
        ..CirrusSettings::default()
    };
    let e = plates.volume(6_360e3, -5.0).unwrap_err().to_string();
    assert!(e.contains("sun elevation -5"), "{e}");
    let tilted = CirrusSettings {
        plates_tilt_deg: Some(45.0),
        ..CirrusSettings::default()
    };
    let e = tilted.volume(6_360e3, 20.0).unwrap_err().to_string();
    assert!(e.contains("tilt spread 45"), "{e}");
    // Random columns do not care where the sun is.
    assert!(CirrusSettings::default().volume(6_360e3, -5.0).is_ok());
}
