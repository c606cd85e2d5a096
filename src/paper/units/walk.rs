//! The walk of a formula's units: each formula's unit as an affine form in the unknown units of
//! its undeclared symbols ([`Form`]), and the equations ([`Constraint`]) that a relation's sides,
//! the terms of its sums, its function arguments, exponents and dots give.

use super::{Relation, links_units, unit_name};
use crate::algebra::expr::{Calc, Expr, Func, Op};
use crate::algebra::poly::Q;
use crate::algebra::units::{ELLIPSIS, INFINITY, OPERAND, Unit, WRITTEN_UNIT, every_unit};
use num_traits::{One, Zero};
use std::collections::{BTreeMap, BTreeSet};

/// The unit of a formula as an affine form in the unknown units.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Form {
    pub(super) coeffs: BTreeMap<String, Q>,
    pub(super) konst: [Q; 7],
}

impl Form {
    pub(super) fn constant(u: Unit) -> Form {
        Form {
            coeffs: BTreeMap::new(),
            konst: u
                .0
                .map(|r| Q::new((*r.numer()).into(), (*r.denom()).into())),
        }
    }

    pub(super) fn var(name: &str) -> Form {
        Form {
            coeffs: [(name.to_string(), Q::one())].into(),
            konst: Default::default(),
        }
    }

    /// `self + k o`.
    pub(super) fn plus(mut self, o: &Form, k: &Q) -> Form {
        for (v, c) in &o.coeffs {
            let e = self.coeffs.entry(v.clone()).or_insert_with(Q::zero);
            *e += c * k;
            if e.is_zero() {
                self.coeffs.remove(v);
            }
        }
        for (x, y) in self.konst.iter_mut().zip(&o.konst) {
            *x += y * k;
        }
        self
    }

    pub(super) fn scaled(&self, k: &Q) -> Form {
        Form::default().plus(self, k)
    }
}

/// One equation: the unit of `left` equals that of `right`.
#[derive(Clone, Debug)]
pub(super) struct Constraint {
    pub(super) left: (String, Form),
    pub(super) right: (String, Form),
    pub(super) what: String,
}

impl Constraint {
    pub(super) fn new(left: (String, Form), right: (String, Form), what: &str) -> Constraint {
        Constraint {
            left,
            right,
            what: what.to_string(),
        }
    }

    /// `(coefficients, right side)` of `left - right = 0`.
    pub(super) fn equation(&self) -> (BTreeMap<String, Q>, [Q; 7]) {
        let d = self.left.1.clone().plus(&self.right.1, &-Q::one());
        (d.coeffs, d.konst.map(|c| -c))
    }
}

/// The prefix of a bound variable's own unknown: `~2~x` is the variable `x` of the second
/// integral or sum met (its unit is that of its bounds, whatever a symbol `x` elsewhere has).
pub(super) const LOCAL: char = '~';

/// Whether an unknown is a bound variable's own.
pub(super) fn is_local(name: &str) -> bool {
    name.starts_with(LOCAL)
}

/// Where [`walk`] is: the bound variables in scope (symbol, its unknown) and a counter for
/// fresh ones.
#[derive(Default)]
pub(super) struct Scope {
    pub(super) bound: Vec<(String, String)>,
    pub(super) fresh: usize,
    /// The relation's index: the unknowns of bound variables are the relation's own.
    pub(super) relation: usize,
}

impl Scope {
    /// A new unknown of this relation's, named for `what`.
    pub(super) fn local(&mut self, what: &str) -> String {
        self.fresh += 1;
        format!("{LOCAL}{}.{}{LOCAL}{what}", self.relation, self.fresh)
    }
}

