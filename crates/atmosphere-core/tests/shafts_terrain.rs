//! The terrain's shadow in the air (`atmosphere_core::shafts`) against closed forms: a
//! straight ridge on the sphere with a low sun, whose shadow boundary is a line-ridge
//! intersection; flat ground, which shadows nothing with the sun up; and the reference's
//! shadowed single scattering against its unshadowed value from the shadow's top.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::models::sky_model::{ModelSettings, SkyModel, ViewRay};
use atmosphere_core::reference::Reference;
use atmosphere_core::shafts::{GnomonicGrid, HeightFieldShadow, Relief, ShadowMap, SunVisibility};
use glam::DVec3;

const RADIUS_M: f64 = 6_360_000.0;
/// The ridge's crest: its sunward top edge lies this far north of the site, m.
const CREST_M: f64 = 10_000.0;
const RIDGE_HEIGHT_M: f64 = 2_000.0;
const RIDGE_TOP_WIDTH_M: f64 = 2_000.0;
/// The sun's elevation over the site, degrees, due north.
const SUN_ELEVATION_DEG: f64 = 5.0;

/// A ridge along the parallels (the site is at latitude 0, longitude 0, x up, z north):
/// a trapezoid in latitude, flanks of slope 1, a flat top from `CREST_M` northwards.
struct Ridge;

impl Relief for Ridge {
    fn elevation_m(&self, d: DVec3) -> f64 {
        let north_m = d.z.asin() * RADIUS_M;
        let rise = RIDGE_HEIGHT_M - (CREST_M - north_m);
        let fall = RIDGE_HEIGHT_M - (north_m - CREST_M - RIDGE_TOP_WIDTH_M);
        rise.min(fall).clamp(0.0, RIDGE_HEIGHT_M)
    }
    fn elevation_bound_m(&self) -> f64 {
        RIDGE_HEIGHT_M
    }
}

struct Flat;

impl Relief for Flat {
    fn elevation_m(&self, _: DVec3) -> f64 {
        0.0
    }
    fn elevation_bound_m(&self) -> f64 {
        0.0
    }
}

fn sun(elevation_deg: f64) -> DVec3 {
    let e = elevation_deg.to_radians();
    DVec3::new(e.sin(), 0.0, e.cos())
}

/// The point `north_m` north of the site (along the meridian) at `altitude_m`.
fn point(north_m: f64, altitude_m: f64) -> DVec3 {
    let phi = north_m / RADIUS_M;
    (RADIUS_M + altitude_m) * DVec3::new(phi.cos(), 0.0, phi.sin())
}

/// Closed form: the ray from `p` to the sun, in the meridian plane, meets the crest's
/// radius line (the direction of the ridge's sunward top edge); the point is shadowed
/// when it passes below the ridge's top there.
fn shadowed_exactly(p: DVec3, s: DVec3) -> bool {
    let phi = CREST_M / RADIUS_M;
    let u = DVec3::new(phi.cos(), 0.0, phi.sin());
    let cross = |a: DVec3, b: DVec3| a.x * b.z - a.z * b.x;
    let t = -cross(u, p) / cross(u, s);
    (p + t * s).length() < RADIUS_M + RIDGE_HEIGHT_M
}

/// The altitude of the shadow's top, by bisection of `shadowed` (a function of the
/// altitude, true below the boundary).
fn boundary_m(shadowed: impl Fn(f64) -> bool) -> f64 {
    let (mut low, mut high) = (0.0, RIDGE_HEIGHT_M);
    for _ in 0..40 {
        let mid = 0.5 * (low + high);
        if shadowed(mid) {
            low = mid;
        } else {
            high = mid;
        }
    }
    0.5 * (low + high)
}

fn ridge_map(cell_m: f64, size: usize) -> ShadowMap {
    let grid = GnomonicGrid::new(DVec3::X, RADIUS_M, cell_m, size).unwrap();
    ShadowMap::new(
        grid,
        &grid.sample(|d| Ridge.elevation_m(d)),
        sun(SUN_ELEVATION_DEG),
    )
    .unwrap()
}

