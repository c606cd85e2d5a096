//! Formulas as text: the parser, printer and converters of the claim files (`verify/*.toml`).
//!
//! A referee writes a printed formula in the paper's notation, e.g. the contact duration of a
//! Hertz impact
//! $$t_c = 3.2181\,(m/k)^{2/5}\,v_0^{-1/5}\qquad\text{as}\qquad
//!   \texttt{3.2181*(m/k)\^{}(2/5)*v0\^{}(-1/5)},$$
//! or $A_1$ of (16) of 000_92d54b11128ea1ec.txt as
//! `E*zeta*(m^2/a^2 + n^2/b^2)^2*h^3*a*b*pi^4/48`.
//!
//! Grammar (`^` binds tightest and to the right, unary minus below it, so `-x^2` is `-(x^2)`):
//! ```text
//! relation := expr (("<" | "<=" | ">" | ">=") expr)?
//! expr     := term (("+" | "-") term)*
//! term     := unary (("*" | "/") unary)*
//! unary    := "-" unary | power
//! power    := atom ("^" unary)?
//! atom     := number | name | function "(" expr ")" | "(" expr ")"
//!           | "diff(" expr "," name ")" | "int(" expr "," name "," expr "," expr ")"
//!           | "at(" expr "," name "," expr ")"
//! ```
//! Numbers (`3`, `3.2181`, `1e-3`) are read as exact rationals; names are
//! `[A-Za-z_][A-Za-z0-9_]*` with dotted parts (`contact.duration`, an outcome quantity); `pi` is
//! the constant; the functions are `sqrt exp ln sin cos tan asin acos atan abs ellipk ellipe
//! factorial gamma erf sign heaviside`, and `max(a, b)`, `min(a, b)`, `beta(a, b)` (read as
//! $(a + b \pm |a - b|)/2$ and $\Gamma(a)\Gamma(b)/\Gamma(a + b)$, so every other part of the tool
//! knows them); and `diff(e, x)`, `int(e, x, lo, hi)`, `at(e, x, v)` (see [`calculus`]).
//!
//! A parsed [`Expr`] is a tree. It becomes an exact [`RatFunc`] when it is rational (integer
//! powers, no functions; `pi` stays a symbol, which is sound for identities because $\pi$ is
//! transcendental), an exact [`Expo`] when it is an exponential polynomial in a time symbol, and
//! is evaluated in `f64` otherwise ([`Expr::eval`]). Printing gives the text a user would write,
//! with only the parentheses the grammar needs, so `parse(print(e)) == e`.
//!
//! Written by hand: a recursive-descent parser is ~300 lines here, and a parser crate would add
//! a dependency for a grammar this small while the exact conversion is ours anyway.

use super::expo::Expo;
use super::poly::{Poly, Q, Sym};
use super::ratfunc::RatFunc;
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::fmt;

pub mod calculus;
mod parse;

pub use parse::{ParseError, parse, parse_inequality};

/// The functions a formula may call. Each name is a call only before `(`; elsewhere it is a
/// symbol, so a paper's `gamma`, `beta` or `erf` may name a parameter (`gamma*(1 + x)` is a
/// product, `gamma(x)` the function).
pub const FUNCTIONS: &[&str] = &[
    "sqrt",
    "exp",
    "ln",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "abs",
    "ellipk",
    "ellipe",
    "factorial",
    "gamma",
    "erf",
    "sign",
    "heaviside",
    "max",
    "min",
    "beta",
];

