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

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;
use std::fmt;
use std::sync::{Mutex, OnceLock};

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

    /// The symbol's name in LaTeX (`alpha` -> `\alpha`, `v0` -> `V_{0}`).
    pub fn latex(self) -> String {
        let n = self.name();
        match n.as_str() {
            "alpha" | "gamma" | "eta" | "nu" | "lambda" | "zeta" | "rho" | "pi" | "theta" => {
                format!("\\{n}")
            }
            "v0" => "V_{0}".into(),
            "a8" => "A_{8}".into(),
            "a9" => "A_{9}".into(),
            "m_s" => "m_{s}".into(),
            "Kw" => "K_{w}".into(),
            "KG" => "K_{G}".into(),
            "CT" => "C_{T}".into(),
            "p1" => "p_{1}".into(),
            "p2" => "p_{2}".into(),
            "tan_theta" => "\\tan\\theta".into(),
            _ => n,
        }
    }
}

/// A monomial: exponent of symbol `i` at index `i`, trailing zeros trimmed.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
pub struct Monomial(pub Vec<u32>);

impl Monomial {
    fn trim(mut self) -> Self {
        while self.0.last() == Some(&0) {
            self.0.pop();
        }
        self
    }

    /// The monomial of one symbol to a power.
    pub fn var(s: Sym, e: u32) -> Self {
        let mut v = vec![0; s.0 as usize + 1];
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

    /// Exact quotient `self / d` if `d` divides `self`, else `None`.
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        let (dm, dc) = d.leading()?;
        let (dm, dc) = (dm.clone(), dc.clone());
        // a single-symbol divisor `x` divides iff every monomial contains `x`
        if d.len() == 1 {
            let mut out = Poly::zero();
            for (m, c) in &self.terms {
                out.terms.insert(m.div(&dm)?, c / &dc);
            }
            return Some(out);
        }
        let mut rem = self.terms.clone();
        let mut quot = Poly::zero();
        while let Some((m, c)) = rem.iter().next_back() {
            let qm = m.div(&dm)?;
            let qc = c / &dc;
            for (dm2, dc2) in &d.terms {
                let key = dm2.mul(&qm);
                let sub = dc2 * &qc;
                match rem.get_mut(&key) {
                    Some(v) => {
                        *v -= sub;
                        if v.is_zero() {
                            rem.remove(&key);
                        }
                    }
                    None => {
                        rem.insert(key, -sub);
                    }
                }
            }
            quot.terms.insert(qm, qc);
        }
        Some(quot)
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

    /// Plain-text rendering, largest monomial first (`3*alpha^2*gamma - v0`).
    pub fn to_text(&self) -> String {
        render(self, false)
    }

    /// LaTeX rendering.
    pub fn to_latex(&self) -> String {
        render(self, true)
    }
}

fn render(p: &Poly, latex: bool) -> String {
    if p.is_zero() {
        return "0".into();
    }
    let mut out = String::new();
    for (i, (m, c)) in p.terms.iter().rev().enumerate() {
        let neg = c.is_negative();
        let a = c.abs();
        if i == 0 {
            if neg {
                out.push('-');
            }
        } else {
            out.push_str(if neg { " - " } else { " + " });
        }
        let factors: Vec<String> = m
            .factors()
            .map(|(s, e)| {
                let name = if latex { s.latex() } else { s.name() };
                match (e, latex) {
                    (1, _) => name,
                    (_, true) => format!("{name}^{{{e}}}"),
                    (_, false) => format!("{name}^{e}"),
                }
            })
            .collect();
        let coef = rat_text(&a, latex);
        if factors.is_empty() {
            out.push_str(&coef);
        } else {
            let sep = if latex { " " } else { "*" };
            if !a.is_one() {
                out.push_str(&coef);
                out.push_str(sep);
            }
            out.push_str(&factors.join(sep));
        }
    }
    out
}

/// A non-negative rational as text: `3/2`, or `\frac{3}{2}` in LaTeX.
/// An exact rational as `"-135232/2187"` or `"7"`.
pub fn q_text(c: &Q) -> String {
    use num_traits::Signed;
    let s = rat_text(&c.abs(), false);
    if c.is_negative() { format!("-{s}") } else { s }
}

pub fn rat_text(a: &Q, latex: bool) -> String {
    if a.is_integer() {
        a.numer().to_string()
    } else if latex {
        format!("\\frac{{{}}}{{{}}}", a.numer(), a.denom())
    } else {
        format!("{}/{}", a.numer(), a.denom())
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
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
    fn mul(self, o: &Poly) -> Poly {
        let mut r = Poly::zero();
        for (m1, c1) in &self.terms {
            for (m2, c2) in &o.terms {
                r.add_term(m1.mul(m2), c1 * c2);
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
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
