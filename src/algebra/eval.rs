//! The one crossing from exact terms to `f64`, accurate where the closed forms cancel.
//!
//! A derived term such as $a_1$ of 000_92d54b11128ea1ec.txt (22) is $O(t^5)$ at small $t$ while
//! its parts ($6A_8V_0^2/\alpha^5$, ...) are $O(1)$: summing them in `f64` loses everything. An
//! [`Evaluator`] is built once per exact term with every symbol replaced by a rational value, and
//! evaluates $g(t) = \sum c_j t^{k_j} e^{-\beta_j t}$ in the first of three ways whose measured
//! condition number $\kappa = \sum|{\rm term}|/|\sum{\rm term}|$ guarantees the result:
//!
//! 1. direct summation in `f64` when $\kappa \le 64$ (error $\lesssim 64 \cdot 4\varepsilon$);
//! 2. the exact Taylor series at $t = 0$ (coefficients computed in rationals, so the cancellation
//!    between parts has already happened exactly), summed in `f64` when it converges with
//!    $\kappa \le 64$;
//! 3. fixed-point big-integer arithmetic with 448 fractional bits (exponentials by scaling and
//!    squaring), exact rational summation, one rounding at the end; it refuses only if the
//!    cancellation exceeds 300 bits.
//!
//! Written by hand: no crate offers a cancellation-aware evaluation of exact exponential sums.

use super::expo::Expo;
use super::poly::Q;
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Why a term could not be evaluated.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
pub enum EvalError {
    /// A symbol was left without a value.
    #[error("symbol(s) {names} have no value; give them with --at NAME=VALUE")]
    Symbolic {
        /// The names left symbolic.
        names: String,
    },
    /// The time is not finite or negative.
    #[error("t = {t} is not a finite time >= 0")]
    BadTime {
        /// The time.
        t: f64,
    },
    /// Even the high-precision path lost too much to cancellation (reported, never hidden).
    #[error("cancellation of more than 300 bits at t = {t}: result not trustworthy")]
    Cancellation {
        /// The time.
        t: f64,
    },
}

/// Which path produced a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Path {
    /// Direct `f64` summation.
    Direct,
    /// Exact Taylor coefficients summed in `f64`.
    Taylor,
    /// Fixed-point big-integer evaluation.
    HighPrecision,
}

const TAYLOR_TERMS: usize = 80;
const KAPPA_MAX: f64 = 64.0;
const FRAC_BITS: u64 = 448;

/// A stable `f64` evaluator of one exact exponential polynomial.
#[derive(Clone, Debug)]
pub struct Evaluator {
    /// `(rate, t_power, coeff)` exactly.
    parts: Vec<(Q, u32, Q)>,
    /// The same in `f64`.
    parts_f: Vec<(f64, i32, f64)>,
    /// Taylor coefficients at 0, rounded from exact values.
    taylor: Vec<f64>,
}

fn q_to_f64(x: &Q) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

impl Evaluator {
    /// Builds the evaluator; every coefficient and rate must be a rational constant.
    pub fn new(e: &Expo) -> Result<Self, EvalError> {
        let mut parts = Vec::new();
        let mut missing: Vec<String> = Vec::new();
        for ((rate, k), c) in e.parts() {
            match (rate.as_constant(), c.as_constant()) {
                (Some(r), Some(cv)) => parts.push((r, *k, cv)),
                _ => {
                    for s in rate.symbols().into_iter().chain(c.symbols()) {
                        missing.push(s.name());
                    }
                }
            }
        }
        if !missing.is_empty() {
            missing.sort();
            missing.dedup();
            return Err(EvalError::Symbolic {
                names: missing.join(", "),
            });
        }
        let taylor = exact_taylor(&parts, TAYLOR_TERMS as u32)
            .iter()
            .map(q_to_f64)
            .collect();
        let parts_f = parts
            .iter()
            .map(|(r, k, c)| (q_to_f64(r), *k as i32, q_to_f64(c)))
            .collect();
        Ok(Evaluator {
            parts,
            parts_f,
            taylor,
        })
    }

    /// $g(t)$ and the path that produced it.
    pub fn eval_with_path(&self, t: f64) -> Result<(f64, Path), EvalError> {
        if !t.is_finite() || t < 0.0 {
            return Err(EvalError::BadTime { t });
        }
        if self.parts.is_empty() {
            return Ok((0.0, Path::Direct));
        }
        let (mut sum, mut mag) = (0.0f64, 0.0f64);
        for (r, k, c) in &self.parts_f {
            let v = c * t.powi(*k) * (-r * t).exp();
            sum += v;
            mag += v.abs();
        }
        if sum.is_finite() && mag.is_finite() && mag <= KAPPA_MAX * sum.abs() {
            return Ok((sum, Path::Direct));
        }
        if let Some(v) = self.taylor_sum(t) {
            return Ok((v, Path::Taylor));
        }
        self.high_precision(t).map(|v| (v, Path::HighPrecision))
    }

