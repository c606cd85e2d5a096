//! A claim kind is one type implementing `Kind` plus one registry entry: a toy kind (`even`:
//! the integer `n` is even) added in this test, without a line of the crate changed, runs
//! beside the built-in kinds; its keys are checked like theirs (an unknown key is an error
//! naming it) and a registry without it refuses the claim. The expected verdicts are
//! arithmetic (4 is even, 3 is not).

use impactcheck::verify::kinds::{self, Checked, Kind, Session};
use impactcheck::verify::{Head, Outcome, Verdict, VerifyError, load_claims, run_with};
use serde::Deserialize;

/// The keys of an `even` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct EvenSpec {
    n: i64,
}

/// A checked `even` claim.
struct Even {
    n: i64,
}

impl Kind for Even {
    const NAME: &'static str = "even";
    type Spec = EvenSpec;

    fn validate(_: &Checked, _: &Head, s: EvenSpec) -> Result<Self, VerifyError> {
        Ok(Even { n: s.n })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let verdict = if self.n % 2 == 0 {
            Verdict::Holds
        } else {
            Verdict::Fails
        };
        Ok(cx.outcome(c, verdict, format!("n = {} mod 2 = {}", self.n, self.n % 2)))
    }

    fn report(&self, _: &Head) -> String {
        "Kind `even`: the remainder of n by 2.".into()
    }
}

fn claims(name: &str, body: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-kinds-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    let p = d.join("claims.toml");
    let head = "paper = \"toy\"\ntitle = \"toy\"\nreport = \"toy.md\"\n[symbols]\nx = \"m\"\n";
    std::fs::write(&p, format!("{head}{body}")).expect("write");
    p
}

fn claim(id: &str, kind: &str, keys: &str) -> String {
    format!(
        "[[claim]]\nid = \"{id}\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"{kind}\"\n{keys}\n"
    )
}

#[test]
fn a_toy_kind_is_one_type_and_one_registry_entry() {
    let body = [
        claim("toy.four", "even", "n = 4"),
        claim("toy.three", "even", "n = 3"),
        claim(
            "toy.square",
            "identity",
            "printed = \"x*x\"\nderived = \"x^2\"",
        ),
    ]
    .concat();
    let p = claims("toy", &body);
    let papers = load_claims(&p).expect("loads");
    let mut table = kinds::BUILTIN.to_vec();
    table.push(kinds::kind::<Even>());
    let out = run_with(&papers, p.parent().expect("dir"), &table).expect("runs");
    let got: Vec<(&str, Verdict, &str)> = out
        .iter()
        .map(|o| (o.id.as_str(), o.verdict, o.kind.as_str()))
        .collect();
    assert_eq!(
        got,
        vec![
            ("toy.four", Verdict::Holds, "even"),
            ("toy.square", Verdict::Holds, "identity"),
            ("toy.three", Verdict::Fails, "even"),
        ]
    );
    assert_eq!(
        out[0].extra_md.as_deref(),
        Some("Kind `even`: the remainder of n by 2.")
    );

    // the toy's keys are checked like a built-in kind's
    let bad = claims("toy-bad", &claim("toy.bad", "even", "n = 4\nm = 2"));
    let papers = load_claims(&bad).expect("loads");
    let err = run_with(&papers, bad.parent().expect("dir"), &table)
        .expect_err("an unknown key is refused")
        .to_string();
    assert!(
        err.contains("claim toy.bad: m: kind `even` does not take this key; allowed: `n`"),
        "{err}"
    );

    // without its registry entry the kind is unknown, and the message lists the kinds there are
    let papers = load_claims(&p).expect("loads");
    let err = run_with(&papers, p.parent().expect("dir"), kinds::BUILTIN)
        .expect_err("unknown without its entry")
        .to_string();
    assert!(
        err.contains("kind: unknown kind `even`; allowed: identity"),
        "{err}"
    );
}
