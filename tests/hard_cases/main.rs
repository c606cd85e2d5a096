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

/// `impact run` on each bad scene: exit code 2, the message on stderr, nothing on stdout.
#[test]
fn every_bad_input_exits_2_without_output() {
    let dir = std::env::temp_dir().join(format!("impactcheck-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (case, text, _) in
        impactcheck::verify::hard_cases::bad_input_cases(std::path::Path::new("."))
    {
        let p = dir.join("bad.toml");
        std::fs::write(&p, &text).expect("write");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_impact"))
            .args(["run", p.to_str().expect("utf8"), "--format", "json"])
            .output()
            .expect("runs");
        assert_eq!(out.status.code(), Some(2), "{case}");
        assert!(out.stdout.is_empty(), "{case}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("bad.toml"),
            "{case}"
        );
    }
}
