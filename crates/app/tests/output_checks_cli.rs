//! Output paths are checked before any work: a missing folder or an image type a command
//! cannot write is named at once, and nothing is left behind.

mod common;

use common::{atmos, atmos_fails_with};

#[test]
fn a_missing_output_folder_is_named_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("missing/sky.png");
    let out = out.to_str().unwrap();
    // bruneton's table build takes seconds on lavapipe; the check comes first.
    let args = [
        "render",
        "--model",
        "bruneton",
        "--altitude-m",
        "10",
        "--sun-zenith-deg",
        "45",
        "--width",
        "8",
        "--height",
        "8",
        "--out",
        out,
    ];
    let output = atmos_fails_with(&args, &format!("cannot write {out}"));
    assert!(!String::from_utf8_lossy(&output.stderr).contains("adapter"));
    for args in [
        vec!["bench", "--model", "riley", "--out", out],
        vec!["contact-sheet", "--model", "riley", "--out", out],
        vec![
            "probe", "--model", "riley", "--input", "rays.csv", "--output", out,
        ],
    ] {
        atmos_fails_with(&args, &format!("cannot write {out}"));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn the_contact_sheet_is_written_in_the_type_its_name_says() {
    let dir = tempfile::tempdir().unwrap();
    let gif = dir.path().join("sheet.gif");
    atmos_fails_with(
        &["contact-sheet", "--out", gif.to_str().unwrap()],
        "the contact sheet is written as .png or .jpg",
    );
    let jpg = dir.path().join("sheet.jpg");
    let output = atmos(&[
        "contact-sheet",
        "--model",
        "riley",
        "--tile",
        "16x9",
        "--out",
        jpg.to_str().unwrap(),
    ]);
    if common::skipped_without_adapter(&output) {
        return;
    }
    assert!(output.status.success(), "{}", common::stderr(&output));
    let bytes = std::fs::read(&jpg).unwrap();
    assert_eq!(&bytes[..3], &[0xFF, 0xD8, 0xFF], "JPEG start of image");
    assert_eq!(
        image::guess_format(&bytes).unwrap(),
        image::ImageFormat::Jpeg
    );
}