/// A function of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// Square root.
    Sqrt,
    /// Exponential.
    Exp,
    /// Natural logarithm.
    Ln,
    /// Sine (radians).
    Sin,
    /// Cosine (radians).
    Cos,
    /// Tangent (radians).
    Tan,
    /// Arc sine (radians).
    Asin,
    /// Arc cosine (radians).
    Acos,
    /// Arc tangent (radians).
    Atan,
    /// Hyperbolic sine.
    Sinh,
    /// Hyperbolic cosine.
    Cosh,
    /// Hyperbolic tangent.
    Tanh,
    /// Inverse hyperbolic sine.
    Asinh,
    /// Inverse hyperbolic cosine (the non-negative branch, argument >= 1).
    Acosh,
    /// Inverse hyperbolic tangent (argument in (-1, 1)).
    Atanh,
    /// Absolute value.
    Abs,
    /// The complete elliptic integral of the first kind $K(k)$, modulus $k$ in [0, 1).
    EllipK,
    /// The complete elliptic integral of the second kind $E(k)$, modulus $k$ in [0, 1].
    EllipE,
    /// $n!$; $\Gamma(x + 1)$ off the integers. Exact for an integer in 0..=1000.
    Factorial,
    /// Euler's $\Gamma(x)$.
    Gamma,
    /// The error function.
    Erf,
    /// The sign: -1, 0 or 1 (dimensionless whatever its argument's unit).
    Sign,
    /// Heaviside's step: 0 for x < 0, 1 for x >= 0 (dimensionless whatever its argument's unit).
    Heaviside,
}

impl Func {
    fn from_name(name: &str) -> Option<Func> {
        Some(match name {
            "sqrt" => Func::Sqrt,
            "exp" => Func::Exp,
            "ln" => Func::Ln,
            "sin" => Func::Sin,
            "cos" => Func::Cos,
            "tan" => Func::Tan,
            "asin" => Func::Asin,
            "acos" => Func::Acos,
            "atan" => Func::Atan,
            "sinh" => Func::Sinh,
            "cosh" => Func::Cosh,
            "tanh" => Func::Tanh,
            "asinh" => Func::Asinh,
            "acosh" => Func::Acosh,
            "atanh" => Func::Atanh,
            "abs" => Func::Abs,
            "ellipk" => Func::EllipK,
            "ellipe" => Func::EllipE,
            "factorial" => Func::Factorial,
            "gamma" => Func::Gamma,
            "erf" => Func::Erf,
            "sign" => Func::Sign,
            "heaviside" => Func::Heaviside,
            _ => return None,
        })
    }

    /// The name as written.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Ln => "ln",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Asinh => "asinh",
            Func::Acosh => "acosh",
            Func::Atanh => "atanh",
            Func::Abs => "abs",
            Func::EllipK => "ellipk",
            Func::EllipE => "ellipe",
            Func::Factorial => "factorial",
            Func::Gamma => "gamma",
            Func::Erf => "erf",
            Func::Sign => "sign",
            Func::Heaviside => "heaviside",
        }
    }

    pub(crate) fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Ln => x.ln(),
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            Func::Tan => x.tan(),
            Func::Asin => x.asin(),
            Func::Acos => x.acos(),
            Func::Atan => x.atan(),
            Func::Sinh => x.sinh(),
            Func::Cosh => x.cosh(),
            Func::Tanh => x.tanh(),
            Func::Asinh => x.asinh(),
            Func::Acosh => x.acosh(),
            Func::Atanh => x.atanh(),
            Func::Abs => x.abs(),
            Func::EllipK => complete_elliptic(x).0,
            Func::EllipE => complete_elliptic(x).1,
            Func::Factorial => {
                if (0.0..=170.0).contains(&x) && x.fract() == 0.0 {
                    (1..=x as u32).map(f64::from).product()
                } else {
                    statrs::function::gamma::gamma(x + 1.0)
                }
            }
            Func::Gamma => statrs::function::gamma::gamma(x),
            Func::Erf => statrs::function::erf::erf(x),
            Func::Sign => {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    x * 0.0 // 0, or NaN for NaN
                }
            }
            Func::Heaviside => {
                if x >= 0.0 {
                    1.0
                } else if x < 0.0 {
                    0.0
                } else {
                    f64::NAN
                }
            }
        }
    }
}

/// $K(k)$ and $E(k)$ for modulus `k` in [0, 1] (NaN outside), from Carlson's symmetric forms
/// (the `ellip` crate) with the complementary parameter $m_c = (1-k)(1+k)$: forming $m = k^2$
/// near $k = 1$ would lose the digits that matter.
pub fn complete_elliptic(k: f64) -> (f64, f64) {
    if !(0.0..=1.0).contains(&k.abs()) {
        return (f64::NAN, f64::NAN);
    }
    let mc = (1.0 - k) * (1.0 + k);
    // K = R_F(0, mc, 1), E = R_F(0, mc, 1) - k^2 R_D(0, mc, 1)/3
    let rf = ellip::elliprf(0.0, mc, 1.0).unwrap_or(f64::INFINITY);
    let rd = ellip::elliprd(0.0, mc, 1.0).unwrap_or(f64::INFINITY);
    if mc <= 0.0 {
        return (f64::INFINITY, 1.0);
    }
    (rf, rf - k * k * rd / 3.0)
}

