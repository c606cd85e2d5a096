//! The Adomian series of the cone equation, 000_92d54b11128ea1ec.txt eqs. (18)-(23).
//!
//! Equation (11) with the operator of section 2, integrated twice as in (9), is the integral
//! equation (20):
//! $$z(t) = V_0 t - A_8 \iint [\tilde L(\alpha) - \tilde L(\gamma)][z^2]
//!               - A_9 \iint [\tilde L(\alpha) - \tilde L(\gamma)][B(z)],$$
//! with $z = \sum_k a_k$ (19), $a_0 = V_0 t$ and
//! $$a_{k+1} = -A_8 \iint [\tilde L(\alpha)-\tilde L(\gamma)][A_k]
//!             -A_9 \iint [\tilde L(\alpha)-\tilde L(\gamma)][B_k],\qquad
//!   A_k = \sum_{i+j=k} a_i a_j .$$
//! The viscous term is read two ways: $B = d(z^2)/dt = 2 z \dot z$ (what $(\eta/E)\,d/dt$ acting
//! on $z^2$ gives, so $B_k = \dot A_k$) and $B = z\dot z$ as printed in (18)
//! ($B_k = \sum_{i+j=k} a_i \dot a_j$).
//!
//! (22) as printed is read from `verify/000_cone_plate.toml` (`a1_22`); [`compare_parts`] sets a
//! printed term beside the derived one, part by part. [`taylor_reference`] is an independent check: the same equation as the ODE
//! $(D+\alpha)(D+\gamma)\ddot z = -(\gamma-\alpha)[A_8 z^2 + A_9 B(z)]$ solved by a power-series
//! recursion that shares no code with the Adomian construction.

use super::AlgebraError;
use super::expo::{Acc, Expo, PartKey};
use super::poly::{Poly, Q, qi};
use super::ratfunc::RatFunc;
use num_traits::One;
use std::collections::HashMap;

/// How the viscous term of (18) is read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Viscous {
    /// $B = d(z^2)/dt = 2 z \dot z$, what the operator $(\eta/E)\,d/dt$ gives.
    TwoZZ,
    /// $B = z \dot z$, as printed in (18).
    ZZ,
}

impl Viscous {
    /// Command-line name (`2zz`, `zz`).
    pub fn name(self) -> &'static str {
        match self {
            Viscous::TwoZZ => "2zz",
            Viscous::ZZ => "zz",
        }
    }
}

/// The series' parameters, each a symbol or an exact value.
#[derive(Clone, Debug)]
pub struct SeriesParams {
    /// $\alpha$ (1/s), a rate of the operator.
    pub alpha: Poly,
    /// $\gamma$ (1/s), the other rate.
    pub gamma: Poly,
    /// $V_0$ (m/s), the impact velocity.
    pub v0: Poly,
    /// $A_8 = A_7 E\zeta/m_s$ as printed (the elastic coefficient of (20)).
    pub a8: Poly,
    /// $A_9 = A_7\eta\zeta/m_s$ as printed (the viscous coefficient of (20)).
    pub a9: Poly,
}

impl SeriesParams {
    /// All five symbolic.
    pub fn symbolic() -> Self {
        SeriesParams {
            alpha: Poly::sym("alpha"),
            gamma: Poly::sym("gamma"),
            v0: Poly::sym("v0"),
            a8: Poly::sym("a8"),
            a9: Poly::sym("a9"),
        }
    }

    /// Replaces the named parameter by an exact value; `Err` for an unknown name.
    pub fn set(&mut self, name: &str, value: Q) -> Result<(), AlgebraError> {
        let slot = match name {
            "alpha" => &mut self.alpha,
            "gamma" => &mut self.gamma,
            "v0" => &mut self.v0,
            "a8" => &mut self.a8,
            "a9" => &mut self.a9,
            _ => {
                return Err(AlgebraError::UnknownSymbol {
                    name: name.into(),
                    allowed: "alpha, gamma, v0, a8, a9".into(),
                });
            }
        };
        *slot = Poly::constant(value);
        Ok(())
    }

    fn rf(p: &Poly) -> RatFunc {
        RatFunc::from_poly(p.clone())
    }
}

/// $[\tilde L(\alpha) - \tilde L(\gamma)][g]$.
pub fn op_diff(g: &Expo, p: &SeriesParams) -> Expo {
    &g.op_l(&p.alpha) - &g.op_l(&p.gamma)
}

