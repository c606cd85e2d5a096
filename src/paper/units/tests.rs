//! The inference's unit tests.

use super::*;
use crate::algebra::expr::parse;
use std::collections::BTreeMap;

fn rel(text: &str) -> Option<Relation> {
    let sides = text.split('=').map(|s| parse(s).unwrap()).collect();
    Some(Relation {
        sides,
        dots: vec![],
        rels: vec![],
    })
}

fn units(pairs: &[(&str, &str)]) -> BTreeMap<String, Unit> {
    pairs
        .iter()
        .map(|(n, u)| (n.to_string(), Unit::parse(u).unwrap()))
        .collect()
}

fn unit_of(inf: &Inference, name: &str) -> Option<String> {
    inf.symbols
        .iter()
        .find(|s| s.name == name)
        .and_then(|s| s.unit.map(|u| u.to_string()))
}

#[test]
fn units_flow_through_a_chain_of_relations() {
    // F = k x, a = F/m, v = a t, E = m v^2/2: from m, x, t and F's unit, by hand
    // k = N/m = kg s^-2, a = m s^-2, v = m s^-1, E = J
    let rs = [
        rel("F = k*x"),
        rel("a = F/m"),
        rel("v = a*t"),
        rel("E = m*v^2/2"),
    ];
    let d = units(&[("m", "kg"), ("x", "m"), ("t", "s"), ("F", "N")]);
    let inf = infer(&rs, &d);
    assert!(
        inf.statuses.iter().all(|s| *s == Status::Consistent),
        "{:?}",
        inf.statuses
    );
    assert_eq!(unit_of(&inf, "k").as_deref(), Some("kg s^-2"));
    assert_eq!(unit_of(&inf, "v").as_deref(), Some("m s^-1"));
    assert_eq!(unit_of(&inf, "E").as_deref(), Some("kg m^2 s^-2"));
    // E's unit came from a = F/m, v = a t and its own relation, not from F = k x
    let e = inf.symbols.iter().find(|s| s.name == "E").unwrap();
    assert_eq!(e.from, vec![1, 2, 3]);
    assert!(!e.declared);
}

#[test]
fn a_bad_relation_is_named_and_does_not_poison_the_rest() {
    // the third says v = a t^2 (m), the fourth v = x/t (m/s): v is declared nowhere, so the
    // two disagree and nothing decides which is wrong: both are blamed, each naming the other;
    // a = F/m, the only relation with `a` alone on its left, is the paper's definition of a
    // and is not blamed (a smallest set that spares it corrects as well); E's unit needs v's
    let rs = [
        rel("F = k*x"),
        rel("a = F/m"),
        rel("v = a*t^2"),
        rel("v = x/t"),
        rel("E = m*v^2/2"),
    ];
    let d = units(&[("m", "kg"), ("x", "m"), ("t", "s"), ("F", "N")]);
    // in any order of the relations
    for shift in 0..rs.len() {
        let order: Vec<usize> = (0..rs.len()).map(|k| (k + shift) % rs.len()).collect();
        let shuffled: Vec<Option<Relation>> = order.iter().map(|&k| rs[k].clone()).collect();
        let inf = infer(&shuffled, &d);
        let at = |k: usize| &inf.statuses[order.iter().position(|&j| j == k).unwrap()];
        let index = |k: usize| order.iter().position(|&j| j == k).unwrap();
        for (bad, other) in [(2, 3), (3, 2)] {
            let Status::Inconsistent { against, .. } = at(bad) else {
                panic!("{bad}: {:?}", inf.statuses)
            };
            assert!(against.contains(&index(other)), "{bad}: {against:?}");
        }
        for k in [0, 1] {
            assert_eq!(*at(k), Status::Consistent, "{k}: {:?}", inf.statuses);
        }
        assert!(
            matches!(at(4), Status::Undetermined(v) if v.contains(&"v".to_string())),
            "{:?}",
            at(4)
        );
        assert_eq!(unit_of(&inf, "k").as_deref(), Some("kg s^-2"));
    }
    // with v declared, only the wrong one is blamed, against the declared units alone
    let d = units(&[
        ("m", "kg"),
        ("x", "m"),
        ("t", "s"),
        ("F", "N"),
        ("v", "m/s"),
    ]);
    let inf = infer(&rs, &d);
    assert!(matches!(&inf.statuses[2], Status::Inconsistent { .. }));
    for i in [0, 1, 3, 4] {
        assert_eq!(
            inf.statuses[i],
            Status::Consistent,
            "{i}: {:?}",
            inf.statuses
        );
    }
    assert_eq!(unit_of(&inf, "E").as_deref(), Some("kg m^2 s^-2"));
    let Status::Inconsistent {
        left,
        left_unit,
        right,
        right_unit,
        what,
        ..
    } = &inf.statuses[2]
    else {
        unreachable!()
    };
    assert_eq!((left.as_str(), left_unit.as_str()), ("v", "m s^-1"));
    assert_eq!((right.as_str(), right_unit.as_str()), ("a*t^2", "m"));
    assert_eq!(what, "the sides");
}