#[test]
fn the_march_finds_the_ridge_shadow_boundary_of_the_closed_form() {
    let s = sun(SUN_ELEVATION_DEG);
    let march = HeightFieldShadow::new(Ridge, RADIUS_M);
    for north_m in [0.0, 4_000.0, 7_500.0] {
        let exact = boundary_m(|a| shadowed_exactly(point(north_m, a), s));
        // The flank's foot is at 8 km: every point here is south of the ridge.
        assert!(exact > 0.0 && exact < RIDGE_HEIGHT_M, "{north_m}: {exact}");
        // Within the march's shortest step times the ray's slope, and a margin.
        for (altitude, lit) in [(exact - 10.0, 0.0), (exact + 10.0, 1.0)] {
            let v = march.sun_visible(point(north_m, altitude), s);
            assert_eq!(
                v, lit,
                "{north_m} m north at {altitude} m (boundary {exact} m)"
            );
        }
    }
    // High above the crest, and just above the ridge's flat top.
    assert_eq!(march.sun_visible(point(0.0, 3_000.0), s), 1.0);
    assert_eq!(march.sun_visible(point(CREST_M + 1_000.0, 2_010.0), s), 1.0);
}

/// A cascade over the site: levels of 64 cells from 50 m (3.2 km wide, far south of the
/// ridge) out to 400 m (25.6 km wide, holding the ridge). The ridge's shadow reaches the
/// finest level only through its sweep's start from the outer levels: alone it would
/// leave the site lit; nested, its boundary is the closed form's within the outermost
/// cell. A level that does not nest is refused by name.
#[test]
fn a_nested_map_takes_the_shadow_of_a_ridge_beyond_its_edge() {
    let s = sun(SUN_ELEVATION_DEG);
    let level = |cell_m: f64| {
        let grid = GnomonicGrid::new(DVec3::X, RADIUS_M, cell_m, 64).unwrap();
        (grid, grid.sample(|d| Ridge.elevation_m(d)))
    };
    let (grid, heights) = level(400.0);
    let mut map = ShadowMap::new(grid, &heights, s).unwrap();
    for cell_m in [200.0, 100.0, 50.0] {
        let (grid, heights) = level(cell_m);
        map = ShadowMap::nested(grid, &heights, s, map).unwrap();
    }
    assert_eq!(map.levels().count(), 4);
    assert_eq!(map.width_m(), 400.0 * 64.0);
    let (grid, heights) = level(50.0);
    let alone = ShadowMap::new(grid, &heights, s).unwrap();
    let tolerance_m = 400.0 * (1.0 + SUN_ELEVATION_DEG.to_radians().tan()) + 1.0;
    for north_m in [-1_000.0, 0.0, 1_000.0] {
        let exact = boundary_m(|a| shadowed_exactly(point(north_m, a), s));
        let mapped = boundary_m(|a| map.sun_visible(point(north_m, a), s) < 1.0);
        assert!(
            (mapped - exact).abs() < tolerance_m,
            "{north_m} m north: cascade {mapped} m, exact {exact} m"
        );
        assert_eq!(alone.sun_visible(point(north_m, exact - 50.0), s), 1.0);
        assert_eq!(map.sun_visible(point(north_m, exact - tolerance_m), s), 0.0);
    }
    let (grid, heights) = level(100.0);
    let outer = ShadowMap::new(level(400.0).0, &level(400.0).1, s).unwrap();
    let error = ShadowMap::nested(grid, &heights, s, outer).unwrap_err();
    assert!(error.to_string().contains("cannot nest"), "{error}");
}

