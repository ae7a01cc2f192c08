//! Dobashi et al. 2000's virtual planes against the closed form and the reference: they
//! converge as planes and lattice points grow, and answer only rays from their camera.

mod common;

use atmosphere_core::beams::methods::id::BeamMethodId;
use common::beams::*;
use glam::DVec3;

#[test]
fn converged_planes_match_the_point_light_closed_form_within_half_a_percent() {
    let (sigma_s, sigma_a, intensity) = (0.05, 0.02, 800.0);
    let light = [1.0, 6.0, -3.0];
    let s = scene(
        &medium(sigma_s, sigma_a, ISOTROPIC),
        &point_light(light, intensity),
    );
    let end = 20.7 / (sigma_s + sigma_a);
    let far = format!("far_m={end}");
    let planes = method(
        BeamMethodId::Planes2000,
        &s,
        &["planes=1024", "lattice=64", &far],
    );
    let iso = s.medium.phase.clone();
    for (x, y) in [(16.0, 12.0), (8.0, 4.0), (24.0, 20.0)] {
        let ray = s.camera.ray(x, y);
        // The planes end at far_m along the view axis, so an oblique ray ends a little
        // farther: the closed form is taken to the same end.
        let ray_end = end / ray.direction.dot(s.camera.forward);
        let expected = point_light_airlight(
            ray.origin_m,
            ray.direction,
            DVec3::from(light),
            intensity,
            sigma_s,
            sigma_s + sigma_a,
            &iso,
            (0.0, ray_end),
        );
        for l in planes.radiance(&ray).unwrap() {
            assert!(
                relative(l, expected) < 0.005,
                "pixel ({x}, {y}): {l} vs {expected}"
            );
        }
    }
}

#[test]
fn planes_converge_to_the_reference_through_a_shadow_and_refuse_other_origins() {
    let rest = "[[lights]]\nkind = \"spot\"\nposition_m = [0, 20, 0]\ndirection = [0, -1, 0]\n\
                cone_deg = 30\nintensity_w_sr_nm = { kind = \"constant\", value = 1000 }\n\
                [[occluders]]\nkind = \"sphere\"\ncenter_m = [0, 10, 0]\nradius_m = 2\n";
    let s = scene(&medium(0.04, 0.01, "{ kind = \"nishita_hazy\" }"), rest);
    let ray = s.camera.ray(12.0, 4.0);
    let truth = method(BeamMethodId::Reference, &s, &[])
        .radiance(&ray)
        .unwrap();
    let error = |options: &[&str]| {
        let got = method(BeamMethodId::Planes2000, &s, options)
            .radiance(&ray)
            .unwrap();
        relative(got[1], truth[1])
    };
    let table_1 = error(&[]);
    let fine = error(&[
        "planes=2048",
        "lattice=64",
        "shadow_map_px=1024",
        "far_m=60",
    ]);
    assert!(fine < 0.005, "fine planes error {fine}");
    assert!(table_1 > fine, "Table 1 defaults {table_1}, fine {fine}");

    let planes = method(BeamMethodId::Planes2000, &s, &[]);
    let mut elsewhere = ray;
    elsewhere.origin_m += DVec3::X;
    let e = planes.radiance(&elsewhere).unwrap_err().to_string();
    assert!(
        e.contains("planes2000 renders from the scene camera"),
        "{e}"
    );
}
