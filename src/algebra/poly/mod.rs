//! Multivariate polynomials over the exact rationals $\mathbb{Q}[x_1, \dots, x_n]$.
//!
//! The symbols are the papers' parameters (`alpha`, `gamma`, `v0`, `a8`, `a9`, the plate's `a`, `b`,
//! `E`, `eta`, ..., and `D` for $d/dt$ in operator algebra). A polynomial is a map from monomials to
//! non-zero `BigRational` coefficients, so the representation is canonical and `==` is sound.
//!
//! Monomials are dense exponent vectors indexed by symbol id, trailing zeros trimmed; their derived
//! `Ord` is the lexicographic order with symbol 0 most significant, which is a monomial order. Exact
//! division by a single polynomial with that order decides divisibility (one polynomial is a Groebner
//! basis of the ideal it generates), which `RatFunc` uses to cancel factors.
//!
//! Written by hand: the registry's symbolic crates either pull in a CAS runtime or lack exact
//! multivariate rationals with a sound equality; this module is ~300 lines and has no floats.
//!
//! Here the symbols, monomials and the arithmetic of [`Poly`]; apart: `fraction_free` (the
//! big-integer working form of products, sums and exact divisions), `residue` (the test modulo
//! 2^61 - 1 that rules a factor out before a division is tried) and `print` (text and LaTeX).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Zero};
use std::collections::BTreeMap;
use std::sync::{Mutex, OnceLock};

mod fraction_free;
mod print;
mod residue;

pub(crate) use fraction_free::FPoly;
pub use print::{q_text, rat_text};
use residue::zero_set_point;

/// Exact rational number.
pub type Q = BigRational;

/// Builds an exact rational `n / d`.
pub fn q(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

/// Builds an exact integer as a rational.
pub fn qi(n: i64) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// Parses an exact rational: `-13`, `3/2`, `0.25`, `2e9`, `1.5e-3`, `-1/4e2`.
pub fn parse_q(text: &str) -> Option<Q> {
    let t = text.trim();
    if let Some((n, d)) = t.split_once('/') {
        let d = parse_decimal(d)?;
        if d.is_zero() {
            return None;
        }
        return Some(parse_decimal(n)? / d);
    }
    parse_decimal(t)
}

fn parse_decimal(text: &str) -> Option<Q> {
    let t = text.trim();
    let (neg, t) = match t.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let (mant, exp) = match t.find(['e', 'E']) {
        Some(i) => (&t[..i], t[i + 1..].parse::<i32>().ok()?),
        None => (t, 0),
    };
    let (int, frac) = mant.split_once('.').unwrap_or((mant, ""));
    if int.is_empty() && frac.is_empty() {
        return None;
    }
    if !int.chars().chain(frac.chars()).all(|c| c.is_ascii_digit()) {
        return None;
    }
    let digits: BigInt = format!("{int}{frac}0").parse::<BigInt>().ok()? / BigInt::from(10);
    let e10 = exp - frac.len() as i32;
    if e10.unsigned_abs() > 4000 {
        return None;
    }
    let ten = BigInt::from(10);
    let mut v = Q::from_integer(digits);
    if e10 >= 0 {
        v *= Q::from_integer(num_traits::pow(ten, e10 as usize));
    } else {
        v /= Q::from_integer(num_traits::pow(ten, (-e10) as usize));
    }
    Some(if neg { -v } else { v })
}

/// An interned symbol name; the id fixes its place in the monomial order.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub struct Sym(pub(crate) u16);

/// Symbols registered first, in this order, so that printing order does not depend on which code
/// path happened to intern a name first.
const PRESET: &[&str] = &[
    "D",
    "alpha",
    "gamma",
    "v0",
    "a8",
    "a9",
    "E",
    "eta",
    "nu",
    "lambda",
    "zeta",
    "a",
    "b",
    "h",
    "rho",
    "pi",
    "Kw",
    "KG",
    "CT",
    "p1",
    "p2",
    "tan_theta",
    "m_s",
    "f",
];

fn registry() -> &'static Mutex<Vec<String>> {
    static REG: OnceLock<Mutex<Vec<String>>> = OnceLock::new();
    REG.get_or_init(|| Mutex::new(PRESET.iter().map(|s| s.to_string()).collect()))
}