#[test]
fn sums_functions_and_powers_constrain() {
    // x0 + v t: v is m/s; exp(-c t/m) makes c kg/s; sqrt(k/m) is 1/s; w^(3/2) scales
    let rs = [
        rel("y = x0 + v*t"),
        rel("z = exp(-c*t/m)"),
        rel("om = sqrt(kk/m)"),
        rel("P = q*w^(3/2)"),
    ];
    let d = units(&[
        ("m", "kg"),
        ("x0", "m"),
        ("t", "s"),
        ("kk", "N/m"),
        ("w", "m"),
        ("P", "N"),
    ]);
    let inf = infer(&rs, &d);
    assert_eq!(unit_of(&inf, "v").as_deref(), Some("m s^-1"));
    assert_eq!(unit_of(&inf, "c").as_deref(), Some("kg s^-1"));
    assert_eq!(unit_of(&inf, "z").as_deref(), Some("1"));
    assert_eq!(unit_of(&inf, "om").as_deref(), Some("s^-1"));
    assert_eq!(unit_of(&inf, "q").as_deref(), Some("kg m^(-1/2) s^-2"));
    assert_eq!(inf.statuses[3], Status::Consistent);
}

#[test]
fn a_sign_or_step_of_a_dimensional_argument_is_a_pure_number() {
    // y = a sign(v) with v in m/s: sign takes any unit and gives 1, as heaviside does
    let d = units(&[("y", "m"), ("a", "m"), ("v", "m/s")]);
    for text in ["y = a*sign(v)", "y = a*heaviside(v)"] {
        let inf = infer(&[rel(text)], &d);
        assert_eq!(inf.statuses[0], Status::Consistent, "{text}");
    }
    // and a sign is no length: y = sign(v) is a unit error
    let inf = infer(&[rel("y = sign(v)")], &d);
    assert!(matches!(inf.statuses[0], Status::Inconsistent { .. }));
}

#[test]
fn nothing_fixes_a_lone_ratio() {
    // a = b c with only a known: b and c are open, named
    let inf = infer(&[rel("a = b*c")], &units(&[("a", "m")]));
    assert_eq!(
        inf.statuses[0],
        Status::Undetermined(vec!["b".into(), "c".into()])
    );
    assert_eq!(unit_of(&inf, "b"), None);
}

#[test]
fn applications_and_dots_take_their_base_unit() {
    // m zdd = -P with z in m, P in N and t in s: m is kg; zd = z per second
    let mut r = Relation {
        sides: vec![
            parse("m*zdd").unwrap(),
            Expr::Neg(Box::new(Expr::Sym("{P(t)}".into()))),
        ],
        dots: vec![],
        rels: vec![],
    };
    r.dots = vec![("zdd".into(), "z".into(), 2), ("zd".into(), "z".into(), 1)];
    let inf = infer(
        &[Some(r.clone())],
        &units(&[("z", "m"), ("P", "N"), ("t", "s")]),
    );
    assert_eq!(unit_of(&inf, "m").as_deref(), Some("kg"));
    assert_eq!(unit_of(&inf, "zd").as_deref(), Some("m s^-1"));
    // a dot is per unit of t, whatever it is: with t declared in kg (any other unit), zd
    // is m/kg, as z/t is
    let inf = infer(
        &[Some(r.clone())],
        &units(&[("z", "m"), ("P", "N"), ("t", "kg")]),
    );
    assert_eq!(unit_of(&inf, "zd").as_deref(), Some("kg^-1 m"));
    // and with t undeclared, a nondimensional `zd = z` is consistent (t a pure number)
    let own = Relation {
        sides: vec![parse("zd").unwrap(), parse("z").unwrap()],
        dots: vec![("zd".into(), "z".into(), 1)],
        rels: vec![],
    };
    let inf = infer(&[Some(own)], &BTreeMap::new());
    assert!(!matches!(inf.statuses[0], Status::Inconsistent { .. }));
    assert_eq!(unit_name("{w(x,y,t)}"), "w");
    assert_eq!(unit_name("{int_S w dS}"), "{int_S w dS}");
}

