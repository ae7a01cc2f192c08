//! One cloud field, two renderings: the spheres (Dobashi, Yamamoto and Nishita 2002,
//! section 5.4) against the volume layer's ray march, which they stand in for from far
//! away. Along single rays through a uniform deck with the same light, the spheres'
//! radiance and transmittance against a fine march of the layer; and a 32 x 18 view
//! from the hand-over altitude composited with a sky model, where the mean radiance and
//! transmittance of the two must agree and no pixel may jump by more than a bound.
//! `-- --nocapture` prints the measured differences (docs/clouds.md quotes them).

use atmosphere_core::atmosphere::presets::earth;
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::clouds::layer::composite::radiance_with_clouds;
use atmosphere_core::clouds::layer::field::CloudLayer;
use atmosphere_core::clouds::layer::march::{CloudLight, MarchRay, march};
use atmosphere_core::clouds::layer::orders::ScatteringOrders;
use atmosphere_core::clouds::layer::settings::{LayerMethod, LayerSettings};
use atmosphere_core::clouds::phase::CloudPhase;
use atmosphere_core::clouds::spheres::composite::{radiance_with_spheres, spheres_only};
use atmosphere_core::clouds::spheres::field::CloudSpheres;
use atmosphere_core::clouds::spheres::settings::SphereSettings;
use atmosphere_core::geo::equirectangular::{direction, lat_lon};
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::{ModelSettings, ViewRay};
use atmosphere_core::optics::legendre_series::LegendreSeries;
use atmosphere_core::optics::phase::PhaseFunction;
use glam::DVec3;

const BOTTOM_M: f64 = 6_360_000.0;
const G: f64 = 0.85;

fn orders(waves: usize) -> ScatteringOrders {
    ScatteringOrders::new(&vec![LegendreSeries::henyey_greenstein(G, 300); waves]).unwrap()
}

fn layer(cover: CoverGrid, extinction_per_m: f64, steps: u32, method: LayerMethod) -> CloudLayer {
    let settings = LayerSettings {
        extinction_per_m,
        detail_strength: 0.0,
        method,
        steps,
        shadow_steps: 64,
        min_transmittance: 1e-6,
        ..LayerSettings::default()
    };
    let phase = CloudPhase::new(PhaseFunction::HenyeyGreenstein { g: G }).unwrap();
    CloudLayer::new(settings, BOTTOM_M, cover, phase).unwrap()
}

fn uniform(cover: f32) -> CoverGrid {
    CoverGrid::from_values("uniform cover", 8, 4, vec![cover; 32]).unwrap()
}

/// A direction `zenith_deg` from `up`, towards `side` at azimuth `azimuth_deg`.
fn tilted(up: DVec3, zenith_deg: f64, azimuth_deg: f64) -> DVec3 {
    let east = up.cross(DVec3::Z).normalize();
    let north = east.cross(up);
    let (z, a) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
    up * z.cos() + (east * a.cos() + north * a.sin()) * z.sin()
}

/// Single rays from 20 km over a uniform deck (cover 0.8), sun and sky fixed: the
/// spheres against a march of 512 steps with 64 shadow steps, under the octaves (a thin
/// deck, extinction 0.002 m^-1: a vertical optical depth of 1.7; 5 and 16 spheres) and
/// under the slab methods (`slab_light.rs`; the thin deck and a thick one, 0.03 m^-1:
/// 26; the default 5 spheres).
#[test]
fn along_single_rays_the_spheres_follow_a_fine_march() {
    let orders = orders(1);
    let cases = [
        (LayerMethod::Octaves, 0.002, 5, 0.03),
        (LayerMethod::Octaves, 0.002, 16, 0.01),
        (LayerMethod::Eddington, 0.002, 5, 0.03),
        (LayerMethod::Eddington, 0.03, 5, 0.03),
        (LayerMethod::FourStream, 0.002, 5, 0.03),
        (LayerMethod::FourStream, 0.03, 5, 0.03),
    ];
    for (method, extinction, count, bound) in cases {
        let deck = layer(uniform(0.8), extinction, 512, method);
        let up = direction(0.3, 0.2);
        let origin = up * (BOTTOM_M + 20_000.0);
        let mut worst_l = 0.0f64;
        let mut worst_t = 0.0f64;
        for (sun_zenith, view_zenith, azimuth) in [
            (30.0, 180.0, 0.0),
            (30.0, 150.0, 180.0),
            (60.0, 130.0, 0.0),
            (60.0, 120.0, 90.0),
            (75.0, 160.0, 180.0),
        ] {
            let sun = tilted(up, sun_zenith, 0.0);
            let d = tilted(up, view_zenith, azimuth);
            let light = CloudLight {
                sun_direction: sun,
                sun_irradiance: vec![1.0],
                sky_irradiance: vec![0.3],
                up,
            };
            let settings = SphereSettings {
                count,
                attenuation_width: 256,
                ..SphereSettings::default()
            };
            let spheres = CloudSpheres::new(&deck, &settings, sun).unwrap();
            let (cloud, _) = spheres_only(&spheres, &orders, &light, origin, d, f64::INFINITY);
            let (t0, t1) = deck
                .shell()
                .first_segment(origin, d, f64::INFINITY)
                .unwrap();
            let ray = MarchRay {
                origin,
                direction: d,
                t0,
                t1,
            };
            let fine = march(&deck, &ray, &light, &orders, deck.settings());
            let l = cloud.radiance[0] / fine.radiance[0] - 1.0;
            let t = cloud.transmittance[0] - fine.transmittance[0];
            println!(
                "{method} {extinction}, {count} spheres, sun {sun_zenith}, view {view_zenith} \
                 at {azimuth}: L {:.5} against {:.5} ({:+.2} %), T {:.4} against {:.4}",
                cloud.radiance[0],
                fine.radiance[0],
                100.0 * l,
                cloud.transmittance[0],
                fine.transmittance[0]
            );
            worst_l = worst_l.max(l.abs());
            worst_t = worst_t.max(t.abs());
        }
        println!(
            "{method} {extinction}, {count} spheres: worst {worst_l:.4} in L, {worst_t:.4} in T"
        );
        assert!(
            worst_l < bound,
            "{method}, {count} spheres: radiance off by {worst_l}"
        );
        assert!(
            worst_t < 0.01,
            "{method}, {count} spheres: transmittance off by {worst_t}"
        );
    }
}

