//! The Lorenz-Mie tables' colours as the wavelengths double, by the relative L1 change
//! of the channel tables P_c per channel over 100 to 180 degrees (the bows, the
//! cloudbow and the glory): the droplet deck's (glory, cloudbow) changes from 32 to 64
//! wavelengths by less than 1 % in every channel and its largest change falls from
//! 16 -> 32 to 32 -> 64; the small drops' (supernumerary bows) green and blue alike,
//! their red not yet (bounded); and the image of the shipped small-drops shaft (the
//! composite over the sky, the probes of the higher orders and the sky's light with it)
//! on a column of rays across its bows changes in colour (CIE XYZ) by less than 1 % RMS
//! from 32 to 64 wavelengths. Slow: each table is built at 112 wavelengths in all,
//! minutes of Lorenz-Mie series on two cores, so the suite leaves them out; run them with
//! `cargo test -p atmosphere-core --test hydrometeor_spectral_convergence -- --ignored`.

use atmosphere_core::atmosphere::Atmosphere;
use atmosphere_core::atmosphere::spectra::Spectra;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::hydrometeors::channel_phase::ChannelPhase;
use atmosphere_core::hydrometeors::mie_droplets::Droplets;
use atmosphere_core::hydrometeors::render::composite;
use atmosphere_core::hydrometeors::scene::{
    DECK_RADII, DECK_SIGMA, RainShaftSettings, SMALL_DROP_RADII, SMALL_DROP_SIGMA, VolumeOptics,
    lit_volume,
};
use atmosphere_core::hydrometeors::spectral_phase::{Particles, SpectralPhase};
use atmosphere_core::hydrometeors::sun_orders::MultipleScattering;
use atmosphere_core::models::id::ModelId;
use atmosphere_core::models::registry::prepare;
use atmosphere_core::models::sky_model::ViewRay;
use atmosphere_core::table_cache::TableCache;
use glam::DVec3;

const SUN_RADIUS_RAD: f64 = 0.004675;
const FRAME_NM: [f64; 3] = [680.0, 550.0, 440.0];
/// Bins of 0.05 degrees from 100 to 180 degrees.
const BOW_SIDE: std::ops::Range<usize> = 2000..3600;

/// Per channel, the relative L1 difference of two tables over [`BOW_SIDE`] and the
/// largest pointwise difference relative to max(P_c, 1 / (4 pi)).
fn change(a: &ChannelPhase, b: &ChannelPhase) -> ([f64; 3], [f64; 3]) {
    let floor = 0.25 / std::f64::consts::PI;
    let l1 = std::array::from_fn(|c| {
        let diff: f64 = BOW_SIDE
            .map(|i| (a.values[i][c] - b.values[i][c]).abs())
            .sum();
        diff / BOW_SIDE.map(|i| b.values[i][c].abs()).sum::<f64>()
    });
    let pointwise = std::array::from_fn(|c| {
        BOW_SIDE
            .map(|i| (a.values[i][c] - b.values[i][c]).abs() / b.values[i][c].max(floor))
            .fold(0.0, f64::max)
    });
    (l1, pointwise)
}

/// Builds `drops` at 16, 32 and 64 wavelengths (kept in `cache`); returns the relative
/// L1 changes per channel from 16 to 32 and from 32 to 64.
fn changes(name: &str, drops: Droplets, cache: &TableCache) -> ([f64; 3], [f64; 3]) {
    let table = |n| {
        let spectral =
            SpectralPhase::build_cached(&Particles::Droplets(drops), n, SUN_RADIUS_RAD, cache)
                .unwrap();
        ChannelPhase::new(&spectral, FRAME_NM).unwrap()
    };
    let (n16, n32, n64) = (table(16), table(32), table(64));
    let (coarse, coarse_point) = change(&n16, &n32);
    let (fine, fine_point) = change(&n32, &n64);
    eprintln!(
        "{name}: relative L1 change (red, green, blue) 16 to 32 {:.2?} %, 32 to 64 {:.2?} %; \
         pointwise {:.2?} %, {:.2?} %",
        coarse.map(|v| 100.0 * v),
        fine.map(|v| 100.0 * v),
        coarse_point.map(|v| 100.0 * v),
        fine_point.map(|v| 100.0 * v),
    );
    (coarse, fine)
}

/// The largest of three values.
fn largest(v: [f64; 3]) -> f64 {
    v.into_iter().fold(0.0, f64::max)
}