impl Sym {
    /// Interns `name` and returns its symbol.
    pub fn new(name: &str) -> Sym {
        let mut reg = registry().lock().unwrap_or_else(|e| e.into_inner());
        if let Some(i) = reg.iter().position(|s| s == name) {
            return Sym(i as u16);
        }
        reg.push(name.to_string());
        Sym((reg.len() - 1) as u16)
    }

    /// The symbol's name as interned.
    pub fn name(self) -> String {
        let reg = registry().lock().unwrap_or_else(|e| e.into_inner());
        reg[self.0 as usize].clone()
    }
}

/// The exponents of a monomial, inline for up to eight symbols (the series' five, the plate's
/// few): monomials are made and compared in the inner loops of every product, and a heap vector
/// per monomial was much of their cost.
pub type Exponents = smallvec::SmallVec<[u32; 8]>;

/// A monomial: exponent of symbol `i` at index `i`, trailing zeros trimmed.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
pub struct Monomial(pub Exponents);

impl Monomial {
    fn trim(mut self) -> Self {
        while self.0.last() == Some(&0) {
            self.0.pop();
        }
        self
    }

    /// The monomial of one symbol to a power.
    pub fn var(s: Sym, e: u32) -> Self {
        let mut v: Exponents = smallvec::smallvec![0; s.0 as usize + 1];
        v[s.0 as usize] = e;
        Monomial(v).trim()
    }

    fn mul(&self, o: &Monomial) -> Monomial {
        let n = self.0.len().max(o.0.len());
        let v = (0..n)
            .map(|i| self.0.get(i).unwrap_or(&0) + o.0.get(i).unwrap_or(&0))
            .collect();
        Monomial(v)
    }

    /// `self / o` if `o` divides `self`.
    fn div(&self, o: &Monomial) -> Option<Monomial> {
        if o.0.len() > self.0.len() {
            return None;
        }
        let mut v = self.0.clone();
        for (i, e) in o.0.iter().enumerate() {
            if v[i] < *e {
                return None;
            }
            v[i] -= e;
        }
        Some(Monomial(v).trim())
    }

    /// Exponent of symbol `s`.
    pub fn exp(&self, s: Sym) -> u32 {
        *self.0.get(s.0 as usize).unwrap_or(&0)
    }

    /// Total degree.
    pub fn degree(&self) -> u32 {
        self.0.iter().sum()
    }

    /// `(symbol, exponent)` pairs with non-zero exponent.
    pub fn factors(&self) -> impl Iterator<Item = (Sym, u32)> + '_ {
        self.0
            .iter()
            .enumerate()
            .filter(|(_, e)| **e > 0)
            .map(|(i, e)| (Sym(i as u16), *e))
    }

    /// Element-wise minimum (the gcd of two monomials).
    pub fn gcd(&self, o: &Monomial) -> Monomial {
        let n = self.0.len().min(o.0.len());
        Monomial((0..n).map(|i| self.0[i].min(o.0[i])).collect()).trim()
    }

    fn is_one(&self) -> bool {
        self.0.is_empty()
    }
}

