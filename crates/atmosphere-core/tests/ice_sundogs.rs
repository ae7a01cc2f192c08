//! Sundogs: falling hexagonal plates' phase function over the sky (`sky_table.rs`) has
//! its brightest azimuth at the sun's elevation where the 60 degree prism's projected
//! ray deviates least, by Bravais's effective index; it integrates to 1, the sun
//! overhead too; bad input is named.

use atmosphere_core::optics::ice::crystal::HexagonalPrism;
use atmosphere_core::optics::ice::phase_table::RaySettings;
use atmosphere_core::optics::ice::sky_table::{IceSkyTable, PlateSky, SkyGrid, plate_sky_table};
use atmosphere_core::optics::refractive_index::ice::ice_refractive_index;

const GRID: SkyGrid = SkyGrid {
    elevation_bin_deg: 0.5,
    azimuth_bin_deg: 0.1,
};

fn plates() -> HexagonalPrism {
    HexagonalPrism::new(50e-6, 20e-6).unwrap()
}

fn settings(rays: usize) -> RaySettings {
    RaySettings {
        rays,
        bin_deg: 0.1,
        seed: 3,
    }
}

fn table(sun_elevation_deg: f64, tilt_spread_deg: f64, sun_radius_rad: f64) -> IceSkyTable {
    let m = ice_refractive_index(550.0).unwrap();
    let sky = PlateSky {
        tilt_spread_deg,
        sun_elevation_deg,
        sun_radius_rad,
    };
    plate_sky_table(&plates(), m, 550e-9, sky, GRID, settings(400_000)).unwrap()
}

/// The sundog's azimuth from the sun, degrees: a ray through two prism faces 60 degrees
/// apart, climbing at the sun's elevation e, deviates in its horizontal projection as a
/// ray in a medium of Bravais's (1847) effective index n' = sqrt(n^2 - sin^2 e) / cos e,
/// least by D = 2 asin(n' sin 30 deg) - 60 deg (Tape 1994, Atmospheric Halos, chapter 4;
/// Greenler 1980, chapter 2).
fn parhelion_azimuth_deg(n: f64, sun_elevation_deg: f64) -> f64 {
    let e = sun_elevation_deg.to_radians();
    let effective = (n * n - e.sin().powi(2)).sqrt() / e.cos();
    (2.0 * (effective * 0.5).asin()).to_degrees() - 60.0
}

/// The centre of the brightest azimuth bin between 15 and 45 degrees over the elevation
/// rows within half a degree of `elevation_deg`.
fn sundog_azimuth_deg(t: &IceSkyTable, elevation_deg: f64) -> f64 {
    let columns = t.grid.azimuth_bins();
    let rows: Vec<usize> = (0..t.grid.elevation_bins())
        .filter(|&r| {
            let centre = -90.0 + (r as f64 + 0.5) * t.grid.elevation_bin_deg;
            (centre - elevation_deg).abs() <= 0.5
        })
        .collect();
    (150..450)
        .map(|c| {
            let sum: f64 = rows.iter().map(|r| t.phase[r * columns + c]).sum();
            ((c as f64 + 0.5) * t.grid.azimuth_bin_deg, sum)
        })
        .fold((0.0, f64::MIN), |b, x| if x.1 > b.1 { x } else { b })
        .0
}

fn integral(t: &IceSkyTable) -> f64 {
    let columns = t.grid.azimuth_bins();
    t.phase
        .iter()
        .enumerate()
        .map(|(c, p)| p * t.grid.bin_solid_angle(c / columns))
        .sum()
}

#[test]
fn the_sundogs_lie_at_the_projected_prisms_minimum_deviation() {
    let n = ice_refractive_index(550.0).unwrap().re;
    let expected: Vec<f64> = [0.0, 20.0, 40.0]
        .iter()
        .map(|&e| parhelion_azimuth_deg(n, e))
        .collect();
    // The closed form: 21.9 degrees on the horizon, farther out as the sun climbs.
    assert!((expected[0] - 21.915).abs() < 0.01, "{expected:?}");
    assert!(expected[1] > expected[0] + 2.0 && expected[2] > expected[1] + 3.0);
    for (&e, &want) in [0.0, 20.0, 40.0].iter().zip(&expected) {
        let t = table(e, 0.0, 0.0);
        let got = sundog_azimuth_deg(&t, e);
        eprintln!("sun {e} deg: sundog at azimuth {got:.2} deg, closed form {want:.3} deg");
        assert!((got - want).abs() <= 0.3, "sun {e}: {got} against {want}");
        assert!((integral(&t) - 1.0).abs() < 1e-9, "{}", integral(&t));
        assert!(t.phase.iter().all(|p| p.is_finite() && *p >= 0.0));
    }
}

#[test]
fn with_the_suns_disc_and_tilted_plates_the_sundog_stays_within_half_a_degree() {
    let n = ice_refractive_index(550.0).unwrap().re;
    let t = table(20.0, 0.5, 0.004675);
    let got = sundog_azimuth_deg(&t, 20.0);
    let want = parhelion_azimuth_deg(n, 20.0);
    eprintln!("sun disc, tilt 0.5 deg: sundog at {got:.2} deg, closed form {want:.3} deg");
    assert!((got - want).abs() <= 0.5, "{got} against {want}");
    assert!((integral(&t) - 1.0).abs() < 1e-9);
    // The sundog is far brighter than the sky at its azimuth 10 degrees higher up.
    let columns = t.grid.azimuth_bins();
    let column = (got / t.grid.azimuth_bin_deg) as usize;
    let row = |h: f64| ((h + 90.0) / t.grid.elevation_bin_deg) as usize;
    let at = |h: f64| t.phase[row(h) * columns + column];
    assert!(at(20.25) > 20.0 * at(30.25), "{} {}", at(20.25), at(30.25));
}

#[test]
fn the_sun_overhead_gives_a_finite_normalised_table() {
    let t = table(90.0, 1.0, 0.004675);
    assert!((integral(&t) - 1.0).abs() < 1e-9, "{}", integral(&t));
    assert!(t.phase.iter().all(|p| p.is_finite() && *p >= 0.0));
    assert!(t.hits > 0);
}

#[test]
fn bad_input_is_named() {
    let m = ice_refractive_index(550.0).unwrap();
    let sky = |e: f64, tilt: f64, r: f64| PlateSky {
        tilt_spread_deg: tilt,
        sun_elevation_deg: e,
        sun_radius_rad: r,
    };
    let run = |s: PlateSky, g: SkyGrid, rays: usize| {
        plate_sky_table(&plates(), m, 550e-9, s, g, settings(rays))
            .unwrap_err()
            .to_string()
    };
    let ok = sky(20.0, 1.0, 0.0);
    assert!(run(sky(95.0, 1.0, 0.0), GRID, 1000).contains("sun elevation 95"));
    assert!(run(sky(f64::NAN, 1.0, 0.0), GRID, 1000).contains("sun elevation"));
    assert!(run(sky(20.0, 40.0, 0.0), GRID, 1000).contains("tilt spread 40"));
    assert!(run(sky(20.0, 1.0, 0.2), GRID, 1000).contains("sun radius 0.2"));
    assert!(run(ok, GRID, 10).contains("rays 10"));
    let odd = SkyGrid {
        elevation_bin_deg: 0.7,
        azimuth_bin_deg: 0.1,
    };
    assert!(run(ok, odd, 1000).contains("bin width 0.7"));
}
