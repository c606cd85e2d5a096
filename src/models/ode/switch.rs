//! Right sides that switch with the sign of a formula (`sign(th)`, `heaviside(x - a)`): each
//! switch's branch is held between its zeros, and its zero is located as an event.
//!
//! An integrator that steps across a jump of the right side sees a large error estimate and
//! shrinks its step until the jump lies between two steps; after every impact of a rocking
//! block that is dozens of rejected steps. So the right sides are compiled with each
//! `sign(g)` read from a held value `s` (and `heaviside(g)` as `(1 + s)/2`): the right side is
//! then smooth, the branch continued past the zero while a step is tried, and the zero of `g` is
//! an event that stops the integrator, where `s` is set to the side the motion goes into.
//!
//! The side: `sign(g)` away from the zero; at the zero (within a few ulps of `t`, where an
//! event or a jump leaves the state) the sign of `dg/dt`, the time derivative of `g` along the
//! right sides with `s` set to each side in turn: the side whose `dg/dt` carries the motion
//! into it. When both sides would carry it back (a sliding state, as friction at rest) the held
//! value is 0, `sign(0)`.

use super::compile::Program;
use super::formulas::Reader;
use crate::algebra::expr::{Expr, Func, Op};

/// A switch: the formula whose sign a right side reads, and its time derivative.
#[derive(Clone, Debug)]
pub(super) struct Switch {
    /// `g`, of `t`, the states and the parameters.
    pub(super) arg: Program,
    /// `dg/dt` along the right sides, with the held values in their slots.
    pub(super) rate: Program,
    /// `g` as written, for messages.
    pub(super) text: String,
}

/// The name of the held value of switch `j`.
pub(super) fn held_name(j: usize) -> String {
    format!("#s{j}")
}

/// `e` with each `sign(g)` and `heaviside(g)` whose `g` depends on `t` or a state read from a
/// held value; the `g`s, in order of first appearance, added to `args`.
pub(super) fn hold(e: &Expr, states: &[String], args: &mut Vec<Expr>) -> Expr {
    let rec = |x: &Expr, args: &mut Vec<Expr>| Box::new(hold(x, states, args));
    match e {
        Expr::Call(f @ (Func::Sign | Func::Heaviside), a)
            if a.symbols().iter().any(|s| s == "t" || states.contains(s)) =>
        {
            let j = match args.iter().position(|g| g == a.as_ref()) {
                Some(j) => j,
                None => {
                    args.push((**a).clone());
                    args.len() - 1
                }
            };
            let s = Expr::Sym(held_name(j));
            if *f == Func::Sign {
                s
            } else {
                let one = Expr::Num(num_rational::BigRational::from_integer(1.into()));
                let two = Expr::Num(num_rational::BigRational::from_integer(2.into()));
                Expr::Bin(
                    Op::Div,
                    Box::new(Expr::Bin(Op::Add, Box::new(one), Box::new(s))),
                    Box::new(two),
                )
            }
        }
        Expr::Neg(a) => Expr::Neg(rec(a, args)),
        Expr::Call(f, a) => Expr::Call(*f, rec(a, args)),
        Expr::Bin(op, a, b) => Expr::Bin(*op, rec(a, args), rec(b, args)),
        _ => e.clone(),
    }
}

impl Reader<'_> {
    /// The switches of the right sides `held` (already read through [`hold`]): each `g`
    /// compiled, and `dg/dt` = dg/dt + sum_i dg/dx_i f_i. `None` for a `g` without a symbolic
    /// derivative (its `sign` is then read as written).
    pub(super) fn switches(
        &self,
        args: &[Expr],
        held: &[Expr],
        states: &[String],
    ) -> Option<Vec<Switch>> {
        let mut out = Vec::new();
        for g in args {
            let lowered = g.lower().ok()?;
            let mut rate = crate::algebra::expr::calculus::derivative(&lowered, "t").ok()?;
            for (x, f) in states.iter().zip(held) {
                let d = crate::algebra::expr::calculus::derivative(&lowered, x).ok()?;
                rate = Expr::Bin(
                    Op::Add,
                    Box::new(rate),
                    Box::new(Expr::Bin(Op::Mul, Box::new(d), Box::new(f.clone()))),
                );
            }
            out.push(Switch {
                arg: self.compile(g, "equations").ok()?,
                rate: self.compile(&rate, "equations").ok()?,
                text: g.to_string(),
            });
        }
        Some(out)
    }
}

/// The side switch `j` is on at `(t, y)` ([`crate::models::ode::switch`]'s module doc): `g`
/// and `rate(s)` give `g` and `dg/dt` with the held value of `j` set to `s`.
pub(super) fn side(t: f64, g: f64, rate: &dyn Fn(f64) -> f64) -> f64 {
    let (up, down) = (rate(1.0), rate(-1.0));
    // within a few ulps of t of the zero: what the motion does decides
    let near = 256.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE);
    if g != 0.0 && g.abs() > near * up.abs().max(down.abs()) {
        return g.signum();
    }
    match (up > 0.0, down < 0.0) {
        (true, false) => 1.0,
        (false, true) => -1.0,
        (true, true) => {
            if g < 0.0 {
                -1.0
            } else {
                1.0
            }
        }
        (false, false) => 0.0,
    }
}