/// $\sin(c\pi)$ (or $\cos(c\pi)$) exactly, when the argument is a rational multiple $c\pi$ and
/// the value is rational ($6c$ an integer, the value then in $\{0, \pm 1/2, \pm 1\}$): a mode
/// shape $\sin(m\pi x/a)$ at an edge or the centre, with $m$ given.
fn sin_cos_of_pi_multiple(cos: bool, arg: &RatFunc) -> Option<Q> {
    let c = if arg.is_zero() {
        Q::zero()
    } else {
        arg.div(&RatFunc::sym("pi"))?.as_constant()?
    };
    let six = c * Q::from_integer(6.into());
    if !six.denom().is_one() {
        return None;
    }
    // sin(k pi/6) for k mod 12; cos(x) = sin(x + pi/2)
    let k: BigInt =
        (six.to_integer() + BigInt::from(if cos { 3 } else { 0 })).mod_floor(&BigInt::from(12));
    let half = Q::new(1.into(), 2.into());
    Some(match k.to_u8()? {
        0 | 6 => Q::zero(),
        1 | 5 => half,
        3 => Q::one(),
        7 | 11 => -half,
        9 => -Q::one(),
        _ => return None,
    })
}

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

impl Op {
    fn symbol(self) -> &'static str {
        match self {
            Op::Add => " + ",
            Op::Sub => " - ",
            Op::Mul => "*",
            Op::Div => "/",
            Op::Pow => "^",
        }
    }
    fn prec(self) -> u8 {
        match self {
            Op::Add | Op::Sub => 1,
            Op::Mul | Op::Div => 2,
            Op::Pow => 4,
        }
    }
}

/// A formula as a tree.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A literal, exact (never negative: `-3` is `Neg(3)`).
    Num(Q),
    /// A symbol or a dotted outcome quantity.
    Sym(String),
    /// The constant pi.
    Pi,
    /// Unary minus.
    Neg(Box<Expr>),
    /// A binary operation.
    Bin(Op, Box<Expr>, Box<Expr>),
    /// A function call.
    Call(Func, Box<Expr>),
    /// A calculus operation on a formula with respect to a variable (`diff(e, x)`,
    /// `int(e, x, lo, hi)`, `at(e, x, v)`): the operation, the formula, the variable and the
    /// further arguments (`[lo, hi]` or `[v]`). See [`calculus`].
    Calc(Calc, Box<Expr>, String, Vec<Expr>),
}

/// A calculus operation of a formula.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Calc {
    /// `diff(e, x)`: the derivative of `e` with respect to `x`.
    Diff,
    /// `int(e, x, lo, hi)`: the definite integral of `e` over `x` from `lo` to `hi`.
    Int,
    /// `at(e, x, v)`: `e` with `x` replaced by `v`.
    At,
    /// `sum(e, i, lo, hi)`: the finite sum of `e` over the integers `i` from `lo` to `hi`.
    Sum,
    /// `prod(e, i, lo, hi)`: the product of `e` over the integers `i` from `lo` to `hi` (read
    /// from a paper's `\prod`).
    Prod,
    /// `max(e, i)`: the largest `e` over the index `i` (a paper's `\max_i`, `\sup`); not
    /// computed: its unit is that of `e`.
    Max,
    /// `min(e, i)`: the least `e` over the index `i` (`\min_i`, `\inf`); not computed.
    Min,
    /// `lim(e, x, v)`: the limit of `e` as `x` tends to `v` (`\lim_{x \to v}`); not computed.
    Lim,
    /// `mean(e)`: an average of `e` (`\langle e \rangle`); not computed.
    Mean,
    /// `region(e, s)`: the integral of `e` over a region with the element `d s` (`\int_V e
    /// dV`, `\iint e d\xi d\eta` as two); not computed: its unit is that of `e s`.
    Region,
    /// `marked(e)`: `e` with a mark the formula language does not compute: taken where an
    /// evaluation bar or a subscript says (`F \big|_a^b`, `(\partial V/\partial q)_0`), a
    /// component (`[\mathbf{D}]_{ab}`), a conjugate or transpose (`[P]^*`), a real part; not
    /// computed: its unit is that of `e`.
    Marked,
}

