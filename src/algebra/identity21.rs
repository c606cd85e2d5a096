//! Identity (21) of 000_92d54b11128ea1ec.txt:
//! $$e^{-\alpha t}\int_0^t e^{\alpha x} x^k\,dx = \sum_{i=0}^{k}\frac{k!}{(k-i)!}
//!   \frac{(-1)^i}{\alpha^{i+1}} t^{k-i} - k!\,\frac{(-1)^k}{\alpha^{k+1}} e^{-\alpha t}.$$
//! The left side is built by the general operator [`Expo::op_l`]; the right side is the printed
//! formula, read from `verify/000_cone_plate.toml` (a formula of `t`, `alpha`, `k` with `sum` and
//! `factorial`), with `k` put in; the two are compared exactly. As a second, independent check
//! the left side must solve $y' + \alpha y = t^k$ with $y(0) = 0$.

use super::expo::Expo;
use super::expr::Expr;
use super::poly::{Poly, Q};
use super::ratfunc::RatFunc;

/// Outcome of checking (21) for one `k`, with `alpha` symbolic.
#[derive(Clone, Debug)]
pub struct Identity21Check {
    /// The power $k$.
    pub k: u32,
    /// Left side (operator) equals the printed right side, exactly.
    pub holds: bool,
    /// The left side solves $y' + \alpha y = t^k$, $y(0) = 0$.
    pub solves_ode: bool,
}

/// The printed right side `rhs` (in `t`, `alpha`, `k`) at one `k`, as an exponential polynomial
/// in `t`; `Err` says why it is not one.
pub fn printed_at(rhs: &Expr, k: u32) -> Result<Expo, String> {
    let kq = Expr::Num(Q::from_integer(k.into()));
    let e = rhs
        .substitute(&|s: &str| (s == "k").then(|| kq.clone()))
        .lower()?;
    e.to_expo("t").ok_or_else(|| {
        format!("`{e}` (k = {k}) is not an exponential polynomial in t with alpha symbolic")
    })
}

/// Checks (21) for one `k` with `alpha` symbolic, against the printed right side at that `k`.
pub fn check(k: u32, printed: &Expo) -> Identity21Check {
    let alpha = Poly::sym("alpha");
    let lhs = Expo::monomial(RatFunc::one(), k).op_l(&alpha);
    let residual = &(&lhs.deriv() + &lhs.scale(&RatFunc::from_poly(alpha.clone())))
        - &Expo::monomial(RatFunc::one(), k);
    Identity21Check {
        k,
        holds: lhs == *printed,
        solves_ode: residual.is_zero() && lhs.taylor_coeff(0).is_zero(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    /// (21)'s right side as the paper prints it (the reference: the paper's formula, built by a
    /// path that shares nothing with `op_l`).
    const PRINTED: &str = "sum(factorial(k)/factorial(k - i)*(-1)^i/alpha^(i + 1)*t^(k - i), i, 0, k) - factorial(k)*(-1)^k/alpha^(k + 1)*exp(-alpha*t)";

    #[test]
    fn identity_21_holds_for_k_0_to_12() {
        let rhs = parse(PRINTED).expect("parses");
        for k in 0..=12 {
            let c = check(k, &printed_at(&rhs, k).expect("an exponential polynomial"));
            assert!(c.holds, "(21) fails at k = {k}");
            assert!(
                c.solves_ode,
                "L(alpha)[t^k] does not solve the ODE at k = {k}"
            );
        }
    }

    #[test]
    fn misprints_are_detected() {
        // the comparison can fail: the sign of the exponential part, the factorial ratio, the
        // power of alpha
        for bad in [
            PRINTED.replace("- factorial(k)*(-1)^k", "+ factorial(k)*(-1)^k"),
            PRINTED.replace("factorial(k)/factorial(k - i)", "factorial(k)/factorial(i)"),
            PRINTED.replace("alpha^(i + 1)", "alpha^i"),
        ] {
            let rhs = parse(&bad).expect("parses");
            let caught = (1..=4).any(|k| !check(k, &printed_at(&rhs, k).expect("expo")).holds);
            assert!(caught, "not caught: {bad}");
        }
    }

    #[test]
    fn a_sum_with_a_symbolic_bound_left_is_an_error() {
        let rhs = parse("sum(t^i, i, 0, n)").expect("parses");
        assert!(printed_at(&rhs, 2).is_err());
    }
}
