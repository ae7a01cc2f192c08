//! `atmos report --section optics` on a narrowed, tiny case: the rainbow's view cut to
//! two rays with a path tracer stopped after a few hundred paths, two rows, through the
//! section's own steps (reference cache and its reuse, answers, errors, Markdown, CSV);
//! and its bad flags named by the binary.

mod common;

use atmos::report::optics::scenes_folder;
use atmos::report::optics_errors::{errors_csv, row_result};
use atmos::report::optics_markdown::{Measured, markdown, points};
use atmos::report::optics_reference::load_or_compute;
use atmos::report::optics_rows::{OpticsRow, SHIPPED, answer};
use atmos::report::optics_scene::OpticsScene;
use atmos::report::optics_views::optics_views;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::color::SpectrumToColor;
use common::atmos_fails_with;
use render_wgpu::frame::atmosphere_uniform::RGB_WAVELENGTHS_NM;

#[test]
fn a_tiny_view_gives_rows_with_finite_errors_and_reuses_its_reference() {
    // The rainbow's view: inside the primary and on it, few paths.
    let mut view = optics_views().swap_remove(0);
    view.angles_deg = vec![38.0, 42.0];
    view.paths = PathSettings {
        target_relative_error: 0.3,
        min_paths: 64,
        max_paths: 256,
        ..PathSettings::default()
    };
    let scenes = vec![OpticsScene::new(view, &scenes_folder()).unwrap()];
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("optics_reference.csv");
    let reference = load_or_compute(&cache, &scenes, |_| false).unwrap();
    assert_eq!(reference[0].len(), 2);
    for r in &reference[0] {
        assert!(r.radiance.radiance.iter().all(|l| *l > 0.0), "{r:?}");
        assert!(r.paths >= 64 && r.volume_transmittance < 1.0, "{r:?}");
        // The volume's light has all three parts.
        let light = &r.volume_light;
        assert!(light.sun_single[1] > 0.0 && light.sun_multiple[1] > 0.0 && light.sky[1] > 0.0);
    }
    // The second time the cache answers, bit for bit.
    let again = load_or_compute(&cache, &scenes, |_| false).unwrap();
    assert_eq!(again, reference);

    let color = SpectrumToColor::new(&RGB_WAVELENGTHS_NM).unwrap();
    let rows = [SHIPPED, OpticsRow::parse("wavelengths=8 steps=4").unwrap()];
    let results: Vec<_> = rows
        .iter()
        .map(|row| {
            let answers = vec![answer(row, &scenes[0]).unwrap()];
            row_result(*row, &answers, &reference, &color)
        })
        .collect();
    for r in &results {
        let v = r.per_view[0];
        assert!(
            v.rms.is_finite() && v.max >= v.rms && v.delta_e.is_finite(),
            "{r:?}"
        );
        assert!(v.frame_s > 0.0 && v.frame_s.is_finite(), "{r:?}");
    }
    // Two settings, two answers: not the same error.
    assert_ne!(results[0].ray_errors, results[1].ray_errors);
    let measured = Measured {
        scenes: &scenes,
        reference: &reference,
        results: &results,
        gpu: None,
        color: &color,
    };
    let page = markdown(&measured);
    for needle in [
        "| wavelengths=32 sun=disc steps=12 |",
        "| wavelengths=8 sun=disc steps=4 |",
        "rain shaft: the bows",
        "GPU: not measured",
    ] {
        assert!(page.contains(needle), "no '{needle}' in\n{page}");
    }
    let (cpu, gpu) = points(&measured);
    assert_eq!(cpu.len(), 2);
    assert!(gpu.is_empty());
    let csv = errors_csv(&results, &scenes);
    assert_eq!(csv.lines().count(), 3, "{csv}");
}

#[test]
fn bad_optics_flags_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    atmos_fails_with(
        &[
            "report",
            "--out",
            out,
            "--section",
            "optics",
            "--variant",
            "sun=square",
        ],
        "optics variant \"sun=square\": \"sun=square\" is none of",
    );
    atmos_fails_with(
        &[
            "report",
            "--out",
            out,
            "--section",
            "optics",
            "--section",
            "clouds",
            "--variant",
            "sun=point",
        ],
        "--variant narrows one section at a time",
    );
    atmos_fails_with(
        &[
            "report",
            "--out",
            out,
            "--section",
            "optics",
            "--recompute-view",
            "sundogs",
        ],
        "--recompute-view sundogs: no such optics view",
    );
}