impl Calc {
    fn from_name(name: &str) -> Option<Calc> {
        Some(match name {
            "diff" => Calc::Diff,
            "int" => Calc::Int,
            "at" => Calc::At,
            "sum" => Calc::Sum,
            _ => return None,
        })
    }

    /// The name as written.
    pub fn name(self) -> &'static str {
        match self {
            Calc::Diff => "diff",
            Calc::Int => "int",
            Calc::At => "at",
            Calc::Sum => "sum",
            Calc::Prod => "prod",
            Calc::Max => "max",
            Calc::Min => "min",
            Calc::Lim => "lim",
            Calc::Mean => "mean",
            Calc::Region => "region",
            Calc::Marked => "marked",
        }
    }

    /// Whether the variable is bound (its own, whatever a symbol of its name is outside).
    pub fn binds(self) -> bool {
        !matches!(self, Calc::Diff | Calc::At | Calc::Region | Calc::Marked)
    }

    /// How many arguments follow the formula and the variable.
    pub fn extra_args(self) -> usize {
        match self {
            Calc::Diff => 0,
            Calc::Int => 2,
            Calc::At => 1,
            Calc::Sum | Calc::Prod => 2,
            Calc::Max | Calc::Min | Calc::Mean | Calc::Region | Calc::Marked => 0,
            Calc::Lim => 1,
        }
    }
}

/// A comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rel {
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
}

impl Rel {
    /// As written.
    pub fn symbol(self) -> &'static str {
        match self {
            Rel::Lt => "<",
            Rel::Le => "<=",
            Rel::Gt => ">",
            Rel::Ge => ">=",
        }
    }
    /// Whether `l REL r` holds.
    pub fn holds(self, l: f64, r: f64) -> bool {
        match self {
            Rel::Lt => l < r,
            Rel::Le => l <= r,
            Rel::Gt => l > r,
            Rel::Ge => l >= r,
        }
    }
}

/// An inequality `lhs REL rhs`.
#[derive(Clone, Debug, PartialEq)]
pub struct Inequality {
    /// Left side.
    pub lhs: Expr,
    /// The relation.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
}

impl Inequality {
    /// How far the inequality is from failing, in units of the larger side (positive: holds with
    /// margin; negative: violated by that much).
    pub fn margin(&self, l: f64, r: f64) -> f64 {
        let scale = l.abs().max(r.abs()).max(f64::MIN_POSITIVE);
        match self.rel {
            Rel::Lt | Rel::Le => (r - l) / scale,
            Rel::Gt | Rel::Ge => (l - r) / scale,
        }
    }
}

impl fmt::Display for Inequality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {} {}", self.lhs, self.rel.symbol(), self.rhs)
    }
}

/// Writes an exact rational literal as a decimal (the parser reads literals only as decimals, so
/// their denominators divide a power of ten), or as `n/d` for other values.
fn number_text(v: &Q) -> String {
    let (n, d) = (v.numer().clone(), v.denom().clone());
    let mut den = d.clone();
    let (two, five) = (BigInt::from(2), BigInt::from(5));
    let mut digits = 0usize;
    let (mut p2, mut p5) = (0usize, 0usize);
    while (&den % &two).is_zero() {
        den /= &two;
        p2 += 1;
    }
    while (&den % &five).is_zero() {
        den /= &five;
        p5 += 1;
    }
    if !den.is_one() {
        return format!("{n}/{d}");
    }
    digits += p2.max(p5);
    if digits == 0 {
        let plain = n.to_string();
        let sci = scientific(&n, 0);
        return if sci.len() + 1 < plain.len() {
            sci
        } else {
            plain
        };
    }
    let scaled = &n * num_traits::pow(BigInt::from(10), digits) / &d;
    let s = scaled.abs().to_string();
    let s = format!("{s:0>width$}", width = digits + 1);
    let (int, frac) = s.split_at(s.len() - digits);
    let sign = if scaled.is_negative() { "-" } else { "" };
    let plain = format!("{sign}{int}.{frac}");
    let sci = scientific(&scaled, -(digits as i64));
    if sci.len() + 1 < plain.len() {
        sci
    } else {
        plain
    }
}