    /// $g(t)$.
    pub fn eval(&self, t: f64) -> Result<f64, EvalError> {
        self.eval_with_path(t).map(|x| x.0)
    }

    fn taylor_sum(&self, t: f64) -> Option<f64> {
        let (mut sum, mut mag) = (0.0f64, 0.0f64);
        let mut tp = 1.0f64;
        let mut small_run = 0;
        for c in &self.taylor {
            let v = c * tp;
            sum += v;
            mag += v.abs();
            tp *= t;
            // leading zero coefficients (a term that starts at t^k) are not a converged tail
            if sum != 0.0 && v.abs() <= 1e-18 * sum.abs() {
                small_run += 1;
                // a run of negligible terms past the leading ones means the tail is negligible
                if small_run >= 6 {
                    break;
                }
            } else {
                small_run = 0;
            }
        }
        let converged = small_run >= 6 || (sum == 0.0 && mag == 0.0);
        (converged && sum.is_finite() && mag <= KAPPA_MAX * sum.abs() && sum != 0.0).then_some(sum)
    }

    /// The high-precision path, exposed for tests and for reference values.
    pub fn high_precision(&self, t: f64) -> Result<f64, EvalError> {
        let tq = Q::from_float(t).ok_or(EvalError::BadTime { t })?;
        let scale = BigInt::one() << FRAC_BITS;
        let mut sum = Q::zero();
        let mut mag = Q::zero();
        for (r, k, c) in &self.parts {
            let x = -(r * &tq);
            let ex = exp_fixed(&x);
            let term = c * tq.pow(*k as i32) * Q::new(ex, scale.clone());
            mag += term.abs();
            sum += term;
        }
        if mag.is_zero() {
            return Ok(0.0);
        }
        if sum.is_zero() || mag.clone() / sum.abs() > Q::from_integer(BigInt::one() << 300u32) {
            return Err(EvalError::Cancellation { t });
        }
        Ok(q_to_f64(&sum))
    }
}

/// The Taylor coefficients at 0 of $\sum c\,t^k e^{-r t}$, exactly, for the powers below `terms`:
/// the coefficient of $t^n$ is $\sum c\,(-r)^{n-k}/(n-k)!$. Each part's terms are made one from
/// the one before (times $-r/j$), not each power and factorial afresh.
fn exact_taylor(parts: &[(Q, u32, Q)], terms: u32) -> Vec<Q> {
    let mut acc = vec![Q::zero(); terms as usize];
    for (r, k, c) in parts {
        let minus_r = -r;
        // c (-r)^j / j! with j = n - k
        let mut term = c.clone();
        for (j, slot) in acc.iter_mut().skip(*k as usize).enumerate() {
            if j > 0 {
                term = term * &minus_r / Q::from_integer(j.into());
            }
            *slot += &term;
        }
    }
    acc
}

/// $e^x \cdot 2^{448}$ rounded, for rational $x$: scale $x$ down by $2^s$ until $|x| < 2^{-8}$,
/// sum the Taylor series in fixed point, square $s$ times.
fn exp_fixed(x: &Q) -> BigInt {
    let bits = FRAC_BITS + 64; // guard bits
    let one = BigInt::one() << bits;
    // s such that |x| / 2^s < 2^-8
    let mag = x.abs();
    let mut s: u32 = 0;
    let mut scaled = mag.clone();
    let limit = Q::new(BigInt::one(), BigInt::from(256));
    while scaled >= limit {
        scaled /= Q::from_integer(BigInt::from(2));
        s += 1;
    }
    let xs = x / Q::from_integer(BigInt::one() << s);
    let xf = (xs * Q::from_integer(one.clone())).round().to_integer();
    let mut sum = one.clone();
    let mut term = one.clone();
    let mut i = 1u32;
    loop {
        term = (&term * &xf) >> bits;
        term /= BigInt::from(i);
        if term.is_zero() {
            break;
        }
        sum += &term;
        i += 1;
    }
    for _ in 0..s {
        sum = (&sum * &sum) >> bits;
    }
    sum >> 64u32
}

