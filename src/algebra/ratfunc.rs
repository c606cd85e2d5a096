//! Rational functions $N/D$ in the papers' symbols, exact, with a sound equality test.
//!
//! The denominator is kept factored: a product of distinct monic polynomials to positive powers
//! (`alpha`, `alpha - gamma`, `m^2 b^2 + n^2 a^2`, ...). After every operation each factor is
//! cancelled against the numerator while it divides it exactly, so with irreducible factors (every
//! linear rate difference the series produces is) the form is canonical. Equality never relies on
//! that: `==` cross-multiplies, $N_1 D_2 = N_2 D_1$, which is sound in $\mathbb{Q}[x]$.
//!
//! With every symbol replaced by a rational value the type degenerates to an exact rational.

use super::poly::{FPoly, Monomial, Poly, Q, Sym};
use num_traits::{One, Zero};
use std::fmt;

/// A denominator factor and its power.
type Factor = (Poly, u32);

/// A rational function with a factored, monic denominator.
#[derive(Clone, Debug)]
pub struct RatFunc {
    num: Poly,
    den: Vec<(Poly, u32)>,
}

impl RatFunc {
    /// Zero.
    pub fn zero() -> Self {
        RatFunc {
            num: Poly::zero(),
            den: vec![],
        }
    }

    /// One.
    pub fn one() -> Self {
        RatFunc::from_poly(Poly::one())
    }

    /// A polynomial.
    pub fn from_poly(p: Poly) -> Self {
        RatFunc {
            num: p,
            den: vec![],
        }
    }

    /// A rational constant.
    pub fn from_q(c: Q) -> Self {
        RatFunc::from_poly(Poly::constant(c))
    }

    /// A symbol, by name.
    pub fn sym(name: &str) -> Self {
        RatFunc::from_poly(Poly::sym(name))
    }

    /// The numerator.
    pub fn numer(&self) -> &Poly {
        &self.num
    }

    /// The factored denominator.
    pub fn denom_factors(&self) -> &[(Poly, u32)] {
        &self.den
    }

    /// The expanded denominator.
    pub fn denom(&self) -> Poly {
        self.den
            .iter()
            .fold(Poly::one(), |acc, (f, e)| &acc * &f.pow(*e))
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        self.num.is_zero()
    }

    /// The value if this is a constant.
    pub fn as_constant(&self) -> Option<Q> {
        if self.den.is_empty() {
            self.num.as_constant()
        } else {
            None
        }
    }

    /// Symbols that occur in numerator or denominator.
    pub fn symbols(&self) -> Vec<Sym> {
        let mut v = self.num.symbols();
        for (f, _) in &self.den {
            v.extend(f.symbols());
        }
        v.sort();
        v.dedup();
        v
    }

    /// True unless the function is constant in `s` (decided exactly: $N'D - ND' = 0$), which also
    /// holds when a non-reduced form still shows `s`.
    pub fn depends_on(&self, s: Sym) -> bool {
        let d = self.denom();
        &self.num.diff(s) * &d != &self.num * &d.diff(s)
    }

    /// Splits a polynomial into `unit * product of monic factors` for use as a denominator: the
    /// monomial content becomes one factor per symbol, the rest one monic factor.
    fn factor_for_denominator(p: &Poly) -> (Q, Vec<(Poly, u32)>) {
        let content = p.monomial_content();
        let rest = p.div_monomial(&content);
        let mut factors: Vec<(Poly, u32)> =
            content.factors().map(|(s, e)| (Poly::var(s), e)).collect();
        let (_, lc) = rest.leading().expect("non-zero polynomial");
        let lc = lc.clone();
        let monic = rest.scale(&(Q::one() / &lc));
        if monic.as_constant().is_none() {
            factors.push((monic, 1));
        }
        (lc, factors)
    }

    /// Multiplies `self` by `1 / prod(factors)` and by `1/unit`, then cancels.
    fn with_extra_den(mut self, unit: &Q, factors: Vec<(Poly, u32)>) -> Self {
        if !unit.is_one() {
            self.num = self.num.scale(&(Q::one() / unit));
        }
        for (f, e) in factors {
            match self.den.iter_mut().find(|(g, _)| *g == f) {
                Some(slot) => slot.1 += e,
                None => self.den.push((f, e)),
            }
        }
        self.cancel()
    }

