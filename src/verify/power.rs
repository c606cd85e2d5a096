//! The power of a claim's check: misprints of its printed side, and whether the check sees them.
//!
//! A verdict is worth the check behind it. For each claim whose verdict holds (or holds with
//! its correction), the printed side (the kind's printed keys, [`super::kinds::Kind::PRINTED`],
//! or `corrected` where the printed form fails and the correction holds) is perturbed the way
//! misprints happen, and the claim is validated and checked again with the misprint in place:
//!
//! - a coefficient $\times 2$, $\times 1/2$, $\times 1.1$, $\times 0.9$ (each literal, and the
//!   whole side, for formulas whose coefficient is a symbol);
//! - an exponent $\pm 1$;
//! - a sign (a unary minus dropped, `+` and `-` exchanged, the whole side negated);
//! - a dropped term of a sum;
//! - a symbol swapped for another of the same unit in the file's `[symbols]`;
//! - a function swapped for its sibling (sin for cos, sinh for cosh, asinh for acosh, and back).
//!
//! A mutant is **killed** when the verdict changes (or the misprint is refused at validation,
//! or its check stops with an error), and **survives** otherwise. Not counted: a mutant equal to
//! the printed side or to an earlier mutant (the same values at three points of its symbols:
//! `a*b` with `a` and `b` swapped), and, for an inequality that holds, a misprint that only
//! weakens it (it still holds, with a least margin over the samples at least the printed one's:
//! a true but weaker statement that no check could refute), nor a side of an inequality against
//! zero scaled by a positive factor (`2 A <= 0` states `A <= 0`; a claim's `allowance`, kept
//! apart from the paper's inequality, is not misprinted), nor a printed side whose derived
//! side is the literal 0 scaled or negated as a whole (`2 A = 0` states `A = 0`). The file definitions a printed side
//! uses are expanded first, so a misprint inside a definition is among the mutants.
//!
//! A claim that fails is not measured (a misprint of a wrong formula stays wrong; its check's
//! power is measured on `corrected` where the claim gives one), nor is a claim with no printed
//! side in the claims file (a named check whose printed values are in Rust; the report says so).
//!
//! Written by hand: mutation of formulas (as cargo-mutants and PIT mutate code) is a walk over
//! our own [`Expr`]; no crate does it.

use super::fingerprint::{Depends, depends_of, fingerprint, fnv, same};
use super::kinds::{Checked, KindEntry, Session};
use super::power_targets::{PathPart, Target, claim_targets, path_text, replaced};
use super::{ClaimSpec, Outcome, Verdict};
use crate::algebra::expr::{self, Expr, Inequality, Op};
use crate::algebra::poly::Q;
use num_traits::{Signed, Zero};
use std::collections::BTreeMap;

pub use crate::report::Power;

/// One misprint of a formula: what was changed, and the formula with it.
#[derive(Clone, Debug)]
pub struct Mutant {
    /// What was changed (`coefficient 3.2181 x2`, `exponent of (m/k) +1`).
    pub what: String,
    /// The formula with the misprint.
    pub expr: Expr,
}

/// Every misprint of `e` of the kinds above; `swaps(s)` gives the symbols of the same unit as
/// `s`.
pub fn mutants(e: &Expr, swaps: &dyn Fn(&str) -> Vec<String>) -> Vec<Mutant> {
    // a bound variable (of `int`, `diff`, `at`) is not a paper's symbol, nor is a model's
    // outcome (`contact.duration`): neither is swapped, or swapped in
    let mut bound = Vec::new();
    bound_variables(e, &mut bound);
    let paper = |s: &str| !bound.iter().any(|b| b == s) && !s.contains('.');
    let swaps = |s: &str| -> Vec<String> {
        if !paper(s) {
            return Vec::new();
        }
        swaps(s).into_iter().filter(|t| paper(t)).collect()
    };
    let mut out = whole(e);
    walk(e, false, &swaps, &mut out);
    numbered(&mut out);
    out
}

/// Misprints that read alike (a symbol swapped at two places) numbered by place, so that a
/// misprint is named the same in every claim that prints the formula, and no other is.
fn numbered(out: &mut [Mutant]) {
    let mut count: BTreeMap<String, usize> = BTreeMap::new();
    for m in out.iter() {
        *count.entry(m.what.clone()).or_default() += 1;
    }
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    for m in out.iter_mut() {
        if count[&m.what] > 1 {
            let k = seen.entry(m.what.clone()).or_default();
            *k += 1;
            m.what = format!("{} (place {k})", m.what);
        }
    }
}