#[test]
fn the_shadow_map_finds_the_same_boundary_within_a_cell() {
    let s = sun(SUN_ELEVATION_DEG);
    let cell_m = 100.0;
    let map = ridge_map(cell_m, 256);
    // The map's boundary: the top S, sampled at cell centres and interpolated; the
    // crest falls between samples, lowering S by at most a cell of the flank's slope.
    let tolerance_m = cell_m * (1.0 + SUN_ELEVATION_DEG.to_radians().tan()) + 1.0;
    let mut worst = 0.0f64;
    for k in 0..=15 {
        let north_m = -7_000.0 + 1_000.0 * f64::from(k);
        let exact = boundary_m(|a| shadowed_exactly(point(north_m, a), s));
        let mapped = boundary_m(|a| map.sun_visible(point(north_m, a), s) < 1.0);
        worst = worst.max((mapped - exact).abs());
        assert!(
            (mapped - exact).abs() < tolerance_m,
            "{north_m} m north: map {mapped} m, exact {exact} m"
        );
        // Below the boundary by more than the penumbra band: dark.
        let below = mapped - f64::from(map.band_m) - 1.0;
        assert_eq!(map.sun_visible(point(north_m, below), s), 0.0);
    }
    println!("largest boundary error of the 100 m map: {worst:.1} m");
    // Outside the grid (the map knows nothing there): lit.
    assert_eq!(map.sun_visible(point(-20_000.0, 10.0), s), 1.0);
}

#[test]
fn flat_ground_shadows_nothing_with_the_sun_up() {
    let march = HeightFieldShadow::new(Flat, RADIUS_M);
    let grid = GnomonicGrid::new(DVec3::X, RADIUS_M, 200.0, 64).unwrap();
    for elevation_deg in [0.5, 5.0, 30.0, 89.0] {
        let s = sun(elevation_deg);
        let map = ShadowMap::new(grid, &grid.sample(|_| 0.0), s).unwrap();
        for north_m in [-6_000.0, 0.0, 3_000.0] {
            for altitude in [0.0, 1.0, 100.0, 5_000.0] {
                let p = point(north_m, altitude);
                assert_eq!(march.sun_visible(p, s), 1.0, "{elevation_deg} {altitude}");
                assert_eq!(map.sun_visible(p, s), 1.0, "{elevation_deg} {altitude}");
            }
        }
    }
}

/// Single scattering only, at one wavelength.
fn single_reference(a: &Atmosphere) -> Reference {
    let settings = ModelSettings {
        wavelengths_nm: vec![550.0],
        max_orders: Some(1),
        ..ModelSettings::default()
    };
    Reference::prepare(a, &settings).unwrap()
}

/// A vertical ray from inside the shadow gets only the light of its lit part: its
/// radiance is the transmittance up to the shadow's top times the unshadowed radiance
/// of the same ray from there. The quadrature's panels do not end at the boundary: the
/// stated tolerance covers the cut panel.
#[test]
fn the_reference_sees_only_the_lit_part_of_a_ray_through_the_shadow() {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = single_reference(&a);
    let s = sun(SUN_ELEVATION_DEG);
    let march = HeightFieldShadow::new(Ridge, a.bottom_radius_m);
    let north_m = 4_000.0;
    let top = boundary_m(|h| shadowed_exactly(point(north_m, h), s));
    let ray = |altitude: f64, max: Option<f64>| ViewRay {
        origin_m: point(north_m, altitude),
        direction: point(north_m, 0.0).normalize(),
        sun_direction: s,
        max_distance_m: max,
    };
    let camera_m = 300.0;
    let shadowed = reference
        .radiance_shadowed(&ray(camera_m, None), Some(&march))
        .unwrap();
    let unshadowed = reference.radiance(&ray(camera_m, None)).unwrap();
    let from_top = reference.radiance(&ray(top, None)).unwrap();
    let below = reference
        .radiance(&ray(camera_m, Some(top - camera_m)))
        .unwrap();
    let expected = below.transmittance[0] * from_top.radiance[0];
    let error = (shadowed.radiance[0] - expected).abs() / expected;
    println!(
        "shadowed {:e}, expected {expected:e}, unshadowed {:e}: error {error:e}",
        shadowed.radiance[0], unshadowed.radiance[0]
    );
    assert!(error < 5e-3, "relative error {error:e}");
    assert!(shadowed.radiance[0] < 0.95 * unshadowed.radiance[0]);
}

