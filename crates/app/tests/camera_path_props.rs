//! Camera path files never panic: the shipped paths with numbers replaced by awkward
//! values, or characters deleted, read as a path or an error naming the file; a path that
//! reads gives, at any time, a frame that passes `Frame::validate` or an error.

use std::path::Path;

use atmos::camera_path::CameraPath;
use proptest::prelude::*;
use proptest::sample::{Index, select};
use proptest::test_runner::FileFailurePersistence;

const PATHS: [&str; 3] = [
    include_str!("../../../assets/paths/ascent_alps.toml"),
    include_str!("../../../assets/paths/sunrise_from_orbit.toml"),
    include_str!("../../../assets/paths/day_at_one_place.toml"),
];

/// Values that break careless number handling.
const AWKWARD: [&str; 12] = [
    "0",
    "-0.0",
    "-1",
    "1e-300",
    "1e300",
    "-1e300",
    "nan",
    "inf",
    "-inf",
    "90.0000001",
    "18446744073709551616",
    "\"x\"",
];

/// The byte ranges of the numbers in `text` (runs starting with a digit or '-').
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        let part = c.is_ascii_digit() || ".eE+-_".contains(c);
        match (start, part) {
            (None, true) if c.is_ascii_digit() || c == '-' => start = Some(i),
            (Some(s), false) => {
                out.push(s..i);
                start = None;
            }
            _ => {}
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 96,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "tests/camera_path_props.proptest-regressions",
        ))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn mutated_paths_never_panic(
        which in 0..PATHS.len(),
        replace in prop::collection::vec((any::<Index>(), select(&AWKWARD[..])), 0..3),
        delete in prop::option::of(any::<Index>()),
        times in prop::collection::vec(-10.0f64..100.0, 4),
    ) {
        let mut text = PATHS[which].to_string();
        for (i, value) in replace {
            let found = numbers(&text);
            text.replace_range(found[i.index(found.len())].clone(), value);
        }
        if let Some(i) = delete {
            let at: Vec<usize> = text.char_indices().map(|(k, _)| k).collect();
            text.remove(at[i.index(at.len())]);
        }
        match CameraPath::parse(&text, Path::new("fuzz.toml")) {
            Ok(path) => {
                prop_assert!(path.duration_s().is_finite() && path.fps() > 0.0);
                for t in times {
                    if let Ok(frame) = path.frame_at(t, 16, 9) {
                        prop_assert!(frame.validate().is_ok());
                    }
                }
            }
            Err(e) => prop_assert!(e.to_string().starts_with("camera path fuzz.toml"), "{e}"),
        }
    }
}
