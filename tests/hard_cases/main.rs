//! The hard-case catalogue (src/verify/hard_cases.rs, scenes beside this file): every case must
//! finish within its tolerance against its independent reference (closed forms, a second method,
//! exact evaluation; each named in the catalogue) or stop with the diagnosis it must give; every
//! bad scene must get one message naming the file, the field and the allowed range.

use impactcheck::verify::hard_cases::{bad_inputs, catalogue};

#[test]
fn every_hard_case_finishes_within_tolerance_or_is_diagnosed() {
    let cases = catalogue(std::path::Path::new("."));
    assert!(cases.len() >= 13);
    let failed: Vec<String> = cases
        .iter()
        .filter(|c| !c.ok)
        .map(|c| format!("{}: {}", c.id, c.outcome))
        .collect();
    assert!(failed.is_empty(), "{failed:#?}");
}

#[test]
fn every_bad_input_names_field_and_range() {
    let bad = bad_inputs(std::path::Path::new("."));
    let failed: Vec<String> = bad
        .iter()
        .filter(|b| !b.ok)
        .map(|b| format!("{}: {:?}", b.case, b.message))
        .collect();
    assert!(failed.is_empty(), "{failed:#?}");
}
