//! The cloud layer lit through the frame's sun map (`march_in_sun_map`, the setting
//! `sun_light = map`) against each sample's own shadow march (`march`): the same view
//! rays, the sun's light alone, Wrenninge et al. 2013's octaves (which depend on the
//! optical depth alone) and Riley et al. 2004's walk (Eq. 25, which depends on how the
//! depth is spread along the path).

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::{CloudLight, MarchRay, march, march_in_sun_map};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings, SunLight};
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;

/// Cells of cloud about 50 km across (a period of 100 km), clear between them.
fn cover() -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let lat = p.z.asin();
        let lon = p.y.atan2(p.x);
        0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos()
    })
    .unwrap()
}

fn orders() -> ScatteringOrders {
    ScatteringOrders::new(&[LegendreSeries::henyey_greenstein(0.85, 300)]).unwrap()
}

/// The default layer (1.5 to 3 km, extinction 0.04 m^-1) over `cover()`, marched with
/// 128 view and 64 shadow steps, with the detail noise at `detail_strength`.
fn layer(method: LayerMethod, detail_strength: f64) -> CloudLayer {
    let settings = LayerSettings {
        method,
        detail_strength,
        steps: 128,
        shadow_steps: 64,
        min_transmittance: 1e-6,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, cover(), phase).unwrap()
}

/// The camera, 1 km up on the x axis.
fn camera() -> DVec3 {
    DVec3::X * (BOTTOM_M + 1_000.0)
}

/// A sun `elevation_deg` above the camera's horizon, from the azimuth `azimuth_deg`.
fn sun(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.sin(), e.cos() * a.sin(), e.cos() * a.cos())
}

/// View rays over the map's region: from the camera upwards, from inside the layer
/// (2.2 km) and from above it (5 km) downwards, 20 to 40 km from the camera's vertical.
fn rays(layer: &CloudLayer) -> Vec<MarchRay> {
    let mut out = Vec::new();
    let at =
        |height: f64, y: f64, z: f64| DVec3::new(BOTTOM_M, y, z).normalize() * (BOTTOM_M + height);
    let mut push = |origin: DVec3, zenith_deg: f64, azimuth_deg: f64| {
        let up = origin.normalize();
        let east = DVec3::Z.cross(up).normalize();
        let north = up.cross(east);
        let (z, a) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
        let d = up * z.cos() + (east * a.sin() + north * a.cos()) * z.sin();
        if let Some((t0, t1)) = layer.shell().first_segment(origin, d, f64::INFINITY) {
            out.push(MarchRay {
                origin,
                direction: d,
                t0,
                t1,
            });
        }
    };
    for a in [0.0, 70.0, 140.0, 210.0, 280.0] {
        for z in [0.0, 30.0, 55.0, 70.0] {
            push(camera(), z, a);
        }
        push(at(2_200.0, 20e3, -15e3), 60.0, a);
        push(at(2_200.0, -25e3, 30e3), 110.0, a);
        push(at(5_000.0, -30e3, -20e3), 160.0, a);
        push(at(5_000.0, 35e3, 10e3), 130.0, a);
    }
    out
}

/// The map's resolution for the lit layer: 128 cells, 16 levels, `steps` steps.
fn resolution(steps: usize) -> SunMapResolution {
    SunMapResolution {
        cells: 128,
        levels: 16,
        steps,
    }
}

/// `layer` with `shadow_steps` shadow steps.
fn with_shadow_steps(layer: &CloudLayer, shadow_steps: u32) -> CloudLayer {
    let settings = LayerSettings {
        shadow_steps,
        ..*layer.settings()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, cover(), phase).unwrap()
}