/// A polynomial with exact rational coefficients; zero coefficients are never stored.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
pub struct Poly {
    terms: BTreeMap<Monomial, Q>,
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly::default()
    }

    /// A constant.
    pub fn constant(c: Q) -> Self {
        let mut p = Poly::zero();
        p.add_term(Monomial::default(), c);
        p
    }

    /// The polynomial `1`.
    pub fn one() -> Self {
        Poly::constant(Q::one())
    }

    /// A single symbol.
    pub fn var(s: Sym) -> Self {
        let mut p = Poly::zero();
        p.add_term(Monomial::var(s, 1), Q::one());
        p
    }

    /// A single symbol, by name.
    pub fn sym(name: &str) -> Self {
        Poly::var(Sym::new(name))
    }

    /// Adds `c * m` in place.
    pub fn add_term(&mut self, m: Monomial, c: Q) {
        if c.is_zero() {
            return;
        }
        let m = m.trim();
        match self.terms.get_mut(&m) {
            Some(v) => {
                *v += c;
                if v.is_zero() {
                    self.terms.remove(&m);
                }
            }
            None => {
                self.terms.insert(m, c);
            }
        }
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value if the polynomial is a constant.
    pub fn as_constant(&self) -> Option<Q> {
        match self.terms.len() {
            0 => Some(Q::zero()),
            1 => self.terms.get(&Monomial::default()).cloned(),
            _ => None,
        }
    }

    /// Terms in ascending monomial order.
    pub fn terms(&self) -> impl DoubleEndedIterator<Item = (&Monomial, &Q)> {
        self.terms.iter()
    }

    /// Number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// True if there are no terms.
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The leading (largest) term.
    pub fn leading(&self) -> Option<(&Monomial, &Q)> {
        self.terms.iter().next_back()
    }

    /// Multiplies by a rational constant.
    pub fn scale(&self, c: &Q) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, v)| (m.clone(), v * c)).collect(),
        }
    }

    /// Multiplies by a monomial.
    pub fn mul_monomial(&self, mono: &Monomial, c: &Q) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, v)| (m.mul(mono), v * c))
                .collect(),
        }
    }

    /// Integer power.
    pub fn pow(&self, e: u32) -> Poly {
        let mut r = Poly::one();
        for _ in 0..e {
            r = &r * self;
        }
        r
    }

    /// Exact quotient `self / d` if `d` divides `self`, else `None` (fraction-free, see
    /// [`FPoly::div_exact`]).
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        let (dm, dc) = d.leading()?;
        // a single-symbol divisor `x` divides iff every monomial contains `x`
        if d.len() == 1 {
            let mut out = Poly::zero();
            for (m, c) in &self.terms {
                out.terms.insert(m.div(dm)?, c / dc);
            }
            return Some(out);
        }
        FPoly::from_poly(self).div_exact(d).map(|q| q.to_poly())
    }

    /// Adds `o` in place (no copy of `self`).
    pub fn add_assign_ref(&mut self, o: &Poly) {
        for (m, c) in &o.terms {
            match self.terms.get_mut(m) {
                Some(v) => {
                    *v += c;
                    if v.is_zero() {
                        self.terms.remove(m);
                    }
                }
                None => {
                    self.terms.insert(m.clone(), c.clone());
                }
            }
        }
    }

    /// False only when `f` certainly does not divide `self`; true when it may (or the test cannot
    /// tell).
    ///
    /// For `f` of degree one in one symbol `x` with a constant coefficient there (every rate
    /// difference the series divides by: `alpha - gamma`, `2 alpha + gamma`, ...): `f | self`
    /// implies `self = 0` on the zero set of `f`. The test evaluates both modulo the prime
    /// 2^61 - 1 at a fixed point of that set (the other symbols at fixed residues, `x` solved from
    /// `f = 0`); a non-zero value proves `f` does not divide. It costs one pass over the
    /// coefficients in machine integers, where the exact division it spares runs long divisions
    /// over big rationals before it fails. `None` (a coefficient's denominator divisible by the
    /// prime, `f` not of that shape) leaves the decision to [`Poly::div_exact`].
    pub fn may_be_divisible_by(&self, f: &Poly) -> bool {
        self.vanishes_on_zero_set_mod_p(f) != Some(false)
    }

    fn vanishes_on_zero_set_mod_p(&self, f: &Poly) -> Option<bool> {
        let (_, mut point) = zero_set_point(f)?;
        let (vn, _) = point.eval(self)?;
        Some(vn == 0)
    }

    /// The sum of many polynomials, fraction-free: integer coefficients over the least common
    /// multiple of all denominators, each coefficient of the sum reduced once.
    pub fn sum_many<'a>(polys: impl IntoIterator<Item = &'a Poly>) -> Poly {
        let parts: Vec<FPoly> = polys.into_iter().map(FPoly::from_poly).collect();
        FPoly::sum(&parts).to_poly()
    }

    /// `(integer coefficients, d)` with `self = (1/d) * sum c_i m_i`, `d` the least common
    /// multiple of the coefficients' denominators.
    fn integer_form(&self) -> (Vec<(&Monomial, BigInt)>, BigInt) {
        let d = self.terms.values().fold(BigInt::one(), |l, c| {
            if c.denom().is_one() {
                l
            } else {
                l.lcm(c.denom())
            }
        });
        let ints = self
            .terms
            .iter()
            .map(|(m, c)| {
                let n = if c.denom() == &d {
                    c.numer().clone()
                } else {
                    c.numer() * (&d / c.denom())
                };
                (m, n)
            })
            .collect();
        (ints, d)
    }

    /// Greatest common monomial divisor of all terms (`1` for zero).
    pub fn monomial_content(&self) -> Monomial {
        let mut it = self.terms.keys();
        match it.next() {
            None => Monomial::default(),
            Some(first) => it.fold(first.clone(), |g, m| g.gcd(m)),
        }
    }

    /// Divides every term by a monomial that divides them all.
    pub fn div_monomial(&self, m: &Monomial) -> Poly {
        if m.is_one() {
            return self.clone();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(k, v)| (k.div(m).expect("monomial content divides"), v.clone()))
                .collect(),
        }
    }

    /// Substitutes `s := value` (a polynomial).
    pub fn subst(&self, s: Sym, value: &Poly) -> Poly {
        let mut out = Poly::zero();
        let mut powers: Vec<Poly> = vec![Poly::one()];
        for (m, c) in &self.terms {
            let e = m.exp(s) as usize;
            while powers.len() <= e {
                let next = powers.last().expect("non-empty") * value;
                powers.push(next);
            }
            let mut rest = m.clone();
            if let Some(x) = rest.0.get_mut(s.0 as usize) {
                *x = 0;
            }
            out = &out + &powers[e].mul_monomial(&rest.trim(), c);
        }
        out
    }

    /// Partial derivative with respect to `s`.
    pub fn diff(&self, s: Sym) -> Poly {
        let mut out = Poly::zero();
        for (m, c) in &self.terms {
            let e = m.exp(s);
            if e == 0 {
                continue;
            }
            let mut rest = m.clone();
            rest.0[s.0 as usize] = e - 1;
            out.add_term(rest, c * Q::from_integer(BigInt::from(e)));
        }
        out
    }

    /// Highest exponent of `s` in any term.
    pub fn degree_in(&self, s: Sym) -> u32 {
        self.terms.keys().map(|m| m.exp(s)).max().unwrap_or(0)
    }

    /// Coefficient of `s^k` as a polynomial in the other symbols.
    pub fn coeff_of(&self, s: Sym, k: u32) -> Poly {
        let mut out = Poly::zero();
        for (m, c) in &self.terms {
            if m.exp(s) == k {
                let mut rest = m.clone();
                if let Some(x) = rest.0.get_mut(s.0 as usize) {
                    *x = 0;
                }
                out.add_term(rest, c.clone());
            }
        }
        out
    }

    /// Symbols that occur.
    pub fn symbols(&self) -> Vec<Sym> {
        let mut v: Vec<Sym> = self
            .terms
            .keys()
            .flat_map(|m| m.factors().map(|(s, _)| s).collect::<Vec<_>>())
            .collect();
        v.sort();
        v.dedup();
        v
    }
}

