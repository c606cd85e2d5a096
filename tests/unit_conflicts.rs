//! The blame of a unit conflict (issue 65): a relation whose every symbol has a declared unit and
//! whose sides differ is `inconsistent`, whatever else the paper holds and in whatever order its
//! displays come; two relations that disagree with nothing to decide between them are both
//! `inconsistent`, each naming the other; and the cart of the issue, audited with a units file.
//!
//! The relations are generated as text: declared symbols `d0..d4` with random units over kg, m
//! and s (exponents -2..2, a pure number among them), undeclared `u0..u3`, relations that are
//! products and quotients of them, sums of two such terms, and the planted one: two products of
//! declared symbols whose units differ (the generator draws until they do, and the test computes
//! both units itself, from the exponents, not through the code under test). The textbook cases
//! are in every draw's reach: a planted relation alone, one that repeats another relation, a
//! relation of declared symbols that holds, an undeclared symbol on both sides.

#[path = "support/scratch.rs"]
mod scratch;

use impactcheck::algebra::expr::parse;
use impactcheck::algebra::units::Unit;
use impactcheck::paper::units::{Relation, Status, infer};
use proptest::prelude::*;
use scratch::Scratch;
use std::collections::BTreeMap;

/// A relation of the text `a = b`.
fn rel(text: &str) -> Option<Relation> {
    Some(Relation {
        sides: text.split('=').map(|s| parse(s).expect("parses")).collect(),
        dots: vec![],
        rels: vec![],
    })
}

/// A unit from exponents of kg, m, s.
fn unit(e: [i64; 3]) -> Unit {
    let mut text = Vec::new();
    for (name, k) in ["kg", "m", "s"].iter().zip(e) {
        if k != 0 {
            text.push(format!("{name}^{k}"));
        }
    }
    if text.is_empty() {
        Unit::parse("1").expect("parses")
    } else {
        Unit::parse(&text.join(" ")).expect("parses")
    }
}

/// A product of symbols with exponents, as text, and its exponent vector over the declared
/// symbols' units (`None` when it names an undeclared symbol).
fn product(factors: &[(usize, i64)], units: &[[i64; 3]]) -> (String, Option<[i64; 3]>) {
    let mut text = Vec::new();
    let mut e = Some([0i64; 3]);
    for &(s, k) in factors {
        let name = if s < units.len() {
            format!("d{s}")
        } else {
            format!("u{}", s - units.len())
        };
        text.push(if k == 1 {
            name
        } else {
            format!("{name}^({k})")
        });
        match (e.as_mut(), units.get(s)) {
            (Some(acc), Some(u)) => {
                for j in 0..3 {
                    acc[j] += k * u[j];
                }
            }
            _ => e = None,
        }
    }
    (text.join("*"), e)
}

fn exponents() -> impl Strategy<Value = [i64; 3]> {
    [-2i64..=2, -2i64..=2, -2i64..=2]
}