pub(super) fn walk_in(
    e: &Expr,
    declared: &dyn Fn(&str) -> Option<Unit>,
    out: &mut Vec<Constraint>,
    scope: &mut Scope,
) -> Form {
    let pure = |x: &Expr, f: Form, what: &str, out: &mut Vec<Constraint>| {
        out.push(Constraint::new(
            (x.to_string(), f),
            ("1".into(), Form::default()),
            what,
        ));
    };
    match e {
        Expr::Num(_) | Expr::Pi => Form::default(),
        Expr::Sym(s) => {
            if let Some((_, local)) = scope.bound.iter().rev().find(|(b, _)| b == s) {
                return Form::var(local);
            }
            // an ellipsis, infinity, a value's written unit: whatever unit its place needs,
            // tied to nothing else
            if s == ELLIPSIS || s == INFINITY || s == WRITTEN_UNIT {
                return Form::var(&scope.local("any"));
            }
            // the operand of an operator written alone: the same on every side
            if s == OPERAND {
                return Form::default();
            }
            let name = unit_name(s);
            match declared(&name) {
                Some(u) => Form::constant(u),
                None => Form::var(&name),
            }
        }
        Expr::Neg(a) => walk_in(a, declared, out, scope),
        Expr::Call(f, a) => {
            let fa = walk_in(a, declared, out, scope);
            match f {
                Func::Sqrt => fa.scaled(&Q::new(1.into(), 2.into())),
                Func::Abs => fa,
                Func::Sign | Func::Heaviside => Form::default(),
                _ => {
                    pure(a, fa, &format!("the argument of {}", f.name()), out);
                    Form::default()
                }
            }
        }
        Expr::Calc(c, body, x, extra) => {
            // the variable of an integral with bounds and the index of a sum are bound: an
            // unknown of their own
            let bound = match c {
                Calc::Int => !extra.is_empty(),
                other => other.binds(),
            };
            let local = bound.then(|| scope.local(x));
            let fx = match &local {
                Some(local) => {
                    let fx = Form::var(local);
                    if matches!(c, Calc::Sum | Calc::Prod) {
                        pure(&Expr::Sym(x.clone()), fx.clone(), "the index of a sum", out);
                    }
                    fx
                }
                None => walk_in(&Expr::Sym(x.clone()), declared, out, scope),
            };
            // the bounds are outside the variable's scope: in `\int_{t_0}^{t} L dt` the upper
            // `t` is the time outside
            for v in extra {
                let fv = walk_in(v, declared, out, scope);
                // a literal 0 bound has every unit, as has infinity
                if every_unit(v) {
                    continue;
                }
                out.push(Constraint::new(
                    (x.clone(), fx.clone()),
                    (v.to_string(), fv),
                    "a variable and its bounds",
                ));
            }
            if let Some(local) = local {
                scope.bound.push((x.clone(), local));
            }
            let fb = walk_in(body, declared, out, scope);
            if bound {
                scope.bound.pop();
            }
            match c {
                Calc::Diff => fb.plus(&fx, &-Q::one()),
                Calc::Int | Calc::Region => fb.plus(&fx, &Q::one()),
                Calc::At
                | Calc::Sum
                | Calc::Max
                | Calc::Min
                | Calc::Lim
                | Calc::Mean
                | Calc::Marked => fb,
                // n factors: the factor's unit n times, when the bounds give n
                Calc::Prod => match (extra[0].exact_constant(), extra[1].exact_constant()) {
                    (Some(lo), Some(hi)) if (&hi - &lo).is_integer() => {
                        fb.scaled(&(hi - lo + Q::one()))
                    }
                    _ => Form::var(&scope.local("power")),
                },
            }
        }
        Expr::Bin(op, a, b) => {
            let fa = walk_in(a, declared, out, scope);
            let fb = if *op == Op::Pow && index_like(b) {
                exponent_walk(b, declared, out, scope)
            } else {
                walk_in(b, declared, out, scope)
            };
            match op {
                Op::Add | Op::Sub => {
                    // a literal 0 has every unit; a number other than 1 alone as a term is a
                    // value in a unit left unsaid (a worked example's `16 I + 4`)
                    let zero = |e: &Expr| every_unit(e) || unsaid(e);
                    if zero(a) {
                        return fb;
                    }
                    if !zero(b) {
                        out.push(Constraint::new(
                            (a.to_string(), fa.clone()),
                            (b.to_string(), fb),
                            "the terms of a sum",
                        ));
                    }
                    fa
                }
                Op::Mul => fa.plus(&fb, &Q::one()),
                Op::Div => fa.plus(&fb, &-Q::one()),
                Op::Pow => {
                    pure(b, fb, "an exponent", out);
                    match b.exact_constant() {
                        Some(k) => fa.scaled(&k),
                        // a dimensional base to a symbolic power (alpha^(i+1)) has a unit no
                        // linear form gives: an unknown of its own, which nothing constrains
                        None => Form::var(&scope.local("power")),
                    }
                }
            }
        }
    }
}

/// Whether an exponent is an index (`\lambda^m`, `x^{n+1}`, `\alpha^{k-i}`, `r^{2n}`): symbols and
/// numbers under sums, with a number beside each product. Its letters name counts, not the
/// quantities the same letters name elsewhere (m a mass, and m in `\lambda^m`).
pub(super) fn index_like(e: &Expr) -> bool {
    match e {
        Expr::Sym(_) | Expr::Num(_) => true,
        Expr::Neg(a) => index_like(a),
        Expr::Bin(Op::Add | Op::Sub, a, b) => index_like(a) && index_like(b),
        Expr::Bin(Op::Mul | Op::Div, a, b) => {
            (matches!(**a, Expr::Num(_)) && index_like(b))
                || (matches!(**b, Expr::Num(_)) && index_like(a))
        }
        _ => false,
    }
}

/// An index exponent walked with each of its letters an unknown of its own (a role apart from
/// the quantity the letter names elsewhere in the paper).
fn exponent_walk(
    b: &Expr,
    declared: &dyn Fn(&str) -> Option<Unit>,
    out: &mut Vec<Constraint>,
    scope: &mut Scope,
) -> Form {
    let letters: Vec<String> = b
        .symbols()
        .into_iter()
        .filter(|s| !scope.bound.iter().any(|(x, _)| x == s))
        .collect();
    for s in &letters {
        let local = scope.local(&format!("exponent {s}"));
        scope.bound.push((s.clone(), local));
    }
    let f = walk_in(b, declared, out, scope);
    for _ in &letters {
        scope.bound.pop();
    }
    f
}

