//! The Lorenz-Mie droplet scenes on the CPU twin (`hydrometeors/render.rs` over the
//! nishita model's sky): a shaft of small drops shows its primary bow and first
//! supernumerary where its phase table has them; a deck of cloud droplets seen from above
//! shows the glory's first ring and the cloudbow where the table has them.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::hydrometeors::render::{LitVolume, composite};
use atmosphere_core::hydrometeors::scene::{
    DeckSettings, RainShaftSettings, VolumeOptics, lit_volume,
};
use atmosphere_core::hydrometeors::volumes::Volume;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::ViewRay;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;

const FRAME_NM: [f64; 3] = [680.0, 550.0, 440.0];
const SUN_RADIUS_RAD: f64 = 0.004675;
/// Wavelengths of the tables (few, to keep the test short: the angles do not depend on
/// the count).
const WAVELENGTHS: usize = 8;
/// Step of the column of pixels, degrees.
const STEP_DEG: f64 = 0.05;

/// A line of pixels from a camera `altitude_m` up at the point X (+X up) with the sun
/// `sun_elevation_deg` up in the -Y azimuth, at parameters `lo_deg` to `hi_deg` in steps
/// of [`STEP_DEG`], `direction` giving each one's view direction: (degrees from the
/// antisolar point, green radiance), and the lit volume.
fn line(
    altitude_m: f64,
    sun_elevation_deg: f64,
    volume: impl Fn(DVec3, f64) -> Volume,
    (lo_deg, hi_deg): (f64, f64),
    direction: impl Fn(f64) -> DVec3,
) -> (Vec<(f64, f64)>, LitVolume) {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let model = prepare(ModelId::Nishita, &atmosphere, &Default::default()).unwrap();
    let e = sun_elevation_deg.to_radians();
    let camera = DVec3::X * (atmosphere.bottom_radius_m + altitude_m);
    let sun = DVec3::new(e.sin(), -e.cos(), 0.0);
    let lit = lit_volume(
        model.as_ref(),
        volume(camera, atmosphere.bottom_radius_m),
        (camera, sun),
        VolumeOptics::new(WAVELENGTHS, SUN_RADIUS_RAD),
        FRAME_NM,
        &TableCache::off(),
    )
    .unwrap();
    let spectra = Spectra::new(&atmosphere, &FRAME_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let steps = ((hi_deg - lo_deg) / STEP_DEG).round() as usize;
    let values = (0..=steps)
        .map(|k| {
            let d = direction(lo_deg + STEP_DEG * k as f64);
            let ray = ViewRay {
                origin_m: camera,
                direction: d,
                sun_direction: sun,
                max_distance_m: None,
            };
            let full = model.radiance(&ray).unwrap().radiance;
            let l = composite(
                &atmosphere,
                &extinction,
                std::slice::from_ref(&lit),
                camera,
                d,
                f64::INFINITY,
                [full[0], full[1], full[2]],
            );
            (d.dot(-sun).clamp(-1.0, 1.0).acos().to_degrees(), l[1])
        })
        .collect();
    (values, lit)
}

/// Up the +Y azimuth at elevation `deg`.
fn vertical(deg: f64) -> DVec3 {
    let a = deg.to_radians();
    DVec3::X * a.sin() + DVec3::Y * a.cos()
}

/// The table's green by degrees from the antisolar point, at the column's steps.
fn table(lit: &LitVolume, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    let steps = ((hi - lo) / STEP_DEG).round() as usize;
    (0..=steps)
        .map(|k| {
            let a = lo + STEP_DEG * k as f64;
            (a, lit.phase.value_at(180.0 - a)[1])
        })
        .collect()
}

/// The angles of the local maxima (the largest over `half` steps either side) within
/// (lo, hi), nearest the antisolar point first.
fn maxima(values: &[(f64, f64)], lo: f64, hi: f64, half: usize) -> Vec<f64> {
    let mut found: Vec<f64> = (half..values.len().saturating_sub(half))
        .filter(|&i| {
            let a = values[i].0;
            a > lo && a < hi && (i - half..=i + half).all(|j| values[j].1 <= values[i].1)
        })
        .map(|i| values[i].0)
        .collect();
    found.sort_by(f64::total_cmp);
    found
}

#[test]
fn small_drops_put_the_bow_and_its_supernumerary_where_their_table_has_them() {
    let shaft = |camera: DVec3, ground: f64| {
        RainShaftSettings {
            height_m: 5_000.0,
            small_drop_radius_um: Some(150.0),
            ..RainShaftSettings::default()
        }
        .volume(camera, DVec3::Y, ground)
        .unwrap()
    };
    // Elevations 4 to 16 degrees: 34 to 46 from the antisolar point.
    let (values, lit) = line(2.0, 30.0, shaft, (4.0, 16.0), vertical);
    let rendered = maxima(&values, 36.0, 43.0, 10);
    let tabled = maxima(&table(&lit, 34.0, 46.0), 36.0, 43.0, 10);
    eprintln!("small drops: rendered maxima {rendered:.2?}, table {tabled:.2?}");
    // The primary (outermost) and the first supernumerary inside it.
    assert!(
        rendered.len() >= 2 && tabled.len() >= 2,
        "{rendered:?} {tabled:?}"
    );
    let n = rendered.len();
    for (r, t) in rendered[n - 2..].iter().zip(&tabled[tabled.len() - 2..]) {
        assert!((r - t).abs() <= 0.1, "rendered {r}, table {t}");
    }
    assert!(rendered[n - 1] - rendered[n - 2] > 1.0, "{rendered:?}");
}

#[test]
fn a_droplet_deck_seen_from_above_shows_the_glory_and_the_cloudbow_of_its_table() {
    let deck = |_: DVec3, ground: f64| DeckSettings::default().volume(ground).unwrap();
    // The antisolar point is 45 degrees down: elevations -45 to -40 are 0 to 5 degrees
    // from it.
    let (values, lit) = line(3_000.0, 45.0, deck, (-45.0, -40.0), vertical);
    let glory = |v: &[(f64, f64)]| maxima(v, 0.5, 4.5, 4)[0];
    let (g_r, g_t) = (glory(&values), glory(&table(&lit, 0.0, 5.0)));
    // The cloudbow is broad: along a vertical its brightest point would move with the
    // path through the deck, longer towards the horizon. Along the row at the antisolar
    // point's elevation every pixel has the same path: azimuths 30 to 80 degrees from
    // the antisolar one are 21 to 55 degrees from the antisolar point.
    let row = |deg: f64| {
        let (e, a) = ((-45f64).to_radians(), deg.to_radians());
        DVec3::X * e.sin() + (DVec3::Y * a.cos() + DVec3::Z * a.sin()) * e.cos()
    };
    let (row_values, _) = line(3_000.0, 45.0, deck, (30.0, 80.0), row);
    // The brightest from 30 to 45 degrees (the cloudbow's supernumeraries lie inside).
    let cloudbow = |v: &[(f64, f64)]| {
        v.iter()
            .filter(|(a, _)| *a > 30.0 && *a < 45.0)
            .fold(
                (0.0, f64::MIN),
                |best, &x| if x.1 > best.1 { x } else { best },
            )
            .0
    };
    let (c_r, c_t) = (cloudbow(&row_values), cloudbow(&table(&lit, 20.0, 55.0)));
    eprintln!(
        "deck: glory's first ring rendered at {g_r:.2}, table {g_t:.2}; \
         cloudbow rendered at {c_r:.2}, table {c_t:.2} deg from the antisolar point"
    );
    assert!((g_r - g_t).abs() <= 0.1, "glory ring {g_r}, table {g_t}");
    assert!((c_r - c_t).abs() <= 0.1, "cloudbow {c_r}, table {c_t}");
    assert!(c_t > 35.0 && c_t < 40.0, "cloudbow at {c_t}");
}
