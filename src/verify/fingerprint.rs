//! Whether two misprints state the same: a formula's values at three points of its symbols (its
//! fingerprint), with each symbol a side differentiates made a generic function of the variables
//! it is differentiated by, so that a misprint inside a derivative is told from the printed side.
//!
//! Written by hand: it evaluates our own [`Expr`]; no crate does it.

use crate::algebra::expr::{self, Expr, Op};
use crate::algebra::poly::Q;
use std::collections::BTreeMap;

/// How many symbol values a fingerprint may look up: nested integrals evaluated by
/// quadrature cost 1024 evaluations per level, and a formula too dear to evaluate is not
/// fingerprinted (its mutants are run, none merged as equivalent).
const FINGERPRINT_BUDGET: usize = 200_000;

/// Values of a formula's symbols at three points (a hash of the name picks each in
/// [0.35, 0.85], where every function of the formula language but `acosh` is defined; a value
/// that is not finite fingerprints nothing, and its mutant is run).
pub(super) fn fingerprint(values: &[&Expr], depends: &Depends) -> Option<Vec<f64>> {
    let generic: Vec<Expr> = values.iter().map(|e| as_functions(e, depends)).collect();
    let values: Vec<&Expr> = generic.iter().collect();
    let mut out = Vec::new();
    let spent = std::cell::Cell::new(0usize);
    for point in 0..3u64 {
        let value = |s: &str| {
            spent.set(spent.get() + 1);
            if spent.get() > FINGERPRINT_BUDGET {
                return None;
            }
            let mut h: u64 = 0xcbf2_9ce4_8422_2325 ^ point.wrapping_mul(0x9e37_79b9_7f4a_7c15);
            for b in s.bytes() {
                h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
            }
            Some(0.35 + 0.5 * ((h >> 11) as f64 / (1u64 << 53) as f64))
        };
        for e in &values {
            let v = e.eval(&value).ok()?;
            if !v.is_finite() {
                return None;
            }
            out.push(v);
        }
    }
    Some(out)
}

/// Each symbol a side differentiates, with the variables it is differentiated by.
pub(super) type Depends = BTreeMap<String, Vec<String>>;

/// The symbols a side as written (its definitions not expanded) differentiates: `z` in
/// `diff(z, t)` is a function of `t`, while `v0` in a definition `z9 = .. + v0*t` stays a
/// constant.
pub(super) fn depends_of(text: &str) -> Depends {
    let mut out = Depends::new();
    match expr::parse_inequality(text) {
        Ok(i) => {
            differentiated(&i.lhs, &mut out);
            differentiated(&i.rhs, &mut out);
        }
        Err(_) => {
            if let Ok(e) = expr::parse(text) {
                differentiated(&e, &mut out);
            }
        }
    }
    out
}

/// Each symbol a `diff` differentiates, with the variables it is differentiated by (`z` in
/// `diff(z, t)`: `t`): a symbol's value alone would make every such derivative 0, and every
/// misprint inside it look like the printed side.
fn differentiated(e: &Expr, out: &mut Depends) {
    match e {
        Expr::Num(_) | Expr::Sym(_) | Expr::Pi => {}
        Expr::Neg(a) | Expr::Call(_, a) => differentiated(a, out),
        Expr::Bin(_, a, b) => {
            differentiated(a, out);
            differentiated(b, out);
        }
        Expr::Calc(c, body, var, extra) => {
            if *c == expr::Calc::Diff {
                for s in body.free_symbols().into_iter().filter(|s| s != var) {
                    let vars = out.entry(s).or_default();
                    if !vars.contains(var) {
                        vars.push(var.clone());
                    }
                }
            }
            differentiated(body, out);
            extra.iter().for_each(|x| differentiated(x, out));
        }
    }
}

/// `e` with each differentiated symbol made a generic function of the variables it is
/// differentiated by: `z` -> `z exp(a t + b t^2)`, `a` and `b` drawn from the names (every
/// derivative, mixed ones too, is then nonzero, and no two symbols' are alike).
fn as_functions(e: &Expr, depends: &Depends) -> Expr {
    if depends.is_empty() {
        return e.clone();
    }
    let drawn = |s: &str, v: &str, k: u64| {
        let h = fnv(&format!("{s}/{v}/{k}"));
        Expr::Num(Q::new(((h % 997) + 101).into(), 1000.into()))
    };
    e.substitute(&|s: &str| {
        let vars = depends.get(s)?;
        let exponent = vars
            .iter()
            .flat_map(|v| {
                let x = Expr::sym(v);
                let square = Expr::Bin(
                    Op::Pow,
                    Box::new(x.clone()),
                    Box::new(Expr::Num(Q::from_integer(2.into()))),
                );
                [
                    Expr::Bin(Op::Mul, Box::new(drawn(s, v, 1)), Box::new(x)),
                    Expr::Bin(Op::Mul, Box::new(drawn(s, v, 2)), Box::new(square)),
                ]
            })
            .reduce(|a, b| Expr::Bin(Op::Add, Box::new(a), Box::new(b)))?;
        Some(Expr::Bin(
            Op::Mul,
            Box::new(Expr::sym(s)),
            Box::new(Expr::Call(expr::Func::Exp, Box::new(exponent))),
        ))
    })
}

pub(super) fn same(a: &[f64], b: &[f64]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| (x - y).abs() <= 1e-9 * x.abs().max(y.abs()).max(1e-300))
}

/// The FNV-1a 64 hash of a text: the seeded draws of the misprints sampled and of the generic
/// functions' coefficients.
pub(super) fn fnv(s: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in s.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    h
}
