//! Calculus inside a formula: `diff(e, x)`, `int(e, x, lo, hi)` and `at(e, x, v)`, so that a
//! claims file can carry a derivation, not only its end: (9) of 000_92d54b11128ea1ec.txt is
//! checked by differentiating the printed Duhamel integral twice and finding (1) and (4);
//! (1.7) of 001_989b2e860c39ca83.txt by integrating (1.1) over a base and finding (1.4), (1.6).
//!
//! - `diff` is symbolic, on the tree ([`derivative`]), with the usual rules, the chain rule for
//!   every function (`ellipk`, `ellipe` included: $dK/dk = E/(k(1-k^2)) - K/k$,
//!   $dE/dk = (E-K)/k$) and Leibniz's rule for an integral whose bounds or integrand depend on
//!   the variable. The result is exact wherever the formula is rational.
//! - `int` is exact when the integrand is a polynomial in the variable with coefficients
//!   rational in the other symbols ([`integral_ratfunc`]); otherwise it is evaluated in `f64` by
//!   tanh-sinh quadrature ([`integral_f64`], Takahashi and Mori's double-exponential rule, levels
//!   halved until two agree), which never evaluates at an endpoint and converges at an
//!   integrable endpoint singularity (`sqrt(1 - x^2)`, `1/sqrt(x)`) as fast as for an analytic
//!   integrand. Each evaluation's error estimate (the last two levels' difference) is logged
//!   per thread ([`quadrature_log`]), so a comparison can widen its tolerance by it and say so.
//!   Written by hand because the integrand is fallible (a formula evaluation returns `Result`)
//!   and nests (`int(int(...))`), which the crates' `Fn(f64) -> f64` rules cannot carry.
//! - `at` substitutes.
//!
//! Written by hand: a computer-algebra crate would bring its own expression type; these rules are
//! ~200 lines over ours.

use super::{Calc, Expr, Func, Op};
use crate::algebra::poly::{Monomial, Poly, Q, Sym, qi};
use crate::algebra::ratfunc::RatFunc;
use num_traits::One;

fn num(v: i64) -> Expr {
    Expr::Num(qi(v))
}

fn is_num(e: &Expr, v: i64) -> bool {
    matches!(e, Expr::Num(q) if *q == qi(v))
}

fn add(a: Expr, b: Expr) -> Expr {
    if is_num(&a, 0) {
        return b;
    }
    if is_num(&b, 0) {
        return a;
    }
    Expr::Bin(Op::Add, Box::new(a), Box::new(b))
}

fn sub(a: Expr, b: Expr) -> Expr {
    if is_num(&b, 0) {
        return a;
    }
    if is_num(&a, 0) {
        return neg(b);
    }
    Expr::Bin(Op::Sub, Box::new(a), Box::new(b))
}

fn neg(a: Expr) -> Expr {
    if is_num(&a, 0) {
        return a;
    }
    match a {
        Expr::Neg(inner) => *inner,
        other => Expr::Neg(Box::new(other)),
    }
}

fn mul(a: Expr, b: Expr) -> Expr {
    if is_num(&a, 0) || is_num(&b, 0) {
        return num(0);
    }
    if is_num(&a, 1) {
        return b;
    }
    if is_num(&b, 1) {
        return a;
    }
    Expr::Bin(Op::Mul, Box::new(a), Box::new(b))
}

fn div(a: Expr, b: Expr) -> Expr {
    if is_num(&a, 0) {
        return a;
    }
    if is_num(&b, 1) {
        return a;
    }
    Expr::Bin(Op::Div, Box::new(a), Box::new(b))
}

fn pow(a: Expr, b: Expr) -> Expr {
    if is_num(&b, 1) {
        return a;
    }
    Expr::Bin(Op::Pow, Box::new(a), Box::new(b))
}

fn call(f: Func, a: Expr) -> Expr {
    Expr::Call(f, Box::new(a))
}

fn depends_on(e: &Expr, x: &str) -> bool {
    e.symbols().iter().any(|s| s == x)
}