    /// Removes every denominator factor that divides the numerator exactly.
    fn cancel(self) -> Self {
        if self.num.is_zero() {
            return RatFunc::zero();
        }
        if self.den.is_empty() {
            return self;
        }
        RatFunc::cancelled(FPoly::from_poly(&self.num), self.den)
    }

    /// `num / den` with every factor of `den` divided out of `num` while it divides, in
    /// fraction-free form (a factor is tried only when a residue test cannot rule it out).
    fn cancelled(mut num: FPoly, mut den: Vec<(Poly, u32)>) -> Self {
        if num.is_zero() {
            return RatFunc::zero();
        }
        for (f, e) in den.iter_mut() {
            while *e > 0 && num.may_be_divisible_by(f) {
                match num.div_exact(f) {
                    Some(qt) => {
                        num = qt;
                        *e -= 1;
                    }
                    None => break,
                }
            }
        }
        den.retain(|(_, e)| *e > 0);
        den.sort();
        RatFunc {
            num: num.to_poly(),
            den,
        }
    }

    /// The sum of many terms over their least common denominator, cancelled once (adding them
    /// one by one would cancel after every addition, trial-dividing numerators that grow); the
    /// numerators are added and multiplied fraction-free.
    pub fn sum<'a>(terms: impl IntoIterator<Item = &'a RatFunc>) -> RatFunc {
        // numerators of terms with the same denominator are grouped first
        let mut by_den: Vec<(&[Factor], Vec<FPoly>)> = Vec::new();
        for t in terms {
            if t.is_zero() {
                continue;
            }
            let n = FPoly::from_poly(&t.num);
            match by_den.iter_mut().find(|(d, _)| *d == t.den.as_slice()) {
                Some((_, ns)) => ns.push(n),
                None => by_den.push((&t.den, vec![n])),
            }
        }
        let mut lcm: Vec<(Poly, u32)> = Vec::new();
        for (den, _) in &by_den {
            for (f, e) in *den {
                match lcm.iter_mut().find(|(g, _)| g == f) {
                    Some(slot) => slot.1 = slot.1.max(*e),
                    None => lcm.push((f.clone(), *e)),
                }
            }
        }
        let parts: Vec<FPoly> = by_den
            .iter()
            .map(|(den, nums)| {
                let n = FPoly::sum(nums);
                // what this denominator lacks of the common one, multiplied out fraction-free
                // (no conversion to rational coefficients between the factors)
                let mut cofactor: Option<FPoly> = None;
                for (f, e) in &lcm {
                    let have = den.iter().find(|(g, _)| g == f).map_or(0, |x| x.1);
                    if *e > have {
                        let f = FPoly::from_poly(f);
                        for _ in have..*e {
                            cofactor = Some(match cofactor {
                                None => f.clone(),
                                Some(c) => c.mul(&f),
                            });
                        }
                    }
                }
                match cofactor {
                    None => n,
                    Some(c) => n.mul(&c),
                }
            })
            .collect();
        RatFunc::cancelled(FPoly::sum(&parts), lcm)
    }

    /// The reciprocal, or `None` for zero.
    pub fn inv(&self) -> Option<Self> {
        if self.num.is_zero() {
            return None;
        }
        let (unit, factors) = RatFunc::factor_for_denominator(&self.num);
        let num = self.denom();
        Some(RatFunc::from_poly(num).with_extra_den(&unit, factors))
    }

    /// `self / o`, or `None` when `o` is zero.
    pub fn div(&self, o: &RatFunc) -> Option<Self> {
        Some(self * &o.inv()?)
    }

    /// Integer power (negative powers through `inv`).
    pub fn powi(&self, e: i32) -> Option<Self> {
        let base = if e < 0 { self.inv()? } else { self.clone() };
        let mut r = RatFunc::one();
        for _ in 0..e.unsigned_abs() {
            r = &r * &base;
        }
        Some(r)
    }

    /// Multiplies by a rational constant.
    pub fn scale(&self, c: &Q) -> Self {
        if c.is_zero() {
            return RatFunc::zero();
        }
        RatFunc {
            num: self.num.scale(c),
            den: self.den.clone(),
        }
    }

    /// Substitutes `s := value`; `None` if a denominator vanishes.
    pub fn subst(&self, s: Sym, value: &RatFunc) -> Option<Self> {
        let sub = |p: &Poly| -> RatFunc {
            // p(value) with value = vn / vd: homogenise by vd^deg.
            let deg = p.degree_in(s);
            let mut acc = RatFunc::zero();
            for k in 0..=deg {
                let c = RatFunc::from_poly(p.coeff_of(s, k));
                let vk = value.powi(k as i32).expect("non-negative power");
                acc = &acc + &(&c * &vk);
            }
            acc
        };
        let mut out = sub(&self.num);
        for (f, e) in &self.den {
            let fv = sub(f);
            out = out.div(&fv.powi(*e as i32)?)?;
        }
        Some(out)
    }

    /// Plain-text rendering.
    pub fn to_text(&self) -> String {
        if self.den.is_empty() {
            return self.num.to_text();
        }
        let n = self.num.to_text();
        let n = if self.num.len() > 1 {
            format!("({n})")
        } else {
            n
        };
        let d: Vec<String> = self
            .den
            .iter()
            .map(|(f, e)| {
                let s = f.to_text();
                let s = if f.len() > 1 { format!("({s})") } else { s };
                if *e > 1 { format!("{s}^{e}") } else { s }
            })
            .collect();
        let d = if d.len() > 1 {
            format!("({})", d.join("*"))
        } else {
            d.join("*")
        };
        format!("{n}/{d}")
    }

    /// LaTeX rendering.
    pub fn to_latex(&self) -> String {
        if self.den.is_empty() {
            return self.num.to_latex();
        }
        let d: Vec<String> = self
            .den
            .iter()
            .map(|(f, e)| {
                let s = f.to_latex();
                let s = if f.len() > 1 {
                    format!("\\left({s}\\right)")
                } else {
                    s
                };
                if *e > 1 { format!("{s}^{{{e}}}") } else { s }
            })
            .collect();
        format!("\\frac{{{}}}{{{}}}", self.num.to_latex(), d.join(" "))
    }

    /// Monomial of the numerator's leading term, for ordering parts deterministically.
    pub fn leading_monomial(&self) -> Option<Monomial> {
        self.num.leading().map(|(m, _)| m.clone())
    }
}

