//! `printed_from` and `printed_tex`: a claim's printed side read from the paper's LaTeX reaches
//! the verdicts of the retyped formula (000 (16): A5 and A6 against the Galerkin derivations, for
//! equal and unequal modes), a misprint pasted as LaTeX fails, and a tag or left side that is
//! not in the paper stops validation with exit 2 naming the claim and the key. The references
//! are the retyped formulas of `verify/000_cone_plate.toml` (typed by hand from the paper).

use std::path::{Path, PathBuf};
use std::process::Command;

const A5: &str = "E*m^2*n^2*pi^4*b/(64*a^3) + E*m^2*n^2*pi^4*a/(64*b^3)";
const A6: &str = "m^2*n^2*pi^4*b/(64*a^3)*eta + m^2*n^2*pi^4*a/(64*b^3)*eta";

/// A claims file for paper 000 in a fresh folder, with the paper's displays beside it.
fn claims_dir(name: &str, body: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impactcheck-tex-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("tex")).expect("temp dir");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(root.join("verify/tex/000.tex"), d.join("tex/000.tex")).expect("copy");
    let head = "paper = \"000\"\ntitle = \"t\"\nreport = \"t.md\"\n[symbols]\nE = \"Pa\"\neta = \"Pa s\"\na = \"m\"\nb = \"m\"\nm = \"1\"\nn = \"1\"\n";
    std::fs::write(d.join("claims.toml"), format!("{head}{body}")).expect("write");
    d
}

fn claim(id: &str, printed: &str, derived: &str, modes: &str) -> String {
    format!(
        "[[claim]]\nid = \"{id}\"\nequation = \"(16)\"\nquote = \"q\"\nkind = \"identity\"\n{printed}\nderived = \"{derived}\"\nmodes = {modes}\n"
    )
}

/// The verdict of every claim, by id.
fn verdicts(dir: &Path) -> Vec<(String, String)> {
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args([
            "--claims",
            dir.join("claims.toml").to_str().expect("utf-8"),
            "--format",
            "json",
        ])
        .output()
        .expect("runs");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|_| panic!("json: {}", String::from_utf8_lossy(&out.stderr)));
    v["claims"]
        .as_array()
        .expect("claims")
        .iter()
        .map(|c| {
            (
                c["id"].as_str().unwrap_or("").into(),
                c["verdict"].as_str().unwrap_or("").into(),
            )
        })
        .collect()
}

#[test]
fn the_papers_latex_reaches_the_verdicts_of_the_retyped_formula() {
    let equal = "[[1, 1], [3, 3]]";
    let unequal = "[[1, 3], [3, 5]]";
    let mut body = String::new();
    for (name, typed, derived) in [
        ("A5", A5, "E*@galerkin.cubic"),
        ("A6", A6, "2*eta*@galerkin.cubic"),
    ] {
        let k = &name[1..];
        for (which, modes) in [("equal", equal), ("unequal", unequal)] {
            body += &claim(
                &format!("typed.{name}.{which}"),
                &format!("printed = \"{typed}\""),
                derived,
                modes,
            );
            body += &claim(
                &format!("tex.{name}.{which}"),
                &format!("printed_from = {{ tag = \"(16)\", lhs = \"A_{{{k}}}\" }}"),
                derived,
                modes,
            );
        }
    }
    // A5 pasted as LaTeX, correct and with a misprint (a^{3} -> a^{2})
    body += &claim(
        "pasted.A5.equal",
        r#"printed_tex = 'E \frac{m^{2} n^{2} \pi^{4} b}{64 a^{3}}+E \frac{m^{2} n^{2} \pi^{4} a}{64 b^{3}}'"#,
        "E*@galerkin.cubic",
        equal,
    );
    body += &claim(
        "misprint.A5.equal",
        r#"printed_tex = 'E \frac{m^{2} n^{2} \pi^{4} b}{64 a^{2}}+E \frac{m^{2} n^{2} \pi^{4} a}{64 b^{3}}'"#,
        "E*@galerkin.cubic",
        equal,
    );
    let v = verdicts(&claims_dir("verdicts", &body));
    let get = |id: &str| {
        v.iter()
            .find(|(i, _)| i == id)
            .map(|x| x.1.clone())
            .unwrap_or_default()
    };
    for name in ["A5", "A6"] {
        for which in ["equal", "unequal"] {
            let (typed, tex) = (
                get(&format!("typed.{name}.{which}")),
                get(&format!("tex.{name}.{which}")),
            );
            assert!(!typed.is_empty(), "{name} {which}: {v:?}");
            assert_eq!(typed, tex, "{name}, {which} modes");
        }
    }
    // the paper's A5 is right for equal modes and wrong for unequal ones; A6 misses a factor 2
    assert_eq!(get("tex.A5.equal"), "holds");
    assert_eq!(get("tex.A5.unequal"), "fails");
    assert_eq!(get("tex.A6.equal"), "fails");
    assert_eq!(get("pasted.A5.equal"), "holds");
    assert_eq!(get("misprint.A5.equal"), "fails");
}

#[test]
fn a_tag_or_left_side_not_in_the_paper_stops_validation() {
    for (name, from, says) in [
        (
            "lhs",
            "printed_from = { tag = \"(16)\", lhs = \"A_{99}\" }",
            "left side",
        ),
        (
            "tag",
            "printed_from = { tag = \"(99)\" }",
            "no display is tagged (99)",
        ),
        (
            "key",
            "printed_from = { tag = \"(16)\", row = 2 }",
            "unknown key `row`",
        ),
    ] {
        let d = claims_dir(
            name,
            &claim("bad.from", from, "E*@galerkin.cubic", "[[1, 1]]"),
        );
        let out = Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(["--claims", d.join("claims.toml").to_str().expect("utf-8")])
            .output()
            .expect("runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains("bad.from") && err.contains("printed_from") && err.contains(says),
            "{name}: {err}"
        );
    }
}
