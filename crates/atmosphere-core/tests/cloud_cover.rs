//! The generated global cloud cover: deterministic, with the climatology's zonal means,
//! its bands where the satellites see them, and weather's structure (clear and cloudy
//! areas hundreds of kilometres across, not a uniform haze of partial cover).

use atmosphere_core::clouds::cover::climatology::zonal_mean_cover;
use atmosphere_core::clouds::cover::generated::{CoverParameters, GeneratedCover};
use atmosphere_core::clouds::cover::grid::CoverGrid;
use atmosphere_core::geo::equirectangular::direction;
use std::f64::consts::PI;

const W: usize = 256;
const H: usize = 128;

fn grid(seed: u32, day_of_year: f64) -> CoverGrid {
    let cover = GeneratedCover::new(CoverParameters { seed, day_of_year }).unwrap();
    CoverGrid::rasterize(W, H, |p| cover.cover(p)).unwrap()
}

fn row_latitude_deg(j: usize) -> f64 {
    90.0 - (j as f64 + 0.5) * 180.0 / H as f64
}

/// Area-weighted mean cover and climatology between two latitudes.
fn band_means(g: &CoverGrid, day: f64, south: f64, north: f64) -> (f64, f64) {
    let (mut cover, mut target, mut weight) = (0.0, 0.0, 0.0);
    for j in 0..H {
        let lat = row_latitude_deg(j);
        if lat < south || lat >= north {
            continue;
        }
        let w = lat.to_radians().cos();
        let row = &g.values()[j * W..(j + 1) * W];
        cover += w * row.iter().map(|&v| f64::from(v)).sum::<f64>() / W as f64;
        target += w * zonal_mean_cover(lat, day);
        weight += w;
    }
    (cover / weight, target / weight)
}

fn correlation(pairs: &[(f64, f64)]) -> f64 {
    let n = pairs.len() as f64;
    let (ma, mb) = pairs
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0 / n, s.1 + p.1 / n));
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for &(a, b) in pairs {
        ab += (a - ma) * (b - mb);
        aa += (a - ma).powi(2);
        bb += (b - mb).powi(2);
    }
    ab / (aa * bb).sqrt()
}

#[test]
fn the_same_seed_gives_the_same_cover_and_another_seed_another() {
    let a = grid(7, 172.0);
    assert_eq!(a, grid(7, 172.0));
    let b = grid(8, 172.0);
    let differing = a
        .values()
        .iter()
        .zip(b.values())
        .filter(|(x, y)| (*x - *y).abs() > 0.5)
        .count();
    assert!(differing > W * H / 5, "{differing}");
}

#[test]
fn zonal_means_follow_the_climatology_and_its_bands() {
    let day = 172.0;
    let g = grid(3, day);
    for south in (-80..80).step_by(10) {
        let (cover, target) = band_means(&g, day, south as f64, south as f64 + 10.0);
        assert!(
            (cover - target).abs() < 0.06,
            "{south}..{}: cover {cover:.3}, climatology {target:.3}",
            south + 10
        );
    }
    let (itcz, _) = band_means(&g, day, 2.0, 12.0);
    let (north_subtropics, _) = band_means(&g, day, 22.0, 32.0);
    let (south_subtropics, _) = band_means(&g, day, -28.0, -18.0);
    let (southern_ocean, _) = band_means(&g, day, -65.0, -55.0);
    assert!(itcz > north_subtropics + 0.1 && itcz > south_subtropics + 0.1);
    assert!(southern_ocean > north_subtropics + 0.2);
}

#[test]
fn the_convergence_zone_moves_with_the_season() {
    let (august, _) = band_means(&grid(3, 228.0), 228.0, 8.0, 14.0);
    let (february, _) = band_means(&grid(3, 45.0), 45.0, 8.0, 14.0);
    assert!(august > february + 0.05, "{august} {february}");
}

#[test]
fn cover_comes_in_clear_and_cloudy_areas_hundreds_of_kilometres_across() {
    let g = grid(5, 172.0);
    let v = g.values();
    let decided = v.iter().filter(|&&c| !(0.1..=0.9).contains(&c)).count();
    assert!(decided * 2 > v.len(), "{decided} of {}", v.len());
    // Neighbouring texels (about 150 km apart at the equator) are alike; texels a
    // quarter of the way round the planet are not.
    let (mut near, mut far) = (Vec::new(), Vec::new());
    for j in H / 6..5 * H / 6 {
        for i in 0..W {
            let at = |di: usize| f64::from(v[j * W + (i + di) % W]);
            near.push((at(0), at(1)));
            far.push((at(0), at(W / 4)));
        }
    }
    let (r_near, r_far) = (correlation(&near), correlation(&far));
    assert!(r_near > 0.6, "{r_near}");
    assert!(r_far.abs() < 0.15, "{r_far}");
    // Every latitude circle between the polar caps has clear and cloudy stretches.
    for j in H / 6..5 * H / 6 {
        let row = &v[j * W..(j + 1) * W];
        let mean = row.iter().map(|&c| f64::from(c)).sum::<f64>() / W as f64;
        let var = row
            .iter()
            .map(|&c| (f64::from(c) - mean).powi(2))
            .sum::<f64>()
            / W as f64;
        assert!(var.sqrt() > 0.25, "row {j}: spread {}", var.sqrt());
    }
}

#[test]
fn the_cover_has_no_seam_at_the_date_line_and_stays_in_range() {
    let cover = GeneratedCover::new(CoverParameters::default()).unwrap();
    for k in 0..50 {
        let lat = -1.4 + 2.8 * k as f64 / 49.0;
        let east = cover.cover(direction(lat, PI - 1e-7));
        let west = cover.cover(direction(lat, -PI + 1e-7));
        assert!((east - west).abs() < 1e-3, "{lat}: {east} {west}");
        assert!((0.0..=1.0).contains(&east));
    }
}

#[test]
fn a_day_outside_the_year_is_refused_by_name() {
    let e = GeneratedCover::new(CoverParameters {
        seed: 1,
        day_of_year: 400.0,
    })
    .unwrap_err();
    assert!(e.to_string().contains("cover day_of_year = 400"), "{e}");
}
