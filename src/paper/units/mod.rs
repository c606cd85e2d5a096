//! Units inferred across a paper's relations from the units of a few symbols, the way unit
//! checkers for programs infer them across a code base (CamFort's units-of-measure for Fortran,
//! Phriky-Units for ROS C++), and the relations that break consistency named.
//!
//! A unit is a vector of rational exponents of the seven SI base units ([`Unit`]). The exponents are
//! linear in the formula: a product adds them, a quotient subtracts them, a rational power
//! scales them, the terms of a sum and the sides of a relation are equal, and the argument of
//! `exp`, `sin`, `ln` (and a symbolic exponent) is a pure number. So every formula's unit is an
//! affine form $\sum_s a_s u_s + c$ in the unknown units $u_s$ of the undeclared symbols, with
//! one rational coefficient $a_s$ for all seven dimensions, and each relation gives equations
//! $\sum_s a_s u_s = -c$: a linear system over the rationals with seven right sides, solved
//! exactly by elimination.
//!
//! One bad relation must not poison the rest: relations are added one at a time, those with
//! the fewest undeclared symbols first (a relation of declared symbols only is a plain check),
//! then in the order of the paper; a relation whose equations contradict what the system
//! already fixes is `inconsistent` and adds nothing. A symbol's unit is determined when the
//! system fixes it; a relation with a symbol nothing fixes is `undetermined`.
//!
//! Names: a function application read as an opaque symbol (`{w(x,y,t)}`) has the unit of its
//! function (`w`); a dotted symbol (`zd`, `zdd` from `\dot{z}`, `\ddot{z}`) the unit of its
//! base per second (per second squared), given as [`Relation::dots`].
//!
//! Written by hand: the system is small (tens of unknowns), must stay exact, and must say which
//! relations fixed each unit; no crate does the bookkeeping.
//!
//! Apart: [`declared`] (the units an audit starts from: a units file, the paper's words) and
//! [`with_words`] (the conflicts that the words decide, and a letter scoped per section).

pub mod declared;
pub mod with_words;

use crate::algebra::expr::{Calc, Expr, Func, Op};
use crate::algebra::poly::Q;
use crate::algebra::units::{ELLIPSIS, INFINITY, OPERAND, Unit, WRITTEN_UNIT, every_unit};
use num_traits::{One, ToPrimitive, Zero};
use std::collections::{BTreeMap, BTreeSet};

/// The unit of a formula as an affine form in the unknown units.
#[derive(Clone, Debug, Default, PartialEq)]
struct Form {
    coeffs: BTreeMap<String, Q>,
    konst: [Q; 7],
}

impl Form {
    fn constant(u: Unit) -> Form {
        Form {
            coeffs: BTreeMap::new(),
            konst: u
                .0
                .map(|r| Q::new((*r.numer()).into(), (*r.denom()).into())),
        }
    }

    fn var(name: &str) -> Form {
        Form {
            coeffs: [(name.to_string(), Q::one())].into(),
            konst: Default::default(),
        }
    }

    /// `self + k o`.
    fn plus(mut self, o: &Form, k: &Q) -> Form {
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

    fn scaled(&self, k: &Q) -> Form {
        Form::default().plus(self, k)
    }
}

/// A relation of the paper as the inference reads it.
#[derive(Clone, Debug, Default)]
pub struct Relation {
    /// Its sides, left to right (each pair equal in unit).
    pub sides: Vec<Expr>,
    /// `(dotted, base, order)`: the symbol `dotted` is the `order`-th time derivative of `base`
    /// (`("zd", "z", 1)` from `\dot{z}`); order 0: an increment, in the unit of its base
    /// (`("Deltat", "t", 0)` from `\Delta t`).
    pub dots: Vec<(String, String, u32)>,
    /// The relation signs between the sides (`=`, `<=`, `propto`); a pair of sides joined by
    /// `propto` or `sim` claims no unit of the factor between them and is not linked. Empty:
    /// every pair is linked.
    pub rels: Vec<&'static str>,
}

/// Whether a relation sign claims its two sides are in one unit (all but a proportionality
/// `\propto` and a scaling `\sim`).
pub fn links_units(rel: &str) -> bool {
    !matches!(rel, "propto" | "sim" | "in")
}

/// What the inference says of one relation.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Every side and term agrees, every unit fixed.
    Consistent,
    /// The relation contradicts what the declared units and the other relations fix: the two
    /// terms that disagree and the unit of each.
    Inconsistent {
        /// One term (or side), as text.
        left: String,
        /// Its unit under the inference (or the unit it would need).
        left_unit: String,
        /// The other term.
        right: String,
        /// Its unit.
        right_unit: String,
        /// What must agree: "the sides", "the terms of a sum", "the argument of exp".
        what: String,
    },
    /// Consistent so far, but these symbols' units are fixed by nothing.
    Undetermined(Vec<String>),
}