impl PartialEq for RatFunc {
    fn eq(&self, o: &RatFunc) -> bool {
        if self.den == o.den {
            return self.num == o.num;
        }
        &self.num * &o.denom() == &o.num * &self.denom()
    }
}

impl Eq for RatFunc {}

impl fmt::Display for RatFunc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
    }
}

impl From<Q> for RatFunc {
    fn from(c: Q) -> Self {
        RatFunc::from_q(c)
    }
}

impl std::ops::Add for &RatFunc {
    type Output = RatFunc;
    fn add(self, o: &RatFunc) -> RatFunc {
        if self.is_zero() {
            return o.clone();
        }
        if o.is_zero() {
            return self.clone();
        }
        if self.den == o.den {
            return RatFunc {
                num: &self.num + &o.num,
                den: self.den.clone(),
            }
            .cancel();
        }
        // Least common multiple of the factored denominators.
        let mut lcm: Vec<(Poly, u32)> = self.den.clone();
        for (f, e) in &o.den {
            match lcm.iter_mut().find(|(g, _)| g == f) {
                Some(slot) => slot.1 = slot.1.max(*e),
                None => lcm.push((f.clone(), *e)),
            }
        }
        let cofactor = |den: &[(Poly, u32)]| -> Poly {
            lcm.iter().fold(Poly::one(), |acc, (f, e)| {
                let have = den.iter().find(|(g, _)| g == f).map_or(0, |x| x.1);
                &acc * &f.pow(e - have)
            })
        };
        let num = &(&self.num * &cofactor(&self.den)) + &(&o.num * &cofactor(&o.den));
        RatFunc { num, den: lcm }.cancel()
    }
}

impl std::ops::Neg for &RatFunc {
    type Output = RatFunc;
    fn neg(self) -> RatFunc {
        RatFunc {
            num: -&self.num,
            den: self.den.clone(),
        }
    }
}

impl std::ops::Sub for &RatFunc {
    type Output = RatFunc;
    fn sub(self, o: &RatFunc) -> RatFunc {
        self + &(-o)
    }
}