/// A sun hidden from every point leaves no single scattering in the air: a ray to space
/// is black, whatever the atmosphere.
#[test]
fn a_sun_hidden_everywhere_leaves_the_air_dark() {
    struct Hidden;
    impl SunVisibility for Hidden {
        fn sun_visible(&self, _: DVec3, _: DVec3) -> f64 {
            0.0
        }
    }
    let a = Atmosphere::preset("earth").unwrap();
    let reference = single_reference(&a);
    let ray = ViewRay {
        origin_m: point(0.0, 1_000.0),
        direction: DVec3::new(0.5, 0.0, -0.5f64.sqrt() * 1.0).normalize(),
        sun_direction: sun(20.0),
        max_distance_m: None,
    };
    let lit = reference.radiance(&ray).unwrap().radiance[0];
    let dark = reference
        .radiance_shadowed(&ray, Some(&Hidden))
        .unwrap()
        .radiance[0];
    assert!(lit > 0.0);
    assert_eq!(dark, 0.0);
}

#[test]
fn bad_grids_and_maps_are_refused_by_name() {
    let message = |e: atmosphere_core::models::error::ModelError| e.to_string();
    let grid = |centre, cell_m, size| GnomonicGrid::new(centre, RADIUS_M, cell_m, size);
    assert!(message(grid(DVec3::ZERO, 100.0, 64).unwrap_err()).contains("centre"));
    assert!(message(grid(DVec3::X, 0.0, 64).unwrap_err()).contains("cell_m 0"));
    assert!(message(grid(DVec3::X, f64::NAN, 64).unwrap_err()).contains("cell_m NaN"));
    assert!(message(grid(DVec3::X, 100.0, 1).unwrap_err()).contains("size 1 outside 2..=8192"));
    let g = grid(DVec3::X, 100.0, 4).unwrap();
    let e = ShadowMap::new(g, &[0.0; 15], DVec3::Z).unwrap_err();
    assert!(message(e).contains("15 heights for 4 x 4 cells"));
    let mut heights = [0.0f32; 16];
    heights[3] = f32::INFINITY;
    let e = ShadowMap::new(g, &heights, DVec3::Z).unwrap_err();
    assert!(message(e).contains("height 3 is inf"));
    let e = ShadowMap::new(g, &[0.0; 16], DVec3::ZERO).unwrap_err();
    assert!(message(e).contains("sun"));
}

/// What the reference takes out of `ray`'s single scattering at 550 nm with the exact
/// march through the ridge.
fn reference_taken_out(ray: &ViewRay) -> f64 {
    let a = Atmosphere::preset("earth").unwrap();
    let reference = single_reference(&a);
    let march = HeightFieldShadow::new(Ridge, a.bottom_radius_m);
    reference.radiance(ray).unwrap().radiance[0]
        - reference
            .radiance_shadowed(ray, Some(&march))
            .unwrap()
            .radiance[0]
}

/// The ridge's 500 m map over 256 km centred 100 km east of the site, for `sun`.
fn wide_ridge_map(sun: DVec3) -> ShadowMap {
    let east = 100_000.0 / RADIUS_M;
    let centre = DVec3::new(east.cos(), east.sin(), 0.0);
    let grid = GnomonicGrid::new(centre, RADIUS_M, 500.0, 512).unwrap();
    ShadowMap::new(grid, &grid.sample(|d| Ridge.elevation_m(d)), sun).unwrap()
}

/// Single scattering only, at 550 nm.
fn single_settings() -> ModelSettings {
    ModelSettings {
        wavelengths_nm: vec![550.0],
        max_orders: Some(1),
        ..ModelSettings::default()
    }
}