/// The right-hand side of (20) as one linear operator on $A_k$ (and $B_k$), applied part by part:
/// with $T[g] = \iint [\tilde L(\alpha) - \tilde L(\gamma)][g]$, linear, and coefficients constant
/// in $t$, $T[\sum_j c_j t^{k_j} e^{-r_j t}] = \sum_j c_j\, T[t^{k_j} e^{-r_j t}]$. The image of
/// each unit part $u_{r,k} = t^k e^{-r t}$ is built once (small rational functions of the rates)
/// and kept for the later orders, where the same parts recur; a term's large coefficients are
/// multiplied by it and summed once per part of the result, instead of being normalised after each
/// of the three integrations. The images are themselves built from kept ones: the single
/// integrals of unit parts, their double integrals, and for $B = d(z^2)/dt$ the viscous part from
/// $\dot u_{r,k} = k\,u_{r,k-1} - r\,u_{r,k}$, so that the image
/// $-A_8 T[u] - A_9 T[\dot u] = (r A_9 - A_8)\,T[u_{r,k}] - k A_9\,T[u_{r,k-1}]$ needs no
/// integration of its own and $B_k$ is never formed.
struct OpT<'a> {
    p: &'a SeriesParams,
    /// $\int_0^t u_{s,j}$.
    single: HashMap<(Poly, u32), Expo>,
    /// $\iint u_{s,j}$.
    double: HashMap<(Poly, u32), Expo>,
    /// $T[u_{r,k}]$.
    t: HashMap<(Poly, u32), Expo>,
    /// $-A_8 T[u_{r,k}] - A_9 T[\dot u_{r,k}]$.
    with_rate: HashMap<(Poly, u32), Expo>,
}

/// $\sum_i c_i\, e_i$ over `(c_i, e_i)`, each coefficient summed once.
fn combine<'e>(terms: impl IntoIterator<Item = (RatFunc, &'e Expo)>) -> Expo {
    let mut acc = Acc::default();
    for (c, e) in terms {
        let c = c.fraction_free();
        for ((r, k), v) in e.parts() {
            acc.push(r.clone(), *k, c.mul(v));
        }
    }
    acc.finish()
}

impl<'a> OpT<'a> {
    fn new(p: &'a SeriesParams) -> Self {
        OpT {
            p,
            single: HashMap::new(),
            double: HashMap::new(),
            t: HashMap::new(),
            with_rate: HashMap::new(),
        }
    }

    fn single(&mut self, s: &Poly, j: u32) -> Expo {
        self.single
            .entry((s.clone(), j))
            .or_insert_with(|| Expo::part(RatFunc::one(), j, s.clone()).integral())
            .clone()
    }

    fn double(&mut self, s: &Poly, j: u32) -> Expo {
        if let Some(e) = self.double.get(&(s.clone(), j)) {
            return e.clone();
        }
        let first = self.single(s, j);
        let seconds: Vec<(RatFunc, Expo)> = first
            .parts()
            .map(|((s2, j2), c)| (c.clone(), self.single(s2, *j2)))
            .collect();
        let e = combine(seconds.iter().map(|(c, e)| (c.clone(), e)));
        self.double.insert((s.clone(), j), e.clone());
        e
    }

    fn t(&mut self, r: &Poly, k: u32) -> Expo {
        if let Some(e) = self.t.get(&(r.clone(), k)) {
            return e.clone();
        }
        let unit = Expo::part(RatFunc::one(), k, r.clone());
        let inner = op_diff(&unit, self.p);
        let doubles: Vec<(RatFunc, Expo)> = inner
            .parts()
            .map(|((s, j), c)| (c.clone(), self.double(s, *j)))
            .collect();
        let e = combine(doubles.iter().map(|(c, e)| (c.clone(), e)));
        self.t.insert((r.clone(), k), e.clone());
        e
    }

    fn with_rate(&mut self, r: &Poly, k: u32) -> Expo {
        if let Some(e) = self.with_rate.get(&(r.clone(), k)) {
            return e.clone();
        }
        let a8 = SeriesParams::rf(&self.p.a8);
        let a9 = SeriesParams::rf(&self.p.a9);
        let own = &(&a9 * &RatFunc::from_poly(r.clone())) - &a8;
        let here = self.t(r, k);
        let e = if k == 0 {
            combine([(own, &here)])
        } else {
            let below = self.t(r, k - 1);
            let kq = RatFunc::from_q(qi(k as i64));
            combine([(own, &here), (-&(&kq * &a9), &below)])
        };
        self.with_rate.insert((r.clone(), k), e.clone());
        e
    }