/// The variables that `int`, `diff` and `at` bind in `e`.
fn bound_variables(e: &Expr, out: &mut Vec<String>) {
    match e {
        Expr::Num(_) | Expr::Sym(_) | Expr::Pi => {}
        Expr::Neg(a) | Expr::Call(_, a) => bound_variables(a, out),
        Expr::Bin(_, a, b) => {
            bound_variables(a, out);
            bound_variables(b, out);
        }
        Expr::Calc(_, body, var, extra) => {
            out.push(var.clone());
            bound_variables(body, out);
            extra.iter().for_each(|x| bound_variables(x, out));
        }
    }
}

/// The whole side scaled and negated.
fn whole(e: &Expr) -> Vec<Mutant> {
    let mut out: Vec<Mutant> = FACTORS
        .iter()
        .map(|(name, f)| Mutant {
            what: format!("the whole side {name}"),
            expr: Expr::Bin(Op::Mul, Box::new(Expr::Num(f())), Box::new(e.clone())),
        })
        .collect();
    out.push(Mutant {
        what: "the whole side negated".into(),
        expr: negate(e),
    });
    out
}

/// A misprint's factor, made on demand (a `Q` is not `const`).
type Factor = fn() -> Q;

/// The coefficient misprints: x2, x1/2, x1.1, x0.9.
const FACTORS: [(&str, Factor); 4] = [
    ("x2", || Q::from_integer(2.into())),
    ("x1/2", || Q::new(1.into(), 2.into())),
    ("x1.1", || Q::new(11.into(), 10.into())),
    ("x0.9", || Q::new(9.into(), 10.into())),
];

fn negate(e: &Expr) -> Expr {
    match e {
        Expr::Neg(a) => (**a).clone(),
        _ => Expr::Neg(Box::new(e.clone())),
    }
}

fn num(v: Q) -> Expr {
    if v.is_negative() {
        Expr::Neg(Box::new(Expr::Num(-v)))
    } else {
        Expr::Num(v)
    }
}

fn short(e: &Expr) -> String {
    let s = e.to_string();
    if s.chars().count() <= 40 {
        s
    } else {
        format!("{}...", s.chars().take(37).collect::<String>())
    }
}

/// The misprints at `e` itself, then those inside it, each rebuilt into `e`.
fn walk(e: &Expr, in_exponent: bool, swaps: &dyn Fn(&str) -> Vec<String>, out: &mut Vec<Mutant>) {
    local(e, in_exponent, swaps, out);
    let inner = |child: &Expr, exp: bool, rebuild: &dyn Fn(Expr) -> Expr, out: &mut Vec<Mutant>| {
        let mut sub = Vec::new();
        walk(child, exp, swaps, &mut sub);
        out.extend(sub.into_iter().map(|m| Mutant {
            what: m.what,
            expr: rebuild(m.expr),
        }));
    };
    match e {
        Expr::Num(_) | Expr::Sym(_) | Expr::Pi => {}
        Expr::Neg(a) => inner(a, in_exponent, &|m| Expr::Neg(Box::new(m)), out),
        Expr::Call(f, a) => inner(a, in_exponent, &|m| Expr::Call(*f, Box::new(m)), out),
        Expr::Bin(op, a, b) => {
            inner(
                a,
                in_exponent,
                &|m| Expr::Bin(*op, Box::new(m), b.clone()),
                out,
            );
            inner(
                b,
                in_exponent || *op == Op::Pow,
                &|m| Expr::Bin(*op, a.clone(), Box::new(m)),
                out,
            );
        }
        Expr::Calc(c, body, var, extra) => {
            let rebuild_body = |m: Expr| Expr::Calc(*c, Box::new(m), var.clone(), extra.clone());
            inner(body, in_exponent, &rebuild_body, out);
            for i in 0..extra.len() {
                let rebuild = |m: Expr| {
                    let mut x = extra.clone();
                    x[i] = m;
                    Expr::Calc(*c, body.clone(), var.clone(), x)
                };
                inner(&extra[i], in_exponent, &rebuild, out);
            }
        }
    }
}