/// The unit found for a symbol.
#[derive(Clone, Debug, PartialEq)]
pub struct SymbolUnit {
    /// The symbol.
    pub name: String,
    /// Its unit, `None` when nothing fixes it.
    pub unit: Option<Unit>,
    /// Whether it was declared (else inferred).
    pub declared: bool,
    /// The relations (indices into the input) that fixed an inferred unit.
    pub from: Vec<usize>,
}

/// The inference over a paper: a status per relation (in input order) and every symbol met.
#[derive(Clone, Debug)]
pub struct Inference {
    /// One per relation given.
    pub statuses: Vec<Status>,
    /// Every symbol of the relations, declared or not, sorted by name.
    pub symbols: Vec<SymbolUnit>,
}

/// The symbol a name's unit is that of: an opaque application `{w(x,y,t)}` is its function `w`.
pub fn unit_name(s: &str) -> String {
    if let Some(inner) = s.strip_prefix('{')
        && let Some(k) = inner.find('(')
        && k > 0
        && inner[..k].chars().all(|c| c.is_alphanumeric() || c == '_')
    {
        return inner[..k].to_string();
    }
    s.to_string()
}

/// One equation: the unit of `left` equals that of `right`.
#[derive(Clone, Debug)]
struct Constraint {
    left: (String, Form),
    right: (String, Form),
    what: String,
}

impl Constraint {
    fn new(left: (String, Form), right: (String, Form), what: &str) -> Constraint {
        Constraint {
            left,
            right,
            what: what.to_string(),
        }
    }

    /// `(coefficients, right side)` of `left - right = 0`.
    fn equation(&self) -> (BTreeMap<String, Q>, [Q; 7]) {
        let d = self.left.1.clone().plus(&self.right.1, &-Q::one());
        (d.coeffs, d.konst.map(|c| -c))
    }
}

/// The prefix of a bound variable's own unknown: `~2~x` is the variable `x` of the second
/// integral or sum met (its unit is that of its bounds, whatever a symbol `x` elsewhere has).
const LOCAL: char = '~';

/// Whether an unknown is a bound variable's own.
fn is_local(name: &str) -> bool {
    name.starts_with(LOCAL)
}

/// Where [`walk`] is: the bound variables in scope (symbol, its unknown) and a counter for
/// fresh ones.
#[derive(Default)]
struct Scope {
    bound: Vec<(String, String)>,
    fresh: usize,
    /// The relation's index: the unknowns of bound variables are the relation's own.
    relation: usize,
}

impl Scope {
    /// A new unknown of this relation's, named for `what`.
    fn local(&mut self, what: &str) -> String {
        self.fresh += 1;
        format!("{LOCAL}{}.{}{LOCAL}{what}", self.relation, self.fresh)
    }
}

