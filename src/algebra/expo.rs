//! Exponential polynomials $g(t) = \sum_j c_j\, t^{k_j} e^{-\beta_j t}$, exact.
//!
//! Coefficients $c_j$ are [`RatFunc`]s; rates $\beta_j$ are exact polynomials (in practice linear
//! forms such as $0$, $\alpha$, $\gamma$, $\alpha+\gamma$, $2\alpha$). Parts with the same
//! $(\beta, k)$ are merged and zero parts dropped, so the representation is canonical up to the
//! canonical form of the coefficients.
//!
//! Operations are those of 000_92d54b11128ea1ec.txt, eqs. (9), (20), (21):
//! $$\int_0^t s^k e^{-\beta s}\,ds = \frac{k!}{\beta^{k+1}} - e^{-\beta t}\sum_{i=0}^{k}
//!   \frac{k!}{(k-i)!}\frac{t^{k-i}}{\beta^{i+1}}, \qquad \beta \ne 0,$$
//! and $t^{k+1}/(k+1)$ for $\beta = 0$ (decided exactly); the operator
//! $$\tilde L(\delta)[g](t) = e^{-\delta t}\int_0^t e^{\delta s} g(s)\,ds,$$
//! which is the integral of $g\,e^{\delta t}$ shifted back, so the resonant case $\beta = \delta$
//! (a part $t^k e^{-\delta t}$ becoming $t^{k+1} e^{-\delta t}/(k+1)$) needs no special code.

use super::poly::{Poly, Q, qi};
use super::ratfunc::RatFunc;
use num_traits::{One, Zero};
use std::collections::BTreeMap;

/// Key of a part: `(rate, t_power)`.
pub type PartKey = (Poly, u32);

/// A finite sum of `coeff * t^k * exp(-rate * t)`.
#[derive(Clone, Debug, Default)]
pub struct Expo {
    parts: BTreeMap<PartKey, RatFunc>,
}

/// Parts collected before their coefficients are added: each key's terms are summed once, over
/// one common denominator, by [`Acc::finish`] (see [`RatFunc::sum`]).
#[derive(Default)]
pub struct Acc {
    parts: BTreeMap<PartKey, Vec<RatFunc>>,
}

impl Acc {
    /// Adds the part `c t^k e^{-rate t}` (summed when finished).
    pub fn push(&mut self, rate: Poly, k: u32, c: RatFunc) {
        if !c.is_zero() {
            self.parts.entry((rate, k)).or_default().push(c);
        }
    }

    /// Adds every part of `e`.
    pub fn push_all(&mut self, e: &Expo) {
        for ((r, k), v) in &e.parts {
            self.push(r.clone(), *k, v.clone());
        }
    }

    /// The sum, each coefficient added once.
    ///
    /// The parts are independent, so their sums run in parallel (rayon); the result does not
    /// depend on the order they finish in.
    pub fn finish(self) -> Expo {
        use rayon::prelude::*;
        let sum = |terms: Vec<RatFunc>| {
            if terms.len() == 1 {
                terms.into_iter().next().expect("one term")
            } else {
                RatFunc::sum(&terms)
            }
        };
        let parts: Vec<(PartKey, Vec<RatFunc>)> = self.parts.into_iter().collect();
        // a few parts per task: small sums are not worth a thread each
        let parts: Vec<(PartKey, RatFunc)> = parts
            .into_par_iter()
            .with_min_len(4)
            .map(|(k, t)| (k, sum(t)))
            .collect();
        Expo {
            parts: parts.into_iter().filter(|(_, c)| !c.is_zero()).collect(),
        }
    }
}

impl PartialEq for Expo {
    fn eq(&self, o: &Expo) -> bool {
        (self - o).is_zero()
    }
}

impl Expo {
    /// Zero.
    pub fn zero() -> Self {
        Expo::default()
    }

    /// One part `c * t^k * exp(-rate t)`.
    pub fn part(c: RatFunc, k: u32, rate: Poly) -> Self {
        let mut e = Expo::zero();
        e.add_part(rate, k, c);
        e
    }

    /// `c * t^k`.
    pub fn monomial(c: RatFunc, k: u32) -> Self {
        Expo::part(c, k, Poly::zero())
    }

    /// Adds one part in place.
    pub fn add_part(&mut self, rate: Poly, k: u32, c: RatFunc) {
        if c.is_zero() {
            return;
        }
        let key = (rate, k);
        match self.parts.get_mut(&key) {
            Some(v) => {
                let s = &*v + &c;
                if s.is_zero() {
                    self.parts.remove(&key);
                } else {
                    *v = s;
                }
            }
            None => {
                self.parts.insert(key, c);
            }
        }
    }

    /// True if every part cancelled.
    pub fn is_zero(&self) -> bool {
        self.parts.is_empty()
    }

