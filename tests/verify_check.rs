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
}