impl std::ops::Add for &Poly {
    type Output = Poly;
    fn add(self, o: &Poly) -> Poly {
        let (mut big, small) = if self.len() >= o.len() {
            (self.clone(), o)
        } else {
            (o.clone(), self)
        };
        for (m, c) in &small.terms {
            big.add_term(m.clone(), c.clone());
        }
        big
    }
}

impl std::ops::Sub for &Poly {
    type Output = Poly;
    fn sub(self, o: &Poly) -> Poly {
        let mut r = self.clone();
        for (m, c) in &o.terms {
            r.add_term(m.clone(), -c.clone());
        }
        r
    }
}

impl std::ops::Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
        }
    }
}

impl std::ops::Mul for &Poly {
    type Output = Poly;
    /// Fraction-free (see [`FPoly`]): a product of rationals reduces by a gcd at every step,
    /// which is where exact series spend their time; here each coefficient is reduced once.
    fn mul(self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::zero();
        }
        FPoly::from_poly(self).mul(&FPoly::from_poly(o)).to_poly()
    }
}

#[cfg(test)]
mod tests {
    use super::fraction_free::q_over;
    use super::*;

    #[test]
    fn decimal_exponents_are_read_up_to_4000() {
        // the limit is inclusive: 1e4000 is a number, 1e4001 is refused (a file from anyone
        // must not ask for a number of a million digits)
        assert!(parse_decimal("1e4000").is_some());
        assert!(parse_decimal("1e-4000").is_some());
        assert!(parse_decimal("1e4001").is_none());
    }