/// The units of the two sides of an inconsistent relation.
fn side_units(s: &Status) -> (&String, &String) {
    let Status::Inconsistent {
        left_unit,
        right_unit,
        ..
    } = s
    else {
        panic!("not inconsistent: {s:?}")
    };
    (left_unit, right_unit)
}

#[test]
fn an_inconsistency_through_an_unknown_shows_the_unknown_with_its_base_unit() {
    // a q + b q^2 + c q^3 with a in m, b in m s, c in s: the first two terms need q in
    // 1/s, the first and the last q^2 in m/s: no unit of q serves. Each pair alone leaves
    // q free, so the sides are shown with q: `m [q]` for a q (by hand)
    let inf = infer(
        &[rel("y = a*q + b*q^2 + c*q^3")],
        &units(&[("a", "m"), ("b", "m s"), ("c", "s")]),
    );
    let (left_unit, right_unit) = side_units(&inf.statuses[0]);
    let both = format!("{left_unit} | {right_unit}");
    assert!(both.contains("m [q]"), "{both}");
}

#[test]
fn a_declared_relation_that_is_wrong_is_inconsistent() {
    let inf = infer(
        &[rel("F = m*x")],
        &units(&[("F", "N"), ("m", "kg"), ("x", "m")]),
    );
    let (left_unit, right_unit) = side_units(&inf.statuses[0]);
    assert_eq!(
        (left_unit.as_str(), right_unit.as_str()),
        ("kg m s^-2", "kg m")
    );
    // and unreadable input has no status of its own
    let inf = infer(&[None, rel("F = m*x")], &units(&[("F", "N")]));
    assert_eq!(inf.statuses[0], Status::Undetermined(vec![]));
}

/// `F = m a`, `E = F x`, `P = E/t`: seven symbols, three independent equations, so four units
/// to give (counted by hand). The picks, by hand: E and F are open in two undetermined
/// relations each (E first by name); with E and F given, x is fixed by `E = F x`; then P, a, m
/// and t are each open in one, P first by name (upper case sorts first), which fixes t; then a,
/// which fixes m.
#[test]
fn the_fewest_symbols_that_decide_every_relation() {
    let rs = [rel("F = m*a"), rel("E = F*x"), rel("P = E/t")];
    let picks = suggest::critical_symbols(&rs, &BTreeMap::new());
    let names: Vec<&str> = picks.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["E", "F", "P", "a"]);
    assert_eq!(picks[0].1, [1, 2]);
    assert_eq!(picks[3].1, [0]);
    // given those (any units), every relation is decided
    let given = units(&[("E", "J"), ("F", "N"), ("P", "W"), ("a", "m/s^2")]);
    let inf = infer(&rs, &given);
    assert!(
        inf.statuses.iter().all(|s| *s == Status::Consistent),
        "{:?}",
        inf.statuses
    );
    // a declared unit is one fewer to give, and is never suggested
    let picks = suggest::critical_symbols(&rs, &units(&[("F", "N")]));
    assert_eq!(picks.len(), 3, "{picks:?}");
    assert!(picks.iter().all(|(n, _)| n != "F"));
    // everything declared: nothing to give
    let all = units(&[
        ("F", "N"),
        ("m", "kg"),
        ("a", "m/s^2"),
        ("E", "J"),
        ("x", "m"),
        ("P", "W"),
        ("t", "s"),
    ]);
    assert!(suggest::critical_symbols(&rs, &all).is_empty());
    // relations called inconsistent are decided already: v = x/t and v = x t (x, t declared)
    // blame each other, and nothing is left to give; with a third relation on w that holds,
    // w's unit is fixed through neither of them and is to give
    let rs = [rel("v = x/t"), rel("v = x*t")];
    assert!(suggest::critical_symbols(&rs, &units(&[("x", "m"), ("t", "s")])).is_empty());
    let rs = [rel("v = x/t"), rel("v = x*t"), rel("w = q*x")];
    let picks = suggest::critical_symbols(&rs, &units(&[("x", "m"), ("t", "s")]));
    assert_eq!(picks, [("q".to_string(), vec![2])]);
}