    /// The parts `((rate, k), coeff)` in canonical order.
    pub fn parts(&self) -> impl Iterator<Item = (&PartKey, &RatFunc)> {
        self.parts.iter()
    }

    /// Number of parts.
    pub fn len(&self) -> usize {
        self.parts.len()
    }

    /// True if there are no parts.
    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }

    /// Multiplies by a coefficient.
    pub fn scale(&self, c: &RatFunc) -> Expo {
        let mut out = Expo::zero();
        for ((r, k), v) in &self.parts {
            out.add_part(r.clone(), *k, v * c);
        }
        out
    }

    /// Multiplies by `exp(-shift t)`.
    pub fn shift_rate(&self, shift: &Poly) -> Expo {
        let mut out = Expo::zero();
        for ((r, k), v) in &self.parts {
            out.add_part(r + shift, *k, v.clone());
        }
        out
    }

    /// $\sum_i f_i g_i$ with every coefficient summed once (the $A_k = \sum a_i a_{k-i}$ of (19)).
    ///
    /// The products of a part of `f_i` with the parts of `g_i` are independent and run in
    /// parallel (rayon); they are collected in the order of the loops, so the sums see their
    /// terms in the same order whatever the threads do.
    pub fn sum_of_products(pairs: &[(&Expo, &Expo)]) -> Expo {
        use rayon::prelude::*;
        let rows: Vec<(&PartKey, &RatFunc, &Expo)> = pairs
            .iter()
            .flat_map(|(f, g)| f.parts.iter().map(move |(key, v)| (key, v, *g)))
            .collect();
        let products: Vec<Vec<(PartKey, RatFunc)>> = rows
            .par_iter()
            .map(|((r1, k1), v1, g)| {
                let v1 = v1.fraction_free();
                g.parts
                    .iter()
                    .map(|((r2, k2), v2)| ((r1 + r2, k1 + k2), v1.mul(v2)))
                    .collect()
            })
            .collect();
        let mut out = Acc::default();
        for ((r, k), c) in products.into_iter().flatten() {
            out.push(r, k, c);
        }
        out.finish()
    }

    /// A sum of many, each coefficient summed once.
    pub fn sum_all<'a>(terms: impl IntoIterator<Item = &'a Expo>) -> Expo {
        let mut out = Acc::default();
        for t in terms {
            out.push_all(t);
        }
        out.finish()
    }

    /// $d/dt$.
    pub fn deriv(&self) -> Expo {
        let mut out = Acc::default();
        for ((r, k), v) in &self.parts {
            if *k > 0 {
                out.push(r.clone(), k - 1, v.scale(&qi(*k as i64)));
            }
            if !r.is_zero() {
                out.push(r.clone(), *k, -&(v * &RatFunc::from_poly(r.clone())));
            }
        }
        out.finish()
    }

    /// $\int_0^t g(s)\,ds$.
    pub fn integral(&self) -> Expo {
        let mut out = Acc::default();
        for ((r, k), v) in &self.parts {
            if r.is_zero() {
                out.push(
                    Poly::zero(),
                    k + 1,
                    v.scale(&(Q::one() / qi(*k as i64 + 1))),
                );
                continue;
            }
            let inv_r = RatFunc::from_poly(r.clone())
                .inv()
                .expect("non-zero rate has an inverse");
            // falling factorial k!/(k-i)! and 1/r^{i+1}
            let mut fall = Q::one();
            let mut inv_pow = inv_r.clone();
            for i in 0..=*k {
                out.push(r.clone(), k - i, -&(v * &inv_pow.scale(&fall)));
                fall *= qi((*k - i) as i64);
                if i < *k {
                    inv_pow = &inv_pow * &inv_r;
                }
            }
            // constant k!/r^{k+1}; after the loop fall == 0, so recompute k!
            let kfact = (1..=*k).fold(Q::one(), |a, j| a * qi(j as i64));
            out.push(Poly::zero(), 0, v * &inv_pow.scale(&kfact));
        }
        out.finish()
    }

    /// The double integral $\int_0^t\int_0^{t'} g\,dt''\,dt'$ of (9) and (20).
    pub fn double_integral(&self) -> Expo {
        self.integral().integral()
    }

    /// The paper's operator $\tilde L(\delta)[g] = e^{-\delta t}\int_0^t e^{\delta s} g(s)\,ds$.
    pub fn op_l(&self, delta: &Poly) -> Expo {
        self.shift_rate(&-delta).integral().shift_rate(delta)
    }

    /// Exact Taylor coefficient of $t^n$ at $t = 0$.
    pub fn taylor_coeff(&self, n: u32) -> RatFunc {
        let mut acc = RatFunc::zero();
        for ((r, k), v) in &self.parts {
            if *k > n {
                continue;
            }
            let j = n - k;
            // (-r)^j / j!
            let jf = (1..=j).fold(Q::one(), |a, i| a * qi(i as i64));
            let rp = (-r).pow(j);
            let term = v * &RatFunc::from_poly(rp.scale(&(Q::one() / jf)));
            acc = &acc + &term;
        }
        acc
    }

    /// The same function with the symbol `var` of the coefficients taken as the variable itself:
    /// $\int_0^t g(s, t)\,ds$ comes out of [`Expo::integral`] with `t` still in the coefficients.
    /// `None` when a coefficient has `var` in its denominator or a rate depends on it.
    pub fn absorb(&self, var: super::poly::Sym) -> Option<Expo> {
        let mut out = Expo::zero();
        for ((r, k), v) in &self.parts {
            if r.degree_in(var) > 0 {
                return None;
            }
            if !v.depends_on(var) {
                out.add_part(r.clone(), *k, v.clone());
                continue;
            }
            let den = RatFunc::from_poly(v.denom());
            if v.denom().degree_in(var) > 0 {
                return None;
            }
            let num = v.numer();
            for j in 0..=num.degree_in(var) {
                let c = RatFunc::from_poly(num.coeff_of(var, j)).div(&den)?;
                out.add_part(r.clone(), k + j, c);
            }
        }
        Some(out)
    }

    /// Substitutes a symbol by a value in every coefficient and rate.
    pub fn subst(&self, s: super::poly::Sym, value: &Q) -> Option<Expo> {
        let pv = Poly::constant(value.clone());
        let rv = RatFunc::from_q(value.clone());
        let mut out = Expo::zero();
        for ((r, k), v) in &self.parts {
            out.add_part(r.subst(s, &pv), *k, v.subst(s, &rv)?);
        }
        Some(out)
    }

    /// Plain text: `c*t^k*exp(-rate*t) + ...`.
    pub fn to_text(&self) -> String {
        if self.is_zero() {
            return "0".into();
        }
        let parts: Vec<String> = self
            .parts
            .iter()
            .map(|((r, k), v)| {
                let mut s = format!("({})", v.to_text());
                if *k > 0 {
                    s.push_str(&if *k == 1 {
                        "*t".to_string()
                    } else {
                        format!("*t^{k}")
                    });
                }
                if !r.is_zero() {
                    s.push_str(&format!("*exp(-({})*t)", r.to_text()));
                }
                s
            })
            .collect();
        parts.join(" + ")
    }

    /// LaTeX.
    pub fn to_latex(&self) -> String {
        if self.is_zero() {
            return "0".into();
        }
        let parts: Vec<String> = self
            .parts
            .iter()
            .map(|((r, k), v)| {
                let mut s = format!("\\left({}\\right)", v.to_latex());
                if *k > 0 {
                    s.push_str(&if *k == 1 {
                        " t".to_string()
                    } else {
                        format!(" t^{{{k}}}")
                    });
                }
                if !r.is_zero() {
                    s.push_str(&format!(" e^{{-\\left({}\\right) t}}", r.to_latex()));
                }
                s
            })
            .collect();
        parts.join(" + ")
    }
}

