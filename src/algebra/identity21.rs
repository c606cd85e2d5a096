//! Identity (21) of 000_92d54b11128ea1ec.txt:
//! $$e^{-\alpha t}\int_0^t e^{\alpha x} x^k\,dx = \sum_{i=0}^{k}\frac{k!}{(k-i)!}
//!   \frac{(-1)^i}{\alpha^{i+1}} t^{k-i} - k!\,\frac{(-1)^k}{\alpha^{k+1}} e^{-\alpha t}.$$
//! The left side is built by the general operator [`Expo::op_l`]; the right side is transcribed
//! from the printed formula; the two are compared exactly. As a second, independent check the left
//! side must solve $y' + \alpha y = t^k$ with $y(0) = 0$.

use super::expo::Expo;
use super::poly::{Poly, Q, qi};
use super::ratfunc::RatFunc;
use num_traits::One;

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

/// The printed right side of (21).
pub fn printed_rhs(k: u32, alpha: &Poly) -> Expo {
    let a = RatFunc::from_poly(alpha.clone());
    let inv = a.inv().expect("alpha is a non-zero symbol");
    let mut out = Expo::zero();
    let mut fall = Q::one();
    let mut inv_pow = inv.clone();
    for i in 0..=k {
        let sign = if i % 2 == 0 { qi(1) } else { qi(-1) };
        out.add_part(Poly::zero(), k - i, inv_pow.scale(&(&fall * &sign)));
        fall *= qi((k - i) as i64);
        if i < k {
            inv_pow = &inv_pow * &inv;
        }
    }
    let kfact = (1..=k).fold(Q::one(), |acc, j| acc * qi(j as i64));
    let sign = if k.is_multiple_of(2) { qi(1) } else { qi(-1) };
    out.add_part(alpha.clone(), 0, inv_pow.scale(&-(kfact * sign)));
    out
}

/// Checks (21) for one `k` with `alpha` symbolic.
pub fn check(k: u32) -> Identity21Check {
    let alpha = Poly::sym("alpha");
    let lhs = Expo::monomial(RatFunc::one(), k).op_l(&alpha);
    let rhs = printed_rhs(k, &alpha);
    let residual = &(&lhs.deriv() + &lhs.scale(&RatFunc::from_poly(alpha.clone())))
        - &Expo::monomial(RatFunc::one(), k);
    Identity21Check {
        k,
        holds: lhs == rhs,
        solves_ode: residual.is_zero() && lhs.taylor_coeff(0).is_zero(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identity_21_holds_for_k_0_to_12() {
        for k in 0..=12 {
            let c = check(k);
            assert!(c.holds, "(21) fails at k = {k}");
            assert!(
                c.solves_ode,
                "L(alpha)[t^k] does not solve the ODE at k = {k}"
            );
        }
    }

    #[test]
    fn a_wrong_sign_is_detected() {
        // The comparison can fail: flip the sign of the exponential part and it must.
        let alpha = Poly::sym("alpha");
        let lhs = Expo::monomial(RatFunc::one(), 3).op_l(&alpha);
        let mut bad = printed_rhs(3, &alpha);
        let e = Expo::part(
            RatFunc::from_poly(alpha.clone())
                .powi(-4)
                .expect("nz")
                .scale(&qi(12)),
            0,
            alpha.clone(),
        );
        bad = &bad + &e;
        assert!(lhs != bad);
    }
}