/// Largest and mean |L - L_ref| / L_ref over `rays` for a sun at `elevation_deg`: L by
/// `layer` lit as `sun_light` says (with the map, one of `resolution` made for a sun
/// `map_offset_deg` higher), L_ref by `reference`'s shadow march.
fn errors(
    (layer, sun_light): (&CloudLayer, SunLight),
    reference: &CloudLayer,
    elevation_deg: f64,
    (resolution, map_offset_deg): (SunMapResolution, f64),
) -> (f64, f64) {
    let orders = orders();
    let s = sun(elevation_deg, 40.0);
    let grid = CloudSunMap::grid_for(layer.shell(), camera(), &resolution).unwrap();
    let map_sun = sun(elevation_deg + map_offset_deg, 40.0);
    let map = CloudSunMap::new(layer, grid, map_sun, &resolution).unwrap();
    let (mut largest, mut sum, mut count): (f64, f64, usize) = (0.0, 0.0, 0);
    for ray in rays(layer) {
        let light = CloudLight {
            sun_direction: s,
            sun_irradiance: vec![1.0],
            sky_irradiance: vec![0.0],
            up: ray.origin.normalize(),
        };
        let settings = layer.settings();
        let truth = march(reference, &ray, &light, &orders, reference.settings()).radiance[0];
        let l = match sun_light {
            SunLight::March => march(layer, &ray, &light, &orders, settings),
            SunLight::Map => march_in_sun_map(layer, &ray, &light, &orders, settings, &map),
        };
        if truth < 1e-6 {
            continue;
        }
        let e = (l.radiance[0] - truth).abs() / truth;
        largest = largest.max(e);
        sum += e;
        count += 1;
    }
    assert!(count >= 20, "only {count} of 40 rays see cloud");
    (largest, sum / count as f64)
}

/// The octaves depend on the optical depth alone: the map's only error is its grid's
/// and its levels' interpolation. 16 levels are needed inside the layer (4 levels,
/// the ground shadows' default, give a mean error of 0.18 at a sun 30 degrees up).
#[test]
fn the_octaves_lit_by_the_map_match_the_shadow_march() {
    let smooth = layer(LayerMethod::Octaves, 0.0);
    let noisy = layer(LayerMethod::Octaves, 0.5);
    for (elevation, largest_bound, mean_bound) in
        [(60.0, 0.06, 0.03), (30.0, 0.09, 0.03), (12.0, 0.15, 0.08)]
    {
        let at = (resolution(64), 0.0);
        let (largest, mean) = errors((&smooth, SunLight::Map), &smooth, elevation, at);
        println!("octaves, no noise, sun {elevation} deg: largest {largest:.4}, mean {mean:.4}");
        assert!(
            largest < largest_bound && mean < mean_bound,
            "{largest} {mean}"
        );
        let (largest, mean) = errors((&noisy, SunLight::Map), &noisy, elevation, at);
        println!(
            "octaves, detail noise, sun {elevation} deg: largest {largest:.4}, mean {mean:.4}"
        );
        assert!(mean < 0.15, "{largest} {mean}");
    }
    let at = (
        SunMapResolution {
            levels: 4,
            ..resolution(64)
        },
        0.0,
    );
    let (largest, mean) = errors((&smooth, SunLight::Map), &smooth, 30.0, at);
    println!("octaves, no noise, 4 levels, sun 30 deg: largest {largest:.4}, mean {mean:.4}");
    assert!(mean > 0.1, "{largest} {mean}");
}

#[test]
fn a_map_for_another_sun_is_caught() {
    let smooth = layer(LayerMethod::Octaves, 0.0);
    let (largest, mean) = errors(
        (&smooth, SunLight::Map),
        &smooth,
        30.0,
        (resolution(64), 5.0),
    );
    println!("octaves, map 5 deg off: largest {largest:.4}, mean {mean:.4}");
    assert!(mean > 0.2, "{largest} {mean}");
}

