//! A paper's units from its own words (issue 52): `verify audit PAPER` with no units file.
//!
//! The references are independent of the code under test: the test paper
//! (tests/papers/words/paper.tex) was written by hand, each quantity named in words in one of
//! the ways papers do, and its three unit errors planted by hand (a velocity equal to `2gH`, a
//! time equal to `L/c^2`, an angular momentum equal to a momentum); the units and the lines below
//! are read off the paper by hand. The seeds' counts are compared with the audits under the
//! claims' units (verify/*.toml, written by hand for the seeds' claims).

use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

#[path = "support/counts.rs"]
mod counts;
#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

const PAPER: &str = "tests/papers/words/paper.tex";

fn verify(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("verify runs")
}

fn json(out: &Output) -> Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("json")
}

fn symbol<'a>(audit: &'a Value, name: &str) -> &'a Value {
    audit["symbols"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == name)
        .unwrap_or_else(|| panic!("no symbol {name}"))
}

#[test]
fn the_planted_errors_are_found_from_the_words_alone_and_nothing_else() {
    let a = json(&verify(&["audit", PAPER, "--format", "json"]));
    let rels = a["relations"].as_array().unwrap();
    let bad: Vec<&str> = rels
        .iter()
        .filter(|r| r["status"] == "inconsistent")
        .map(|r| r["label"].as_str().unwrap_or("?"))
        .collect();
    assert_eq!(
        bad,
        ["eq:planted-v0", "eq:planted-T", "eq:planted-J"],
        "{a:#}"
    );
    // every other relation is decided, and consistent
    for r in rels.iter().filter(|r| r["status"] != "inconsistent") {
        assert_eq!(r["status"], "consistent", "{r}");
    }
    // each finding names the words that gave its units
    let planted_t = rels.iter().find(|r| r["label"] == "eq:planted-T").unwrap();
    let detail = planted_t["detail"].as_str().unwrap();
    assert!(detail.contains("in m^-1 s^2: `L/c^2`"), "{detail}");
    assert!(
        detail.contains("`T` in s (line 23: \"$T$ the duration of the contact\")"),
        "{detail}"
    );
}

#[test]
fn each_unit_from_the_words_carries_its_sentence_and_line() {
    let a = json(&verify(&["audit", PAPER, "--format", "json"]));
    // by hand: (symbol, unit, quantity, words of the quote, line)
    let want = [
        // a nomenclature table with units in brackets, taken as written
        (
            "E",
            "kg m^-1 s^-2",
            "written",
            "Young's modulus of the bar",
            12,
        ),
        ("rho", "kg m^-3", "written", "density of the bar", 13),
        ("c", "m s^-1", "written", "wave speed in the bar", 14),
        ("A", "m^2", "written", "cross-section of the bar", 15),
        // "<quantity> $x$"
        ("m", "kg", "mass", "A ball of mass $m$", 19),
        ("H", "m", "length", "falls from the height $H$", 19),
        ("L", "m", "length", "a bar of length $L$", 19),
        ("R", "m", "length", "the radius $R$", 21),
        // "where $x$ is", "$x$ denotes", "$x$ stands for", "$x$ is its"
        (
            "g",
            "m s^-2",
            "acceleration",
            "$g$ is the gravitational acceleration",
            19,
        ),
        (
            "v0",
            "m s^-1",
            "velocity",
            "$v_{0}$ denotes the impact velocity",
            20,
        ),
        (
            "J",
            "kg m^2",
            "moment_of_inertia",
            "$J$ is its moment of inertia",
            21,
        ),
        (
            "e",
            "1",
            "ratio",
            "$e$ stands for the coefficient of restitution",
            24,
        ),
        // a plural over a list, a list with "respectively"
        (
            "omega",
            "s^-1",
            "angular_velocity",
            "are the angular velocities",
            21,
        ),
        (
            "omegaplus",
            "s^-1",
            "angular_velocity",
            "are the angular velocities",
            21,
        ),
        ("mu", "1", "ratio", "the coefficient of friction", 22),
        ("Ft", "kg m s^-2", "force", "the tangential force", 22),
        ("N", "kg m s^-2", "force", "the normal reaction", 22),
        // "we denote by $x$ the <quantity>"
        ("T", "s", "time", "$T$ the duration of the contact", 23),
    ];
    for (name, unit, quantity, words, line) in want {
        let s = symbol(&a, name);
        assert_eq!(s["unit"], unit, "{s}");
        assert_eq!(s["source"], "words", "{s}");
        assert_eq!(s["quantity"], quantity, "{s}");
        assert!(s["quote"].as_str().unwrap().contains(words), "{s}");
        assert_eq!(s["line"], line, "{s}");
    }
    // a stiffness is left to its law (the inference gives it, from k = EA/L), a symbol the
    // paper defines in a display (p := m v_0) to the inference
    for (name, unit) in [("k", "kg s^-2"), ("p", "kg m s^-1")] {
        let s = symbol(&a, name);
        assert_eq!(s["unit"], unit, "{s}");
        assert_eq!(s["source"], "inferred", "{s}");
    }
    // the text report shows each source
    let text = String::from_utf8(verify(&["audit", PAPER]).stdout).unwrap();
    assert!(
        text.contains("words, line 19: \"$g$ is the gravitational acceleration\""),
        "{text}"
    );
    let md = String::from_utf8(verify(&["audit", PAPER, "--format", "markdown"]).stdout).unwrap();
    assert!(
        md.contains("| `m` | kg | words, line 19: \"A ball of mass $m$\" |"),
        "{md}"
    );
}