/// `m * 10^e` as `1.5e-9` (the mantissa's trailing zeros moved into the exponent).
fn scientific(m: &BigInt, mut e: i64) -> String {
    let mut digits = m.abs().to_string();
    while digits.len() > 1 && digits.ends_with('0') {
        digits.pop();
        e += 1;
    }
    let sign = if m.is_negative() { "-" } else { "" };
    let exp = e + digits.len() as i64 - 1;
    let (head, tail) = digits.split_at(1);
    if tail.is_empty() {
        format!("{sign}{head}e{exp}")
    } else {
        format!("{sign}{head}.{tail}e{exp}")
    }
}

impl Expr {
    /// A symbol.
    pub fn sym(name: &str) -> Expr {
        Expr::Sym(name.to_string())
    }

    /// Binding strength when printed: atoms 5, `^` 4, unary minus 3, `* /` 2, `+ -` 1.
    fn prec(&self) -> u8 {
        match self {
            Expr::Num(v) if v.is_negative() => 3,
            Expr::Num(v) if !v.denom().is_one() && number_text(v).contains('/') => 2,
            Expr::Num(_) | Expr::Sym(_) | Expr::Pi | Expr::Call(..) | Expr::Calc(..) => 5,
            Expr::Neg(_) => 3,
            Expr::Bin(op, ..) => op.prec(),
        }
    }

    fn write(&self, out: &mut String) {
        let wrap = |e: &Expr, paren: bool, out: &mut String| {
            if paren {
                out.push('(');
                e.write(out);
                out.push(')');
            } else {
                e.write(out);
            }
        };
        match self {
            Expr::Num(v) => out.push_str(&number_text(v)),
            Expr::Sym(s) => out.push_str(s),
            Expr::Pi => out.push_str("pi"),
            Expr::Neg(e) => {
                out.push('-');
                wrap(e, e.prec() < 3, out);
            }
            Expr::Call(f, a) => {
                out.push_str(f.name());
                out.push('(');
                a.write(out);
                out.push(')');
            }
            Expr::Calc(c, body, var, extra) => {
                out.push_str(c.name());
                out.push('(');
                body.write(out);
                if !var.is_empty() {
                    out.push_str(", ");
                    out.push_str(var);
                }
                for e in extra {
                    out.push_str(", ");
                    e.write(out);
                }
                out.push(')');
            }
            Expr::Bin(op, l, r) => {
                let p = op.prec();
                match op {
                    Op::Pow => {
                        // right-associative; the exponent is a `unary`
                        wrap(l, l.prec() <= p, out);
                        out.push('^');
                        wrap(r, r.prec() < 3, out);
                    }
                    _ => {
                        // left-associative; a `unary` operand needs no parentheses after an
                        // operator, but a product's left operand must not be a bare negation
                        // of a sum, which `prec` already covers
                        wrap(l, l.prec() < p, out);
                        out.push_str(op.symbol());
                        wrap(r, r.prec() <= p, out);
                    }
                }
            }
        }
    }

    /// Every symbol the formula uses (dotted names included, `pi` excluded), sorted, once each;
    /// the variable of a `diff`, `int` or `at` too (it needs a unit like any symbol), not the index
    /// of a `sum` (a pure number).
    pub fn symbols(&self) -> Vec<String> {
        self.walk_symbols(false)
    }

    /// The symbols the value depends on: [`Expr::symbols`] without the variable of an `int` or
    /// an `at` inside (which is bound there).
    pub fn free_symbols(&self) -> Vec<String> {
        self.walk_symbols(true)
    }