    /// Adds the image of `g` to `acc`: $-A_8 T[g] - A_9 T[\dot g]$ when `with_rate`, else
    /// $c\,T[g]$.
    ///
    /// The images are built first (in order: they are kept); the products of the coefficients
    /// with them, independent of each other, run in parallel (rayon).
    fn apply_into(&mut self, g: &Expo, c: &RatFunc, with_rate: bool, acc: &mut Acc) {
        use rayon::prelude::*;
        let units: Vec<Expo> = g
            .parts()
            .map(|((r, k), _)| {
                if with_rate {
                    self.with_rate(r, *k)
                } else {
                    self.t(r, *k)
                }
            })
            .collect();
        let parts: Vec<(&RatFunc, &Expo)> = g.parts().map(|(_, v)| v).zip(&units).collect();
        let products: Vec<Vec<(PartKey, RatFunc)>> = parts
            .par_iter()
            .map(|(v, unit)| {
                let cv = if with_rate { (*v).clone() } else { *v * c };
                let cv = cv.fraction_free();
                unit.parts()
                    .map(|(key, w)| (key.clone(), cv.mul(w)))
                    .collect()
            })
            .collect();
        for ((ru, ku), p) in products.into_iter().flatten() {
            acc.push(ru, ku, p);
        }
    }
}

/// $\sum_{i+j=k} f_i g_j$, each unordered pair once when `f` and `g` are the same sequence.
fn cauchy_product(f: &[Expo], g: &[Expo], k: usize, same: bool) -> Expo {
    if !same {
        let pairs: Vec<(&Expo, &Expo)> = (0..=k).map(|i| (&f[i], &g[k - i])).collect();
        return Expo::sum_of_products(&pairs);
    }
    // a_i a_{k-i} + a_{k-i} a_i = 2 a_i a_{k-i} for i < k - i, the middle one once
    let pairs: Vec<(&Expo, &Expo)> = (0..=k / 2)
        .filter(|i| 2 * i != k)
        .map(|i| (&f[i], &g[k - i]))
        .collect();
    let twice = Expo::sum_of_products(&pairs).scale(&RatFunc::from_q(qi(2)));
    if k.is_multiple_of(2) {
        &twice + &(&f[k / 2] * &g[k / 2])
    } else {
        twice
    }
}

/// The Adomian terms $a_0, \dots, a_N$ of (19)-(20).
pub fn adomian_terms(p: &SeriesParams, order: usize, visc: Viscous) -> Vec<Expo> {
    let mut a: Vec<Expo> = vec![Expo::monomial(SeriesParams::rf(&p.v0), 1)];
    let mut da: Vec<Expo> = vec![a[0].deriv()];
    let minus_a8 = -&SeriesParams::rf(&p.a8);
    let minus_a9 = -&SeriesParams::rf(&p.a9);
    let mut op = OpT::new(p);
    for k in 0..order {
        let ak = cauchy_product(&a, &a, k, true);
        // a_{k+1} = -A8 T[A_k] - A9 T[B_k]
        let mut next = Acc::default();
        match visc {
            // B_k = dA_k/dt: one image per part of A_k
            Viscous::TwoZZ => op.apply_into(&ak, &minus_a8, true, &mut next),
            Viscous::ZZ => {
                let bk = cauchy_product(&a, &da, k, false);
                op.apply_into(&ak, &minus_a8, false, &mut next);
                op.apply_into(&bk, &minus_a9, false, &mut next);
            }
        }
        let next = next.finish();
        if visc == Viscous::ZZ {
            da.push(next.deriv());
        }
        a.push(next);
    }
    a
}

/// The sum $a_0 + \dots + a_N$.
pub fn partial_sum(terms: &[Expo]) -> Expo {
    Expo::sum_all(terms)
}

/// One part of a term-by-term comparison.
#[derive(Clone, Debug)]
pub struct PartComparison {
    /// Power of $t$.
    pub t_power: u32,
    /// Rate $\beta$ of $e^{-\beta t}$.
    pub rate: Poly,
    /// Derived coefficient (zero if the part is absent).
    pub derived: RatFunc,
    /// Printed coefficient (zero if absent).
    pub printed: RatFunc,
    /// Exact equality.
    pub agrees: bool,
}

/// Compares two exponential polynomials part by part (each power of t, each exponential).
pub fn compare_parts(derived: &Expo, printed: &Expo) -> Vec<PartComparison> {
    let mut keys: Vec<(Poly, u32)> = derived
        .parts()
        .chain(printed.parts())
        .map(|(k, _)| k.clone())
        .collect();
    keys.sort();
    keys.dedup();
    let find = |e: &Expo, key: &(Poly, u32)| {
        e.parts()
            .find(|(k, _)| *k == key)
            .map_or(RatFunc::zero(), |(_, v)| v.clone())
    };
    keys.into_iter()
        .map(|key| {
            let d = find(derived, &key);
            let p = find(printed, &key);
            PartComparison {
                t_power: key.1,
                rate: key.0.clone(),
                agrees: d == p,
                derived: d,
                printed: p,
            }
        })
        .collect()
}