/// The misprints of the node `e` alone.
fn local(e: &Expr, in_exponent: bool, swaps: &dyn Fn(&str) -> Vec<String>, out: &mut Vec<Mutant>) {
    match e {
        Expr::Num(v) if !in_exponent && !v.is_zero() => {
            for (name, f) in FACTORS {
                out.push(Mutant {
                    what: format!("coefficient {} {name}", e),
                    expr: num(v * f()),
                });
            }
        }
        Expr::Sym(s) => {
            for t in swaps(s) {
                out.push(Mutant {
                    what: format!("`{s}` swapped for `{t}`"),
                    expr: Expr::Sym(t),
                });
            }
        }
        Expr::Call(f, a) => {
            if let Some(g) = sibling(*f) {
                out.push(Mutant {
                    what: format!("`{}` for `{}`", g.name(), f.name()),
                    expr: Expr::Call(g, a.clone()),
                });
            }
        }
        Expr::Neg(a) => out.push(Mutant {
            what: format!("sign of -{} dropped", short(a)),
            expr: (**a).clone(),
        }),
        Expr::Bin(Op::Pow, base, x) => {
            for (name, d) in [("+1", 1i64), ("-1", -1)] {
                let d = Q::from_integer(d.into());
                let shifted = match x.exact_constant() {
                    Some(v) => num(v + d),
                    None => Expr::Bin(Op::Add, x.clone(), Box::new(num(d))),
                };
                out.push(Mutant {
                    what: format!("exponent of {} {name}", short(base)),
                    expr: Expr::Bin(Op::Pow, base.clone(), Box::new(shifted)),
                });
            }
            // a fractional exponent misprinted in its numerator or its denominator (2/5 as
            // 3/5, 1/5, 2/3 or 2/4): the misprints a typeset fraction suffers
            if let Some(v) = x.exact_constant().filter(|v| !v.is_integer()) {
                let (p, q) = (v.numer().clone(), v.denom().clone());
                let one = num_bigint::BigInt::from(1);
                for (name, np, nq) in [
                    ("numerator +1", &p + &one, q.clone()),
                    ("numerator -1", &p - &one, q.clone()),
                    ("denominator +1", p.clone(), &q + &one),
                    ("denominator -1", p.clone(), &q - &one),
                ] {
                    let w = Q::new(np, nq);
                    if w != v && !w.is_zero() {
                        out.push(Mutant {
                            what: format!("exponent {v} of {} by its {name}", short(base)),
                            expr: Expr::Bin(Op::Pow, base.clone(), Box::new(num(w))),
                        });
                    }
                }
            }
        }
        Expr::Bin(op @ (Op::Add | Op::Sub), a, b) => {
            let flipped = if *op == Op::Add { Op::Sub } else { Op::Add };
            out.push(Mutant {
                what: format!("sign of the term {}", short(b)),
                expr: Expr::Bin(flipped, a.clone(), b.clone()),
            });
            out.push(Mutant {
                what: format!("term {} dropped", short(b)),
                expr: (**a).clone(),
            });
            out.push(Mutant {
                what: format!("term {} dropped", short(a)),
                expr: if *op == Op::Add {
                    (**b).clone()
                } else {
                    negate(b)
                },
            });
            // a term printed with no number before it has the coefficient 1, misprinted as
            // any other (a balance `left - right` with its left side doubled)
            for (term, first) in [(a, true), (b, false)] {
                if has_coefficient(term) {
                    continue;
                }
                for (name, f) in &FACTORS[..2] {
                    let scaled =
                        Box::new(Expr::Bin(Op::Mul, Box::new(Expr::Num(f())), term.clone()));
                    out.push(Mutant {
                        what: format!("term {} {name}", short(term)),
                        expr: if first {
                            Expr::Bin(*op, scaled, b.clone())
                        } else {
                            Expr::Bin(*op, a.clone(), scaled)
                        },
                    });
                }
            }
        }
        _ => {}
    }
}

/// Whether a term carries a coefficient of its own that the literal misprints reach (a
/// number, a product led by one, a negated such term), or is a sum, whose terms are misprinted
/// one by one.
fn has_coefficient(e: &Expr) -> bool {
    match e {
        Expr::Num(_) | Expr::Bin(Op::Add | Op::Sub, ..) => true,
        Expr::Neg(a) => has_coefficient(a),
        Expr::Bin(Op::Mul | Op::Div, a, _) => has_coefficient(a),
        _ => false,
    }
}