/// The equations of a relation: its sides pairwise equal, every term of every sum equal, every
/// function argument pure, and each dotted symbol its base per second.
pub(super) fn constraints(
    r: &Relation,
    declared: &dyn Fn(&str) -> Option<Unit>,
    index: usize,
) -> Vec<Constraint> {
    let mut out = Vec::new();
    let mut scope = Scope {
        relation: index,
        ..Scope::default()
    };
    let forms: Vec<Form> = r
        .sides
        .iter()
        .map(|s| walk_in(s, declared, &mut out, &mut scope))
        .collect();
    // `a = b = 0` says that both vanish, not that a and b are one quantity
    let all_vanish = r.sides.len() > 2
        && r.sides.last().is_some_and(every_unit)
        && r.rels.iter().all(|rel| *rel == "=");
    for k in 1..forms.len() {
        // in a chain, a side that is a number is a value in some unit (`v = 2\pi r/T =
        // 408/1800 = 0.23\,\text{m/s}`), not a claim that the others are pure numbers
        // a symbol given as a written number (`p_0 = 0.025`, `h(t) = 0.125 \cos(4\pi t) +
        // 0.375`) is a value in a unit left unsaid, not a claim that it is a pure number
        let given = |e: &Expr, other: &Expr| {
            r.sides.len() == 2 && matches!(other, Expr::Sym(_)) && written_number(e) || unsaid(e)
        };
        let value = |e: &Expr| r.sides.len() > 2 && e.symbols().is_empty();
        // a side that is a literal 0 has every unit; a proportionality links no units
        if all_vanish
            || every_unit(&r.sides[k])
            || every_unit(&r.sides[k - 1])
            || value(&r.sides[k])
            || value(&r.sides[k - 1])
            || given(&r.sides[k], &r.sides[k - 1])
            || given(&r.sides[k - 1], &r.sides[k])
            || r.rels.get(k - 1).is_some_and(|rel| !links_units(rel))
        {
            continue;
        }
        out.push(Constraint::new(
            (r.sides[k - 1].to_string(), forms[k - 1].clone()),
            (r.sides[k].to_string(), forms[k].clone()),
            "the sides",
        ));
    }
    // a dot differentiates by the paper's time `t`: in seconds when `t` is declared so, and in
    // whatever unit `t` has otherwise (a nondimensional paper's `\dot{x} = x` is consistent)
    let second = match declared("t") {
        Some(u) => Form::constant(u),
        None => Form::var("t"),
    };
    for (dotted, base, order) in &r.dots {
        let fd = walk_in(
            &Expr::Sym(dotted.clone()),
            declared,
            &mut Vec::new(),
            &mut scope,
        );
        let fb = walk_in(
            &Expr::Sym(base.clone()),
            declared,
            &mut Vec::new(),
            &mut scope,
        );
        out.push(Constraint::new(
            (dotted.clone(), fd),
            (
                format!("{base}/t^{order}"),
                fb.plus(&second, &-Q::from_integer((*order).into())),
            ),
            "a time derivative and its base",
        ));
    }
    out
}

/// Whether `e` is a number other than 0 and 1 standing alone (`12`, `-4`, `0.5`): where a
/// term or a side is expected, a value in a unit the paper leaves unsaid (`12 = 16 I + 4` of a
/// worked example), where `1 + x` says that x is a pure number.
fn unsaid(e: &Expr) -> bool {
    match e {
        Expr::Num(q) => !q.is_zero() && !q.is_one(),
        Expr::Neg(a) => unsaid(a),
        _ => false,
    }
}

/// Whether `e` is a number as a paper writes a value: a literal with a decimal point among its
/// numbers, and no symbol but inside a function's argument (`0.125 \cos(4\pi t) + 0.375`).
fn written_number(e: &Expr) -> bool {
    fn go(e: &Expr, decimal: &mut bool) -> bool {
        match e {
            Expr::Num(q) => {
                *decimal |= !q.is_integer();
                true
            }
            Expr::Pi => true,
            Expr::Sym(_) | Expr::Calc(..) => false,
            Expr::Call(f, a) => !matches!(f, Func::Sqrt | Func::Abs) || go(a, decimal),
            Expr::Neg(a) => go(a, decimal),
            Expr::Bin(_, a, b) => go(a, decimal) && go(b, decimal),
        }
    }
    let mut decimal = false;
    go(e, &mut decimal) && decimal
}

/// The equations of every relation ([`constraints`]; none for an unreadable one).
pub(super) fn all_constraints(
    relations: &[Option<Relation>],
    declared: &BTreeMap<String, Unit>,
) -> Vec<Vec<Constraint>> {
    let decl = |s: &str| declared.get(s).copied();
    relations
        .iter()
        .enumerate()
        .map(|(i, r)| {
            r.as_ref()
                .map_or_else(Vec::new, |r| constraints(r, &decl, i))
        })
        .collect()
}

/// The undeclared symbols a relation's unit forms name.
pub(super) fn unknowns(cs: &[Constraint]) -> BTreeSet<String> {
    cs.iter()
        .flat_map(|c| c.left.1.coeffs.keys().chain(c.right.1.coeffs.keys()))
        .cloned()
        .collect()
}