    #[test]
    fn exact_division_recovers_factor_and_rejects_non_factor() {
        let x = Poly::sym("alpha");
        let y = Poly::sym("gamma");
        let f = &(&x - &y) * &(&(&x * &x) + &y);
        assert_eq!(f.div_exact(&(&x - &y)), Some(&(&x * &x) + &y));
        assert_eq!(f.div_exact(&(&x + &y)), None);
    }

    #[test]
    fn the_residue_test_never_rules_out_a_true_factor_and_rules_out_false_ones() {
        // f | p is decided by exact division (the reference); the residue test may only say
        // "no" when the division fails
        let x = Poly::sym("alpha");
        let y = Poly::sym("gamma");
        let c = |n: i64, d: i64| Poly::constant(q(n, d));
        let factors = [
            &x - &y,
            &(&x + &y.scale(&q(1, 2))) + &Poly::zero(),
            &(&x.scale(&q(3, 1)) - &y) + &c(5, 3),
            &x + &c(-2, 1),
        ];
        let other = &(&x * &x) + &(&y * &c(7, 5));
        for f in &factors {
            let multiple = &(&other * f) * &(&y + &c(1, 3));
            assert!(multiple.may_be_divisible_by(f));
            assert!(FPoly::from_poly(&multiple).may_be_divisible_by(f));
            let back = multiple.div_exact(f).expect("a multiple divides");
            assert_eq!(&back * f, multiple);
            // a non-multiple: the test must say no (it is exact for these linear factors at the
            // fixed point unless p vanishes there by accident, which these do not)
            let not = &multiple + &c(1, 1);
            assert_eq!(not.div_exact(f), None);
            assert!(!not.may_be_divisible_by(f));
            assert!(!FPoly::from_poly(&not).may_be_divisible_by(f));
        }
        // a factor with no symbol of degree one cannot be tested: the division decides
        let square = &(&x * &x) + &(&y * &y);
        assert!(other.may_be_divisible_by(&square));
        assert_eq!(other.div_exact(&square), None);
    }

    #[test]
    fn fraction_free_products_and_sums_equal_the_rational_ones() {
        // Reference: the term-by-term definition with rational arithmetic
        let x = Poly::sym("alpha");
        let y = Poly::sym("gamma");
        let a = &(&x.scale(&q(2, 3)) + &y.scale(&q(-5, 4))) + &Poly::constant(q(1, 6));
        let b = &(&x * &y).scale(&q(7, 10)) - &Poly::constant(q(3, 8));
        let mut direct = Poly::zero();
        for (m1, c1) in a.terms() {
            for (m2, c2) in b.terms() {
                direct.add_term(m1.mul(m2), c1 * c2);
            }
        }
        assert_eq!(&a * &b, direct);
        let mut s = a.clone();
        s.add_assign_ref(&b);
        s.add_assign_ref(&-&a);
        assert_eq!(s, b);
        assert_eq!(Poly::sum_many([&a, &b, &-&a]), b);
        assert_eq!(
            q_over(&BigInt::from(-6), &BigInt::from(4), Some(4)),
            q(-3, 2)
        );
        assert_eq!(q_over(&BigInt::from(9), &BigInt::from(3), None), qi(3));
    }

    #[test]
    fn parses_exact_rationals() {
        assert_eq!(parse_q("3/2"), Some(q(3, 2)));
        assert_eq!(parse_q("-13"), Some(qi(-13)));
        assert_eq!(parse_q("0.25"), Some(q(1, 4)));
        assert_eq!(parse_q("2e9"), Some(qi(2_000_000_000)));
        assert_eq!(parse_q("1.5e-3"), Some(q(3, 2000)));
        assert_eq!(parse_q("1/0"), None);
        assert_eq!(parse_q("abc"), None);
        assert_eq!(parse_q(""), None);
    }

    #[test]
    fn subst_evaluates() {
        let x = Poly::sym("alpha");
        let p = &(&x * &x) - &Poly::constant(qi(3));
        let v = p.subst(Sym::new("alpha"), &Poly::constant(q(1, 2)));
        assert_eq!(v.as_constant(), Some(q(-11, 4)));
    }
}