/// The function a misprint puts for `f`: its sibling of the same family (sin and cos, sinh and
/// cosh, asin and acos, asinh and acosh, tan and tanh, atan and atanh).
fn sibling(f: expr::Func) -> Option<expr::Func> {
    use expr::Func as F;
    Some(match f {
        F::Sin => F::Cos,
        F::Cos => F::Sin,
        F::Sinh => F::Cosh,
        F::Cosh => F::Sinh,
        F::Asin => F::Acos,
        F::Acos => F::Asin,
        F::Asinh => F::Acosh,
        F::Acosh => F::Asinh,
        F::Tan => F::Tanh,
        F::Tanh => F::Tan,
        F::Atan => F::Atanh,
        F::Atanh => F::Atan,
        _ => return None,
    })
}

/// A misprint of a side: what was changed, the side's text with it, and whether it states the
/// same as the side (then not run, and named so that no claim on the formula counts it).
#[derive(Debug)]
struct Misprint {
    what: String,
    text: String,
    equivalent: bool,
}

/// A side read as a formula or as an inequality, to mutate.
enum Side {
    Formula(Expr),
    Relation(Inequality),
}

impl Side {
    fn read(text: &str, cx: &Checked) -> Option<Side> {
        if text.contains('@') {
            return None;
        }
        let side = match expr::parse_inequality(text) {
            Ok(i) => Side::Relation(Inequality {
                lhs: cx.expand_defs(&i.lhs),
                rel: i.rel,
                rhs: cx.expand_defs(&i.rhs),
            }),
            Err(_) => Side::Formula(cx.expand_defs(&expr::parse(text).ok()?)),
        };
        Some(side)
    }

    fn exprs(&self) -> Vec<&Expr> {
        match self {
            Side::Formula(e) => vec![e],
            Side::Relation(i) => vec![&i.lhs, &i.rhs],
        }
    }

    /// Every misprint, marked `equivalent` where it states the same as the side (a side of an
    /// inequality against zero times a positive factor).
    fn mutants(&self, swaps: &dyn Fn(&str) -> Vec<String>, depends: &Depends) -> Vec<Misprint> {
        let mut out = Vec::new();
        let base = fingerprint(&self.exprs(), depends);
        let mut seen: Vec<Vec<f64>> = Vec::new();
        let mut keep = |what: String, text: String, vals: Vec<&Expr>, equivalent: bool| {
            let fp = fingerprint(&vals, depends);
            if let Some(fp) = &fp {
                // the same values as the printed side: it states the same, and is named so;
                // the same as an earlier misprint: counted once
                if base.as_ref().is_some_and(|b| same(b, fp)) {
                    out.push(Misprint {
                        what: format!("{what} (the same values as the printed side)"),
                        text,
                        equivalent: true,
                    });
                    return;
                }
                if seen.iter().any(|s| same(s, fp)) {
                    return;
                }
                seen.push(fp.clone());
            }
            out.push(Misprint {
                what,
                text,
                equivalent,
            });
        };
        match self {
            Side::Formula(e) => {
                for m in mutants(e, swaps) {
                    keep(m.what, m.expr.to_string(), vec![&m.expr], false);
                }
            }
            Side::Relation(i) => {
                // against zero, a side scaled by a positive factor states the same (2 A <= 0 is
                // A <= 0): not a misprint of the statement
                let same = |m: &Mutant, other: &Expr| {
                    matches!(other, Expr::Num(q) if q.is_zero())
                        && m.what.starts_with("the whole side x")
                };
                for m in mutants(&i.lhs, swaps) {
                    let text = format!("{} {} {}", m.expr, i.rel.symbol(), i.rhs);
                    let eq = same(&m, &i.rhs);
                    keep(format!("left: {}", m.what), text, vec![&m.expr, &i.rhs], eq);
                }
                for m in mutants(&i.rhs, swaps) {
                    let text = format!("{} {} {}", i.lhs, i.rel.symbol(), m.expr);
                    let eq = same(&m, &i.lhs);
                    keep(
                        format!("right: {}", m.what),
                        text,
                        vec![&i.lhs, &m.expr],
                        eq,
                    );
                }
            }
        }
        out
    }
}

/// How many mutants a claim runs at most (a seeded sample of its mutants beyond that, spread
/// over their kinds in order).
pub const MAX_MUTANTS: usize = 40;

