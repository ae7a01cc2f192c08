//! The phase tables rain and ice volumes are rendered with: energy conserved, the bows
//! at Descartes's angles and the halos at the prisms' minimum deviations, geometric
//! optics against Lorenz-Mie, the sun's disc, the reduction to a frame's wavelengths,
//! and enough wavelengths that doubling them changes little.

use std::f64::consts::PI;

use atmosphere_core::hydrometeors::channel_phase::ChannelPhase;
use atmosphere_core::hydrometeors::error::HydrometeorError;
use atmosphere_core::hydrometeors::spectral_phase::{Particles, SpectralPhase, wavelengths_nm};
use atmosphere_core::hydrometeors::sun_disk_blur::blur_with_sun_disk;
use atmosphere_core::optics::mie::polydisperse::particle_optics;
use atmosphere_core::optics::mie::size_distribution::SizeDistribution;
use atmosphere_core::optics::refractive_index::ice::ice_refractive_index;
use atmosphere_core::optics::refractive_index::water::water_refractive_index;

const RAIN: Particles = Particles::Rain {
    rain_rate_mm_h: 5.0,
};
const SUN_RADIUS_RAD: f64 = 0.004675;
const FRAME_NM: [f64; 3] = [680.0, 550.0, 440.0];

/// Descartes's minimum deviation after `k` internal reflections as a scattering angle.
fn descartes_deg(n: f64, k: f64) -> f64 {
    let i = ((n * n - 1.0) / (k * (k + 2.0))).sqrt().acos();
    let r = (i.sin() / n).asin();
    let d = (2.0 * (i - r) + k * (PI - 2.0 * r)).to_degrees() % 360.0;
    if d > 180.0 { 360.0 - d } else { d }
}

/// The angle of the largest value of wavelength `w`'s table within (lo, hi) degrees.
fn peak_deg(table: &SpectralPhase, w: usize, lo: f64, hi: f64) -> f64 {
    let mut best = (0.0, f64::MIN);
    for (b, &v) in table.phase[w].iter().enumerate() {
        let a = (b as f64 + 0.5) * table.bin_deg;
        if a > lo && a < hi && v > best.1 {
            best = (a, v);
        }
    }
    best.0
}

#[test]
fn rain_rays_conserve_energy_and_bow_at_descartes_angles() {
    // A point sun: the caustics fall in the bins that hold Descartes's angles, or in the
    // next on their bright side (where the bin holding the angle gets only a sliver).
    let table = SpectralPhase::build(&RAIN, 3, 0.0).unwrap();
    let mut primary = Vec::new();
    let mut secondary = Vec::new();
    for (w, &l) in table.wavelengths_nm.iter().enumerate() {
        assert!(
            (table.integral(w) - 1.0).abs() < 1e-6,
            "{l} nm: {}",
            table.integral(w)
        );
        let n = water_refractive_index(l).unwrap().re;
        let (d1, d2) = (descartes_deg(n, 1.0), descartes_deg(n, 2.0));
        let (p1, p2) = (
            peak_deg(&table, w, 130.0, 145.0),
            peak_deg(&table, w, 120.0, 133.0),
        );
        assert!((p1 - d1).abs() <= table.bin_deg, "{l} nm: {p1} vs {d1}");
        assert!((p2 - d2).abs() <= table.bin_deg, "{l} nm: {p2} vs {d2}");
        // Alexander's dark band: between the bows, darker than just outside either.
        let band = table.value_at(w, 0.5 * (d1 + d2));
        assert!(
            band < 0.2 * table.value_at(w, d1 + 1.0),
            "{l} nm: band {band}"
        );
        assert!(
            band < 0.5 * table.value_at(w, d2 - 1.0),
            "{l} nm: band {band}"
        );
        primary.push(p1);
        secondary.push(p2);
    }
    // Blue (short waves) deviated more in the primary, less in the secondary: red outside
    // the primary, inside the secondary (seen from the antisolar point, 180 - angle).
    assert!(primary[0] > primary[2] + 0.5, "{primary:?}");
    assert!(secondary[0] < secondary[2] - 0.5, "{secondary:?}");
}

