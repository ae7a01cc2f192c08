//! The march with shadow maps against the closed form and the reference: it converges
//! as its steps and shadow maps grow.

mod common;

use atmosphere_core::beams::methods::id::BeamMethodId;
use atmosphere_core::beams::ray::SceneRay;
use common::beams::*;
use glam::DVec3;

#[test]
fn converged_march_matches_the_point_light_closed_form_within_half_a_percent() {
    let (sigma_s, sigma_a, intensity) = (0.05, 0.02, 800.0);
    let light = [1.0, 4.0, -3.0];
    let s = scene(
        &medium(sigma_s, sigma_a, ISOTROPIC),
        &point_light(light, intensity),
    );
    let march = method(BeamMethodId::March, &s, &["steps=8192"]);
    let iso = s.medium.phase.clone();
    for (origin, direction) in [
        (DVec3::new(0.0, 2.0, 20.0), DVec3::new(0.0, 0.1, -1.0)),
        (DVec3::new(-10.0, 4.3, -3.0), DVec3::X),
    ] {
        let ray = SceneRay::new(origin, direction, None).unwrap();
        let end = 20.7 / (sigma_s + sigma_a);
        let expected = point_light_airlight(
            ray.origin_m,
            ray.direction,
            DVec3::from(light),
            intensity,
            sigma_s,
            sigma_s + sigma_a,
            &iso,
            (0.0, end),
        );
        for l in march.radiance(&ray).unwrap() {
            assert!(relative(l, expected) < 0.005, "{origin}: {l} vs {expected}");
        }
    }
}

#[test]
fn march_with_shadow_map_converges_to_the_reference_through_a_shadow() {
    let rest = "[[lights]]\nkind = \"spot\"\nposition_m = [0, 20, 0]\ndirection = [0, -1, 0]\n\
                cone_deg = 30\nintensity_w_sr_nm = { kind = \"constant\", value = 1000 }\n\
                [[occluders]]\nkind = \"sphere\"\ncenter_m = [0, 10, 0]\nradius_m = 2\n";
    let s = scene(&medium(0.04, 0.01, "{ kind = \"nishita_hazy\" }"), rest);
    let ray = SceneRay::new(
        DVec3::new(-30.0, 5.0, 0.5),
        DVec3::new(1.0, 0.02, 0.0),
        None,
    )
    .unwrap();
    let truth = method(BeamMethodId::Reference, &s, &[])
        .radiance(&ray)
        .unwrap();
    let error = |options: &[&str]| {
        let got = method(BeamMethodId::March, &s, options)
            .radiance(&ray)
            .unwrap();
        relative(got[1], truth[1])
    };
    let coarse = error(&["steps=16", "shadow_map_px=64"]);
    let fine = error(&["steps=4096", "shadow_map_px=1024"]);
    assert!(fine < 0.005, "fine march error {fine}");
    assert!(coarse > fine, "coarse {coarse} fine {fine}");
}
