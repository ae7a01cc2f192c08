//! The cloud's shadow in the air taken from the field itself (`clouds/layer/
//! direct_shade.rs`), the path-traced reference's: converged at its steps (four times
//! finer along the view ray and towards the sun changes the loss by under 1 %), marched
//! over the whole part of the ray below the base (to the ground here) in samples of its
//! length, nothing taken where the layer is empty, and the frames' sun map within 5 %
//! of it on the same field.

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::air_shadow::{AirShadow, CloudAirShadow, CloudShade};
use atmosphere_core::clouds::layer::direct_shade::{
    DirectCloudShade, REFERENCE_SAMPLE_M, REFERENCE_STEPS,
};
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::settings::LayerSettings;
use atmosphere_core::clouds::layer::sun_map::{CloudSunMap, SunMapResolution};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::models::hillaire::Hillaire;
use atmosphere_core::models::hillaire::settings::HillaireSettings;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::phase::PhaseFunction;
use atmosphere_core::optics::view_segment::ViewSegment;
use glam::DQuat;

const BOTTOM_M: f64 = 6_360_000.0;

/// Cells of cloud about 50 km across with clear gaps, broken by detail noise.
fn cloud_layer(extinction_per_m: f64) -> CloudLayer {
    let cover = CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = (p.z.asin(), p.y.atan2(p.x));
        0.5 + 0.8 * (lat * 400.0).sin() * (lon * 300.0).cos()
    })
    .unwrap();
    let settings = LayerSettings {
        base_m: 2_000.0,
        thickness_m: 1_000.0,
        extinction_per_m,
        detail_strength: 0.5,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: 0.85 }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, cover, phase).unwrap()
}

fn model() -> Hillaire {
    let settings = ModelSettings {
        wavelengths_nm: vec![680.0, 550.0, 440.0],
        ..ModelSettings::default()
    };
    Hillaire::prepare(&earth(), &settings, HillaireSettings::default()).unwrap()
}

/// From 1 km up at (0 N, 0 E), 3 degrees below the horizon, towards the sun 30 degrees
/// up: about 15 km of air below the base before the ground. (`from_angles` stands at
/// the north pole, where the cover's rows are 20 km apart and its columns meet.)
fn ray() -> ViewRay {
    let at_pole = ViewRay::from_angles(BOTTOM_M, 1_000.0, 93.0, 60.0, 0.0, None).unwrap();
    let to_equator = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
    ViewRay {
        origin_m: to_equator * at_pole.origin_m,
        direction: to_equator * at_pole.direction,
        sun_direction: to_equator * at_pole.sun_direction,
        ..at_pole
    }
}

/// What `shade` takes out of `ray` per unit solar irradiance, per wavelength.
fn lost(shade: &dyn CloudShade) -> Vec<f64> {
    let model = model();
    let air = CloudAirShadow::new(&earth(), &model);
    let segment = ViewSegment::new(&earth(), &ray()).unwrap().unwrap();
    let mut out = vec![0.0; 3];
    let shadow = AirShadow {
        terrain: None,
        clouds: shade,
    };
    shadow.cloud_single(&air.medium(), &segment, &mut out);
    out
}

#[test]
fn the_shade_is_converged_at_its_steps_and_near_the_frames_map() {
    let layer = cloud_layer(0.04);
    let direct = |steps, sample_m| DirectCloudShade {
        layer: &layer,
        steps,
        sample_m,
    };
    let shipped = lost(&DirectCloudShade::reference(&layer));
    let finer = lost(&direct(4 * REFERENCE_STEPS, REFERENCE_SAMPLE_M / 4.0));
    let ray = ray();
    let resolution = SunMapResolution {
        levels: 1,
        ..SunMapResolution::default()
    };
    let grid = CloudSunMap::grid_for(layer.shell(), ray.origin_m, &resolution).unwrap();
    let map = CloudSunMap::new(&layer, grid, ray.sun_direction, &resolution).unwrap();
    let mapped = lost(&map);
    let empty = cloud_layer(0.0);
    let unshaded = lost(&DirectCloudShade::reference(&empty));
    // The whole part below the base, to the ground, in samples of at most 100 m.
    let segment = ViewSegment::new(&earth(), &ray).unwrap().unwrap();
    let shade = DirectCloudShade::reference(&layer);
    let ((start, end), samples) = AirShadow {
        terrain: None,
        clouds: &shade,
    }
    .span(&segment)
    .unwrap();
    assert!(
        start == 0.0 && (end - segment.length).abs() < 1.0,
        "{start} {end}"
    );
    assert_eq!(samples, (end / REFERENCE_SAMPLE_M).ceil() as usize);
    // The ray passes under cloud and under a gap: the loss has edges to resolve.
    let seen: Vec<f64> = (0..100)
        .map(|k| {
            let p = segment.start + (k as f64 + 0.5) * end / 100.0 * segment.direction;
            shade.sun_transmittance(p, segment.sun_direction)
        })
        .collect();
    assert!(
        seen.iter().any(|&t| t < 0.1) && seen.iter().any(|&t| t > 0.5),
        "{seen:?}"
    );
    for w in 0..3 {
        println!(
            "wavelength {w}: lost {:.4e} (finer {:.4e}, the map {:.4e})",
            shipped[w], finer[w], mapped[w]
        );
        assert!(
            shipped[w] > 0.0 && unshaded[w] == 0.0,
            "{w}: {shipped:?}, {unshaded:?}"
        );
        assert!(
            (shipped[w] - finer[w]).abs() < 0.01 * finer[w],
            "{w}: {} against {}",
            shipped[w],
            finer[w]
        );
        assert!(
            (mapped[w] - finer[w]).abs() < 0.05 * finer[w],
            "{w}: the map {} against {}",
            mapped[w],
            finer[w]
        );
    }
}