/// What hillaire's shafts on [`wide_ridge_map`] take out of `ray`'s single scattering
/// at 550 nm, what the reference takes out with the exact march, and the unshadowed
/// single scattering.
fn single_taken_out(ray: &ViewRay) -> (f64, f64, f64) {
    use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
    let a = Atmosphere::preset("earth").unwrap();
    let settings = single_settings();
    let mut hillaire = Hillaire::prepare(&a, &settings, HillaireSettings::default()).unwrap();
    let lit = hillaire.radiance(ray).unwrap().radiance[0];
    hillaire.set_terrain_shadow(Some(wide_ridge_map(ray.sun_direction)));
    let taken = lit - hillaire.radiance(ray).unwrap().radiance[0];
    (taken, reference_taken_out(ray), lit)
}

/// Hillaire's shafts on the ridge's 500 m map take out of a ray's single scattering what
/// the reference takes out with the exact march: a ray 300 m up, 4 km south of the ridge,
/// looking east along it, in shadow for its first 100 km or so (until the sphere's
/// curvature lifts it out). The difference is the map's cells and the march's 8 km
/// samples at the shadow's far end.
#[test]
fn hillaire_shafts_take_out_what_the_reference_does() {
    let ray = ViewRay {
        origin_m: point(4_000.0, 300.0),
        direction: DVec3::Y,
        sun_direction: sun(SUN_ELEVATION_DEG),
        max_distance_m: None,
    };
    let (taken, exact, lit) = single_taken_out(&ray);
    let error = (taken - exact).abs() / exact;
    println!("taken out: hillaire {taken:e}, reference {exact:e} (of {lit:e}): {error:.3}");
    assert!(
        exact > 0.05 * lit,
        "the shadow takes out {exact:e} of {lit:e}"
    );
    assert!(error < 0.03, "relative error {error}");
}

/// From above the shadow volume's top the march starts where the ray enters it, after
/// the transmittance from the camera there: a ray from 6 km up, 4 km south of the ridge,
/// going down 3 degrees eastwards along it, enters the top's sphere (2 km) about 75 km
/// away and the shadow itself some 10 km further; what hillaire takes out is the
/// reference's within 5 % (the map's and the samples' error on a ray that crosses the
/// shadow's top at 3 degrees: a march from the segment's start has the same, docs/shafts.md).
#[test]
fn hillaire_shafts_from_above_the_shadow_start_where_the_ray_enters_it() {
    let down = 3.0_f64.to_radians();
    let ray = ViewRay {
        origin_m: point(4_000.0, 6_000.0),
        direction: DVec3::new(-down.sin(), down.cos(), 0.0),
        sun_direction: sun(SUN_ELEVATION_DEG),
        max_distance_m: None,
    };
    let (taken, exact, lit) = single_taken_out(&ray);
    let error = (taken - exact).abs() / exact;
    println!("from above: hillaire {taken:e}, reference {exact:e} (of {lit:e}): {error:.3}");
    assert!(
        exact > 0.1 * lit,
        "the shadow takes out {exact:e} of {lit:e}"
    );
    assert!(error < 0.05, "relative error {error}");
}

/// Bruneton's shadow-length approximation (Eq. 17-18) on [`wide_ridge_map`] takes out of
/// the two rays above (along the ridge from 300 m, shadowed at its start, to space: Eq.
/// 18; from 6 km down to the ground, shadowed near its end: Eq. 17) the single
/// scattering the reference takes out with the exact march, within 5 %.
#[test]
fn bruneton_shadow_lengths_take_out_what_the_reference_does() {
    use atmosphere_core::models::bruneton::Bruneton;
    let a = Atmosphere::preset("earth").unwrap();
    let mut bruneton = Bruneton::prepare(&a, &single_settings()).unwrap();
    takes_out_what_the_reference_does("bruneton", 0.05, |ray, map| {
        bruneton.set_terrain_shadow(map);
        bruneton.radiance(ray).unwrap().radiance[0]
    });
}

