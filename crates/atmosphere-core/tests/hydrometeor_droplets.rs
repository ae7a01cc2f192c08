//! Lorenz-Mie droplet tables (`hydrometeors/mie_droplets.rs`): the small drops'
//! supernumerary bow against Airy's theory, the tables' normalisation, bad settings named.

use std::f64::consts::PI;

use atmosphere_core::hydrometeors::mie_droplets::Droplets;
use atmosphere_core::hydrometeors::scene::{
    DECK_RADII, DECK_SIGMA, DeckSettings, RainShaftSettings, SMALL_DROP_RADII, SMALL_DROP_SIGMA,
};
use atmosphere_core::hydrometeors::spectral_phase::bin_solid_angle;
use atmosphere_core::hydrometeors::sun_disk_blur::blur_with_sun_disk;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;
use glam::DVec3;

const BIN_DEG: f64 = 0.05;
const SUN_RADIUS_RAD: f64 = 0.004675;

/// The primary bow's deviation D(u) in u = sin i for index `n`, its minimum's u and
/// D'' there (Descartes; van de Hulst 1957, section 13.23).
fn primary_rainbow_ray(n: f64) -> (f64, f64) {
    let deviation = |u: f64| {
        let (i, r) = (u.asin(), (u / n).asin());
        2.0 * (i - r) + (PI - 2.0 * r)
    };
    let u = (1.0 - (n * n - 1.0) / 3.0).sqrt();
    let h = 1e-4;
    let second = (deviation(u + h) - 2.0 * deviation(u) + deviation(u - h)) / (h * h);
    (deviation(u), second)
}

/// The table's local maxima (bin centres, degrees) within (lo, hi), each the largest
/// over `half` bins either side (the residual ripple is narrower).
fn maxima(p: &[f64], lo: f64, hi: f64, half: usize) -> Vec<f64> {
    (half..p.len() - half)
        .filter(|&b| {
            let a = (b as f64 + 0.5) * BIN_DEG;
            a > lo && a < hi && (b - half..=b + half).all(|j| p[j] <= p[b])
        })
        .map(|b| (b as f64 + 0.5) * BIN_DEG)
        .collect()
}

#[test]
fn small_drops_show_the_first_supernumerary_where_airy_puts_it() {
    let m = water_refractive_index(550.0).unwrap();
    for radius_um in [100.0, 150.0, 250.0] {
        let drops = Droplets {
            effective_radius_m: radius_um * 1e-6,
            sigma: SMALL_DROP_SIGMA,
            radii: SMALL_DROP_RADII,
        };
        // Seen with the sun's disc, as the frames see it: what is left of the reflected
        // light's ripple is averaged away.
        let raw = drops.phase_bins(m, 550e-9, BIN_DEG).unwrap();
        let p = blur_with_sun_disk(&raw, BIN_DEG, SUN_RADIUS_RAD);
        let (descartes, second) = primary_rainbow_ray(m.re);
        let bow = descartes.to_degrees();
        // Airy: the amplitude Ai(-z), z = (D - D_R) x^(2/3) / (D''/2)^(1/3), brightest
        // at z = 1.0188, then at 3.2482 (the first supernumerary).
        let x = 2.0 * PI * radius_um * 1e-6 / 550e-9;
        let scale = ((second / 2.0).cbrt() * x.powf(-2.0 / 3.0)).to_degrees();
        let airy = [bow + 1.0188 * scale, bow + 3.2482 * scale];
        let found = maxima(&p, bow - 1.0, bow + 4.0 * scale, 4);
        eprintln!(
            "{radius_um} um: Airy maxima {:.3}, {:.3}; Lorenz-Mie table {found:.3?}",
            airy[0], airy[1]
        );
        assert!(found.len() >= 2, "{found:?}");
        let (primary, first) = (found[0], found[1]);
        assert!((primary - airy[0]).abs() < 0.1, "primary at {primary}");
        let (spacing, airy_spacing) = (first - primary, airy[1] - airy[0]);
        assert!(
            (spacing / airy_spacing - 1.0).abs() < 0.06,
            "supernumerary {spacing} from the primary, Airy {airy_spacing}"
        );
    }
}

#[test]
fn droplet_tables_integrate_to_one() {
    for (radius_m, sigma, radii, nm) in [
        (150e-6, SMALL_DROP_SIGMA, SMALL_DROP_RADII, 700.0),
        (10e-6, DECK_SIGMA, DECK_RADII, 400.0),
    ] {
        let drops = Droplets {
            effective_radius_m: radius_m,
            sigma,
            radii,
        };
        let m = water_refractive_index(nm).unwrap();
        let p = drops.phase_bins(m, nm * 1e-9, BIN_DEG).unwrap();
        let integral: f64 = p
            .iter()
            .enumerate()
            .map(|(b, v)| v * bin_solid_angle(b as f64 * BIN_DEG, (b + 1) as f64 * BIN_DEG))
            .sum();
        eprintln!("{radius_m} m at {nm} nm: integral {integral:.6}");
        assert!((integral - 1.0).abs() < 1e-2, "integral {integral}");
    }
}

#[test]
fn bad_droplet_settings_are_named() {
    let good = Droplets {
        effective_radius_m: 10e-6,
        sigma: 0.1,
        radii: 64,
    };
    for (bad, name) in [
        (
            Droplets {
                effective_radius_m: 1e-3,
                ..good
            },
            "droplet effective radius (m) 0.001",
        ),
        (Droplets { sigma: 0.0, ..good }, "droplet lognormal sigma 0"),
        (
            Droplets {
                sigma: f64::NAN,
                ..good
            },
            "droplet lognormal sigma NaN",
        ),
        (
            Droplets { radii: 1, ..good },
            "droplet radii of the size average 1",
        ),
    ] {
        let m = water_refractive_index(550.0).unwrap();
        let e = bad.phase_bins(m, 550e-9, BIN_DEG).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
    }
}

#[test]
fn bad_deck_and_small_drop_settings_are_named() {
    let ground = 6_360e3;
    for (deck, name) in [
        (
            DeckSettings {
                droplet_radius_um: 60.0,
                ..DeckSettings::default()
            },
            "deck droplet radius (um) 60",
        ),
        (
            DeckSettings {
                optical_depth: -1.0,
                ..DeckSettings::default()
            },
            "deck optical depth -1",
        ),
        (
            DeckSettings {
                thickness_m: f64::INFINITY,
                ..DeckSettings::default()
            },
            "deck thickness (m) inf",
        ),
        (
            DeckSettings {
                base_m: 30_000.0,
                ..DeckSettings::default()
            },
            "deck base (m) 30000",
        ),
    ] {
        let e = deck.volume(ground).unwrap_err().to_string();
        assert!(e.contains(name), "{e}");
    }
    let camera = DVec3::X * (ground + 2.0);
    for radius in [10.0, 1000.0, f64::NAN] {
        let shaft = RainShaftSettings {
            small_drop_radius_um: Some(radius),
            ..RainShaftSettings::default()
        };
        let e = shaft
            .volume(camera, DVec3::Y, ground)
            .unwrap_err()
            .to_string();
        assert!(e.contains("small drop radius (um)"), "{e}");
    }
}