#[test]
fn geometric_optics_agrees_with_lorenz_mie_away_from_the_bows() {
    // Drops of 50 um effective radius (x from 300 to 1100 at 550 nm) by Lorenz-Mie, and
    // the rain's geometric optics (the same for every drop size but for diffraction,
    // negligible past 20 degrees), both averaged over 4 degrees around each angle. At
    // 110 and 170 degrees Lorenz-Mie's surface waves and glory, which geometric optics
    // lacks, still matter at these sizes (docs/optics-rendering.md); they fade as x grows.
    let distribution = SizeDistribution::lognormal(50e-6, 0.1).unwrap();
    let m = water_refractive_index(550.0).unwrap();
    let checks = [(30.0, 0.03), (60.0, 0.04), (90.0, 0.1), (150.0, 0.1)];
    let cosines: Vec<f64> = checks
        .iter()
        .flat_map(|(a, _)| (0..41).map(move |k| (a - 2.0 + 0.1 * f64::from(k)).to_radians().cos()))
        .collect();
    let mie = particle_optics(m, 550e-9, &distribution, &cosines, 1e-2).unwrap();
    let rays = SpectralPhase::build(&RAIN, 3, 0.0).unwrap();
    assert_eq!(rays.wavelengths_nm[1], 550.0);
    for (i, (a, tolerance)) in checks.iter().enumerate() {
        let lorenz_mie = mie.phase[i * 41..(i + 1) * 41].iter().sum::<f64>() / 41.0;
        let geometric = (0..41)
            .map(|k| rays.value_at(1, a - 2.0 + 0.1 * f64::from(k)))
            .sum::<f64>()
            / 41.0;
        let error = geometric / lorenz_mie - 1.0;
        assert!(
            error.abs() < *tolerance,
            "{a} deg: {geometric} vs {lorenz_mie}"
        );
    }
}

#[test]
fn the_sun_disc_spreads_a_line_over_its_radius_and_keeps_a_constant() {
    let bin = 0.05;
    let mut line = vec![0.0; 3600];
    line[1800] = 1.0; // 90.025 degrees
    let blurred = blur_with_sun_disk(&line, bin, SUN_RADIUS_RAD);
    let radius_deg = SUN_RADIUS_RAD.to_degrees();
    for (b, v) in blurred.iter().enumerate() {
        let a = (b as f64 + 0.5) * bin;
        if (a - 90.025).abs() > radius_deg + bin {
            assert_eq!(*v, 0.0, "{a}");
        }
    }
    // The disc's mean of a line: the sum over bins keeps its integral (in angle near 90
    // degrees, where bins have equal solid angles) within the quadrature's error.
    let sum: f64 = blurred.iter().sum();
    assert!((sum - 1.0).abs() < 0.02, "{sum}");
    let flat = blur_with_sun_disk(&[0.3; 3600], bin, SUN_RADIUS_RAD);
    assert!(flat.iter().all(|v| (v - 0.3).abs() < 1e-12));
}

#[test]
fn a_phase_function_equal_at_every_wavelength_keeps_its_values_in_a_frame() {
    let wavelengths = wavelengths_nm(16);
    let grey: Vec<f64> = (0..3600)
        .map(|b| 0.1 + 0.5 * (f64::from(b) * 0.01).sin().abs())
        .collect();
    let table = SpectralPhase {
        phase: vec![grey.clone(); wavelengths.len()],
        wavelengths_nm: wavelengths,
        bin_deg: 0.05,
        sky: None,
    };
    let channels = ChannelPhase::new(&table, FRAME_NM).unwrap();
    for (v, g) in channels.values.iter().zip(&grey) {
        for c in v {
            assert!((c / g - 1.0).abs() < 1e-9, "{c} vs {g}");
        }
    }
}