/// The ridge's two rays (along it from 300 m, shadowed at its start, to space; from 6 km
/// down to the ground, shadowed near its end): `answer` (a model's radiance of a ray
/// without and with [`wide_ridge_map`]) takes out what the reference takes out with the
/// exact march, within `tolerance`, where the shadow takes out over a tenth.
fn takes_out_what_the_reference_does(
    name: &str,
    tolerance: f64,
    mut answer: impl FnMut(&ViewRay, Option<ShadowMap>) -> f64,
) {
    let s = sun(SUN_ELEVATION_DEG);
    let down = 3.0_f64.to_radians();
    let rays = [
        (point(4_000.0, 300.0), DVec3::Y),
        (
            point(4_000.0, 6_000.0),
            DVec3::new(-down.sin(), down.cos(), 0.0),
        ),
    ];
    for (origin_m, direction) in rays {
        let ray = ViewRay {
            origin_m,
            direction,
            sun_direction: s,
            max_distance_m: None,
        };
        let lit = answer(&ray, None);
        let taken = lit - answer(&ray, Some(wide_ridge_map(s)));
        let exact = reference_taken_out(&ray);
        let error = (taken - exact).abs() / exact;
        println!("{name}: taken out {taken:e}, reference {exact:e} (of {lit:e}): {error:.2e}");
        assert!(
            exact > 0.1 * lit,
            "the shadow takes out {exact:e} of {lit:e}"
        );
        assert!(error < tolerance, "{name}: relative error {error}");
    }
}

/// Dobashi's sampling planes (Dobashi, Yamamoto and Nishita 2002, section 4.2.2's H at
/// each plane, Fig. 10(a)) on [`wide_ridge_map`] take out of the two rays above the
/// single scattering the reference takes out with the exact march, within 8 %: each
/// 8.8 km segment is lit or shadowed as its plane is, so the shadow's ends fall on the
/// planes, and the model's own single scattering errs by a few per cent
/// (docs/models/dobashi.md).
#[test]
fn dobashi_planes_take_out_what_the_reference_does() {
    use atmosphere_core::models::dobashi::{Dobashi, DobashiSettings};
    let a = Atmosphere::preset("earth").unwrap();
    let settings = DobashiSettings::default();
    let mut dobashi = Dobashi::prepare(&a, &single_settings(), settings).unwrap();
    takes_out_what_the_reference_does("dobashi", 0.08, |ray, map| {
        dobashi.set_terrain_shadow(map);
        dobashi.radiance(ray).unwrap().radiance[0]
    });
}

/// A model with light shafts: its radiance of a ray with the terrain's shadow map, or
/// without shadow.
type Shadowed = Box<dyn FnMut(&ViewRay, Option<ShadowMap>) -> f64>;

/// `model`'s radiance at 550 nm with the shadow map it is given.
macro_rules! shadowed {
    ($model:ident) => {
        Box::new(move |ray: &ViewRay, map| {
            $model.set_terrain_shadow(map);
            $model.radiance(ray).unwrap().radiance[0]
        }) as Shadowed
    };
}

