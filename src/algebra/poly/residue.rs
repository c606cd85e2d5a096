//! The residue test of [`Poly::may_be_divisible_by`]: polynomials evaluated modulo the Mersenne
//! prime 2^61 - 1 at a point of a divisor's zero set, in machine integers, so that a factor is
//! ruled out before a long division over big rationals is tried.

use super::{Monomial, Poly, Q, Sym};
use num_bigint::BigInt;

/// The Mersenne prime 2^61 - 1 of [`Poly::may_be_divisible_by`]'s residues.
pub(super) const P: u64 = (1 << 61) - 1;

/// `a b mod P` by the Mersenne reduction (no 128-bit division).
pub(super) fn mulm(a: u64, b: u64) -> u64 {
    let x = a as u128 * b as u128;
    let r = ((x as u64) & P) + ((x >> 61) as u64);
    let r = (r & P) + (r >> 61);
    if r >= P { r - P } else { r }
}

fn powm(mut a: u64, mut e: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = mulm(r, a);
        }
        a = mulm(a, a);
        e >>= 1;
    }
    r
}

pub(super) fn int_mod(n: &BigInt) -> u64 {
    let (sign, digits) = n.to_u64_digits();
    // 2^64 = 8 mod P
    let mut r: u64 = 0;
    for d in digits.iter().rev() {
        r = (mulm(r, 8) + (d & P) + (d >> 61)) % P;
    }
    if sign == num_bigint::Sign::Minus && r != 0 {
        P - r
    } else {
        r
    }
}

/// A point modulo [`P`]: symbol `i` at `1_000_003 + 2 i` but `x` at its own value, with the powers
/// each symbol needs cached; values of polynomials come out as fractions `(num, den)` so that no
/// coefficient needs an inverse.
pub(super) struct ModPoint {
    xs: Sym,
    x: Option<u64>,
    powers: Vec<Vec<u64>>,
}

impl ModPoint {
    fn new(xs: Sym) -> Self {
        ModPoint {
            xs,
            x: None,
            powers: Vec::new(),
        }
    }

    fn q(&self, c: &Q) -> Option<(u64, u64)> {
        let d = int_mod(c.denom());
        (d != 0).then(|| (int_mod(c.numer()), d))
    }

    pub(super) fn pow(&mut self, i: usize, e: u32) -> Option<u64> {
        let base = if i == self.xs.0 as usize {
            self.x?
        } else {
            1_000_003 + 2 * i as u64
        };
        if self.powers.len() <= i {
            self.powers.resize(i + 1, Vec::new());
        }
        let table = &mut self.powers[i];
        if table.is_empty() {
            table.push(1);
        }
        while table.len() <= e as usize {
            let next = mulm(*table.last().expect("non-empty"), base);
            table.push(next);
        }
        Some(table[e as usize])
    }

    pub(super) fn eval(&mut self, p: &Poly) -> Option<(u64, u64)> {
        let (mut an, mut ad) = (0u64, 1u64);
        for (m, c) in &p.terms {
            let (mut n, d) = self.q(c)?;
            for (i, e) in m.0.iter().enumerate() {
                if *e > 0 {
                    n = mulm(n, self.pow(i, *e)?);
                }
            }
            // an/ad + n/d
            an = (mulm(an, d) + mulm(n, ad)) % P;
            ad = mulm(ad, d);
        }
        Some((an, ad))
    }
}

/// A point of the zero set of `f` modulo [`P`] when `f` has a symbol of degree one with a
/// constant coefficient (that symbol solved, the others at fixed residues), else `None`.
pub(super) fn zero_set_point(f: &Poly) -> Option<(Sym, ModPoint)> {
    let (x, _) = f.terms.keys().find_map(|m| {
        let fs: Vec<(Sym, u32)> = m.factors().collect();
        let only_here = |s: Sym| f.terms.keys().filter(|k| k.exp(s) > 0).count() == 1;
        (fs.len() == 1 && fs[0].1 == 1 && only_here(fs[0].0)).then(|| fs[0])
    })?;
    let mut point = ModPoint::new(x);
    let (cn, cd) = point.q(f.terms.get(&Monomial::var(x, 1))?)?;
    let mut rest = f.clone();
    rest.terms.remove(&Monomial::var(x, 1));
    let (rn, rd) = point.eval(&rest)?;
    if cn == 0 || rd == 0 {
        return None;
    }
    // x = -(rn/rd) / (cn/cd) = (P - rn) cd / (rd cn)
    point.x = Some(mulm(mulm((P - rn) % P, cd), powm(mulm(rd, cn), P - 2)));
    Some((x, point))
}
