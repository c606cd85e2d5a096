//! A finding's correction, applied: the claim checked again with the paper's error mended, so
//! that a finding is filed under the cause whose correction makes its claims hold.
//!
//! A claim that fails or holds only with a correction shows a finding. Its correction is:
//! - the claim's `correction`, a table of its keys as the paper should have printed them
//!   (`correction = { printed = "..." }`, `{ printed_matrix = [...] }`, `{ require = "..." }`):
//!   each replaces the key of that name, and the claim is validated and checked again;
//! - otherwise its `corrected` formula, where it gives one: `printed` becomes `corrected`.
//!
//! The correction holds when the claim so changed holds (`holds`, `holds-with-assumption`, or a
//! definition found consistent);
//! the verdict is computed by the claim's kind, as the printed one is. A claim with neither key
//! has no correction stated, and the report says so.

use super::kinds::{Checked, KindEntry, Session};
use super::{ClaimSpec, Verdict};
use crate::report::Corrected;

/// The claim's keys with its correction applied, or `None` when it states none.
pub fn corrected_keys(spec: &ClaimSpec) -> Option<toml::Table> {
    let mut keys = spec.keys.clone();
    if let Some(fix) = &spec.head.correction {
        for (k, v) in fix {
            keys.insert(k.clone(), v.clone());
        }
        // a corrected form checked beside the printed one is the printed one now
        keys.remove("corrected");
        return Some(keys);
    }
    let fixed = keys.remove("corrected")?;
    keys.insert("printed".into(), fixed);
    Some(keys)
}

/// Whether `verdict` is one a finding's claim shows (it fails, or holds only with a correction).
pub fn shows_finding(verdict: Verdict) -> bool {
    matches!(verdict, Verdict::Fails | Verdict::HoldsWithCorrection)
}

/// The claim checked with its correction applied (`None`: it states none).
pub fn apply(
    cx: &Checked,
    entry: &KindEntry,
    spec: &ClaimSpec,
    run: &mut Session,
) -> Option<Corrected> {
    let keys = corrected_keys(spec)?;
    let mut fixed = spec.clone();
    fixed.keys = keys;
    fixed.head.correction = None;
    Some(
        match (entry.validate)(cx, &fixed).and_then(|claim| claim.run(cx, &fixed.head, run)) {
            Ok(o) => {
                let o = super::with_assumption(o, &fixed.head);
                Corrected {
                    holds: matches!(
                        o.verdict,
                        Verdict::Holds | Verdict::HoldsWithAssumption | Verdict::Definition
                    ),
                    verdict: o.verdict,
                    detail: o.detail,
                }
            }
            Err(e) => Corrected {
                holds: false,
                verdict: Verdict::NotCheckable,
                detail: format!("the correction does not run: {e}"),
            },
        },
    )
}

/// Every claim of `papers` checked, and each claim that shows a finding (and does not extend
/// the paper) checked again with its correction applied, in a session of its own: the test
/// that every finding names its true cause.
pub fn check_all(
    papers: &[super::PaperClaims],
    root: &std::path::Path,
) -> Result<Vec<(super::Outcome, Option<Corrected>)>, super::VerifyError> {
    let checked: Vec<Checked> = papers
        .iter()
        .map(Checked::validate)
        .collect::<Result<_, _>>()?;
    let mut run = super::session(root);
    let mut out = Vec::new();
    for file in &checked {
        let outcomes = file.check_all(&mut run)?;
        for ((spec, entry), o) in file.file.claim.iter().zip(&file.entries).zip(outcomes) {
            let fix = (shows_finding(o.verdict) && spec.head.extends.is_none())
                .then(|| apply(file, entry, spec, &mut super::session(root)))
                .flatten();
            out.push((o, fix));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A claims file of identities on `2 x^2` printed for `x^2` (by hand: only the factor is
    /// wrong), each with another correction.
    fn run(body: &str) -> Vec<(String, Option<(bool, Verdict)>)> {
        let (papers, d) =
            crate::verify::test_claims("toy", &format!("[symbols]\nx = \"m\"\n{body}")).unwrap();
        check_all(&papers, &d)
            .unwrap()
            .into_iter()
            .map(|(o, c)| (o.id, c.map(|c| (c.holds, c.verdict))))
            .collect()
    }

    fn claim(id: &str, keys: &str) -> String {
        format!(
            "[[claim]]\nid = \"{id}\"\nequation = \"(1)\"\nreading = \"q\"\nkind = \"identity\"\nderived = \"x^2\"\n{keys}\n"
        )
    }

    #[test]
    fn a_correction_that_mends_the_wrong_thing_is_caught() {
        let body = [
            claim(
                "toy.right",
                "printed = \"2*x*x\"\ncorrection = { printed = \"x*x\" }",
            ),
            claim(
                "toy.wrong-fix",
                "printed = \"2*x*x\"\ncorrection = { printed = \"2*x\" }",
            ),
            claim("toy.implicit", "printed = \"2*x*x\"\ncorrected = \"x*x\""),
            claim("toy.none", "printed = \"2*x*x\""),
            claim(
                "toy.broken",
                "printed = \"2*x*x\"\ncorrection = { printed = \"x*z\" }",
            ),
            claim("toy.holds", "printed = \"x*x\""),
            claim(
                "toy.both",
                "printed = \"2*x*x\"\ncorrected = \"3*x*x\"\ncorrection = { printed = \"x*x\" }",
            ),
        ]
        .concat();
        let out = run(&body);
        let fix = |id: &str| out.iter().find(|(i, _)| i == id).expect(id).1;
        // the factor mended: holds; the exponent "mended" instead: fails; the `corrected` form
        // stands for a correction; none stated: none run; a correction that does not run (an
        // unknown symbol) is no correction; a claim that holds shows no finding; a correction
        // stated beside a `corrected` form is the one applied, the corrected form dropped
        assert_eq!(fix("toy.right"), Some((true, Verdict::Holds)));
        assert_eq!(fix("toy.wrong-fix"), Some((false, Verdict::Fails)));
        assert_eq!(fix("toy.implicit"), Some((true, Verdict::Holds)));
        assert_eq!(fix("toy.none"), None);
        assert_eq!(fix("toy.broken"), Some((false, Verdict::NotCheckable)));
        assert_eq!(fix("toy.holds"), None);
        assert_eq!(fix("toy.both"), Some((true, Verdict::Holds)));
    }

    #[test]
    fn the_keys_of_a_correction_replace_the_claims() {
        let spec = |keys: &str| -> ClaimSpec {
            toml::from_str(&format!(
                "id = \"t.a\"\nequation = \"(1)\"\nkind = \"identity\"\n{keys}"
            ))
            .unwrap()
        };
        let k = corrected_keys(&spec(
            "printed = \"a\"\nderived = \"b\"\ncorrected = \"c\"\ncorrection = { printed = \"d\" }",
        ))
        .unwrap();
        assert_eq!(k.get("printed").and_then(|v| v.as_str()), Some("d"));
        assert_eq!(k.get("derived").and_then(|v| v.as_str()), Some("b"));
        assert!(!k.contains_key("corrected"));
        let k = corrected_keys(&spec("printed = \"a\"\ncorrected = \"c\"")).unwrap();
        assert_eq!(k.get("printed").and_then(|v| v.as_str()), Some("c"));
        assert!(!k.contains_key("corrected"));
        assert!(corrected_keys(&spec("printed = \"a\"")).is_none());
        assert!(shows_finding(Verdict::Fails) && shows_finding(Verdict::HoldsWithCorrection));
        assert!(!shows_finding(Verdict::Holds) && !shows_finding(Verdict::NotCheckable));
    }
}