/// Every model with light shafts, at single scattering and 550 nm.
fn models_with_shafts() -> Vec<(&'static str, Shadowed)> {
    use atmosphere_core::models::bruneton::Bruneton;
    use atmosphere_core::models::dobashi::{Dobashi, DobashiSettings};
    use atmosphere_core::models::hillaire::{Hillaire, HillaireSettings};
    use atmosphere_core::models::nishita::{Nishita, NishitaSettings};
    use atmosphere_core::models::oneil::{Oneil, OneilSettings};
    let a = Atmosphere::preset("earth").unwrap();
    let s = single_settings();
    let mut hillaire = Hillaire::prepare(&a, &s, HillaireSettings::default()).unwrap();
    let mut nishita = Nishita::prepare(&a, &s, NishitaSettings::default()).unwrap();
    let mut oneil = Oneil::prepare(&a, &s, OneilSettings::default()).unwrap();
    let mut bruneton = Bruneton::prepare(&a, &s).unwrap();
    let mut dobashi = Dobashi::prepare(&a, &s, DobashiSettings::default()).unwrap();
    vec![
        ("hillaire", shadowed!(hillaire)),
        ("nishita", shadowed!(nishita)),
        ("oneil", shadowed!(oneil)),
        ("bruneton", shadowed!(bruneton)),
        ("dobashi", shadowed!(dobashi)),
    ]
}

/// Stability of the shafts at their degenerate suns: the sun exactly on the ridge's
/// line seen from the site's ground (the ground there on the shadow's boundary), the sun
/// along the ridge, and a sun grazing at 0.1 degree. Every model with shafts and the
/// reference's exact march answer rays from the ground (towards the ridge, along it,
/// towards the sun) and from 6 km down with finite, non-negative radiance no brighter
/// than without the shadow; the grazing sun's shadow takes light out of the ray along
/// the ridge, which runs in it.
#[test]
fn shafts_stay_finite_with_the_sun_on_the_ridge_line_and_grazing() {
    let crest_top = point(CREST_M, RIDGE_HEIGHT_M);
    let site = point(0.0, 2.0);
    let on_ridge_line = (crest_top - point(0.0, 0.0)).normalize();
    let along = 5.0_f64.to_radians();
    let along_ridge = DVec3::new(along.sin(), along.cos(), 0.0);
    let grazing = sun(0.1);
    let a = Atmosphere::preset("earth").unwrap();
    let reference = single_reference(&a);
    let march = HeightFieldShadow::new(Ridge, a.bottom_radius_m);
    let mut models = models_with_shafts();
    let down = 3.0_f64.to_radians();
    for (sun_name, s) in [
        ("on the ridge line", on_ridge_line),
        ("along the ridge", along_ridge),
        ("grazing at 0.1 deg", grazing),
    ] {
        let map = wide_ridge_map(s);
        let rays = [
            (site, (crest_top - site).normalize()),
            (site, DVec3::Y),
            (site, s),
            (
                point(4_000.0, 6_000.0),
                DVec3::new(-down.sin(), down.cos(), 0.0),
            ),
        ];
        for (origin_m, direction) in rays {
            let ray = ViewRay {
                origin_m,
                direction,
                sun_direction: s,
                max_distance_m: None,
            };
            let lit = reference.radiance(&ray).unwrap().radiance[0];
            let exact = reference
                .radiance_shadowed(&ray, Some(&march))
                .unwrap()
                .radiance[0];
            let mut answers = vec![("reference", lit, exact)];
            for (name, answer) in models.iter_mut() {
                answers.push((name, answer(&ray, None), answer(&ray, Some(map.clone()))));
            }
            for (name, lit, shadowed) in answers {
                assert!(
                    lit.is_finite() && shadowed.is_finite() && shadowed >= 0.0,
                    "{name}, sun {sun_name}, ray {direction}: {shadowed:e} (lit {lit:e})"
                );
                assert!(
                    shadowed <= lit * (1.0 + 1e-6),
                    "{name}, sun {sun_name}, ray {direction}: shadowed {shadowed:e} above lit {lit:e}"
                );
            }
        }
    }
    let ray = ViewRay {
        origin_m: point(4_000.0, 300.0),
        direction: DVec3::Y,
        sun_direction: grazing,
        max_distance_m: None,
    };
    let taken = reference.radiance(&ray).unwrap().radiance[0]
        - reference
            .radiance_shadowed(&ray, Some(&march))
            .unwrap()
            .radiance[0];
    assert!(taken > 0.0, "the grazing sun's shadow took out {taken:e}");
}