fn walk_in(
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
            let fb = walk_in(b, declared, out, scope);
            match op {
                Op::Add | Op::Sub => {
                    // a literal 0 has every unit
                    let zero = every_unit;
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

/// A row of the eliminated system: `pivot + sum coeffs_v v = rhs`, with the relations it came
/// from.
#[derive(Clone, Debug)]
struct Row {
    coeffs: BTreeMap<String, Q>,
    rhs: [Q; 7],
    from: BTreeSet<usize>,
}

/// The system in reduced echelon form: no pivot appears in another row.
#[derive(Clone, Debug, Default)]
struct System {
    rows: BTreeMap<String, Row>,
}

impl System {
    /// The equation reduced by the pivots: what is left, its right side and its relations.
    fn reduce(
        &self,
        mut coeffs: BTreeMap<String, Q>,
        mut rhs: [Q; 7],
        mut from: BTreeSet<usize>,
    ) -> (BTreeMap<String, Q>, [Q; 7], BTreeSet<usize>) {
        let pivots: Vec<String> = coeffs
            .keys()
            .filter(|v| self.rows.contains_key(*v))
            .cloned()
            .collect();
        for p in pivots {
            let Some(c) = coeffs.remove(&p) else { continue };
            let row = &self.rows[&p];
            for (v, a) in &row.coeffs {
                let e = coeffs.entry(v.clone()).or_insert_with(Q::zero);
                *e -= &c * a;
                if e.is_zero() {
                    coeffs.remove(v);
                }
            }
            for (x, y) in rhs.iter_mut().zip(&row.rhs) {
                *x -= &c * y;
            }
            from.extend(row.from.iter().copied());
        }
        (coeffs, rhs, from)
    }

    /// Adds an equation; `Err` when it contradicts the system (0 = a non-zero unit).
    fn add(&mut self, c: &Constraint, rel: usize) -> Result<(), ()> {
        let (coeffs, rhs) = c.equation();
        let (mut coeffs, mut rhs, from) = self.reduce(coeffs, rhs, [rel].into());
        let Some((pivot, a)) = coeffs.iter().next().map(|(v, a)| (v.clone(), a.clone())) else {
            return if rhs.iter().all(Zero::is_zero) {
                Ok(())
            } else {
                Err(())
            };
        };
        coeffs.remove(&pivot);
        for v in coeffs.values_mut() {
            *v /= &a;
        }
        for x in rhs.iter_mut() {
            *x /= &a;
        }
        // the new pivot leaves every other row
        for row in self.rows.values_mut() {
            let Some(k) = row.coeffs.remove(&pivot) else {
                continue;
            };
            for (v, b) in &coeffs {
                let e = row.coeffs.entry(v.clone()).or_insert_with(Q::zero);
                *e -= &k * b;
                if e.is_zero() {
                    row.coeffs.remove(v);
                }
            }
            for (x, y) in row.rhs.iter_mut().zip(&rhs) {
                *x -= &k * y;
            }
            row.from.extend(from.iter().copied());
        }
        self.rows.insert(pivot, Row { coeffs, rhs, from });
        Ok(())
    }

    /// The unit of `v` when the system fixes it, with the relations that did.
    fn fixed(&self, v: &str) -> Option<(Unit, &BTreeSet<usize>)> {
        let row = self.rows.get(v)?;
        if !row.coeffs.is_empty() {
            return None;
        }
        Some((to_unit(&row.rhs)?, &row.from))
    }

    /// A form's unit under the system, or the form written with its unknowns.
    fn show(&self, f: &Form) -> String {
        let (coeffs, rhs, _) = self.reduce(
            f.coeffs.clone(),
            f.konst.clone().map(|c| -c),
            BTreeSet::new(),
        );
        let konst = rhs.map(|c| -c);
        let base = to_unit(&konst).map_or("?".to_string(), |u| u.to_string());
        if coeffs.is_empty() {
            return base;
        }
        let mut parts: Vec<String> = coeffs
            .iter()
            .map(|(v, a)| {
                if a.is_one() {
                    format!("[{v}]")
                } else {
                    format!("[{v}]^({a})")
                }
            })
            .collect();
        if base != "1" {
            parts.insert(0, base);
        }
        parts.join(" ")
    }
}

fn to_unit(x: &[Q; 7]) -> Option<Unit> {
    let r = |q: &Q| {
        Some(num_rational::Rational64::new(
            q.numer().to_i64()?,
            q.denom().to_i64()?,
        ))
    };
    let mut u = Unit::default();
    for (e, q) in u.0.iter_mut().zip(x) {
        *e = r(q)?;
    }
    Some(u)
}

/// The equations of a relation: its sides pairwise equal, every term of every sum equal, every
/// function argument pure, and each dotted symbol its base per second.
fn constraints(
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
        let value = |e: &Expr| r.sides.len() > 2 && e.symbols().is_empty();
        // a side that is a literal 0 has every unit; a proportionality links no units
        if all_vanish
            || every_unit(&r.sides[k])
            || every_unit(&r.sides[k - 1])
            || value(&r.sides[k])
            || value(&r.sides[k - 1])
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

/// The undeclared symbols a relation's unit forms name.
fn unknowns(cs: &[Constraint]) -> BTreeSet<String> {
    cs.iter()
        .flat_map(|c| c.left.1.coeffs.keys().chain(c.right.1.coeffs.keys()))
        .cloned()
        .collect()
}

/// Infers the units of every symbol of `relations` from the `declared` ones and judges each
/// relation. `None` relations (unreadable) are passed over and get no status of their own
/// (their index still holds a status, `Undetermined(vec![])`, which the caller replaces).
pub fn infer(relations: &[Option<Relation>], declared: &BTreeMap<String, Unit>) -> Inference {
    infer_ordered(relations, declared, false)
}

/// As [`infer`]; with `anchored_first` (units from a paper's words), the relations are taken
/// one at a time against what is fixed so far: a definition that fixes its symbol and claims
/// nothing else, then the relation with the most terms whose units are all fixed (a governing
/// equation, whose known terms fix each other term's unit, before a two-term definition of a
/// derived constant), then the fewest unknowns, in the paper's order.
pub fn infer_ordered(
    relations: &[Option<Relation>],
    declared: &BTreeMap<String, Unit>,
    anchored_first: bool,
) -> Inference {
    let decl = |s: &str| declared.get(s).copied();
    let cs: Vec<Vec<Constraint>> = relations
        .iter()
        .enumerate()
        .map(|(i, r)| {
            r.as_ref()
                .map_or_else(Vec::new, |r| constraints(r, &decl, i))
        })
        .collect();
    let mut order: Vec<usize> = (0..relations.len())
        .filter(|&i| relations[i].is_some())
        .collect();
    // definitions first (a bare undeclared symbol on the left: the paper's own statement of
    // its unit), then the relations with the fewest unknowns, each group in the paper's order
    let defines = |i: usize| {
        relations[i].as_ref().is_some_and(|r| {
            r.sides.len() == 2
                && matches!(&r.sides[0], Expr::Sym(s) if declared.get(&unit_name(s)).is_none())
        })
    };
    // a dotted symbol or an increment whose base is declared is as good as declared (`\Delta
    // V` with V a velocity): it is no unknown when the relations are ordered
    let as_declared: BTreeSet<String> = relations
        .iter()
        .flatten()
        .flat_map(|r| &r.dots)
        .filter(|(_, base, order)| {
            declared.contains_key(base) && (*order == 0 || declared.contains_key("t"))
        })
        .map(|(dotted, _, _)| dotted.clone())
        .collect();
    let open = |i: usize| unknowns(&cs[i]).difference(&as_declared).count();
    let mut system = System::default();
    let mut rejected = BTreeSet::new();
    let mut take = |i: usize, system: &mut System| {
        let mut trial = system.clone();
        if cs[i].iter().all(|c| trial.add(c, i).is_ok()) {
            *system = trial;
        } else {
            rejected.insert(i);
        }
    };
    if anchored_first {
        // one at a time, each chosen against what the system fixes so far
        let mut left: Vec<usize> = order.clone();
        while !left.is_empty() {
            let key = |i: usize| {
                // the unknowns nothing fixes yet (an integral's variable is none)
                let open: BTreeSet<String> = unknowns(&cs[i])
                    .into_iter()
                    .filter(|v| {
                        !is_local(v) && !as_declared.contains(v) && system.fixed(v).is_none()
                    })
                    .collect();
                let known = |e: &Expr| e.symbols().iter().all(|s| !open.contains(&unit_name(s)));
                let r = relations[i].as_ref();
                // it fixes every unknown it names, with what is fixed so far (a definition of
                // known things, `L(\delta) = e^{-\delta t}..`): it can contradict nothing else
                let closes = || {
                    let mut trial = system.clone();
                    cs[i].iter().all(|c| trial.add(c, i).is_ok())
                        && open.iter().all(|v| trial.fixed(v).is_some())
                };
                // a definition that fixes its symbol and claims nothing else: one term on the
                // right (or every term known), every unknown fixed by it
                let pure_definition = r.is_some_and(|r| {
                    defines(i)
                        && !known(&r.sides[0])
                        && (r.sides[1].terms().len() == 1
                            || r.sides[1].terms().iter().all(|t| known(t)))
                        && closes()
                });
                let anchored = r.map_or(0, |r| {
                    r.sides
                        .iter()
                        .flat_map(|e| e.terms())
                        .filter(|t| !t.symbols().is_empty() && known(t))
                        .count()
                });
                (!pure_definition, std::cmp::Reverse(anchored), open.len(), i)
            };
            let Some(k) = (0..left.len()).min_by_key(|&k| key(left[k])) else {
                break;
            };
            let i = left.remove(k);
            take(i, &mut system);
        }
    } else {
        order.sort_by_key(|&i| (!defines(i), open(i), i));
        for &i in &order {
            take(i, &mut system);
        }
    }
    let statuses = (0..relations.len())
        .map(|i| {
            if rejected.contains(&i) {
                return inconsistency(&system, &cs[i]);
            }
            let open: Vec<String> = unknowns(&cs[i])
                .into_iter()
                .filter(|v| !is_local(v) && system.fixed(v).is_none())
                .collect();
            if open.is_empty() && relations[i].is_some() {
                Status::Consistent
            } else {
                Status::Undetermined(open)
            }
        })
        .collect();
    let mut names: BTreeSet<String> = cs
        .iter()
        .flatten()
        .flat_map(|c| {
            c.left
                .1
                .coeffs
                .keys()
                .chain(c.right.1.coeffs.keys())
                .filter(|v| !is_local(v))
                .cloned()
        })
        .collect();
    for r in relations.iter().flatten() {
        for s in &r.sides {
            names.extend(
                s.symbols()
                    .iter()
                    .filter(|x| {
                        !x.is_empty()
                            && ![ELLIPSIS, INFINITY, OPERAND, WRITTEN_UNIT].contains(&x.as_str())
                    })
                    .map(|x| unit_name(x)),
            );
        }
    }
    let symbols = names
        .into_iter()
        .map(|name| {
            if let Some(u) = declared.get(&name) {
                return SymbolUnit {
                    name,
                    unit: Some(*u),
                    declared: true,
                    from: vec![],
                };
            }
            let fixed = system.fixed(&name);
            SymbolUnit {
                unit: fixed.map(|(u, _)| u),
                from: fixed.map_or_else(Vec::new, |(_, f)| f.iter().copied().collect()),
                name,
                declared: false,
            }
        })
        .collect();
    Inference { statuses, symbols }
}

/// The first equation of a rejected relation that the final system contradicts, as the two
/// terms and their units (the first that does not hold if none contradicts alone).
fn inconsistency(system: &System, cs: &[Constraint]) -> Status {
    let broken = cs
        .iter()
        .find(|c| {
            let (coeffs, rhs) = c.equation();
            let (rest, rhs, _) = system.reduce(coeffs, rhs, BTreeSet::new());
            rest.is_empty() && rhs.iter().any(|x| !x.is_zero())
        })
        .or_else(|| {
            cs.iter().find(|c| {
                let (coeffs, rhs) = c.equation();
                let (rest, rhs, _) = system.reduce(coeffs, rhs, BTreeSet::new());
                !rest.is_empty() || rhs.iter().any(|x| !x.is_zero())
            })
        })
        .or(cs.first());
    match broken {
        Some(c) => Status::Inconsistent {
            left: c.left.0.clone(),
            left_unit: system.show(&c.left.1),
            right: c.right.0.clone(),
            right_unit: system.show(&c.right.1),
            what: c.what.clone(),
        },
        None => Status::Undetermined(vec![]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

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
        // the third says v = a t^2: wrong; the fourth fixes v from declared units alone
        let rs = [
            rel("F = k*x"),
            rel("a = F/m"),
            rel("v = a*t^2"),
            rel("v = x/t"),
            rel("E = m*v^2/2"),
        ];
        let d = units(&[("m", "kg"), ("x", "m"), ("t", "s"), ("F", "N")]);
        let inf = infer(&rs, &d);
        assert!(
            matches!(&inf.statuses[2], Status::Inconsistent { .. }),
            "{:?}",
            inf.statuses
        );
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
}