/// The keys whose misprints a claim's power is measured on, given its verdict (`None`: not
/// measured, and why).
fn measured_keys(
    entry: &KindEntry,
    spec: &ClaimSpec,
    verdict: Verdict,
) -> Result<Vec<&'static str>, String> {
    match verdict {
        Verdict::Fails => Err("fails: a misprint of a wrong formula stays wrong (power is measured on `corrected` where a claim gives one)".into()),
        Verdict::NotCheckable => Err("not checkable".into()),
        Verdict::HoldsWithCorrection if spec.keys.contains_key("corrected") => Ok(vec!["corrected"]),
        Verdict::HoldsWithCorrection => Err("holds with a correction computed in Rust".into()),
        _ => {
            let keys: Vec<&'static str> = entry
                .printed
                .iter()
                .copied()
                .filter(|k| spec.keys.contains_key(*k))
                .collect();
            if keys.is_empty() {
                Err("no printed formula or value in the claims file: a statement its Rust check tests (a decay, a separation, an equivalence, a diagnosis), with nothing printed to misprint".into())
            } else {
                Ok(keys)
            }
        }
    }
}

/// The least margin an inequality check reached (`extra.least_margin`), if it records one.
fn least_margin(o: &Outcome) -> Option<f64> {
    o.extra.get("least_margin").and_then(|v| v.as_f64())
}

/// What became of one mutant.
enum Fate {
    Killed(String),
    Survived(String),
    /// An inequality's mutant that keeps the verdict by weakening the inequality (its least
    /// margin is no smaller than the printed one's): no check could kill it.
    Excused(String),
}

/// Measures the power of one claim: each misprint validated and checked as the claim would
/// be, the mutants in parallel, each worker with a session of its own from `new_session`.
pub fn measure<'s>(
    cx: &Checked,
    entry: &KindEntry,
    spec: &ClaimSpec,
    original: &Outcome,
    new_session: &(dyn Fn() -> Session<'s> + Sync),
) -> Power {
    let mut power = misprinted(cx, entry, spec, original, new_session);
    // a finding's claim: checked with its correction applied too
    if super::correction::shows_finding(original.verdict) && spec.head.extends.is_none() {
        power.correction = super::correction::apply(cx, entry, spec, &mut new_session());
    }
    power
}