/// Evaluates a rational function in `f64` at named values (`pi` defaults to $\pi$). For the plate
/// coefficients, which are sums of positive-looking products and do not cancel.
pub fn ratfunc_f64(
    r: &super::ratfunc::RatFunc,
    values: &std::collections::BTreeMap<String, f64>,
) -> Result<f64, EvalError> {
    let val = |name: &str| -> Option<f64> {
        values
            .get(name)
            .copied()
            .or_else(|| (name == "pi").then_some(std::f64::consts::PI))
    };
    let mut missing: Vec<String> = r
        .symbols()
        .into_iter()
        .map(|s| s.name())
        .filter(|n| val(n).is_none())
        .collect();
    if !missing.is_empty() {
        missing.sort();
        return Err(EvalError::Symbolic {
            names: missing.join(", "),
        });
    }
    let poly = |p: &super::poly::Poly| -> f64 {
        p.terms()
            .map(|(m, c)| {
                m.factors().fold(q_to_f64(c), |acc, (s, e)| {
                    acc * val(&s.name()).unwrap_or(f64::NAN).powi(e as i32)
                })
            })
            .sum()
    };
    Ok(poly(r.numer()) / poly(&r.denom()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::poly::{Poly, q};
    use crate::algebra::ratfunc::RatFunc;

    #[test]
    fn the_taylor_coefficients_are_the_closed_form() {
        // 5 e^{-2t} + (1/3) t^2 e^{3t/2}: the coefficient of t^n is
        // 5 (-2)^n / n! + (1/3) (3/2)^(n-2) / (n-2)!, each power and factorial made afresh here
        let parts = vec![(q(2, 1), 0, q(5, 1)), (q(-3, 2), 2, q(1, 3))];
        let got = exact_taylor(&parts, 12);
        assert_eq!(got.len(), 12);
        let fact = |j: u32| (1..=j).fold(Q::one(), |a, i| a * Q::from_integer(i.into()));
        for (n, c) in got.iter().enumerate() {
            let n = n as u32;
            let mut want = q(5, 1) * q(-2, 1).pow(n as i32) / fact(n);
            if n >= 2 {
                want += q(1, 3) * q(3, 2).pow(n as i32 - 2) / fact(n - 2);
            }
            assert_eq!(*c, want, "t^{n}");
        }
    }

    #[test]
    fn an_exponential_with_a_fractional_rate_is_read_exactly() {
        // exp(-3 t/2) and 2 t exp(-t/4) read as exponential polynomials: the reference is the
        // same formula evaluated by f64's exp
        for text in ["exp(-3*t/2)", "2*t*exp(-t/4) + exp(5*t/3)"] {
            let e = crate::algebra::expr::parse(text).expect("parses");
            let expo = e.to_expo("t").expect("an exponential polynomial");
            let ev = Evaluator::new(&expo).expect("constant rates");
            for t in [0.0, 0.3, 1.7] {
                let want = e.eval(&|s| (s == "t").then_some(t)).expect("evaluates");
                let got = ev.eval(t).expect("evaluates");
                assert!(
                    (got - want).abs() < 1e-13 * want.abs().max(1.0),
                    "{text} at {t}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn a_rational_function_is_evaluated_at_the_values_given() {
        // x^2/(1 + y) at x = 3, y = 1 is 4.5 (by hand); pi is known without a value
        let r = crate::algebra::expr::parse("x^2/(1 + y) + pi")
            .expect("parses")
            .to_ratfunc()
            .expect("rational");
        let values = [("x".to_string(), 3.0), ("y".to_string(), 1.0)].into();
        let v = ratfunc_f64(&r, &values).expect("evaluates");
        assert!((v - (4.5 + std::f64::consts::PI)).abs() < 1e-14, "{v}");
    }

    #[test]
    fn fixed_point_exp_matches_libm() {
        // Reference: f64 exp, correct to ~1 ulp.
        for x in [-3.5f64, -0.001, 0.0, 0.7, 12.25] {
            let e = exp_fixed(&Q::from_float(x).expect("finite"));
            let v = Q::new(e, BigInt::one() << FRAC_BITS)
                .to_f64()
                .expect("finite");
            assert!((v - x.exp()).abs() <= 4.0 * f64::EPSILON * x.exp(), "x={x}");
        }
    }

    #[test]
    fn cancelling_sum_is_accurate_at_small_t() {
        // g(t) = e^{-t} - 1 + t = t^2/2 - t^3/6 + ...: the naive sum loses all digits at t=1e-9.
        let mut g = Expo::part(RatFunc::one(), 0, Poly::constant(q(1, 1)));
        g = &g - &Expo::monomial(RatFunc::one(), 0);
        g = &g + &Expo::monomial(RatFunc::one(), 1);
        let ev = Evaluator::new(&g).expect("numeric");
        for t in [1e-9, 1e-5, 0.1, 1.0, 30.0] {
            // reference: the alternating series sum_{j>=2} (-t)^j/j! (no cancellation for t <= 1),
            // or the plain closed form where it does not cancel (t > 1)
            let reference = if t <= 1.0 {
                let (mut s, mut term) = (0.0f64, -t);
                for j in 2..60 {
                    term *= -t / j as f64;
                    s += term;
                }
                s
            } else {
                (-t).exp() - 1.0 + t
            };
            let v = ev.eval(t).expect("ok");
            assert!(
                (v - reference).abs() <= 1e-13 * reference.abs(),
                "t={t}: {v} vs {reference}"
            );
        }
    }
}