/// Taylor coefficients $c_0..c_n$ of the exact solution of the cone equation, from the ODE form
/// $(D+\alpha)(D+\gamma)\ddot z = -(\gamma-\alpha)[A_8 z^2 + A_9 B(z)]$ with
/// $z(0)=0$, $\dot z(0) = V_0$, $\ddot z(0) = \dddot z(0) = 0$: an independent second method.
pub fn taylor_reference(p: &SeriesParams, n: usize, visc: Viscous) -> Vec<RatFunc> {
    let rf = SeriesParams::rf;
    let (al, ga) = (rf(&p.alpha), rf(&p.gamma));
    let (a8, a9) = (rf(&p.a8), rf(&p.a9));
    let sum_rates = &al + &ga;
    let prod_rates = &al * &ga;
    let gap = &ga - &al;
    let mut c: Vec<RatFunc> = vec![RatFunc::zero(), rf(&p.v0), RatFunc::zero(), RatFunc::zero()];
    let q = |x: usize| RatFunc::from_q(qi(x as i64));
    // w = z'': w_j = (j+2)(j+1) c_{j+2}
    let w = |c: &[RatFunc], j: usize| &c[j + 2] * &q((j + 2) * (j + 1));
    let mut k = 0;
    while c.len() <= n {
        // order t^k of the equation gives c_{k+4}
        let mut z2 = RatFunc::zero();
        let mut b = RatFunc::zero();
        for i in 0..=k {
            z2 = &z2 + &(&c[i] * &c[k - i]);
            // (z z')_k = sum_i c_i (k-i+1) c_{k-i+1}
            b = &b + &(&(&c[i] * &c[k - i + 1]) * &q(k - i + 1));
        }
        if visc == Viscous::TwoZZ {
            b = b.scale(&qi(2));
        }
        let rhs = -&(&gap * &(&(&a8 * &z2) + &(&a9 * &b)));
        let lower = &(&(&sum_rates * &w(&c, k + 1)) * &q(k + 1)) + &(&prod_rates * &w(&c, k));
        let top = &rhs - &lower;
        let denom = Q::one() / qi(((k + 1) * (k + 2) * (k + 3) * (k + 4)) as i64);
        c.push(top.scale(&denom));
        k += 1;
    }
    c.truncate(n + 1);
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numeric() -> SeriesParams {
        let mut p = SeriesParams::symbolic();
        p.set("alpha", Q::new((-3).into(), 1.into())).unwrap();
        p.set("gamma", Q::new(5.into(), 2.into())).unwrap();
        p.set("v0", Q::new(2.into(), 1.into())).unwrap();
        p.set("a8", Q::new(7.into(), 1.into())).unwrap();
        p.set("a9", Q::new(1.into(), 3.into())).unwrap();
        p
    }

    #[test]
    fn partial_sums_match_independent_taylor_recursion() {
        // Reference: the power-series recursion of the ODE form, a second method.
        for visc in [Viscous::TwoZZ, Viscous::ZZ] {
            let p = numeric();
            let terms = adomian_terms(&p, 2, visc);
            let reference = taylor_reference(&p, 12, visc);
            for n_terms in 1..=3 {
                let s = partial_sum(&terms[..n_terms]);
                let valid = 4 * (n_terms - 1) + 4;
                for (j, r) in reference.iter().enumerate().take(valid + 1) {
                    assert_eq!(
                        s.taylor_coeff(j as u32),
                        *r,
                        "visc {visc:?} N={n_terms} t^{j}"
                    );
                }
            }
        }
    }

    #[test]
    fn symbolic_terms_match_the_taylor_recursion_with_every_symbol_free() {
        // Reference: the power-series recursion of the ODE form (a second method sharing no code
        // with the memoised operator images), exact in all five symbols; both viscous readings,
        // through a0..a3 (the partial sum is valid to t^16: 4 (N - 1) + 4 with N = 4 terms).
        let p = SeriesParams::symbolic();
        for visc in [Viscous::TwoZZ, Viscous::ZZ] {
            let terms = adomian_terms(&p, 3, visc);
            let reference = taylor_reference(&p, 16, visc);
            let s = partial_sum(&terms);
            for (j, r) in reference.iter().enumerate() {
                assert_eq!(s.taylor_coeff(j as u32), *r, "visc {visc:?} t^{j}");
            }
            // a misprinted term (a3 doubled) is told apart at t^13, its first non-zero power
            let mut wrong = terms.clone();
            wrong[3] = &wrong[3] + &terms[3];
            let w = partial_sum(&wrong);
            assert!((0..=16).any(|j| w.taylor_coeff(j) != reference[j as usize]));
        }
    }

    #[test]
    fn higher_terms_vanish_to_second_order_at_zero() {
        let p = SeriesParams::symbolic();
        for visc in [Viscous::TwoZZ, Viscous::ZZ] {
            let terms = adomian_terms(&p, 2, visc);
            for a in &terms[1..] {
                for j in 0..=2 {
                    assert!(a.taylor_coeff(j).is_zero());
                }
            }
        }
    }
}
