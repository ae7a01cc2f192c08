//! `atmos contact-sheet` end to end on tiny tiles: the sheet has one labelled row per
//! model and one column per view, the noon sky is blue over a reddish-grey ground, space
//! in the 100 km view is black; a bad tile size is named; the file's type follows its
//! extension. Without an adapter the GPU cases fail with the message saying what to
//! install, unless `ATMOS_SKIP_GPU_TESTS=1`.

mod common;

use std::path::Path;

use common::{atmos, atmos_fails_with, skipped_without_adapter, stderr};

/// Renders a sheet of `model` with tiles of `tile` into `out`; `false` when it skipped for
/// want of an adapter.
fn sheet(model: &str, tile: &str, out: &Path) -> bool {
    let output = atmos(&[
        "contact-sheet",
        "--model",
        model,
        "--tile",
        tile,
        "--out",
        out.to_str().unwrap(),
    ]);
    if skipped_without_adapter(&output) {
        return false;
    }
    assert!(output.status.success(), "{}", stderr(&output));
    true
}

#[test]
fn the_sheet_lays_out_labelled_views() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sheet.png");
    if !sheet("nishita", "32x18", &out) {
        return;
    }
    let sheet = image::open(&out).unwrap().to_rgb8();
    // 110 px of model names, six 32 px columns; 26 px of view names, one 18 px row.
    assert_eq!(sheet.dimensions(), (110 + 6 * 32, 26 + 18));
    let lit = |x0: u32, x1: u32, y0: u32, y1: u32| {
        (x0..x1).any(|x| (y0..y1).any(|y| sheet.get_pixel(x, y).0.iter().any(|&c| c > 128)))
    };
    assert!(lit(0, 110, 26, 44), "no model name");
    assert!(lit(110, 142, 0, 26), "no view name");
    let noon_sky = sheet.get_pixel(110 + 16, 26 + 1);
    let noon_ground = sheet.get_pixel(110 + 16, 26 + 16);
    assert!(noon_sky[2] > noon_sky[0], "noon sky {noon_sky:?}");
    assert!(noon_ground[0] > noon_ground[2], "ground {noon_ground:?}");
    assert_eq!(
        sheet.get_pixel(110 + 4 * 32 + 16, 26).0,
        [0, 0, 0],
        "space at 100 km"
    );
}

#[test]
fn a_bad_tile_is_named() {
    let output = atmos(&["contact-sheet", "--tile", "0x9"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(stderr(&output).contains("0x9"), "{}", stderr(&output));
}

#[test]
fn the_sheet_is_written_in_the_type_its_name_says() {
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("sheet.gif");
    atmos_fails_with(
        &["contact-sheet", "--out", gif.to_str().unwrap()],
        "the contact sheet is written as .png or .jpg",
    );
    let jpg = dir.path().join("sheet.jpg");
    if !sheet("riley", "16x9", &jpg) {
        return;
    }
    let bytes = std::fs::read(&jpg).unwrap();
    assert_eq!(
        image::guess_format(&bytes).unwrap(),
        image::ImageFormat::Jpeg
    );
}