/// `e` with `x` replaced by `v` (an integral over `x` inside keeps its own `x`).
fn at(e: &Expr, x: &str, v: &Expr) -> Expr {
    e.substitute(&|s: &str| (s == x).then(|| v.clone()))
}

impl Expr {
    /// The formula as [`Expr::eval`] will evaluate it, made once for many evaluations: every
    /// operation that `eval` lowers at each call (`diff`, `at`, `prod`, `max`, ...) is replaced
    /// by its lowering, computed here once; `sum` keeps its numeric loop with its parts prepared,
    /// `int` stays as written (its body is lowered by `eval` itself). `eval` of the result is
    /// `eval` of `self`, to the bit, at every point: the same lowered trees are evaluated.
    /// An operation whose lowering fails stays, so that `eval` reports it as before.
    pub fn prepared(&self) -> Expr {
        match self {
            Expr::Num(_) | Expr::Sym(_) | Expr::Pi => self.clone(),
            Expr::Neg(a) => Expr::Neg(Box::new(a.prepared())),
            Expr::Call(f, a) => Expr::Call(*f, Box::new(a.prepared())),
            Expr::Bin(op, a, b) => {
                // an exponent `eval` would find to be a small integer, found once
                let small = (*op == Op::Pow).then(|| super::small_power(b)).flatten();
                let b = match small {
                    Some(n) => Expr::Num(Q::from_integer(n.into())),
                    None => b.prepared(),
                };
                Expr::Bin(*op, Box::new(a.prepared()), Box::new(b))
            }
            Expr::Calc(Calc::Int, ..) => self.clone(),
            Expr::Calc(Calc::Sum, body, i, extra) => Expr::Calc(
                Calc::Sum,
                Box::new(body.prepared()),
                i.clone(),
                extra.iter().map(Expr::prepared).collect(),
            ),
            Expr::Calc(..) => self.lower().unwrap_or_else(|_| self.clone()),
        }
    }

    /// The formula with every `diff` and `at` carried out (an `int` stays, with its parts
    /// lowered). Errors name the operation that has no rule (`diff` of `abs` at a kink is the
    /// only one).
    pub fn lower(&self) -> Result<Expr, String> {
        Ok(match self {
            Expr::Num(_) | Expr::Sym(_) | Expr::Pi => self.clone(),
            Expr::Neg(a) => Expr::Neg(Box::new(a.lower()?)),
            Expr::Call(f, a) => Expr::Call(*f, Box::new(a.lower()?)),
            Expr::Bin(op, a, b) => Expr::Bin(*op, Box::new(a.lower()?), Box::new(b.lower()?)),
            Expr::Calc(Calc::Diff, body, x, _) => derivative(&body.lower()?, x)?,
            Expr::Calc(Calc::At, body, x, v) => at(&body.lower()?, x, &v[0].lower()?),
            Expr::Calc(c @ (Calc::Sum | Calc::Prod), body, i, b) => {
                let bound = |e: &Expr| -> Result<f64, String> {
                    let v = e.lower()?.exact_constant().ok_or_else(|| {
                        format!("`{self}`: the bounds of `sum` must be integers once the formula's values are in (`{e}` is not)")
                    })?;
                    if !v.is_integer() {
                        return Err(format!(
                            "`{self}`: the bound {v} of `sum` is not an integer"
                        ));
                    }
                    use num_traits::ToPrimitive;
                    Ok(v.to_integer().to_f64().unwrap_or(f64::NAN))
                };
                let (lo, hi) = sum_range(bound(&b[0])?, bound(&b[1])?, body)?;
                let body = body.lower()?;
                if *c == Calc::Prod {
                    let mut acc = num(1);
                    for k in lo..=hi {
                        acc = mul(acc, at(&body, i, &num(k)));
                    }
                    acc
                } else {
                    let mut acc = num(0);
                    for k in lo..=hi {
                        acc = add(acc, at(&body, i, &num(k)));
                    }
                    acc
                }
            }
            Expr::Calc(
                c @ (Calc::Max | Calc::Min | Calc::Lim | Calc::Mean | Calc::Region | Calc::Marked),
                ..,
            ) => {
                return Err(format!(
                    "`{self}`: a `{}` read from a paper is not computed (its unit is that of its formula)",
                    c.name()
                ));
            }
            Expr::Calc(Calc::Int, body, x, b) => Expr::Calc(
                Calc::Int,
                Box::new(body.lower()?),
                x.clone(),
                vec![b[0].lower()?, b[1].lower()?],
            ),
        })
    }
}

