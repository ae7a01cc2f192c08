//! A skipped test records itself (`common::skip`): one line per skip, naming the test
//! binary and the test, appended to the file `scripts/test.sh` counts.

mod common;

use common::skip::record_skip_in;

#[test]
fn a_skip_appends_one_line_naming_binary_test_and_reason() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("skipped.txt");
    record_skip_in(Some(&file), "no GPU adapter\nhere");
    record_skip_in(Some(&file), "again");
    let name = "skips_recorded::a_skip_appends_one_line_naming_binary_test_and_reason";
    assert_eq!(
        std::fs::read_to_string(&file).unwrap(),
        format!("{name}: no GPU adapter here\n{name}: again\n")
    );
}