impl std::ops::Mul for &RatFunc {
    type Output = RatFunc;
    fn mul(self, o: &RatFunc) -> RatFunc {
        if self.is_zero() || o.is_zero() {
            return RatFunc::zero();
        }
        self.fraction_free().mul(o)
    }
}

/// A rational function whose numerator is held fraction-free, to multiply by many others without
/// converting it again each time (the products of (19) and of the operator of (20)).
pub(crate) struct FfRatFunc<'a> {
    num: FPoly,
    den: &'a [Factor],
}

impl RatFunc {
    /// The fraction-free form of this function, for repeated products.
    pub(crate) fn fraction_free(&self) -> FfRatFunc<'_> {
        FfRatFunc {
            num: FPoly::from_poly(&self.num),
            den: &self.den,
        }
    }
}

impl FfRatFunc<'_> {
    /// The product with `o`, cancelled.
    pub(crate) fn mul(&self, o: &RatFunc) -> RatFunc {
        if self.num.is_zero() || o.is_zero() {
            return RatFunc::zero();
        }
        let num = self.num.mul(&FPoly::from_poly(&o.num));
        if self.den.is_empty() && o.den.is_empty() {
            return RatFunc::from_poly(num.to_poly());
        }
        let mut den = self.den.to_vec();
        for (f, e) in &o.den {
            match den.iter_mut().find(|(g, _)| g == f) {
                Some(slot) => slot.1 += e,
                None => den.push((f.clone(), *e)),
            }
        }
        RatFunc::cancelled(num, den)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::poly::qi;

    #[test]
    fn cancels_common_factor() {
        let a = RatFunc::sym("alpha");
        let g = RatFunc::sym("gamma");
        // (alpha^2 - gamma^2) / (alpha - gamma) == alpha + gamma
        let num = &(&a * &a) - &(&g * &g);
        let r = num.div(&(&a - &g)).expect("non-zero");
        assert_eq!(r, &a + &g);
        assert!(r.denom_factors().is_empty());
    }

    #[test]
    fn a_sum_of_many_equals_the_sum_two_at_a_time() {
        // Reference: pairwise addition (cross-multiplication with its own cancellation); the
        // terms share and cancel the factors alpha - gamma and 2 alpha + gamma
        let a = RatFunc::sym("alpha");
        let g = RatFunc::sym("gamma");
        let d1 = &a - &g;
        let d2 = &(&a + &a) + &g;
        let terms = vec![
            (&a * &a).div(&d1).expect("nz"),
            (-&(&g * &g)).div(&d1).expect("nz"),
            RatFunc::from_q(qi(3)).div(&(&d1 * &d2)).expect("nz"),
            (&a * &RatFunc::from_q(crate::algebra::poly::q(1, 7)))
                .div(&d2)
                .expect("nz"),
            RatFunc::zero(),
        ];
        let pairwise = terms.iter().fold(RatFunc::zero(), |s, t| &s + t);
        let once = RatFunc::sum(&terms);
        assert_eq!(once, pairwise);
        // the same canonical form, not only the same function: (a^2 - g^2)/(a - g) cancelled
        assert_eq!(once.denom_factors(), pairwise.denom_factors());
        assert_eq!(
            RatFunc::sum(&terms[..2]).denom_factors(),
            &[] as &[(Poly, u32)]
        );
        assert!(RatFunc::sum(&[]).is_zero());
    }

    #[test]
    fn partial_fraction_identity() {
        // 1/alpha - 1/gamma == (gamma - alpha)/(alpha*gamma)
        let a = RatFunc::sym("alpha");
        let g = RatFunc::sym("gamma");
        let lhs = &a.inv().expect("nz") - &g.inv().expect("nz");
        let rhs = (&g - &a).div(&(&a * &g)).expect("nz");
        assert_eq!(lhs, rhs);
        assert_ne!(lhs, RatFunc::zero());
        let at = lhs
            .subst(Sym::new("alpha"), &RatFunc::from_q(qi(2)))
            .and_then(|r| r.subst(Sym::new("gamma"), &RatFunc::from_q(qi(4))))
            .expect("defined");
        assert_eq!(at.as_constant(), Some(crate::algebra::poly::q(1, 4)));
    }
}