/// Cells about 60 km across on a 2048 x 1024 grid (20 km texels): broken cloud over
/// the view.
fn broken_cover() -> CoverGrid {
    CoverGrid::rasterize(2048, 1024, |p| {
        let (lat, lon) = lat_lon(p);
        0.3 + 0.8 * (lat * 300.0).sin() * (lon * 250.0).cos()
    })
    .unwrap()
}

/// The hand-over: from 50 km, 32 x 18 rays from 25 to 70 degrees below the horizon, with
/// riley's sky, the default cloud (extinction 0.04 m^-1, 128 view steps; 512 change its
/// mean by 0.02 %) as the volume and as the default 5 spheres, lit by the octaves and by
/// the four-stream slab.
/// Single pixels at the cloud's edges differ most: the spheres interpolate each
/// texel's optical depth, the volume the cover under its profile, whose top falls
/// with the cover.
#[test]
fn at_the_hand_over_the_volume_and_the_spheres_agree() {
    for method in [LayerMethod::Octaves, LayerMethod::FourStream] {
        hand_over_view(method);
    }
}

fn hand_over_view(method: LayerMethod) {
    let model = prepare(ModelId::Riley, &earth(), &ModelSettings::default()).unwrap();
    let orders = orders(model.wavelengths_nm().len());
    let deck = layer(broken_cover(), 0.04, 128, method);
    let up = direction(0.4, 0.1);
    let sun = tilted(up, 40.0, 30.0);
    let spheres = CloudSpheres::new(&deck, &SphereSettings::default(), sun).unwrap();
    let origin = up * (BOTTOM_M + 50_000.0);
    let (mut volume_l, mut spheres_l, mut volume_t, mut spheres_t) = (0.0, 0.0, 0.0, 0.0);
    let (mut jump, mut jump_t, mut n, mut apart) = (0.0f64, 0.0f64, 0.0, 0.0);
    let mut brightest = 0.0f64;
    for j in 0..18 {
        for i in 0..32 {
            let zenith = 180.0 - 20.0 - 45.0 * (j as f64 + 0.5) / 18.0;
            let azimuth = -30.0 + 60.0 * (i as f64 + 0.5) / 32.0;
            let ray = ViewRay {
                origin_m: origin,
                direction: tilted(up, zenith, azimuth),
                sun_direction: sun,
                max_distance_m: None,
            };
            let v = radiance_with_clouds(model.as_ref(), &deck, &orders, &ray).unwrap();
            let s = radiance_with_spheres(model.as_ref(), &spheres, &orders, &ray).unwrap();
            volume_l += v.radiance[1];
            spheres_l += s.radiance[1];
            volume_t += v.transmittance[1];
            spheres_t += s.transmittance[1];
            brightest = brightest.max(v.radiance[1]);
            jump = jump.max((s.radiance[1] - v.radiance[1]).abs());
            apart += (s.radiance[1] - v.radiance[1]).abs();
            jump_t = jump_t.max((s.transmittance[1] - v.transmittance[1]).abs());
            n += 1.0;
        }
    }
    let mean_l = spheres_l / volume_l - 1.0;
    let mean_t = (spheres_t - volume_t) / n;
    let mean_apart = apart / volume_l;
    println!(
        "{method}, 550 nm: mean radiance {:.5} (volume) {:.5} (spheres), {:+.2} %; mean T {:.4} {:.4}; \
         mean absolute pixel difference {:.1} % of the mean; largest {:.5} ({:.1} % of the \
         brightest), in T {:.4}",
        volume_l / n,
        spheres_l / n,
        100.0 * mean_l,
        volume_t / n,
        spheres_t / n,
        100.0 * mean_apart,
        jump,
        100.0 * jump / brightest,
        jump_t
    );
    assert!(
        volume_t / n < 0.9 && volume_t / n > 0.05,
        "the view must hold broken cloud"
    );
    assert!(mean_l.abs() < 0.05, "mean radiance off by {mean_l}");
    assert!(mean_t.abs() < 0.02, "mean transmittance off by {mean_t}");
    assert!(
        mean_apart < 0.15,
        "pixels apart by {mean_apart} of the mean"
    );
    assert!(
        jump < 0.4 * brightest,
        "a pixel jumps by {jump} of {brightest}"
    );
    assert!(jump_t < 0.25, "a pixel's transmittance jumps by {jump_t}");
}