/// Against the 64-step shadow march, the frame's map (`SunMapResolution::LIT`, in
/// `shadow_steps` parts) and a march of `shadow_steps` steps. The octaves converge: the map's error is below the 2-step
/// march's. Riley's walk (Eq. 25) depends on how the depth is spread along the path and
/// does not converge as the shadow steps grow (docs/clouds.md, Cost): the map's equal
/// parts are as far off as a march of as many steps.
#[test]
fn lit_by_the_map_the_march_is_no_further_from_the_fine_march() {
    for method in [LayerMethod::Octaves, LayerMethod::Riley] {
        let reference = layer(method, 0.0);
        for shadow_steps in [2, 8] {
            let coarse = with_shadow_steps(&reference, shadow_steps);
            for elevation in [60.0, 30.0] {
                let at = (SunMapResolution::LIT, 0.0);
                let map = errors((&coarse, SunLight::Map), &reference, elevation, at);
                let marched = errors((&coarse, SunLight::March), &reference, elevation, at);
                println!(
                    "{method}, {shadow_steps} shadow steps, sun {elevation} deg, mean against \
                     64 steps: map {:.4}, march {:.4}",
                    map.1, marched.1
                );
                assert!(map.1 < marched.1 + 0.05, "{map:?} {marched:?}");
                if method == LayerMethod::Octaves && shadow_steps == 2 {
                    assert!(map.1 < 0.5 * marched.1, "{map:?} {marched:?}");
                }
            }
        }
    }
}

/// 25 times the default density, a camera inside the cloud and on its top, and a sun 10
/// degrees below the horizon (the sky model's light, not tested here, darkens the night):
/// finite, non-negative, bounded answers, opaque where dense.
#[test]
fn lit_by_the_map_dense_inside_and_night_stay_finite() {
    let uniform = CoverGrid::from_values("overcast", 4, 2, vec![1.0; 8]).unwrap();
    let orders = orders();
    for method in [
        LayerMethod::Riley,
        LayerMethod::Octaves,
        LayerMethod::Eddington,
        LayerMethod::FourStream,
    ] {
        for extinction_per_m in [0.04, 1.0] {
            let settings = LayerSettings {
                method,
                extinction_per_m,
                sun_light: SunLight::Map,
                ..LayerSettings::default()
            };
            let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
            let layer = CloudLayer::new(settings, BOTTOM_M, uniform.clone(), phase).unwrap();
            let top = BOTTOM_M + settings.base_m + settings.thickness_m;
            let resolution = SunMapResolution {
                cells: 16,
                levels: 16,
                steps: 8,
            };
            for (elevation, camera) in [(30.0, 2_200.0), (30.0, top - BOTTOM_M), (-10.0, 2_200.0)] {
                let origin = DVec3::X * (BOTTOM_M + camera);
                let s = sun(elevation, 40.0);
                let grid = CloudSunMap::grid_for(layer.shell(), origin, &resolution).unwrap();
                let map = CloudSunMap::new(&layer, grid, s, &resolution).unwrap();
                for d in [DVec3::X, DVec3::Y, -DVec3::X] {
                    let Some((t0, t1)) = layer.shell().first_segment(origin, d, f64::INFINITY)
                    else {
                        continue;
                    };
                    let ray = MarchRay {
                        origin,
                        direction: d,
                        t0,
                        t1,
                    };
                    let light = CloudLight {
                        sun_direction: s,
                        sun_irradiance: vec![1.0],
                        sky_irradiance: vec![0.0],
                        up: origin.normalize(),
                    };
                    let c = march_in_sun_map(&layer, &ray, &light, &orders, &settings, &map);
                    let (l, t) = (c.radiance[0], c.transmittance[0]);
                    let what = format!(
                        "{method} {extinction_per_m} sun {elevation} at {camera} m along {d}"
                    );
                    assert!((0.0..10.0).contains(&l), "{what}: {l}");
                    assert!((0.0..=1.0).contains(&t), "{what}: T {t}");
                    if extinction_per_m == 1.0 && camera == 2_200.0 {
                        assert!(t < 1e-3, "{what}: T {t}");
                    }
                }
            }
        }
    }
}

#[test]
fn the_sun_light_setting_reads_back_and_others_are_named() {
    for s in [SunLight::March, SunLight::Map] {
        assert_eq!(s.to_string().parse::<SunLight>().unwrap(), s);
    }
    let e = "shadow".parse::<SunLight>().unwrap_err().to_string();
    assert!(
        e.contains("sun_light") && e.contains("\"shadow\"") && e.contains("march, map"),
        "{e}"
    );
}