/// The integer range of a `sum` over `body`: at most 10,000 terms, bounds in [-1e6, 1e6], and
/// no `sum` inside its body, so that a formula from anyone cannot ask for an endless loop.
pub fn sum_range(lo: f64, hi: f64, body: &Expr) -> Result<(i64, i64), String> {
    for v in [lo, hi] {
        if v.fract() != 0.0 || v.abs() > 1e6 {
            return Err(format!(
                "a bound of `sum` must be an integer in [-1000000, 1000000], not {v}"
            ));
        }
    }
    if hi - lo >= 1e4 {
        return Err(format!("`sum` from {lo} to {hi}: at most 10000 terms"));
    }
    if contains_sum(body) {
        return Err("a `sum` inside a `sum` is not supported".into());
    }
    Ok((lo as i64, hi as i64))
}

fn contains_sum(e: &Expr) -> bool {
    match e {
        Expr::Num(_) | Expr::Sym(_) | Expr::Pi => false,
        Expr::Neg(a) | Expr::Call(_, a) => contains_sum(a),
        Expr::Bin(_, a, b) => contains_sum(a) || contains_sum(b),
        Expr::Calc(c, body, _, extra) => {
            matches!(c, Calc::Sum | Calc::Prod)
                || contains_sum(body)
                || extra.iter().any(contains_sum)
        }
    }
}