impl std::ops::Add for &Expo {
    type Output = Expo;
    fn add(self, o: &Expo) -> Expo {
        let mut out = Acc::default();
        out.push_all(self);
        out.push_all(o);
        out.finish()
    }
}

impl std::ops::Sub for &Expo {
    type Output = Expo;
    fn sub(self, o: &Expo) -> Expo {
        let mut out = Acc::default();
        out.push_all(self);
        for ((r, k), v) in &o.parts {
            out.push(r.clone(), *k, -v);
        }
        out.finish()
    }
}

impl std::ops::Neg for &Expo {
    type Output = Expo;
    fn neg(self) -> Expo {
        &Expo::zero() - self
    }
}

impl std::ops::Mul for &Expo {
    type Output = Expo;
    fn mul(self, o: &Expo) -> Expo {
        Expo::sum_of_products(&[(self, o)])
    }
}

/// `Zero` for generic code and proptest.
impl Zero for Expo {
    fn zero() -> Self {
        Expo::default()
    }
    fn is_zero(&self) -> bool {
        self.parts.is_empty()
    }
}

impl std::ops::Add for Expo {
    type Output = Expo;
    fn add(self, o: Expo) -> Expo {
        &self + &o
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_t_print_as_written() {
        // t^0 is not printed, t^1 is `t`, t^2 is `t^2` (the constant 3 as a rational function)
        let three = || RatFunc::from_q(crate::algebra::poly::qi(3));
        let texts: Vec<String> = (0..3)
            .map(|k| Expo::monomial(three(), k).to_text())
            .collect();
        assert!(!texts[0].contains('t'), "{}", texts[0]);
        assert!(texts[1].ends_with("*t"), "{}", texts[1]);
        assert!(texts[2].ends_with("*t^2"), "{}", texts[2]);
    }
}