fn factors(symbols: usize) -> impl Strategy<Value = Vec<(usize, i64)>> {
    proptest::collection::vec(
        (0..symbols, prop_oneof![Just(1i64), Just(2), Just(-1)]),
        1..4,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn a_relation_of_declared_symbols_whose_sides_differ_is_inconsistent_in_any_order(
        units in proptest::collection::vec(exponents(), 5),
        others in proptest::collection::vec((factors(9), factors(9), proptest::bool::ANY), 0..7),
        planted in (factors(5), factors(5)),
        rotate in 0usize..8,
        repeat in proptest::bool::ANY,
    ) {
        let declared: BTreeMap<String, Unit> = units
            .iter()
            .enumerate()
            .map(|(k, e)| (format!("d{k}"), unit(*e)))
            .collect();
        let (left, lu) = product(&planted.0, &units);
        let (right, ru) = product(&planted.1, &units);
        // the planted relation's sides differ in unit (computed here, from the exponents)
        prop_assume!(lu.is_some() && ru.is_some() && lu != ru);
        let mut texts: Vec<String> = others
            .iter()
            .map(|(a, b, sum)| {
                let (a, _) = product(a, &units);
                let (b, _) = product(b, &units);
                if *sum { format!("{a} = {b} + {a}") } else { format!("{a} = {b}") }
            })
            .collect();
        let at = rotate % (texts.len() + 1);
        texts.insert(at, format!("{left} = {right}"));
        if repeat {
            // the same wrong relation printed twice: both are wrong
            texts.push(format!("{left} = {right}"));
        }
        let relations: Vec<Option<Relation>> = texts.iter().map(|t| rel(t)).collect();
        let inf = infer(&relations, &declared);
        prop_assert!(
            matches!(inf.statuses[at], Status::Inconsistent { .. }),
            "{} in {:?}: {:?}", texts[at], texts, inf.statuses[at]
        );
        if repeat {
            let last = matches!(inf.statuses.last(), Some(Status::Inconsistent { .. }));
            prop_assert!(last, "the repeat: {:?}", inf.statuses.last());
        }
        // in the reverse order too
        let reversed: Vec<Option<Relation>> = relations.iter().rev().cloned().collect();
        let back = infer(&reversed, &declared);
        let reversed_at = &back.statuses[relations.len() - 1 - at];
        let blamed = matches!(reversed_at, Status::Inconsistent { .. });
        prop_assert!(blamed, "reversed: {:?}", reversed_at);
    }

    #[test]
    fn two_relations_that_disagree_on_an_undeclared_symbol_are_both_blamed_in_any_order(
        units in proptest::collection::vec(exponents(), 5),
        a in factors(5),
        b in factors(5),
        others in proptest::collection::vec((factors(5), factors(5)), 0..4),
        first in proptest::bool::ANY,
    ) {
        let declared: BTreeMap<String, Unit> = units
            .iter()
            .enumerate()
            .map(|(k, e)| (format!("d{k}"), unit(*e)))
            .collect();
        let (ta, ua) = product(&a, &units);
        let (tb, ub) = product(&b, &units);
        prop_assume!(ua != ub);
        // relations of declared symbols that hold (each side the same product)
        let mut texts: Vec<String> = others
            .iter()
            .map(|(x, _)| {
                let (x, _) = product(x, &units);
                format!("{x} = {x}")
            })
            .collect();
        let (one, two) = (format!("p = {ta}"), format!("p = {tb}"));
        if first {
            texts.insert(0, one);
            texts.push(two);
        } else {
            texts.insert(0, two);
            texts.push(one);
        }
        let relations: Vec<Option<Relation>> = texts.iter().map(|t| rel(t)).collect();
        let inf = infer(&relations, &declared);
        let last = texts.len() - 1;
        for (i, other) in [(0, last), (last, 0)] {
            let Status::Inconsistent { against, .. } = &inf.statuses[i] else {
                return Err(TestCaseError::fail(format!("{}: {:?}", texts[i], inf.statuses[i])));
            };
            prop_assert!(against.contains(&other), "{}: {against:?}", texts[i]);
        }
        for i in 1..last {
            prop_assert_eq!(&inf.statuses[i], &Status::Consistent);
        }
    }
}

/// The cart of issue 65, with a units file: `F t = m v` holds, `p = m v^2` and `p = F t`
/// disagree on p and nothing decides which is wrong; the order of the displays changes nothing.
#[test]
fn the_cart_blames_both_relations_that_disagree_on_p() {
    let dir = Scratch::new("cart");
    let units = dir.join("units.toml");
    std::fs::write(
        &units,
        "[symbols]\nm = \"kg\"\nv = \"m/s\"\nF = \"N\"\nt = \"s\"\n",
    )
    .expect("writes");
    let displays = [r"F t = m v", r"p = m v^{2}", r"p = F t"];
    for order in [[0, 1, 2], [2, 1, 0], [1, 2, 0]] {
        let mut tex = String::from(
            "\\documentclass{article}\n\\begin{document}\nA cart of mass $m$ moves at the speed $v$ under the force $F$ during the time $t$.\n",
        );
        for k in order {
            tex.push_str(&format!(
                "\\begin{{equation}} {} \\label{{eq:{k}}} \\end{{equation}}\n",
                displays[k]
            ));
        }
        tex.push_str("\\end{document}\n");
        let paper = dir.join("paper.tex");
        std::fs::write(&paper, &tex).expect("writes");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(["audit"])
            .arg(&paper)
            .arg("--units")
            .arg(&units)
            .args(["--format", "json"])
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
        let rels = json["relations"].as_array().expect("relations");
        let status = |k: usize| {
            let at = order.iter().position(|&j| j == k).unwrap();
            (
                rels[at]["status"].as_str().unwrap().to_string(),
                rels[at]["detail"].as_str().unwrap().to_string(),
            )
        };
        assert_eq!(status(0).0, "consistent", "{order:?}");
        for (bad, other) in [(1, 2), (2, 1)] {
            let (s, detail) = status(bad);
            assert_eq!(s, "inconsistent", "{order:?}: {detail}");
            let number = order.iter().position(|&j| j == other).unwrap() + 1;
            assert!(
                detail.contains(&format!(
                    "it and ({number}) cannot both hold: one of them is wrong"
                )),
                "{order:?}: {detail}"
            );
        }
    }
}

/// `verify audit --suggest`: `F = m a`, `E = F x`, `P = E/t` hold seven symbols in three
/// independent equations, so four units must be given (counted by hand: 7 - 3); given the units
/// the suggestion asks for (any units), every relation is decided. With F declared, three.
#[test]
fn the_suggestion_names_the_fewest_symbols_that_decide_every_relation() {
    let dir = Scratch::new("suggest");
    let paper = dir.join("paper.tex");
    std::fs::write(
        &paper,
        "\\begin{equation} F = m a \\end{equation}\n\\begin{equation} E = F x \\end{equation}\n\\begin{equation} P = E / t \\end{equation}\n",
    )
    .expect("writes");
    let run = |extra: &[&std::ffi::OsStr]| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .arg("audit")
            .arg(&paper)
            .args(extra)
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).expect("utf-8")
    };
    let suggested = run(&["--suggest".as_ref()]);
    assert_eq!(suggested.matches("= \"?\"").count(), 4, "{suggested}");
    let units = dir.join("units.toml");
    std::fs::write(&units, suggested.replace("\"?\"", "\"kg m\"")).expect("writes");
    let audited = run(&["--units".as_ref(), units.as_os_str()]);
    assert!(audited.contains("3 relations: 3 consistent"), "{audited}");
    std::fs::write(&units, "[symbols]\nF = \"N\"\n").expect("writes");
    let again = run(&["--units".as_ref(), units.as_os_str(), "--suggest".as_ref()]);
    assert_eq!(again.matches("= \"?\"").count(), 3, "{again}");
    assert!(again.contains("F = \"N\""), "{again}");
}