/// $\partial e/\partial x$ of a lowered formula (no `diff` or `at` inside).
pub fn derivative(e: &Expr, x: &str) -> Result<Expr, String> {
    if !depends_on(e, x) {
        return Ok(num(0));
    }
    Ok(match e {
        Expr::Num(_) | Expr::Pi => num(0),
        Expr::Sym(s) => num(i64::from(s == x)),
        Expr::Neg(a) => neg(derivative(a, x)?),
        Expr::Bin(op, a, b) => {
            let (da, db) = (derivative(a, x)?, derivative(b, x)?);
            let (a, b) = ((**a).clone(), (**b).clone());
            match op {
                Op::Add => add(da, db),
                Op::Sub => sub(da, db),
                Op::Mul => add(mul(da, b.clone()), mul(a, db)),
                Op::Div => div(sub(mul(da, b.clone()), mul(a, db)), pow(b, num(2))),
                Op::Pow if !depends_on(&b, x) => mul(mul(b.clone(), pow(a, sub(b, num(1)))), da),
                // a^b = exp(b ln a)
                Op::Pow => mul(
                    e.clone(),
                    add(mul(db, call(Func::Ln, a.clone())), div(mul(b, da), a)),
                ),
            }
        }
        Expr::Call(f, a) => {
            let da = derivative(a, x)?;
            let a = (**a).clone();
            let outer = match f {
                // d/dx x! = x! psi(x + 1): no digamma here
                Func::Factorial => {
                    return Err(format!(
                        "`diff` of `factorial({a})` in `{x}`: no rule (its argument must not depend on `{x}`)"
                    ));
                }
                Func::Gamma => {
                    return Err(format!(
                        "`diff` of `gamma({a})` in `{x}`: no rule (its argument must not depend on `{x}`)"
                    ));
                }
                // 2/sqrt(pi) exp(-a^2)
                Func::Erf => div(
                    mul(num(2), call(Func::Exp, neg(pow(a, num(2))))),
                    call(Func::Sqrt, Expr::Pi),
                ),
                // piecewise constant: 0 away from the jump
                Func::Sign | Func::Heaviside => num(0),
                Func::Sqrt => div(num(1), mul(num(2), call(Func::Sqrt, a))),
                Func::Exp => call(Func::Exp, a),
                Func::Ln => div(num(1), a),
                Func::Sin => call(Func::Cos, a),
                Func::Cos => neg(call(Func::Sin, a)),
                Func::Tan => div(num(1), pow(call(Func::Cos, a), num(2))),
                Func::Abs => call(Func::Sign, a),
                Func::Asin => div(num(1), call(Func::Sqrt, sub(num(1), pow(a, num(2))))),
                Func::Acos => neg(div(num(1), call(Func::Sqrt, sub(num(1), pow(a, num(2)))))),
                Func::Atan => div(num(1), add(num(1), pow(a, num(2)))),
                Func::Sinh => call(Func::Cosh, a),
                Func::Cosh => call(Func::Sinh, a),
                Func::Tanh => div(num(1), pow(call(Func::Cosh, a), num(2))),
                Func::Asinh => div(num(1), call(Func::Sqrt, add(pow(a, num(2)), num(1)))),
                Func::Acosh => div(num(1), call(Func::Sqrt, sub(pow(a, num(2)), num(1)))),
                Func::Atanh => div(num(1), sub(num(1), pow(a, num(2)))),
                Func::EllipK => sub(
                    div(
                        call(Func::EllipE, a.clone()),
                        mul(a.clone(), sub(num(1), pow(a.clone(), num(2)))),
                    ),
                    div(call(Func::EllipK, a.clone()), a),
                ),
                Func::EllipE => div(
                    sub(call(Func::EllipE, a.clone()), call(Func::EllipK, a.clone())),
                    a,
                ),
            };
            mul(outer, da)
        }
        // Leibniz: d/dx int_lo^hi g(y) dy = int_lo^hi dg/dx dy + g(hi) hi' - g(lo) lo'
        Expr::Calc(Calc::Int, body, y, b) => {
            let inner = if y == x {
                num(0) // x is bound inside: only the bounds depend on the outer x
            } else {
                let d = derivative(body, x)?;
                if is_num(&d, 0) {
                    d
                } else {
                    Expr::Calc(Calc::Int, Box::new(d), y.clone(), b.clone())
                }
            };
            let (dlo, dhi) = (derivative(&b[0], x)?, derivative(&b[1], x)?);
            let upper = mul(at(body, y, &b[1]), dhi);
            let lower = mul(at(body, y, &b[0]), dlo);
            sub(add(inner, upper), lower)
        }
        Expr::Calc(c, ..) => return Err(format!("`{}` inside `diff` was not lowered", c.name())),
    })
}

/// $\int_{lo}^{hi} e\,dx$ exactly, when `e` is a polynomial in `x` (its denominator free of `x`)
/// and the bounds are rational; `None` otherwise.
pub fn integral_ratfunc(e: &Expr, x: &str, lo: &Expr, hi: &Expr) -> Option<RatFunc> {
    let r = e.to_ratfunc()?;
    let xs = Sym::new(x);
    let den = r.denom();
    if den.degree_in(xs) > 0 {
        return None;
    }
    let n = r.numer();
    let mut anti = Poly::zero();
    for k in 0..=n.degree_in(xs) {
        let c = n.coeff_of(xs, k);
        if c.is_zero() {
            continue;
        }
        let scale = Q::one() / qi(i64::from(k) + 1);
        anti = &anti + &c.mul_monomial(&Monomial::var(xs, k + 1), &scale);
    }
    let anti = RatFunc::from_poly(anti).div(&RatFunc::from_poly(den))?;
    let (lo, hi) = (
        lo.lower().ok()?.to_ratfunc()?,
        hi.lower().ok()?.to_ratfunc()?,
    );
    Some(&anti.subst(xs, &hi)? - &anti.subst(xs, &lo)?)
}

/// The quadratures evaluated on this thread since the last [`quadrature_log`]: their number
/// and the largest error estimate relative to the integral of the integrand's magnitude
/// (absolute where that is below 1e-300).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct QuadLog {
    /// How many integrals were evaluated numerically.
    pub count: usize,
    /// The largest relative error estimate among them.
    pub worst_rel: f64,
}