/// [`measure`]'s misprints: each validated and checked as the claim would be.
fn misprinted<'s>(
    cx: &Checked,
    entry: &KindEntry,
    spec: &ClaimSpec,
    original: &Outcome,
    new_session: &(dyn Fn() -> Session<'s> + Sync),
) -> Power {
    use rayon::prelude::*;
    let keys = match measured_keys(entry, spec, original.verdict) {
        Ok(k) => k,
        Err(why) => return Power::not_measured(why),
    };
    let swaps = |s: &str| cx.same_unit(s);
    let mut all: Vec<(String, Target, String)> = Vec::new();
    let mut equivalent: Vec<String> = Vec::new();
    let mut unread = Vec::new();
    let all_targets = claim_targets(spec, &keys);
    for t in all_targets.iter().cloned() {
        let Some(side) = Side::read(&t.text, cx) else {
            unread.push(path_text(&t.path));
            continue;
        };
        // a printed side whose derived value is the literal 0 states `side = 0`, as a condition
        // read from the paper as `left - right` does: the whole side times a factor, or
        // negated, states the same
        let against_zero = t.text.trim() != "0"
            && (spec.head.conditions.contains(&path_text(&t.path))
                || matches!(&t.path[..], [PathPart::Key(k)] if k == "printed" || k == "corrected")
                    && spec
                        .keys
                        .get("derived")
                        .and_then(|v| v.as_str())
                        .map(str::trim)
                        == Some("0"));
        for m in side.mutants(&swaps, &depends_of(&t.text)) {
            if m.equivalent || (against_zero && m.what.starts_with("the whole side")) {
                equivalent.push(format!("{}: {}", path_text(&t.path), m.what));
                continue;
            }
            all.push((m.what, t.clone(), m.text));
        }
    }
    if all.is_empty() {
        let why = if unread.is_empty() {
            "no misprint of the printed side differs from it".to_string()
        } else {
            format!("the printed side ({}) is not a formula", unread.join(", "))
        };
        return Power::not_measured(why);
    }
    // drawn by the printed text, not the claim: claims printing the same formula meet the same
    // misprints, so that a formula's power is that of all its claims (`report::formulas`)
    let seed: String = all_targets
        .iter()
        .map(|t| t.text.as_str())
        .collect::<Vec<_>>()
        .join("\n");
    let mut picked = sample(all.len(), MAX_MUTANTS, &seed);
    // the misprint the paper made, where it is one of the corrected side's: always run
    for i in own_misprints(cx, spec, &keys, &all) {
        all[i].0 = format!("{} (the paper's own misprint)", all[i].0);
        if !picked.contains(&i) {
            picked.push(i);
        }
    }
    let base_margin = least_margin(original);
    let fates: Vec<Fate> = picked
        .par_iter()
        .map_init(new_session, |run, &i| {
            let (what, target, text) = &all[i];
            let mut mutated = spec.clone();
            mutated.keys = replaced(&spec.keys, &target.path, text.clone());
            let verdict = (entry.validate)(cx, &mutated)
                .and_then(|claim| claim.run(cx, &spec.head, run))
                .map(|o| super::with_assumption(o, &spec.head));
            match verdict {
                Ok(o) if o.verdict == original.verdict => match (base_margin, least_margin(&o)) {
                    // strictly wider: a margin that stays the same (an inequality against 0, whose
                    // relative margin is 1 whatever the factor) cannot tell, and survives
                    (Some(b), Some(m)) if m > b + 1e-9 * b.abs().max(1e-300) => {
                        Fate::Excused(format!("{}: {what}", path_text(&target.path)))
                    }
                    _ => Fate::Survived(format!("{}: {what}", path_text(&target.path))),
                },
                _ => Fate::Killed(format!("{}: {what}", path_text(&target.path))),
            }
        })
        .collect();
    let mut power = Power {
        mutants: 0,
        killed: 0,
        survivors: Vec::new(),
        excused: 0,
        not_measured: None,
        blind: None,
        formula: None,
        killed_names: Vec::new(),
        equivalent,
        weaker: Vec::new(),
        correction: None,
        not_applied: unread
            .iter()
            .map(|k| {
                format!(
                    "{k}: not a formula (a value the claim computes or looks up), so not misprinted"
                )
            })
            .collect(),
        key: None,
    };
    if let [one] = all_targets.as_slice() {
        power.formula = Some(one.text.clone());
    }
    for fate in fates {
        match fate {
            Fate::Killed(what) => {
                power.mutants += 1;
                power.killed += 1;
                power.killed_names.push(what);
            }
            Fate::Survived(what) => {
                power.mutants += 1;
                power.survivors.push(what);
            }
            Fate::Excused(what) => {
                power.excused += 1;
                power.weaker.push(what);
            }
        }
    }
    if power.weak() {
        power.blind = spec
            .head
            .blind
            .clone()
            .or_else(|| entry.blind.map(str::to_string));
    }
    power
}

/// The misprints of a `corrected` side that state what the paper printed (the same values as
/// its `printed` side at three points of their symbols): the error the claim found.
fn own_misprints(
    cx: &Checked,
    spec: &ClaimSpec,
    keys: &[&str],
    all: &[(String, Target, String)],
) -> Vec<usize> {
    let printed = match (keys, spec.keys.get("printed").and_then(|v| v.as_str())) {
        (["corrected"], Some(p)) => p,
        _ => return Vec::new(),
    };
    let Some(target) = all.first().map(|(_, t, _)| t) else {
        return Vec::new();
    };
    let depends = depends_of(&target.text);
    let print = |text: &str| Side::read(text, cx).and_then(|s| fingerprint(&s.exprs(), &depends));
    let Some(want) = print(printed) else {
        return Vec::new();
    };
    (0..all.len())
        .filter(|&i| print(&all[i].2).is_some_and(|fp| same(&fp, &want)))
        .collect()
}