#[test]
fn a_letter_as_an_index_exponent_is_not_the_quantity_it_names_elsewhere() {
    // m a mass in F = m a, and m the power of lambda in y = lambda^m: the mass keeps kg and
    // F = m a stays consistent in N, by hand; before, the exponent made m (and F) pure
    let rs = [rel("F = m*a"), rel("y = lambda^m"), rel("w = x^(2*m + 1)")];
    let d = units(&[("a", "m/s^2"), ("F", "N")]);
    let inf = infer(&rs, &d);
    assert_eq!(unit_of(&inf, "m").as_deref(), Some("kg"));
    assert_eq!(inf.statuses[0], Status::Consistent);
    // a physical exponent (a product of two letters) is still the quantities': t in s makes
    // k t a time, not a pure number
    let rs = [rel("y = z^(k*t)"), rel("k = 1/s")];
    let d = units(&[("t", "s"), ("s", "s")]);
    let inf = infer(&rs, &d);
    assert_eq!(unit_of(&inf, "k").as_deref(), Some("s^-1"));
    let rs = [rel("y = z^(k*t)"), rel("k = 1/s")];
    let d = units(&[("t", "s"), ("s", "m")]);
    let inf = infer(&rs, &d);
    assert!(
        inf.statuses
            .iter()
            .any(|s| matches!(s, Status::Inconsistent { .. })),
        "{:?}",
        inf.statuses
    );
}

#[test]
fn an_index_exponent_is_sums_of_letters_and_numbers_with_a_number_beside_each_product() {
    use super::walk::index_like;
    let p = |s: &str| parse(s).unwrap();
    for yes in ["m", "n + 1", "k - i", "2*n", "n/2", "-m", "3"] {
        assert!(index_like(&p(yes)), "{yes}");
    }
    for no in ["k*t", "alpha*t/2", "sqrt(n)", "x^2", "m/n"] {
        assert!(!index_like(&p(no)), "{no}");
    }
}

#[test]
fn a_symbol_given_as_a_written_number_is_a_value_in_a_unit_left_unsaid() {
    // p0 a pressure, h a length: `p0 = 0.025` and `h = 0.125 cos(4 pi t) + 0.375` give their
    // values in units the paper does not write, as a parameter list does
    let d = units(&[("p0", "Pa"), ("h", "m"), ("t", "1")]);
    for text in ["p0 = 0.025", "h = 0.125*cos(4*pi*t) + 0.375", "0.5 = h"] {
        let inf = infer(&[rel(text)], &d);
        assert!(
            !matches!(inf.statuses[0], Status::Inconsistent { .. }),
            "{text}: {:?}",
            inf.statuses
        );
    }
    // a number alone is a value too (`h = 2`, a term `+ 4`), but not 1 (`h = 1 + t` says h is
    // a pure number), nor a formula with a symbol outside a function (`h = 0.5 t`), nor a
    // decimal in a product of more than one symbol
    for text in ["h = 2", "h = 4 + 2*h", "12 = 16*h + 4"] {
        let inf = infer(&[rel(text)], &d);
        assert!(
            !matches!(inf.statuses[0], Status::Inconsistent { .. }),
            "{text}: {:?}",
            inf.statuses
        );
    }
    for text in [
        "h = 1",
        "h = 1 + t",
        "h = 0.5*t",
        "h*p0 = 0.5*t",
        "h = sqrt(0.5*t)",
    ] {
        let inf = infer(&[rel(text)], &d);
        assert!(
            matches!(inf.statuses[0], Status::Inconsistent { .. }),
            "{text}: {:?}",
            inf.statuses
        );
    }
}

#[test]
fn a_product_over_bounds_has_its_factors_unit_that_many_times() {
    // by hand: \prod_{k=2}^{3} x is x x, m^2 for x in m; bounds that give no count leave the
    // power open
    let tex = |t: &str| {
        crate::paper::formulas::read_formula(t, &crate::paper::formulas::TexSymbols::default())
            .expect("reads")
    };
    let rel_tex = |l: &str, r: &str| {
        Some(Relation {
            sides: vec![tex(l), tex(r)],
            dots: vec![],
            rels: vec!["="],
        })
    };
    let d = units(&[("P", "m^2"), ("Q", "m^3"), ("x", "m")]);
    let inf = infer(&[rel_tex("P", "\\prod_{k=2}^{3} x")], &d);
    assert_eq!(inf.statuses[0], Status::Consistent);
    let inf = infer(&[rel_tex("Q", "\\prod_{k=2}^{3} x")], &d);
    assert!(
        matches!(inf.statuses[0], Status::Inconsistent { .. }),
        "{:?}",
        inf.statuses
    );
}

#[test]
fn a_number_in_a_chain_is_a_value_on_either_side() {
    // `a = 2 pi = b`: 2 pi a value in some unit, so a (m) and b (s) are not set equal through it
    let d = units(&[("a", "m"), ("b", "s")]);
    let inf = infer(&[rel("a = 2*pi = b")], &d);
    assert!(
        !matches!(inf.statuses[0], Status::Inconsistent { .. }),
        "{:?}",
        inf.statuses
    );
}
