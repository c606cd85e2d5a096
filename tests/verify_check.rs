//! CI's verdict regression check, as a test: `verify --check` reruns every claim of `verify/`
//! and compares it with the committed `reports/summary.json` (every verdict, and every number of
//! every detail to 1e-6). The baseline is what `verify` wrote and a reviewer read; each verdict
//! in it comes from its own computation (a closed form, exact algebra, a second method), and CI
//! (`.ci/run`) runs the same command. Here it runs with the other tests so that a change the
//! unit tests do not see, but which moves a verdict or a number of a report, fails `cargo test`
//! too (cargo-mutants measures `src/verify/` with it, reports/mutation.md).

use std::process::Command;

#[test]
fn every_claim_keeps_its_committed_verdict_and_numbers() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .current_dir(root)
        .args(["--check"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "verify --check:\n{err}");
    assert!(err.contains("no verdict or value changed"), "{err}");
    // the verdicts' times are said only when asked for (--timing)
    assert!(!err.contains("slowest verdicts"), "{err}");
}

/// `verify --check --timing` says where the verdicts' time goes: the twelve slowest of all the
/// claims' verdicts (a power measured is no verdict), each a claim of `verify/`.
#[test]
fn the_slowest_verdicts_are_named_under_timing() {
    let root = env!("CARGO_MANIFEST_DIR");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .current_dir(root)
        .args(["--check", "--timing"])
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "verify --check --timing:\n{err}");
    let head = err
        .lines()
        .find(|l| l.contains("slowest verdicts"))
        .unwrap_or_else(|| panic!("no list of the slowest verdicts:\n{err}"));
    assert!(head.contains("the 12 slowest verdicts (of "), "{head}");
    let n: usize = head
        .split("for all ")
        .nth(1)
        .and_then(|r| r.trim_end_matches("):").parse().ok())
        .unwrap_or_else(|| panic!("{head}"));
    assert!(n >= 207, "{n} verdicts timed: {head}");
    let listed: Vec<&str> = err
        .lines()
        .filter(|l| l.split_whitespace().nth(1) == Some("s"))
        .collect();
    assert_eq!(listed.len(), 12, "{err}");
}
