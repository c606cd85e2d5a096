//! Fraction-free polynomials ([`FPoly`]): big-integer coefficients over one common denominator,
//! the working form of products, sums and exact divisions.

use super::residue::{P, int_mod, mulm, zero_set_point};
use super::{Monomial, Poly, Q};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::collections::BTreeMap;

/// A polynomial kept fraction-free, `(1/d) * sum z_m m` with big-integer `z_m`: the working form
/// of sums and exact divisions in [`crate::algebra::ratfunc::RatFunc`], where rational
/// coefficients would reduce by a gcd at every operation. Converted back to [`Poly`] (each
/// coefficient reduced once) when the work is done.
#[derive(Clone, Debug)]
pub(crate) struct FPoly {
    /// Terms in ascending monomial order, no zero coefficient, no repeated monomial.
    z: Vec<(Monomial, BigInt)>,
    d: BigInt,
}

/// Sorts terms by monomial and adds those with the same one, dropping zeros: products and sums
/// are built as flat lists and merged once (a map insertion per term was most of their cost).
///
/// The lists come as concatenated sorted runs (a sorted polynomial times one monomial stays
/// sorted: the order is a monomial order), which the standard library's stable sort detects and
/// merges in O(n log runs).
fn merge_terms(mut z: Vec<(Monomial, BigInt)>) -> Vec<(Monomial, BigInt)> {
    z.sort_by(|a, b| a.0.cmp(&b.0));
    let mut out: Vec<(Monomial, BigInt)> = Vec::with_capacity(z.len());
    for (m, c) in z {
        match out.last_mut() {
            Some((lm, lc)) if *lm == m => *lc += c,
            _ => {
                if out.last().is_some_and(|(_, lc)| lc.is_zero()) {
                    out.pop();
                }
                out.push((m, c));
            }
        }
    }
    if out.last().is_some_and(|(_, lc)| lc.is_zero()) {
        out.pop();
    }
    out
}

impl FPoly {
    pub(crate) fn from_poly(p: &Poly) -> FPoly {
        let (ints, d) = p.integer_form();
        FPoly {
            z: ints.into_iter().map(|(m, c)| (m.clone(), c)).collect(),
            d,
        }
    }

    pub(crate) fn is_zero(&self) -> bool {
        self.z.is_empty()
    }

    /// The product.
    pub(crate) fn mul(&self, o: &FPoly) -> FPoly {
        // one sorted run per term of the shorter factor
        let (long, short) = if self.z.len() >= o.z.len() {
            (&self.z, &o.z)
        } else {
            (&o.z, &self.z)
        };
        let mut z = Vec::with_capacity(long.len() * short.len());
        for (m2, c2) in short {
            for (m1, c1) in long {
                z.push((m1.mul(m2), c1 * c2));
            }
        }
        FPoly {
            z: merge_terms(z),
            d: &self.d * &o.d,
        }
    }

    /// The sum of many, over the least common multiple of their denominators.
    pub(crate) fn sum(parts: &[FPoly]) -> FPoly {
        let d = parts.iter().fold(
            BigInt::one(),
            |l, p| if p.d.is_one() { l } else { l.lcm(&p.d) },
        );
        let mut z = Vec::with_capacity(parts.iter().map(|p| p.z.len()).sum());
        for p in parts {
            let f = &d / &p.d;
            for (m, c) in &p.z {
                let c = if f.is_one() { c.clone() } else { c * &f };
                z.push((m.clone(), c));
            }
        }
        FPoly {
            z: merge_terms(z),
            d,
        }
    }

    /// False only when `f` certainly does not divide (see [`Poly::may_be_divisible_by`]).
    pub(crate) fn may_be_divisible_by(&self, f: &Poly) -> bool {
        let Some((_, mut point)) = zero_set_point(f) else {
            return true;
        };
        let mut acc = 0u64;
        for (m, c) in &self.z {
            let mut n = int_mod(c);
            for (i, e) in m.0.iter().enumerate() {
                if *e > 0 {
                    match point.pow(i, *e) {
                        Some(v) => n = mulm(n, v),
                        None => return true,
                    }
                }
            }
            acc = (acc + n) % P;
        }
        acc == 0
    }

    /// `self / f` when `f` divides it, else `None`. With `f = g F / fd` (`F` integer and
    /// primitive), `F | Z` in Q[x] implies an integer quotient (Gauss's lemma), so the long
    /// division runs in big integers and fails at the first leading coefficient that `F`'s does not
    /// divide (or monomial its leading monomial does not divide; one polynomial is a Groebner basis
    /// of its ideal, so a remainder decides).
    pub(crate) fn div_exact(&self, f: &Poly) -> Option<FPoly> {
        let (fz, fd) = f.integer_form();
        let g = fz.iter().fold(BigInt::zero(), |g, (_, c)| g.gcd(c));
        let fz: Vec<(&Monomial, BigInt)> = fz.into_iter().map(|(m, c)| (m, c / &g)).collect();
        let (lm, lc) = fz
            .iter()
            .max_by(|a, b| a.0.cmp(b.0))
            .map(|(m, c)| (*m, c.clone()))?;
        let mut rem: BTreeMap<Monomial, BigInt> = self.z.iter().cloned().collect();
        let mut quot: Vec<(Monomial, BigInt)> = Vec::new();
        while let Some((m, c)) = rem.pop_last() {
            let qm = m.div(lm)?;
            let (qc, r) = c.div_rem(&lc);
            if !r.is_zero() {
                return None;
            }
            for (fm, fc) in &fz {
                if *fm == lm {
                    continue;
                }
                let key = fm.mul(&qm);
                let sub = fc * &qc;
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
            quot.push((qm, qc));
        }
        // found from the largest monomial down
        quot.reverse();
        // self / f = (Z/d) / (g F / fd) = (Z/F) fd / (d g)
        let quot = if fd.is_one() {
            quot
        } else {
            quot.into_iter().map(|(m, c)| (m, c * &fd)).collect()
        };
        Some(FPoly {
            z: quot,
            d: &self.d * g,
        })
    }

    /// Back to rational coefficients, each reduced once.
    pub(crate) fn to_poly(&self) -> Poly {
        use num_traits::ToPrimitive;
        let small = self.d.to_u64();
        Poly {
            terms: self
                .z
                .iter()
                .map(|(m, c)| (m.clone(), q_over(c, &self.d, small)))
                .collect(),
        }
    }
}

/// `c / d` in lowest terms for `d > 0`, the gcd taken as that of `d` and `c mod d` (in machine
/// integers when `d` fits one, `small`): a big-integer gcd of `c` and `d` directly shifts the whole
/// of `c`, which is much the larger.
pub(super) fn q_over(c: &BigInt, d: &BigInt, small: Option<u64>) -> Q {
    use num_traits::ToPrimitive;
    let g = match small {
        Some(1) => return Q::from_integer(c.clone()),
        Some(ds) => BigInt::from(num_integer::gcd(ds, (c % d).abs().to_u64().unwrap_or(0))),
        None => d.gcd(&(c % d)),
    };
    if g.is_one() {
        Q::new_raw(c.clone(), d.clone())
    } else {
        Q::new_raw(c / &g, d / &g)
    }
}
