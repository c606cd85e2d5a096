//! The verifier's power over its own checks (`verify --power`): each printed side is misprinted
//! and checked again. The expectations are algebra done by hand: every misprint of `x*x` (a
//! coefficient, an exponent, a sign, `x` swapped for `y`) is a polynomial other than `x^2`, so
//! an identity check kills them all; a unit check cannot see `2*(x^2/y + y)` against `x^2/y + y`, so a
//! dimension claim is weak and says why; a failing claim is not measured.

use impactcheck::verify::{Verdict, kinds, load_claims, run_measured};

fn claims(name: &str, body: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-power-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    let p = d.join("claims.toml");
    let head =
        "paper = \"toy\"\ntitle = \"toy\"\nreport = \"toy.md\"\n[symbols]\nx = \"m\"\ny = \"m\"\n";
    std::fs::write(&p, format!("{head}{body}")).expect("write");
    p
}

fn claim(id: &str, kind: &str, keys: &str) -> String {
    format!(
        "[[claim]]\nid = \"{id}\"\nequation = \"(1)\"\nquote = \"q\"\nkind = \"{kind}\"\n{keys}\n"
    )
}

#[test]
fn misprints_are_killed_or_the_claim_is_weak_and_says_why() {
    let body = [
        claim(
            "toy.square",
            "identity",
            "printed = \"x*x\"\nderived = \"x^2\"",
        ),
        claim(
            "toy.length",
            "dimension",
            "printed = \"x^2/y + y\"\nexpect = \"m\"",
        ),
        claim(
            "toy.length-said",
            "dimension",
            "printed = \"3*x\"\nexpect = \"m\"\nblind = \"the factor 3\"",
        ),
        claim(
            "toy.wrong",
            "identity",
            "printed = \"2*x*x\"\nderived = \"x^2\"",
        ),
    ]
    .concat();
    let p = claims("toy", &body);
    let papers = load_claims(&p).expect("loads");
    let root = p.parent().expect("dir");
    let out = run_measured(&papers, root, kinds::BUILTIN, &|_| true).expect("runs");
    let get = |id: &str| out.iter().find(|o| o.id == id).expect(id);

    let square = get("toy.square");
    assert_eq!(square.verdict, Verdict::Holds);
    let power = square.power.as_ref().expect("measured");
    // x2, x1/2, x1.1, x0.9, negated, `x` -> `y` (once: both swaps give x*y)
    assert_eq!(power.mutants, 6, "{power:?}");
    assert_eq!(power.killed, power.mutants, "{power:?}");
    assert!(!power.weak());

    let length = get("toy.length");
    let power = length.power.as_ref().expect("measured");
    assert!(power.weak(), "{power:?}");
    assert!(
        power
            .survivors
            .iter()
            .any(|s| s == "printed: the whole side x2"),
        "{power:?}"
    );
    assert!(
        power.blind.as_deref().unwrap_or("").contains("unit check"),
        "the kind says what it cannot see: {power:?}"
    );
    // `x^2/y` -> `x^3/y` changes the unit: a dimension check is not blind to everything
    assert!(power.killed > 0, "{power:?}");

    let said = get("toy.length-said").power.as_ref().expect("measured");
    assert_eq!(said.blind.as_deref(), Some("the factor 3"));

    let wrong = get("toy.wrong");
    assert_eq!(wrong.verdict, Verdict::Fails);
    let power = wrong.power.as_ref().expect("measured");
    assert!(
        power.not_measured.is_some() && power.mutants == 0,
        "{power:?}"
    );

    // nothing picked, nothing measured
    let out = run_measured(&papers, root, kinds::BUILTIN, &|_| false).expect("runs");
    assert!(out.iter().all(|o| o.power.is_none()));
}