    fn walk_symbols(&self, free: bool) -> Vec<String> {
        fn go(e: &Expr, free: bool, out: &mut Vec<String>) {
            match e {
                Expr::Sym(s) => out.push(s.clone()),
                Expr::Num(_) | Expr::Pi => {}
                Expr::Neg(a) | Expr::Call(_, a) => go(a, free, out),
                Expr::Bin(_, a, b) => {
                    go(a, free, out);
                    go(b, free, out);
                }
                Expr::Calc(c, body, var, extra) => {
                    let mut inner = Vec::new();
                    go(body, free, &mut inner);
                    if matches!(c, Calc::Sum | Calc::Prod) {
                        // the index of a sum is bound and a pure number: it needs no unit
                        inner.retain(|s| s != var);
                    } else if free && !matches!(c, Calc::Diff | Calc::Region) {
                        inner.retain(|s| s != var);
                    } else if !free {
                        inner.push(var.clone());
                    }
                    out.extend(inner);
                    for e in extra {
                        go(e, free, out);
                    }
                }
            }
        }
        let mut v = Vec::new();
        go(self, free, &mut v);
        v.sort();
        v.dedup();
        v
    }

    /// Replaces symbols by expressions (`m` -> `1`).
    pub fn substitute(&self, with: &dyn Fn(&str) -> Option<Expr>) -> Expr {
        match self {
            Expr::Sym(s) => with(s).unwrap_or_else(|| self.clone()),
            Expr::Num(_) | Expr::Pi => self.clone(),
            Expr::Neg(a) => Expr::Neg(Box::new(a.substitute(with))),
            Expr::Call(f, a) => Expr::Call(*f, Box::new(a.substitute(with))),
            Expr::Bin(op, a, b) => Expr::Bin(
                *op,
                Box::new(a.substitute(with)),
                Box::new(b.substitute(with)),
            ),
            // the variable is local to the operation: it is not replaced inside
            Expr::Calc(c, body, var, extra) => Expr::Calc(
                *c,
                Box::new(body.substitute(&|s: &str| if s == var { None } else { with(s) })),
                var.clone(),
                extra.iter().map(|e| e.substitute(with)).collect(),
            ),
        }
    }

    /// The terms of a sum (a difference's, a negation's), or the formula itself.
    pub fn terms(&self) -> Vec<&Expr> {
        match self {
            Expr::Bin(Op::Add | Op::Sub, a, b) => {
                let mut v = a.terms();
                v.extend(b.terms());
                v
            }
            Expr::Neg(a) => a.terms(),
            other => vec![other],
        }
    }

    /// The exact value when the formula is a rational number (no symbols, integer powers).
    pub fn exact_constant(&self) -> Option<Q> {
        self.to_ratfunc().and_then(|r| r.as_constant())
    }

    /// The formula as an exact rational function, when it is one: `+ - * /`, integer powers (a
    /// power whose exponent is an exact integer), no functions. `pi` is the symbol `pi`.
    pub fn to_ratfunc(&self) -> Option<RatFunc> {
        Some(match self {
            Expr::Num(v) => RatFunc::from_q(v.clone()),
            Expr::Sym(s) => RatFunc::sym(s),
            Expr::Pi => RatFunc::sym("pi"),
            Expr::Neg(a) => -&a.to_ratfunc()?,
            Expr::Call(f @ (Func::Sin | Func::Cos), a) => {
                return RatFunc::from_q(sin_cos_of_pi_multiple(*f == Func::Cos, &a.to_ratfunc()?)?)
                    .into();
            }
            // the hyperbolic functions and their inverses at the points where they are rational
            Expr::Call(Func::Sinh | Func::Tanh | Func::Asinh | Func::Atanh, a)
                if a.exact_constant()?.is_zero() =>
            {
                RatFunc::from_q(Q::zero())
            }
            Expr::Call(Func::Cosh, a) if a.exact_constant()?.is_zero() => RatFunc::one(),
            Expr::Call(Func::Acosh, a) if a.exact_constant()?.is_one() => {
                RatFunc::from_q(Q::zero())
            }
            Expr::Call(Func::Factorial, a) => {
                let n = a.exact_constant()?;
                let n = n.is_integer().then(|| n.to_integer().to_u32())??;
                if n > 1000 {
                    return None;
                }
                RatFunc::from_q(Q::from_integer(
                    (1..=n).fold(BigInt::from(1), |acc, k| acc * k),
                ))
            }
            Expr::Call(..) => return None,
            Expr::Calc(Calc::Int, body, var, extra) => {
                calculus::integral_ratfunc(&body.lower().ok()?, var, &extra[0], &extra[1])?
            }
            Expr::Calc(..) => return self.lower().ok()?.to_ratfunc(),
            Expr::Bin(op, a, b) => {
                if *op == Op::Pow {
                    let e = b.exact_constant()?;
                    if !e.denom().is_one() {
                        return None;
                    }
                    let e = e.to_integer().to_i32()?;
                    if e.unsigned_abs() > 64 {
                        return None;
                    }
                    return a.to_ratfunc()?.powi(e);
                }
                let (x, y) = (a.to_ratfunc()?, b.to_ratfunc()?);
                match op {
                    Op::Add => &x + &y,
                    Op::Sub => &x - &y,
                    Op::Mul => &x * &y,
                    Op::Div => x.div(&y)?,
                    Op::Pow => unreachable!("handled above"),
                }
            }
        })
    }

