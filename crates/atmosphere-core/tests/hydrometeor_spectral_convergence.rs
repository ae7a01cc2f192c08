//! The Lorenz-Mie tables' colours as the wavelengths double, by the relative L1 change
//! of the channel tables P_c per channel over 100 to 180 degrees (the bows, the
//! cloudbow and the glory): the droplet deck's (glory, cloudbow) changes from 32 to 64
//! wavelengths by less than 1 % in every channel and its largest change falls from
//! 16 -> 32 to 32 -> 64; the small drops' (supernumerary bows) green and blue alike,
//! their red not yet (bounded). Slow: each table is built at 112 wavelengths in all,
//! minutes of Lorenz-Mie series on two cores, so the suite leaves them out; run them with
//! `cargo test -p atmosphere-core --test hydrometeor_spectral_convergence -- --ignored`.

use atmosphere_core::hydrometeors::channel_phase::ChannelPhase;
use atmosphere_core::hydrometeors::mie_droplets::Droplets;
use atmosphere_core::hydrometeors::scene::{
    DECK_RADII, DECK_SIGMA, SMALL_DROP_RADII, SMALL_DROP_SIGMA,
};
use atmosphere_core::hydrometeors::spectral_phase::{Particles, SpectralPhase};

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

/// Builds `drops` at 16, 32 and 64 wavelengths; returns the relative L1 changes per
/// channel from 16 to 32 and from 32 to 64.
fn changes(name: &str, drops: Droplets) -> ([f64; 3], [f64; 3]) {
    let table = |n| {
        let spectral =
            SpectralPhase::build(&Particles::Droplets(drops), n, SUN_RADIUS_RAD).unwrap();
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
    let (coarse, fine) = changes(
        "small drops, 150 um",
        Droplets {
            effective_radius_m: 150e-6,
            sigma: SMALL_DROP_SIGMA,
            radii: SMALL_DROP_RADII,
        },
    );
    // Green and blue settle below 1 % and fall as the wavelengths double.
    for c in 1..3 {
        assert!(fine[c] < 0.01, "channel {c}: 32 to 64 {}", fine[c]);
        assert!(fine[c] < coarse[c], "channel {c}: {coarse:?}, {fine:?}");
    }
    // Red has not settled (2.4 % measured, its 16 to 32 change alike: the remainder
    // docs/optics-rendering.md names under "Not yet"); this bound keeps it from growing.
    assert!(fine[0] < 0.025, "red: 32 to 64 {}", fine[0]);
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
    );
    for c in 0..3 {
        assert!(fine[c] < 0.01, "channel {c}: 32 to 64 {}", fine[c]);
    }
    // The image's largest change falls as the wavelengths double. A channel already at
    // the size average's floor (the deck's blue, about 0.5 %) need not fall further.
    assert!(largest(fine) < largest(coarse), "{coarse:?}, {fine:?}");
}