#[test]
#[ignore = "a measurement: about 11 CPU minutes of Lorenz-Mie; run with --ignored"]
fn doubling_the_wavelengths_settles_the_small_drops_green_and_blue_below_one_percent() {
    let dir = tempfile::tempdir().unwrap();
    let cache = TableCache::at(dir.path());
    let (coarse, fine) = changes(
        "small drops, 150 um",
        Droplets {
            effective_radius_m: 150e-6,
            sigma: SMALL_DROP_SIGMA,
            radii: SMALL_DROP_RADII,
        },
        &cache,
    );
    // Green and blue settle below 1 % and fall as the wavelengths double.
    for c in 1..3 {
        assert!(fine[c] < 0.01, "channel {c}: 32 to 64 {}", fine[c]);
        assert!(fine[c] < coarse[c], "channel {c}: {coarse:?}, {fine:?}");
    }
    // Red has not settled (2.4 % measured, its 16 to 32 change alike: the remainder
    // docs/optics-rendering.md names under "Not yet"); this bound keeps it from growing.
    assert!(fine[0] < 0.025, "red: 32 to 64 {}", fine[0]);
    // The image's colour (CIE XYZ of the frame's three channels) settles below 1 %;
    // its red channel alone, which the colour's inverse map amplifies, changes more.
    for orders in [MultipleScattering::Probes, MultipleScattering::None] {
        let (xyz, channels) = image_change(&cache, orders);
        assert!(
            largest(xyz) < 0.01,
            "{orders:?}: the image's RMS change {xyz:?}"
        );
        assert!(channels[0] < 0.025, "{orders:?}: red {channels:?}");
    }
}

/// The RMS relative change, from 32 to 64 wavelengths, of the composite over nishita's
/// sky of the shipped small-drops shaft (150 um, 3 km ahead, the sun 30 degrees up
/// behind the camera) on a column of rays from the horizon to 60 degrees up towards the
/// antisolar point, every 0.1 degree, the higher orders as `orders` says: of its colour
/// X, Y, Z, and of its three channels.
fn image_change(cache: &TableCache, orders: MultipleScattering) -> ([f64; 3], [f64; 3]) {
    let atmosphere = Atmosphere::preset("earth").unwrap();
    let model = prepare(ModelId::Nishita, &atmosphere, &Default::default()).unwrap();
    let camera = DVec3::X * (atmosphere.bottom_radius_m + 2.0);
    let e = 30f64.to_radians();
    let sun = DVec3::new(e.sin(), -e.cos(), 0.0);
    let settings = RainShaftSettings {
        small_drop_radius_um: Some(150.0),
        ..RainShaftSettings::default()
    };
    let shaft = settings
        .volume(camera, DVec3::Y, atmosphere.bottom_radius_m)
        .unwrap();
    let spectra = Spectra::new(&atmosphere, &FRAME_NM);
    let extinction: [[f64; 3]; 3] = std::array::from_fn(|c| spectra.extinction[c]);
    let image = |wavelengths| {
        let optics = VolumeOptics {
            multiple_scattering: orders,
            ..VolumeOptics::new(wavelengths, SUN_RADIUS_RAD)
        };
        let lit = [lit_volume(
            model.as_ref(),
            shaft,
            (camera, sun),
            optics,
            FRAME_NM,
            cache,
        )
        .unwrap()];
        (0..=600)
            .map(|k| {
                let up = (0.1 * f64::from(k)).to_radians();
                let d = DVec3::X * up.sin() + DVec3::Y * up.cos();
                let ray = ViewRay {
                    origin_m: camera,
                    direction: d,
                    sun_direction: sun,
                    max_distance_m: None,
                };
                let full = model.radiance(&ray).unwrap().radiance;
                let full = [full[0], full[1], full[2]];
                composite(
                    &atmosphere,
                    &extinction,
                    &lit,
                    camera,
                    d,
                    f64::INFINITY,
                    full,
                )
            })
            .collect::<Vec<_>>()
    };
    let (n32, n64) = (image(32), image(64));
    let rms = |a: &[[f64; 3]], b: &[[f64; 3]]| -> [f64; 3] {
        std::array::from_fn(|c| {
            let sum: f64 = a
                .iter()
                .zip(b)
                .map(|(a, b)| ((a[c] - b[c]) / b[c]).powi(2))
                .sum();
            (sum / a.len() as f64).sqrt()
        })
    };
    let color = SpectrumToColor::new(&FRAME_NM).unwrap();
    let xyz = |image: &[[f64; 3]]| -> Vec<[f64; 3]> {
        image.iter().map(|l| color.xyz_cd_m2(l)).collect()
    };
    let (colour, channels) = (rms(&xyz(&n32), &xyz(&n64)), rms(&n32, &n64));
    eprintln!(
        "small drops' image, higher orders {}: RMS change 32 to 64 of X, Y, Z {:.2?} %, \
         of the channels (red, green, blue) {:.2?} %",
        orders.name(),
        colour.map(|v| 100.0 * v),
        channels.map(|v| 100.0 * v)
    );
    (colour, channels)
}

#[test]
#[ignore = "a measurement: about 4 CPU minutes of Lorenz-Mie; run with --ignored"]
fn doubling_the_wavelengths_changes_the_deck_table_by_less_than_one_percent() {
    let (coarse, fine) = changes(
        "deck, 10 um",
        Droplets {
            effective_radius_m: 10e-6,
            sigma: DECK_SIGMA,
            radii: DECK_RADII,
        },
        &TableCache::off(),
    );
    for c in 0..3 {
        assert!(fine[c] < 0.01, "channel {c}: 32 to 64 {}", fine[c]);
    }
    // The image's largest change falls as the wavelengths double. A channel already at
    // the size average's floor (the deck's blue, about 0.5 %) need not fall further.
    assert!(largest(fine) < largest(coarse), "{coarse:?}, {fine:?}");
}
