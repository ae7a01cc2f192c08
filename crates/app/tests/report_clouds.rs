//! `atmos report --section clouds` on a narrowed, tiny case: one view of two rays with
//! a path tracer stopped after a few hundred paths, two rows, through the section's own
//! steps (reference cache, answers, errors, Markdown, CSV); and its bad flags named by
//! the binary.

mod common;

use atmos::report::clouds_errors::{errors_csv, row_result};
use atmos::report::clouds_markdown::{Measured, markdown, points};
use atmos::report::clouds_reference::load_or_compute;
use atmos::report::clouds_rows::{CloudRow, answer};
use atmos::report::clouds_scene::ViewScene;
use atmos::report::clouds_views::cloud_views;
use atmos::table_cache_dir::table_cache;
use atmosphere_core::clouds::layer::droplets::droplet_orders_cached;
use atmosphere_core::clouds::reference::settings::PathSettings;
use atmosphere_core::color::SpectrumToColor;
use atmosphere_core::models::sky_model::ModelSettings;
use common::atmos_fails_with;

#[test]
fn a_tiny_view_gives_rows_with_finite_errors_and_reuses_its_reference() {
    let settings = ModelSettings::default();
    let orders = droplet_orders_cached(&settings.wavelengths_nm, &table_cache()).unwrap();
    // The view above the deck, 2 x 1 rays, a thin deck, few paths.
    let mut view = cloud_views(2, 1).swap_remove(1);
    view.cloud.extinction_per_m = 0.002;
    view.paths = PathSettings {
        target_relative_error: 0.3,
        min_paths: 64,
        max_paths: 256,
        ..PathSettings::default()
    };
    let scenes = vec![ViewScene::new(view, &settings, &orders).unwrap()];
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("clouds_reference.csv");
    let reference = load_or_compute(&cache, &scenes, &settings, |_| false).unwrap();
    assert_eq!(reference[0].len(), 2);
    for r in &reference[0] {
        assert!(r.radiance.radiance.iter().all(|l| *l > 0.0), "{r:?}");
        assert!(
            r.paths.unwrap() >= 64 && r.cloud_transmittance < 1.0,
            "{r:?}"
        );
    }
    // The second time the cache answers, bit for bit, even asked with other rays'
    // settings left as they are.
    let again = load_or_compute(&cache, &scenes, &settings, |_| false).unwrap();
    assert_eq!(again, reference);

    let color = SpectrumToColor::new(&settings.wavelengths_nm).unwrap();
    let rows = [
        CloudRow::parse("riley interactive march").unwrap(),
        CloudRow::parse("octaves offline map").unwrap(),
        CloudRow::parse("spheres").unwrap(),
    ];
    let results: Vec<_> = rows
        .iter()
        .map(|row| {
            let answers = vec![answer(row, &scenes[0]).unwrap()];
            row_result(*row, &answers, &reference, &color)
        })
        .collect();
    for r in &results[..2] {
        let v = r.per_view[0].unwrap();
        assert!(
            v.rms.is_finite() && v.max.is_finite() && v.max >= v.rms,
            "{r:?}"
        );
        assert!(v.frame_s > 0.0 && v.frame_s.is_finite(), "{r:?}");
    }
    // Two methods, two answers: not the same error.
    assert_ne!(results[0].ray_errors, results[1].ray_errors);
    // The spheres are measured on the view from orbit only.
    assert_eq!(results[2].per_view, [None]);
    let measured = Measured {
        scenes: &scenes,
        reference: &reference,
        results: &results,
        gpu: None,
        color: &color,
    };
    let page = markdown(&measured);
    for needle in [
        "| riley interactive march |",
        "| octaves offline map |",
        "above a deck",
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
fn bad_clouds_flags_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().to_str().unwrap();
    atmos_fails_with(
        &[
            "report",
            "--out",
            out,
            "--section",
            "clouds",
            "--variant",
            "riley fast",
        ],
        "clouds variant \"riley fast\": \"fast\" is none of spheres, riley, octaves",
    );
    atmos_fails_with(
        &[
            "report",
            "--out",
            out,
            "--section",
            "clouds",
            "--section",
            "skies",
            "--variant",
            "riley",
        ],
        "--variant narrows one section at a time",
    );
}