    /// The formula as a rational function in which every function value that is not an exact
    /// rational (`sin(n*pi*y/b)`, `exp(-t)`) and every integral that is not exact stands as a
    /// symbol of its own, named by its text (`{sin(n*pi*y/b)}`). A difference that is zero in
    /// this form is zero for every value of those functions, so it proves an identity; a non-zero
    /// one proves nothing (`sin(x)^2 + cos(x)^2 - 1` is not zero here).
    pub fn to_ratfunc_opaque(&self) -> Option<RatFunc> {
        fn go(e: &Expr) -> Expr {
            match e {
                Expr::Num(_) | Expr::Sym(_) | Expr::Pi => e.clone(),
                Expr::Neg(a) => Expr::Neg(Box::new(go(a))),
                Expr::Bin(op, a, b) => Expr::Bin(*op, Box::new(go(a)), Box::new(go(b))),
                Expr::Call(..) | Expr::Calc(..) => match e.to_ratfunc() {
                    Some(_) => e.clone(),
                    None => Expr::Sym(format!("{{{e}}}")),
                },
            }
        }
        go(&self.lower().ok()?).to_ratfunc()
    }

    /// The formula as an exact exponential polynomial in the time symbol `t`: sums of
    /// `c * t^k * exp(-rate*t)` with `c` rational in the other symbols and `rate` a polynomial
    /// in them. `None` when it is not one (a division by something that depends on `t`, a power
    /// of `t` that is not a non-negative integer, `exp` of something not linear in `t`).
    pub fn to_expo(&self, t: &str) -> Option<Expo> {
        let tsym = Sym::new(t);
        let free = |e: &Expr| -> Option<RatFunc> {
            let r = e.to_ratfunc()?;
            (!r.depends_on(tsym)).then_some(r)
        };
        Some(match self {
            Expr::Sym(s) if s == t => Expo::monomial(RatFunc::one(), 1),
            Expr::Num(_) | Expr::Sym(_) | Expr::Pi => Expo::monomial(self.to_ratfunc()?, 0),
            Expr::Neg(a) => -&a.to_expo(t)?,
            Expr::Call(Func::Exp, arg) => {
                let r = arg.to_ratfunc()?;
                if r.denom().as_constant().is_none_or(|c| c.is_zero()) {
                    return None;
                }
                let num = r.numer();
                if num.degree_in(tsym) != 1 || !num.coeff_of(tsym, 0).is_zero() {
                    return None;
                }
                let slope = num.coeff_of(tsym, 1);
                let inv = Q::one() / r.denom().as_constant()?;
                let rate: Poly = slope.scale(&-inv);
                Expo::part(RatFunc::one(), 0, rate)
            }
            // sinh and cosh of a multiple of t: (exp(x) -+ exp(-x))/2
            Expr::Call(f @ (Func::Sinh | Func::Cosh), arg) if free(self).is_none() => {
                let up = Expr::Call(Func::Exp, arg.clone()).to_expo(t)?;
                let down = Expr::Call(Func::Exp, Box::new(Expr::Neg(arg.clone()))).to_expo(t)?;
                let half = RatFunc::from_q(Q::new(1.into(), 2.into()));
                if *f == Func::Sinh {
                    (&up - &down).scale(&half)
                } else {
                    (&up + &down).scale(&half)
                }
            }
            Expr::Call(..) => Expo::monomial(free(self)?, 0),
            // int_0^t g(s) ds, g an exponential polynomial in s (t may appear in it)
            Expr::Calc(Calc::Int, body, s, b)
                if b[0].exact_constant().is_some_and(|v| v.is_zero())
                    && b[1] == Expr::Sym(t.to_string())
                    && s != t =>
            {
                body.lower().ok()?.to_expo(s)?.integral().absorb(tsym)?
            }
            Expr::Calc(Calc::Int, ..) => Expo::monomial(free(self)?, 0),
            Expr::Calc(..) => return self.lower().ok()?.to_expo(t),
            Expr::Bin(op, a, b) => match op {
                Op::Add => &a.to_expo(t)? + &b.to_expo(t)?,
                Op::Sub => &a.to_expo(t)? - &b.to_expo(t)?,
                Op::Mul => &a.to_expo(t)? * &b.to_expo(t)?,
                Op::Div => a.to_expo(t)?.scale(&free(b)?.inv()?),
                Op::Pow => {
                    let e = b.exact_constant()?;
                    if !e.denom().is_one() || e.is_negative() {
                        // a negative power is a division: fine when the base is free of t
                        return Some(Expo::monomial(free(self)?, 0));
                    }
                    let k = e.to_integer().to_u32().filter(|k| *k <= 64)?;
                    let base = a.to_expo(t)?;
                    let mut acc = Expo::monomial(RatFunc::one(), 0);
                    for _ in 0..k {
                        acc = &acc * &base;
                    }
                    acc
                }
            },
        })
    }

