//! Bruneton's fourth coordinate as the azimuth between the view's and the sun's vertical
//! planes (`nu_by_azimuth`): every texel holds a direction its (mu, mu_s) allows, so a
//! table of a smooth function of the direction is read continuously, also by rays in the
//! sun's vertical plane, where the paper's nu axis holds texels clamped to the edge of
//! their range at other mu and the read jumps where the ray's nu crosses a texel.

mod common;

use atmosphere_core::models::bruneton::BrunetonSettings;
use atmosphere_core::models::bruneton::parameterization::{
    AngleMapping, NuAxis, Radii, ScatteringSize, azimuth_unit, nu_at_azimuth_unit, nu_range,
};
use atmosphere_core::models::bruneton::tables::Table4;
use atmosphere_core::models::options::ModelOptions;
use common::bruneton_tables::{earth_radii, table_of};

const AZIMUTH: AngleMapping = AngleMapping {
    nu_by_azimuth: true,
    ..AngleMapping::PAPER
};

#[test]
fn the_azimuth_coordinate_inverts_and_stays_within_the_range_of_nu() {
    for &mu in &[-0.9, -0.3, 0.0, 0.05, 0.5, 0.99] {
        for &mu_s in &[-0.31, -0.2, 0.0, 0.4, 0.95] {
            let (low, high) = nu_range(mu, mu_s);
            for k in 0..=20 {
                let u = k as f64 / 20.0;
                let nu = nu_at_azimuth_unit(mu, mu_s, u);
                assert!(
                    nu >= low - 1e-12 && nu <= high + 1e-12,
                    "{mu} {mu_s} {u}: {nu}"
                );
                let back = azimuth_unit(mu, mu_s, nu);
                assert!((back - u).abs() < 1e-6, "{mu} {mu_s} {u}: {back}");
            }
            // The ends: towards the sun (u = 1) and away (u = 0).
            assert!((nu_at_azimuth_unit(mu, mu_s, 1.0) - high).abs() < 1e-12);
            assert!((nu_at_azimuth_unit(mu, mu_s, 0.0) - low).abs() < 1e-12);
        }
    }
    // A view or sun at the zenith: every azimuth is one direction; no NaN, u in [0, 1],
    // also for a nu off its single value by rounding.
    for &(mu, mu_s) in &[(1.0, 0.3), (-1.0, 0.3), (0.2, 1.0), (1.0, 1.0)] {
        for nu in [mu * mu_s, mu * mu_s + 1e-9, mu * mu_s - 1e-9] {
            let u = azimuth_unit(mu, mu_s, nu);
            assert!((0.0..=1.0).contains(&u), "{mu} {mu_s} {nu}: {u}");
            let axis = NuAxis::new(&AZIMUTH, 8, mu, mu_s, nu);
            assert!((0.0..=1.0).contains(&axis.weight(mu, mu_s)));
        }
    }
}

/// A table of `angles` whose every texel holds a smooth function of its true direction:
/// brighter towards the sun and towards the horizon.
fn direction_table(radii: &Radii, angles: AngleMapping) -> Table4 {
    let size = ScatteringSize {
        r: 4,
        mu: 32,
        mu_s: 8,
        nu: 16,
        angles,
    };
    table_of(radii, size, field)
}

fn field(mu: f64, nu: f64) -> f64 {
    (1.0 + 3.0 * (1.0 + nu) / 2.0) * (1.0 + (1.0 - mu.abs()))
}

/// The largest relative change between reads 0.05 deg apart, over the median change:
/// reads of the table up the sun's vertical plane from the ground, the sun 12 deg down.
fn worst_step_over_median(radii: &Radii, table: &Table4) -> f64 {
    let mu_s = (-12f64).to_radians().sin();
    let r = radii.bottom_m + 1.0;
    let reads: Vec<f64> = (0..1700)
        .map(|k| {
            let elevation = (5.0 + 0.05 * k as f64).to_radians();
            let mu = elevation.sin();
            let nu = (elevation - (-12f64).to_radians()).cos();
            table.lookup(radii, r, mu, mu_s, nu, false)[0]
        })
        .collect();
    let mut steps: Vec<f64> = reads
        .windows(2)
        .map(|w| (w[1] / w[0] - 1.0).abs())
        .collect();
    let worst = steps.iter().fold(0.0f64, |m, s| m.max(*s));
    steps.sort_by(f64::total_cmp);
    worst / steps[steps.len() / 2]
}

#[test]
fn reads_in_the_sun_s_vertical_plane_are_continuous_by_azimuth_and_jump_by_nu() {
    let radii = earth_radii();
    let edge = AngleMapping {
        nu_by_angle: true,
        nu_edge: true,
        ..AngleMapping::PAPER
    };
    let by_nu = worst_step_over_median(&radii, &direction_table(&radii, edge));
    let by_azimuth = worst_step_over_median(&radii, &direction_table(&radii, AZIMUTH));
    println!("worst step over median: by nu {by_nu:.1}, by azimuth {by_azimuth:.1}");
    assert!(by_nu > 20.0, "{by_nu}");
    assert!(by_azimuth < 5.0, "{by_azimuth}");
}

#[test]
fn nu_by_azimuth_is_a_switch_that_excludes_the_nu_mappings() {
    let parse = |o: &[&str]| BrunetonSettings::from_options(&ModelOptions::parse(o).unwrap());
    assert!(
        parse(&["nu_by_azimuth=true"])
            .unwrap()
            .scattering_size
            .angles
            .nu_by_azimuth
    );
    assert!(!parse(&[]).unwrap().scattering_size.angles.nu_by_azimuth);
    for other in ["nu_by_angle=true", "nu_edge=true"] {
        let e = parse(&["nu_by_azimuth=true", other])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("nu_by_azimuth=true replaces nu_by_angle and nu_edge"),
            "{e}"
        );
    }
}