thread_local! {
    static QUAD_LOG: std::cell::Cell<QuadLog> = const {
        std::cell::Cell::new(QuadLog { count: 0, worst_rel: 0.0 })
    };
}

/// The numeric integrals of this thread since the last call, and a fresh log.
pub fn quadrature_log() -> QuadLog {
    QUAD_LOG.with(|l| l.replace(QuadLog::default()))
}

/// The relative accuracy a tanh-sinh evaluation aims for (a level halving stops once two
/// successive levels agree to it).
const QUAD_RTOL: f64 = 1e-14;
/// The finest level: step 2^-10 in the transformed variable.
const QUAD_LEVELS: u32 = 10;
/// The transformed variable's range [-T, T]: at 6.5 a node's distance from its endpoint is
/// below 1e-300 of the interval (it underflows or rounds onto the endpoint before).
const QUAD_T: f64 = 6.5;

/// $\int_{lo}^{hi} g(x)\,dx$ by tanh-sinh quadrature, with its error estimate: returns
/// (value, estimated absolute error). The nodes are $lo + d$ and $hi - d$ with
/// $d = r\,(1 - \tanh(\frac{\pi}{2}\sinh t))$ computed without cancellation; a node that
/// rounds onto its endpoint is not evaluated. The estimate is the last two levels' difference
/// plus the outermost evaluated term of each side (what is left out beyond it is smaller: an
/// integrable endpoint singularity away from 0, `1/sqrt(1 - x^2)` at -1, is resolved only to
/// about the square root of the rounding of that endpoint, and the estimate says so).
pub fn integral_with_error(
    g: &dyn Fn(f64) -> Result<f64, String>,
    lo: f64,
    hi: f64,
) -> Result<(f64, f64), String> {
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(format!("an integral over [{lo}, {hi}] needs finite bounds"));
    }
    #[allow(clippy::float_cmp)] // exactly equal bounds: an empty interval
    if lo == hi {
        // over an empty interval: zero, whatever the integrand does at its one point
        return Ok((0.0, 0.0));
    }
    let (c, r) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    let half_pi = std::f64::consts::FRAC_PI_2;
    // the outermost evaluated term (|weight * integrand|) on each side: (t, term)
    let mut outer = [(0.0_f64, 0.0_f64); 2];
    // the sum of |terms| of the finest level: the integral of |g|, the scale of the error
    let mut sum_abs = 0.0;
    // the terms of the node pair at +-t (t > 0)
    let mut pair = |t: f64| -> Result<f64, String> {
        let u = half_pi * t.sinh();
        // 1 - tanh(u) without cancellation, and the weight pi/2 cosh t / cosh^2 u
        let e = (-2.0 * u).exp();
        let d = r * 2.0 * e / (1.0 + e);
        let w = half_pi * t.cosh() * 4.0 * e / ((1.0 + e) * (1.0 + e));
        let mut sum = 0.0;
        for (side, x) in [lo + d, hi - d].into_iter().enumerate() {
            // strictly inside: a node that rounds onto an endpoint is left out
            if (x - lo) * (hi - x) > 0.0 && w > 0.0 {
                let term = w * g(x)?;
                sum += term;
                sum_abs += term.abs();
                if t > outer[side].0 {
                    outer[side] = (t, term.abs());
                }
            }
        }
        Ok(sum)
    };
    // level 0: step 1, nodes at the integers
    let mut h = 1.0;
    let centre = half_pi * g(c)?;
    let mut sum = centre;
    let mut k = 1.0;
    while k <= QUAD_T {
        sum += pair(k)?;
        k += 1.0;
    }
    let mut value = r * h * sum;
    let mut diff = f64::INFINITY;
    for _ in 1..=QUAD_LEVELS {
        // halving the step adds the odd multiples of the new step
        h *= 0.5;
        let mut t = h;
        while t <= QUAD_T {
            sum += pair(t)?;
            t += 2.0 * h;
        }
        let next = r * h * sum;
        diff = (next - value).abs();
        value = next;
        if !value.is_finite() {
            return Err(format!(
                "the integral over [{lo}, {hi}] is not finite (the integrand is not integrable there)"
            ));
        }
        if diff <= QUAD_RTOL * value.abs() {
            break;
        }
    }
    let err = diff + r.abs() * (outer[0].1 + outer[1].1);
    // relative to the integral of |g| (at least |value|), so that an integral that vanishes by
    // cancellation (the integral of sin over a period) is not judged by its rounding
    let scale = (r.abs() * h * (sum_abs + centre.abs())).max(value.abs());
    let rel = if scale > 1e-300 { err / scale } else { err };
    QUAD_LOG.with(|l| {
        let mut log = l.get();
        log.count += 1;
        log.worst_rel = log.worst_rel.max(rel);
        l.set(log);
    });
    Ok((value, err))
}