#[test]
fn a_units_file_overrides_the_words_and_says_so() {
    let dir = Scratch::new("words-override");
    let units = dir.join("units.toml");
    // by hand: c declared in km/s would be a different unit; the declared one is used
    std::fs::write(&units, "[symbols]\nc = \"m/s\"\nk = \"N/m\"\n").unwrap();
    let a = json(&verify(&[
        "audit",
        PAPER,
        "--units",
        units.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let c = symbol(&a, "c");
    assert_eq!(c["source"], "declared", "{c}");
    assert!(
        c["overrides"]
            .as_str()
            .unwrap()
            .contains("m s^-1 (line 14: \"$c$ wave speed in the bar [m s^-1]\")"),
        "{c}"
    );
    assert_eq!(symbol(&a, "k")["source"], "declared");
    // a unit from the file that contradicts the words: the file's is used, and the
    // relations that hold in the words' units are now inconsistent
    std::fs::write(&units, "[symbols]\nH = \"s\"\n").unwrap();
    let a = json(&verify(&[
        "audit",
        PAPER,
        "--units",
        units.to_str().unwrap(),
        "--format",
        "json",
    ]));
    let v0 = a["relations"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["label"] == "eq:v0")
        .unwrap();
    assert_eq!(v0["status"], "inconsistent", "{v0}");
}

#[test]
fn init_writes_the_units_of_the_words_each_with_its_quoted_source() {
    let out = verify(&["init", PAPER, "--paper", "ball"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains(
            "v0 = \"m s^-1\"    # from the words (velocity), line 20: \"$v_{0}$ denotes the impact velocity\""
        ),
        "{text}"
    );
    assert!(
        text.contains("A = \"m^2\"    # from the words (written), line 15:"),
        "{text}"
    );
}

#[test]
fn a_bad_vocabulary_exits_2_naming_it() {
    let dir = Scratch::new("words-vocabulary");
    let bad_unit = dir.join("bad_unit.toml");
    std::fs::write(
        &bad_unit,
        "[wobble]\nwords = [\"wobble\"]\nunit = \"furlong\"\n",
    )
    .unwrap();
    let out = verify(&["audit", PAPER, "--vocabulary", bad_unit.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad_unit.toml"), "{err}");
    assert!(err.contains("[wobble] unit = \"furlong\""), "{err}");
    assert!(err.contains("unknown unit `furlong`"), "{err}");

    let twice = dir.join("twice.toml");
    std::fs::write(
        &twice,
        "[grip]\nwords = [\"grip\"]\nunit = \"N\"\n\n[hold]\nwords = [\"Grips\"]\nunit = \"N\"\n",
    )
    .unwrap();
    let out = verify(&["audit", PAPER, "--vocabulary", twice.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the words \"Grips\" are given twice, in [grip] and [hold]"),
        "{err}"
    );

    // a good one is used: its words name a quantity the built-in vocabulary does not know
    let good = dir.join("good.toml");
    std::fs::write(
        &good,
        "[impedance]\nwords = [\"impedance\"]\nunit = \"kg/s\"\n",
    )
    .unwrap();
    let paper = dir.join("p.md");
    std::fs::write(
        &paper,
        "Here $Z$ is the impedance and $v$ is the velocity.\n\n$$ F = Z v $$\n",
    )
    .unwrap();
    let a = json(&verify(&[
        "audit",
        paper.to_str().unwrap(),
        "--vocabulary",
        good.to_str().unwrap(),
        "--format",
        "json",
    ]));
    assert_eq!(symbol(&a, "Z")["unit"], "kg s^-1");
    assert_eq!(symbol(&a, "F")["unit"], "kg m s^-2");
}

#[test]
fn the_seeds_from_their_words() {
    let seeds = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/seeds");
    if !seeds.is_dir() {
        println!("../shared/seeds is not here: the seeds' words are not read");
        return;
    }
    // (paper, claims, counts with no units file)
    let cases = [
        ("000", "verify/000_cone_plate.toml", [39, 3, 6, 3]),
        ("001", "verify/001_disk.toml", [75, 1, 20, 1]),
        // 002: the adjoint row with `\tilde{B}^{'}` (line 307) is read since the bare-sign
        // superscript is a mark; nothing in the words gives B a unit, so it is undetermined
        ("002", "verify/002_constrained_impact.toml", [78, 3, 58, 2]),
    ];
    for (paper, claims, want) in cases {
        let file = std::fs::read_dir(&seeds)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .find(|p| {
                p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with(&format!("{paper}_")))
            })
            .unwrap();
        let words = json(&verify(&[
            "audit",
            file.to_str().unwrap(),
            "--format",
            "json",
        ]));
        let declared = json(&verify(&[
            "audit",
            &format!("verify/tex/{paper}.tex"),
            "--units",
            claims,
            "--format",
            "json",
        ]));
        let (cw, cd) = (
            counts::status_counts(&words),
            counts::status_counts(&declared),
        );
        assert_eq!(cw, want, "{paper}");
        // at least 75 % of the relations the claims' units decide, decided from the words
        let decided = |c: [usize; 4]| c[0] + c[1];
        assert!(
            4 * decided(cw) >= 3 * decided(cd),
            "{paper}: {cw:?} against {cd:?}"
        );
        // no relation consistent under the claims' units is inconsistent from the words
        let (rw, rd) = (
            words["relations"].as_array().unwrap(),
            declared["relations"].as_array().unwrap(),
        );
        assert_eq!(rw.len(), rd.len(), "{paper}");
        for (w, d) in rw.iter().zip(rd) {
            let squeeze = |v: &Value| v.as_str().unwrap().split_whitespace().collect::<String>();
            assert_eq!(
                squeeze(&w["latex"]),
                squeeze(&d["latex"]),
                "{paper}: the two audits pair up"
            );
            if w["status"] == "inconsistent" {
                assert_eq!(d["status"], "inconsistent", "{paper}: {w}");
            }
        }
        if paper == "000" {
            // the two dimension findings: (15)'s A5 f^3, the operator's constant
            let eq15 = rw.iter().find(|r| r["number"] == "15").unwrap();
            assert_eq!(eq15["status"], "inconsistent", "{eq15}");
            assert!(
                eq15["detail"].as_str().unwrap().contains("`A5*f^3`"),
                "{eq15}"
            );
            let op = rw
                .iter()
                .find(|r| {
                    r["latex"]
                        .as_str()
                        .unwrap()
                        .starts_with("\\frac{\\tilde{E}}{1-\\tilde{v}^{2}}=E \\zeta")
                })
                .unwrap();
            assert_eq!(op["status"], "inconsistent", "{op}");
        }
    }
}
