//! The committed `reports/summary.json` keeps the counting rules of issue 25: every claim that
//! fails or holds only with a correction, and does not extend the paper, is in exactly one
//! finding; a claim that extends the paper is in none; a weak claim carries its power and says
//! what its check cannot see. (The file is written by `verify`; `verify --check` in CI keeps it
//! current, so this test reads what a reader of the reports reads.)

use std::collections::BTreeMap;

#[test]
fn every_error_is_in_one_finding_and_every_weak_claim_says_why() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/reports/summary.json");
    let text = std::fs::read_to_string(path).expect("reports/summary.json");
    let s: serde_json::Value = serde_json::from_str(&text).expect("json");
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for f in s["findings"].as_array().expect("findings") {
        assert!(f["name"].as_str().is_some_and(|n| !n.is_empty()), "{f}");
        for id in f["claims"].as_array().expect("claims") {
            *seen
                .entry(id.as_str().expect("id").to_string())
                .or_default() += 1;
        }
    }
    for c in s["claims"].as_array().expect("claims") {
        let id = c["id"].as_str().expect("id");
        let verdict = c["verdict"].as_str().expect("verdict");
        let extends = c.get("extends").is_some();
        let error = matches!(verdict, "fails" | "holds-with-correction");
        let n = seen.get(id).copied().unwrap_or(0);
        if error && !extends {
            assert_eq!(n, 1, "{id} ({verdict}) is in {n} findings");
        } else {
            assert_eq!(n, 0, "{id} ({verdict}, extends: {extends}) is in a finding");
        }
        if c.get("weak").and_then(|w| w.as_bool()) == Some(true) {
            let power = &c["power"];
            assert!(
                power["survivors"].as_array().is_some_and(|v| !v.is_empty()),
                "{id}"
            );
            assert!(
                power["blind"].as_str().is_some_and(|b| !b.is_empty()),
                "{id} is weak and does not say what its check cannot see"
            );
        }
    }
}