/// The relative L1 difference of two tables over 100 to 180 degrees, per channel.
fn bow_side_change(a: &ChannelPhase, b: &ChannelPhase) -> f64 {
    let range = 2000..3600;
    (0..3)
        .map(|c| {
            let diff: f64 = range
                .clone()
                .map(|i| (a.values[i][c] - b.values[i][c]).abs())
                .sum();
            let size: f64 = range.clone().map(|i| b.values[i][c].abs()).sum();
            diff / size
        })
        .fold(0.0, f64::max)
}

#[test]
fn doubling_the_wavelengths_changes_the_rain_table_by_less_than_one_percent() {
    let table = |n| {
        let spectral = SpectralPhase::build(&RAIN, n, SUN_RADIUS_RAD).unwrap();
        for w in 0..n {
            assert!((spectral.integral(w) - 1.0).abs() < 1e-9);
        }
        ChannelPhase::new(&spectral, FRAME_NM).unwrap()
    };
    let (n16, n32, n64) = (table(16), table(32), table(64));
    let (coarse, fine) = (bow_side_change(&n16, &n32), bow_side_change(&n32, &n64));
    assert!(fine < 0.01, "32 to 64 wavelengths: {fine}");
    assert!(fine < coarse, "16 to 32: {coarse}, 32 to 64: {fine}");
}

#[test]
fn ice_columns_scatter_their_halos_at_the_prisms_minimum_deviations() {
    let ice = Particles::Ice {
        radius_m: 20e-6,
        length_m: 80e-6,
        rays: 200_000,
    };
    let table = SpectralPhase::build(&ice, 3, 0.0).unwrap();
    let n = ice_refractive_index(550.0).unwrap().re;
    // D = 2 asin(n sin(A / 2)) - A for prism angles of 60 and 90 degrees.
    let deviation = |prism: f64| {
        let a = prism.to_radians();
        (2.0 * (n * (0.5 * a).sin()).asin() - a).to_degrees()
    };
    assert!(
        (table.integral(1) - 1.0).abs() < 0.02,
        "{}",
        table.integral(1)
    );
    let (d22, d46) = (deviation(60.0), deviation(90.0));
    let (p22, p46) = (
        peak_deg(&table, 1, 20.0, 25.0),
        peak_deg(&table, 1, 43.0, 49.0),
    );
    assert!((p22 - d22).abs() < 0.3, "{p22} vs {d22}");
    assert!((p46 - d46).abs() < 0.3, "{p46} vs {d46}");
    // Inside the 22 degree halo the sky is dark: no ray is deviated less.
    assert!(table.value_at(1, d22 - 1.5) < 0.1 * table.value_at(1, p22));
}

#[test]
fn bad_settings_are_named() {
    let error = |r: Result<SpectralPhase, HydrometeorError>| r.unwrap_err().to_string();
    let rain = |rate| Particles::Rain {
        rain_rate_mm_h: rate,
    };
    assert!(error(SpectralPhase::build(&rain(0.0), 16, 0.0)).contains("rain rate"));
    assert!(error(SpectralPhase::build(&rain(f64::NAN), 16, 0.0)).contains("rain rate"));
    assert!(error(SpectralPhase::build(&RAIN, 2, 0.0)).contains("wavelength count"));
    assert!(error(SpectralPhase::build(&RAIN, 16, 0.1)).contains("sun radius"));
    let flat = Particles::Ice {
        radius_m: 1e-3,
        length_m: 1e-6,
        rays: 10_000,
    };
    assert!(error(SpectralPhase::build(&flat, 16, 0.0)).contains("aspect"));
    let few = Particles::Ice {
        radius_m: 2e-5,
        length_m: 8e-5,
        rays: 10,
    };
    assert!(error(SpectralPhase::build(&few, 16, 0.0)).contains("rays"));
}