    /// Evaluates in `f64`; `value` gives each symbol's value (`None`: unknown).
    pub fn eval(&self, value: &dyn Fn(&str) -> Option<f64>) -> Result<f64, String> {
        Ok(match self {
            Expr::Num(v) => v.to_f64().unwrap_or(f64::NAN),
            Expr::Sym(s) => value(s).ok_or_else(|| format!("no value for `{s}`"))?,
            Expr::Pi => std::f64::consts::PI,
            Expr::Neg(a) => -a.eval(value)?,
            Expr::Call(f, a) => f.apply(a.eval(value)?),
            Expr::Calc(Calc::Int, body, var, extra) => {
                let body = body.lower()?;
                let (lo, hi) = (extra[0].eval(value)?, extra[1].eval(value)?);
                calculus::integral_f64(
                    &|x: f64| body.eval(&|s: &str| if s == var { Some(x) } else { value(s) }),
                    lo,
                    hi,
                )?
            }
            Expr::Calc(Calc::Sum, body, var, extra) => {
                let (lo, hi) = (extra[0].eval(value)?, extra[1].eval(value)?);
                let (lo, hi) = calculus::sum_range(lo, hi, body)?;
                let mut acc = 0.0;
                for i in lo..=hi {
                    let x = i as f64;
                    acc += body.eval(&|s: &str| if s == var { Some(x) } else { value(s) })?;
                }
                acc
            }
            Expr::Calc(..) => self.lower()?.eval(value)?,
            Expr::Bin(op, a, b) => {
                let (x, y) = (a.eval(value)?, b.eval(value)?);
                match op {
                    Op::Add => x + y,
                    Op::Sub => x - y,
                    Op::Mul => x * y,
                    Op::Div => x / y,
                    Op::Pow => match small_power(b) {
                        Some(n) => x.powi(n),
                        None => x.powf(y),
                    },
                }
            }
        })
    }
}

/// The exponent as [`Expr::eval`] raises to it with `powi`: an exact integer below 64 in size
/// (a number read as such without the exact algebra).
pub(crate) fn small_power(b: &Expr) -> Option<i32> {
    let small = |e: &Q| {
        (e.denom().is_one() && e.numer().abs() < BigInt::from(64))
            .then(|| e.to_integer().to_i32().unwrap_or(0))
    };
    match b {
        Expr::Num(e) => small(e),
        _ => small(&b.exact_constant()?),
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut s = String::new();
        self.write(&mut s);
        f.write_str(&s)
    }
}

#[cfg(test)]
mod tests;