/// $\int_{lo}^{hi} g(x)\,dx$ by [`integral_with_error`], the error estimate logged.
pub fn integral_f64(
    g: &dyn Fn(f64) -> Result<f64, String>,
    lo: f64,
    hi: f64,
) -> Result<f64, String> {
    integral_with_error(g, lo, hi).map(|(v, _)| v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    fn rat(text: &str) -> RatFunc {
        parse(text).unwrap().to_ratfunc().unwrap()
    }

    #[test]
    fn derivatives_of_polynomials_and_quotients_are_exact() {
        // by hand: d/dx (x^3 y + 1/x) = 3 x^2 y - 1/x^2
        assert_eq!(rat("diff(x^3*y + 1/x, x)"), rat("3*x^2*y - 1/x^2"));
        assert_eq!(rat("diff(diff(x^4, x), x)"), rat("12*x^2"));
        assert_eq!(rat("at(x^2 + y, x, 3)"), rat("9 + y"));
    }

    #[test]
    fn integrals_of_polynomials_are_exact() {
        // int_0^t (t - s) s ds = t^3/6 (by hand)
        assert_eq!(rat("int((t - s)*s, s, 0, t)"), rat("t^3/6"));
        // the second moment of [-A, A] x [-B, B] about the x axis: 4 A B^3/3
        assert_eq!(rat("int(int(y^2, y, -B, B), x, -A, A)"), rat("4*A*B^3/3"));
        // an integrand with x in a denominator is not exact
        assert!(parse("int(1/x, x, 1, 2)").unwrap().to_ratfunc().is_none());
    }

    #[test]
    fn duhamel_integral_solves_its_equation() {
        // z = -1/m int_0^t P(s)(t - s) ds + V0 t with P = p0 + p1 s + p2 s^2: z'' = -P(t)/m,
        // z(0) = 0, z'(0) = V0; Leibniz's rule on the integral is what is tested
        let z = "(-1/m*int((p0 + p1*s + p2*s^2)*(t - s), s, 0, t) + V0*t)";
        assert_eq!(
            rat(&format!("diff(diff({z}, t), t)")),
            rat("-(p0 + p1*t + p2*t^2)/m")
        );
        assert_eq!(rat(&format!("at(diff({z}, t), t, 0)")), rat("V0"));
        // the same derivative with the integral kept symbolic (exp is not a polynomial)
        let g = parse("diff(int(exp(-s)*(t - s), s, 0, t), t)")
            .unwrap()
            .eval(&|v| (v == "t").then_some(0.7))
            .unwrap();
        // d/dt int_0^t e^{-s}(t - s) ds = int_0^t e^{-s} ds = 1 - e^{-t}
        assert!((g - (1.0 - (-0.7f64).exp())).abs() < 1e-14, "{g}");
    }

    #[test]
    fn nested_integrals_of_exponential_polynomials_are_exact() {
        // (21) of 000 at k = 1 (closed form by hand): e^{-a t} int_0^t e^{a s} s ds
        // = t/a - 1/a^2 + e^{-a t}/a^2
        let e = parse("exp(-a*t)*int(exp(a*s)*s, s, 0, t)").unwrap();
        let want = parse("t/a - 1/a^2 + exp(-a*t)/a^2").unwrap();
        assert_eq!(e.to_expo("t").unwrap(), want.to_expo("t").unwrap());
        // a double integral with t in the inner integrand: int_0^t int_0^u (t - s) ds du = t^3/3
        let e = parse("int(int(t - s, s, 0, u), u, 0, t)").unwrap();
        assert_eq!(
            e.to_expo("t").unwrap(),
            parse("t^3/3").unwrap().to_expo("t").unwrap()
        );
    }

    #[test]
    fn elliptic_derivatives_match_differences() {
        // central differences of K and E at k = 0.6 against the chain-rule forms
        let h = 1e-6;
        // (and the hyperbolic functions and their inverses; acosh at 1.6, inside its domain)
        for (f, k) in [
            ("ellipk(k)", 0.6),
            ("ellipe(k)", 0.6),
            ("asin(k)", 0.6),
            ("acos(k)", 0.6),
            ("atan(k)", 0.6),
            ("sinh(k)", 0.6),
            ("cosh(k)", 0.6),
            ("tanh(k)", 0.6),
            ("asinh(k)", 0.6),
            ("acosh(k)", 1.6),
            ("atanh(k)", 0.6),
        ] {
            let e = parse(f).unwrap();
            let d = parse(&format!("diff({f}, k)")).unwrap();
            let v = |x: f64| e.eval(&|_| Some(x)).unwrap();
            let fd = (v(k + h) - v(k - h)) / (2.0 * h);
            let an = d.eval(&|_| Some(k)).unwrap();
            assert!((fd - an).abs() < 1e-8, "{f}: {fd} vs {an}");
        }
    }

    #[test]
    fn tanh_sinh_integrates_smooth_and_endpoint_singular_functions() {
        // closed forms: int_0^pi sin = 2; int_0^1 sqrt(1 - x^2) = pi/4 (a square-root endpoint,
        // where 64-panel Gauss-Legendre is off by 1e-5); int_0^1 x^(-1/2) = 2 (an integrable
        // singularity); int_-1^1 1/sqrt(1 - x^2) = pi (two of them)
        let _ = quadrature_log();
        let pi = std::f64::consts::PI;
        type Case<'a> = (&'a dyn Fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 4] = [
            (&|x: f64| x.sin(), 0.0, pi, 2.0),
            (&|x: f64| (1.0 - x * x).sqrt(), 0.0, 1.0, pi / 4.0),
            (&|x: f64| 1.0 / x.sqrt(), 0.0, 1.0, 2.0),
            (&|x: f64| 1.0 / (1.0 - x * x).sqrt(), -1.0, 1.0, pi),
        ];
        // (the last: at -1 and 1 a node rounds onto the endpoint within 1e-16, and the mass
        // left out is about sqrt(2e-16) = 1.5e-8, which the estimate covers)
        let accuracy = [1e-14, 1e-14, 1e-14, 1e-7];
        for (i, (f, lo, hi, exact)) in cases.iter().enumerate() {
            let (v, err) = integral_with_error(&|x| Ok(f(x)), *lo, *hi).unwrap();
            assert!(
                (v - exact).abs() < accuracy[i] * exact,
                "case {i}: {v} vs {exact}"
            );
            // the estimate is honest (no smaller than the true error, less a few roundings of
            // the sum) and not idle
            assert!(
                err + 8.0 * f64::EPSILON * exact >= (v - exact).abs(),
                "case {i}: estimate {err}, error {}",
                (v - exact).abs()
            );
            assert!(
                err < 100.0 * accuracy[i] * exact,
                "case {i}: estimate {err}"
            );
        }
        let log = quadrature_log();
        assert_eq!(log.count, 4);
        assert!(log.worst_rel > 1e-9 && log.worst_rel < 1e-5, "{log:?}");
        // the log starts afresh
        assert_eq!(quadrature_log(), QuadLog::default());
        // an integral that vanishes by cancellation is judged against the integral of |g|
        // (4 for sin over a period), not against its own rounding
        let v = integral_f64(&|x| Ok(x.sin()), 0.0, 2.0 * pi).unwrap();
        assert!(v.abs() < 1e-14, "{v}");
        let log = quadrature_log();
        assert!(log.count == 1 && log.worst_rel < 1e-12, "{log:?}");
        // reversed bounds change the sign; an empty interval is zero
        let v = integral_f64(&|x| Ok(x * x), 1.0, 0.0).unwrap();
        assert!((v + 1.0 / 3.0).abs() < 1e-15, "{v}");
        assert!(integral_f64(&|_| Err("no".into()), 2.0, 2.0).unwrap().abs() < 1e-300);
        assert!(integral_f64(&|x| Ok(x), 0.0, f64::INFINITY).is_err());
        // a non-integrable singularity is an error, not a number
        assert!(integral_f64(&|x| Ok(1.0 / x), 0.0, 1.0).is_err_or_huge());
        // an integrand's error comes through
        assert!(integral_f64(&|_| Err("bad".into()), 0.0, 1.0).is_err());
    }

    trait ErrOrHuge {
        fn is_err_or_huge(&self) -> bool;
    }
    impl ErrOrHuge for Result<f64, String> {
        fn is_err_or_huge(&self) -> bool {
            self.as_ref().map_or(true, |v| v.abs() > 1e10)
        }
    }

    #[test]
    fn calculus_prints_back_and_binds_its_variable() {
        let e = parse("int(f*(t - s), s, 0, t)").unwrap();
        assert_eq!(e.to_string(), "int(f*(t - s), s, 0, t)");
        assert_eq!(parse(&e.to_string()).unwrap(), e);
        // substituting s outside does not touch the bound s
        let r = e.substitute(&|v| (v == "s" || v == "f").then(|| Expr::Num(qi(2))));
        assert_eq!(r.to_string(), "int(2*(t - s), s, 0, t)");
        assert!(parse("diff(x)").is_err());
        assert!(parse("int(x, x, 0)").is_err());
        assert!(parse("at(x, 2, 0)").is_err());
    }

    #[test]
    fn sums_and_factorials_are_exact_and_bounded() {
        // by hand: sum_{i=0}^{3} x^i/i! = 1 + x + x^2/2 + x^3/6; 5! = 120
        assert_eq!(
            rat("sum(x^i/factorial(i), i, 0, 3)"),
            rat("1 + x + x^2/2 + x^3/6")
        );
        assert_eq!(rat("factorial(5)"), rat("120"));
        assert_eq!(rat("sum(i, i, 1, 100)"), rat("5050"));
        // an empty range is 0; bounds given later through a substitution
        assert_eq!(rat("sum(x, i, 1, 0)"), rat("0"));
        let e = parse("sum(y^i, i, 0, n)").unwrap();
        assert!(e.lower().is_err(), "a symbolic bound cannot be expanded");
        let v = e.eval(&|s| match s {
            "y" => Some(2.0),
            "n" => Some(4.0),
            _ => None,
        });
        assert_eq!(v, Ok(31.0));
        // the index is bound and needs no unit; factorial off the integers is Gamma(x + 1)
        assert_eq!(e.symbols(), vec!["n".to_string(), "y".to_string()]);
        let half = parse("factorial(x)").unwrap().eval(&|_| Some(0.5)).unwrap();
        assert!((half - std::f64::consts::PI.sqrt() / 2.0).abs() < 1e-12);
        // too many terms, a fractional bound, diff of a factorial: errors, not loops or panics
        assert!(parse("sum(x, i, 0, 1000000)").unwrap().lower().is_err());
        let nested = parse("sum(sum(x, j, 0, 9999), i, 0, 9999)").unwrap();
        assert!(nested.lower().is_err());
        assert!(nested.eval(&|_| Some(1.0)).is_err());
        assert!(parse("sum(x, i, 0, 1/2)").unwrap().lower().is_err());
        assert!(parse("diff(factorial(x), x)").unwrap().lower().is_err());
    }
}