/// `k` of `n` indices, spread evenly with a seeded offset (all of them when `n <= k`).
fn sample(n: usize, k: usize, seed: &str) -> Vec<usize> {
    if n <= k {
        return (0..n).collect();
    }
    let offset = (fnv(seed) % n as u64) as usize;
    let mut out: Vec<usize> = (0..k).map(|i| (offset + i * n / k) % n).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// `n` of the claims `ids`, picked by `seed` (the `n` smallest hashes of seed and id).
pub fn pick(ids: &[String], n: usize, seed: &str) -> std::collections::BTreeSet<String> {
    let mut keyed: Vec<(u64, &String)> = ids
        .iter()
        .map(|id| (fnv(&format!("{seed}/{id}")), id))
        .collect();
    keyed.sort();
    keyed
        .into_iter()
        .take(n)
        .map(|(_, id)| id.clone())
        .collect()
}

/// The power of a file's claims, measured as its check is made.
impl Checked<'_> {
    /// Measures the power of each claim for which `pick(id)` holds, given its outcome of
    /// [`Checked::check_all`] ([`measure`]).
    pub fn measure_power<'s>(
        &self,
        outcomes: &mut [Outcome],
        pick: &dyn Fn(&str) -> bool,
        new_session: &(dyn Fn() -> Session<'s> + Sync),
        tick: &dyn Fn(&str),
    ) {
        for ((c, entry), o) in self.file.claim.iter().zip(&self.entries).zip(outcomes) {
            if pick(&c.id) {
                o.power = Some(measure(self, entry, c, o, new_session));
                tick(&c.id);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(f: &str) -> Vec<String> {
        let e = expr::parse(f).unwrap();
        mutants(&e, &|s| if s == "k" { vec!["c".into()] } else { vec![] })
            .into_iter()
            .map(|m| m.expr.to_string())
            .collect()
    }

    #[test]
    fn every_kind_of_misprint_is_made() {
        // by hand: the misprints of 3.2*(m/k)^(2/5) - v
        let t = texts("3.2*(m/k)^(2/5) - v");
        for want in [
            "6.4*(m/k)^(2/5) - v",
            "1.6*(m/k)^(2/5) - v",
            "3.52*(m/k)^(2/5) - v",
            "2.88*(m/k)^(2/5) - v",
            "3.2*(m/k)^1.4 - v",
            "3.2*(m/k)^-0.6 - v",
            "3.2*(m/k)^(2/5) + v",
            "3.2*(m/k)^(2/5)",
            "-v",
            "3.2*(m/c)^(2/5) - v",
            "-(3.2*(m/k)^(2/5) - v)",
        ] {
            assert!(t.contains(&want.to_string()), "{want} missing from {t:?}");
        }
        // the exponent's literals are not scaled as coefficients (2/5 x2, x1.1, x0.9), but a
        // fractional exponent is misprinted in its numerator and its denominator
        for scaled in ["^0.8 ", "^0.44 ", "^0.36 "] {
            assert!(!t.iter().any(|x| x.contains(scaled)), "{scaled} in {t:?}");
        }
        for want in [
            "3.2*(m/k)^0.6 - v",
            "3.2*(m/k)^0.2 - v",
            "3.2*(m/k)^(1/3) - v",
            "3.2*(m/k)^0.5 - v",
        ] {
            assert!(t.contains(&want.to_string()), "{want} missing from {t:?}");
        }
        // a misprint's text reads back as the misprint: (m/k)^-0.6 at m = 2, k = 1 is 2^-0.6
        let back = expr::parse("3.2*(m/k)^-0.6 - v").unwrap();
        let at = |s: &str| match s {
            "m" => Some(2.0),
            "k" => Some(1.0),
            _ => Some(0.0),
        };
        assert!((back.eval(&at).unwrap() - 3.2 * 2f64.powf(-0.6)).abs() < 1e-12);
    }

    #[test]
    fn a_function_is_misprinted_as_its_sibling() {
        // by hand: each function of the family for the other, once; exp has no sibling
        let t = texts("sin(x) + acosh(y) - tanh(z)*exp(w)");
        for want in [
            "cos(x) + acosh(y) - tanh(z)*exp(w)",
            "sin(x) + asinh(y) - tanh(z)*exp(w)",
            "sin(x) + acosh(y) - tan(z)*exp(w)",
        ] {
            assert!(t.contains(&want.to_string()), "{want} missing from {t:?}");
        }
        for (f, g) in [
            ("cos", "sin"),
            ("cosh", "sinh"),
            ("acos", "asin"),
            ("asinh", "acosh"),
            ("atan", "atanh"),
            ("atanh", "atan"),
        ] {
            assert!(
                texts(&format!("{f}(x)")).contains(&format!("{g}(x)")),
                "{f}"
            );
        }
        assert!(!texts("exp(x)").iter().any(|m| !m.contains("exp")));
    }

    #[test]
    fn misprints_that_read_alike_are_numbered_by_place() {
        // by hand: k at two places, each swapped for c; every other misprint named once
        let e = expr::parse("x*k + y*k").unwrap();
        let names: Vec<String> = mutants(&e, &|s| if s == "k" { vec!["c".into()] } else { vec![] })
            .into_iter()
            .map(|m| m.what)
            .collect();
        assert!(
            names.contains(&"`k` swapped for `c` (place 1)".to_string()),
            "{names:?}"
        );
        assert!(
            names.contains(&"`k` swapped for `c` (place 2)".to_string()),
            "{names:?}"
        );
        let mut unique = names.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
    }

    #[test]
    fn equivalent_mutants_are_not_counted() {
        // a*b with a and b of the same unit: the swap a -> b gives b*b (kept), and a
        // whole-side x2 equals the literal's x2 in 2*a*b (kept once)
        let cxless = Side::Formula(expr::parse("2*a*b").unwrap());
        let m = cxless.mutants(
            &|s| match s {
                "a" => vec!["b".into()],
                "b" => vec!["a".into()],
                _ => vec![],
            },
            &Depends::new(),
        );
        let doubled = m
            .iter()
            .map(|m| m.text.as_str())
            .filter(|t| t.contains("4*a*b") || t.starts_with("2*(2*a*b)") || *t == "2*2*a*b")
            .count();
        assert_eq!(doubled, 1, "{m:?}");
        assert!(m.iter().any(|x| x.text == "2*b*b"));
        assert!(m.iter().any(|x| x.text == "2*a*a"));
    }

    #[test]
    fn a_misprint_inside_a_derivative_is_made_and_told_from_the_printed_side() {
        // by hand: in E z^2 + 2 eta z z' (000's (18) corrected), z a function of t, halving the
        // 2 gives E z^2 + eta z z' (the paper's own misprint), which differs wherever z z' is not
        // 0; with z a constant the derivative would vanish and the misprint look the same
        let text = "E*z^2 + 2*eta*z*diff(z, t)";
        let side = Side::Formula(expr::parse(text).unwrap());
        let depends = depends_of(text);
        assert_eq!(depends.get("z"), Some(&vec!["t".to_string()]));
        let m = side.mutants(&|_| vec![], &depends);
        let halved = m
            .iter()
            .find(|x| x.what == "coefficient 2 x1/2")
            .expect("the coefficient inside the derivative's term is misprinted");
        assert!(!halved.equivalent, "{halved:?}");
        // with nothing differentiated, the term is 0: that misprint states the same, and is named so
        let flat = side.mutants(&|_| vec![], &Depends::new());
        let same = flat
            .iter()
            .find(|x| x.what.starts_with("coefficient 2 x1/2"))
            .unwrap();
        assert!(same.equivalent && same.what.ends_with("(the same values as the printed side)"));
    }

    #[test]
    fn a_definitions_constant_stays_constant_under_a_derivative() {
        // diff(z9, t) with z9 = v0 t + c t^2 expanded: v0 is no function of t, so v0 t
        // misprinted (x2) changes the second derivative by nothing, by hand
        let printed = "diff(diff(z9, t), t)";
        let depends = depends_of(printed);
        assert!(depends.contains_key("z9") && !depends.contains_key("v0"));
        let expanded = expr::parse("diff(diff(v0*t + c*t^2, t), t)").unwrap();
        let misprint = expr::parse("diff(diff(2*v0*t + c*t^2, t), t)").unwrap();
        assert!(same(
            &fingerprint(&[&expanded], &depends).unwrap(),
            &fingerprint(&[&misprint], &depends).unwrap()
        ));
        let other = expr::parse("diff(diff(v0*t + 2*c*t^2, t), t)").unwrap();
        assert!(!same(
            &fingerprint(&[&expanded], &depends).unwrap(),
            &fingerprint(&[&other], &depends).unwrap()
        ));
    }

    #[test]
    fn a_term_without_a_number_is_scaled_as_a_coefficient_would_be() {
        // a balance a*b - c: its left term doubled, by hand 2*(a*b) - c
        let m = texts("a*b - c");
        assert!(m.contains(&"2*(a*b) - c".to_string()), "{m:?}");
        assert!(m.contains(&"a*b - 0.5*c".to_string()), "{m:?}");
        // a term with a number of its own is reached by the literal's misprints only
        assert!(!m.iter().any(|t| t.contains("2*(3")), "{m:?}");
        let n = texts("3*a - c");
        assert!(!n.contains(&"2*(3*a) - c".to_string()), "{n:?}");
    }

    #[test]
    fn samples_are_spread_and_distinct() {
        let s = sample(100, 40, "x");
        assert_eq!(s.len(), 40);
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(sample(5, 40, "x"), vec![0, 1, 2, 3, 4]);
    }
}
