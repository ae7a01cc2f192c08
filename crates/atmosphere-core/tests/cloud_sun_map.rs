//! The cloud layer's sun map (Dobashi et al. 2002 section 5.4's attenuation textures)
//! against the direct march through the density from each point towards the sun.

use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::sun_map::{
    CloudSunMap, SunMapResolution, optical_depth_to_sun,
};
use atmosphere_core::clouds::phase::CloudPhase;
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

fn layer(detail_strength: f64) -> CloudLayer {
    let settings = LayerSettings {
        extinction_per_m: 0.002,
        detail_strength,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, cover(), phase).unwrap()
}

/// A sun `elevation_deg` above the horizon at the camera, from the azimuth `azimuth_deg`.
fn sun(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.sin(), e.cos() * a.sin(), e.cos() * a.cos())
}

/// Points over the map's region: on the ground (up to 60 km from the camera's vertical,
/// some on 2 km high ground) and inside the layer at a few heights.
fn points() -> Vec<DVec3> {
    let mut out = Vec::new();
    for i in 0..24 {
        for j in 0..24 {
            let (y, z) = (-60e3 + 5.2e3 * f64::from(i), -60e3 + 5.2e3 * f64::from(j));
            let d = DVec3::new(BOTTOM_M, y, z).normalize();
            let height = match (i + j) % 6 {
                0 => 0.0,
                1 => 2_000.0,
                2 => 500.0,
                3 => 1_700.0,
                4 => 2_300.0,
                _ => 2_900.0,
            };
            out.push(d * (BOTTOM_M + height));
        }
    }
    out
}

/// Largest |T_map - T_direct| over `points()` below the layer's base and inside it, and
/// the mean over all.
fn errors(layer: &CloudLayer, map: &CloudSunMap, sun: DVec3) -> (f64, f64, f64) {
    let (mut below, mut inside): (f64, f64) = (0.0, 0.0);
    let mut sum = 0.0;
    let ps = points();
    for &p in &ps {
        let direct = (-optical_depth_to_sun(layer, p, sun, 1024)).exp();
        let e = (map.transmittance(p) - direct).abs();
        if p.length() <= layer.shell().base_radius_m {
            below = below.max(e);
        } else {
            inside = inside.max(e);
        }
        sum += e;
    }
    (below, inside, sum / ps.len() as f64)
}

fn map(layer: &CloudLayer, sun: DVec3, resolution: &SunMapResolution) -> CloudSunMap {
    let camera = DVec3::X * (BOTTOM_M + 500.0);
    let mut grid = CloudSunMap::grid_for(layer.shell(), camera, resolution).unwrap();
    // The test's points lie within 85 km of the camera's vertical: a smaller grid.
    grid.cell_m = 200_000.0 / resolution.cells as f64;
    CloudSunMap::new(layer, grid, sun, resolution).unwrap()
}

#[test]
fn the_map_gives_the_direct_march_of_the_density_towards_the_sun() {
    let smooth = layer(0.0);
    let resolution = SunMapResolution {
        cells: 128,
        levels: 8,
        steps: 32,
    };
    for (elevation, azimuth) in [(30.0, 40.0), (60.0, 200.0), (12.0, 120.0)] {
        let s = sun(elevation, azimuth);
        let m = map(&smooth, s, &resolution);
        let (below, inside, mean) = errors(&smooth, &m, s);
        println!(
            "sun {elevation} deg up: |T_map - T_direct| at most {below:.4} below the base, \
             {inside:.4} inside the layer, mean {mean:.5}"
        );
        assert!(
            below < 0.04 && inside < 0.08 && mean < 0.006,
            "{below} {inside} {mean}"
        );
        // The points see cloud and clear sky alike: the comparison has something to see.
        let ts: Vec<f64> = points().iter().map(|&p| m.transmittance(p)).collect();
        assert!(ts.iter().any(|&t| t < 0.2) && ts.iter().any(|&t| t > 0.9));
    }
}

#[test]
fn the_comparison_sees_a_map_made_for_another_sun() {
    let smooth = layer(0.0);
    let resolution = SunMapResolution {
        cells: 128,
        levels: 8,
        steps: 32,
    };
    let wrong = map(&smooth, sun(35.0, 40.0), &resolution);
    let (below, _, _) = errors(&smooth, &wrong, sun(30.0, 40.0));
    assert!(below > 0.05, "{below}");
}

#[test]
fn with_detail_noise_the_default_resolution_stays_close_on_average() {
    let noisy = layer(0.5);
    let s = sun(30.0, 40.0);
    let m = map(&noisy, s, &SunMapResolution::default());
    let (below, inside, mean) = errors(&noisy, &m, s);
    println!("detail noise, default resolution: at most {below:.4} / {inside:.4}, mean {mean:.5}");
    assert!(mean < 0.03, "{mean}");
}

#[test]
fn above_the_top_and_off_the_grid_the_sun_is_clear() {
    let smooth = layer(0.0);
    let resolution = SunMapResolution {
        cells: 16,
        levels: 1,
        steps: 4,
    };
    let m = map(&smooth, sun(30.0, 40.0), &resolution);
    assert_eq!(m.transmittance(DVec3::X * (BOTTOM_M + 3_500.0)), 1.0);
    let far = DVec3::new(BOTTOM_M, 2e6, 0.0).normalize() * BOTTOM_M;
    assert_eq!(m.transmittance(far), 1.0);
}

#[test]
fn a_resolution_out_of_range_is_named() {
    let smooth = layer(0.0);
    for (bad, name) in [
        (
            SunMapResolution {
                cells: 8,
                ..Default::default()
            },
            "sun map cells",
        ),
        (
            SunMapResolution {
                levels: 0,
                ..Default::default()
            },
            "sun map levels",
        ),
        (
            SunMapResolution {
                steps: 1000,
                ..Default::default()
            },
            "sun map steps",
        ),
    ] {
        let e = CloudSunMap::grid_for(smooth.shell(), DVec3::X * BOTTOM_M, &bad).unwrap_err();
        assert!(e.to_string().contains(name), "{e}");
    }
    let grid =
        CloudSunMap::grid_for(smooth.shell(), DVec3::X * BOTTOM_M, &Default::default()).unwrap();
    let e = CloudSunMap::new(&smooth, grid, DVec3::ZERO, &Default::default()).unwrap_err();
    assert!(e.to_string().contains("sun"), "{e}");
}
