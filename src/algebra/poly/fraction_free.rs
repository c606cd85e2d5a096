//! Fraction-free polynomials ([`FPoly`]): big-integer coefficients over one common denominator,
//! the working form of products, sums and exact divisions.

use super::residue::{P, int_mod, mulm, zero_set_point};
use super::{Monomial, Poly, Q};
use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use smallvec::SmallVec;
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
    ///
    /// When every exponent of the product fits a field of a 128-bit key (the series' five
    /// symbols to degree well under 2^25), the monomials are packed into integers whose order is
    /// the monomial order and whose sum is the product's monomial, and the coefficients are
    /// accumulated per key in a hash map: a product of n and m terms then costs n m hash updates
    /// and a sort of its distinct terms, not a sort of n m big-integer pairs (which was half the
    /// time of `impact series`, with its memory). Otherwise the terms are merged as lists.
    pub(crate) fn mul(&self, o: &FPoly) -> FPoly {
        let d = &self.d * &o.d;
        if let Some(pack) = Packing::of(&self.z, &o.z) {
            return FPoly {
                z: pack.product(&self.z, &o.z),
                d,
            };
        }
        self.mul_by_lists(o)
    }

    /// The product by concatenated lists merged once: the general path of [`FPoly::mul`], and
    /// its reference in the tests.
    fn mul_by_lists(&self, o: &FPoly) -> FPoly {
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

/// Monomials packed into one integer: symbol 0's exponent in the highest `bits` of a 128-bit key,
/// symbol `len - 1`'s in the lowest. With every exponent below `2^bits`, comparing keys compares
/// the monomials (trailing zeros trimmed, lexicographic order is that of the zero-padded
/// vectors) and adding keys multiplies them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Packing {
    bits: u32,
    len: usize,
}

/// A hasher for packed keys (one multiply-and-fold per key): the keys are distinct integers of
/// the form above, and the standard library's SipHash was a third of the accumulation's cost.
#[derive(Default)]
struct KeyHasher(u64);

impl std::hash::Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for b in bytes {
            self.0 = (self.0.rotate_left(5) ^ (u64::from(*b) | 0x100))
                .wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
        }
    }

    fn write_u128(&mut self, k: u128) {
        let low = (k as u64 ^ self.0).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        let h = (low.rotate_left(31) ^ (k >> 64) as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f);
        self.0 = h ^ (h >> 32);
    }
}

/// Products of up to this many term pairs are sorted as a list; larger ones add in a hash map.
const SORTED_UP_TO: usize = 1024;

type KeyMap = std::collections::HashMap<u128, BigInt, std::hash::BuildHasherDefault<KeyHasher>>;

impl Packing {
    /// The packing in which every monomial of a product of `a` and `b` fits, if one does: each
    /// symbol's exponent in the product is at most the sum of the factors' largest exponents.
    fn of(a: &[(Monomial, BigInt)], b: &[(Monomial, BigInt)]) -> Option<Packing> {
        let widest = |z: &[(Monomial, BigInt)]| z.iter().map(|(m, _)| m.0.len()).max();
        let largest = |z: &[(Monomial, BigInt)]| {
            z.iter()
                .flat_map(|(m, _)| m.0.iter().copied())
                .max()
                .unwrap_or(0)
        };
        let len = widest(a)?.max(widest(b)?).max(1);
        let top = u64::from(largest(a)) + u64::from(largest(b));
        let bits = (64 - top.leading_zeros()).max(1);
        (len as u64 * u64::from(bits) <= 128).then_some(Packing { bits, len })
    }

    fn pack(self, m: &Monomial) -> u128 {
        (0..self.len).fold(0u128, |k, i| {
            (k << self.bits) | u128::from(m.0.get(i).copied().unwrap_or(0))
        })
    }

    fn unpack(self, mut k: u128) -> Monomial {
        let mask = (1u128 << self.bits) - 1;
        let mut v: super::Exponents = smallvec::smallvec![0; self.len];
        for e in v.iter_mut().rev() {
            *e = (k & mask) as u32;
            k >>= self.bits;
        }
        Monomial(v).trim()
    }

    /// The terms of `a b`, sorted, without zeros.
    fn product(
        self,
        a: &[(Monomial, BigInt)],
        b: &[(Monomial, BigInt)],
    ) -> Vec<(Monomial, BigInt)> {
        // most products are of a few terms: their keys, coefficients and pairs stay inline
        let ka: SmallVec<[u128; 8]> = a.iter().map(|(m, _)| self.pack(m)).collect();
        let kb: SmallVec<[u128; 8]> = b.iter().map(|(m, _)| self.pack(m)).collect();
        if let Some(terms) = self.product_small(a, &ka, b, &kb) {
            return terms;
        }
        let mut acc =
            KeyMap::with_capacity_and_hasher(a.len().max(b.len()) * 2, Default::default());
        for ((_, c1), k1) in a.iter().zip(&ka) {
            for ((_, c2), k2) in b.iter().zip(&kb) {
                let c = c1 * c2;
                match acc.entry(k1 + k2) {
                    std::collections::hash_map::Entry::Occupied(mut e) => *e.get_mut() += c,
                    std::collections::hash_map::Entry::Vacant(e) => {
                        e.insert(c);
                    }
                }
            }
        }
        let mut terms: Vec<(u128, BigInt)> =
            acc.into_iter().filter(|(_, c)| !c.is_zero()).collect();
        terms.sort_unstable_by_key(|(k, _)| *k);
        terms
            .into_iter()
            .map(|(k, c)| (self.unpack(k), c))
            .collect()
    }

    /// The product in machine integers, when no sum of products can leave an `i128`: most
    /// products of the series are of a few terms with coefficients of a few bits, where the
    /// big integers' allocations were the cost. `None` when the bound does not hold.
    fn product_small(
        self,
        a: &[(Monomial, BigInt)],
        ka: &[u128],
        b: &[(Monomial, BigInt)],
        kb: &[u128],
    ) -> Option<Vec<(Monomial, BigInt)>> {
        use num_traits::ToPrimitive;
        let bits = |z: &[(Monomial, BigInt)]| z.iter().map(|(_, c)| c.bits()).max().unwrap_or(0);
        // every |c1 c2| < 2^(ba + bb); at most min(n, m) of them add up at one key
        let count = a.len().min(b.len()) as u64;
        let headroom = 64 - count.leading_zeros() as u64;
        if bits(a) + bits(b) + headroom > 126 {
            return None;
        }
        let ca: SmallVec<[i128; 8]> = a.iter().map(|(_, c)| c.to_i128()).collect::<Option<_>>()?;
        let cb: SmallVec<[i128; 8]> = b.iter().map(|(_, c)| c.to_i128()).collect::<Option<_>>()?;
        let mut pairs: SmallVec<[(u128, i128); 16]> = if a.len() * b.len() <= SORTED_UP_TO {
            let mut pairs = SmallVec::with_capacity(a.len() * b.len());
            for (c1, k1) in ca.iter().zip(ka) {
                for (c2, k2) in cb.iter().zip(kb) {
                    pairs.push((k1 + k2, c1 * c2));
                }
            }
            pairs
        } else {
            // a large product collapses onto far fewer keys: add in place
            let mut acc: std::collections::HashMap<u128, i128, _> =
                std::collections::HashMap::with_capacity_and_hasher(
                    a.len().max(b.len()) * 2,
                    std::hash::BuildHasherDefault::<KeyHasher>::default(),
                );
            for (c1, k1) in ca.iter().zip(ka) {
                for (c2, k2) in cb.iter().zip(kb) {
                    *acc.entry(k1 + k2).or_insert(0) += c1 * c2;
                }
            }
            acc.into_iter().collect()
        };
        pairs.sort_unstable_by_key(|(k, _)| *k);
        let mut out: Vec<(Monomial, BigInt)> = Vec::with_capacity(pairs.len());
        let mut i = 0;
        while i < pairs.len() {
            let key = pairs[i].0;
            let mut sum = 0i128;
            while i < pairs.len() && pairs[i].0 == key {
                sum += pairs[i].1;
                i += 1;
            }
            if sum != 0 {
                out.push((self.unpack(key), BigInt::from(sum)));
            }
        }
        Some(out)
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (the tests need no statistics, only variety).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self, below: u64) -> u64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 33) % below
        }
    }

    /// A polynomial of `n` random terms over `syms` symbols, exponents below `top`, coefficients
    /// of about `bits` bits (a few of each sign), in the form every `FPoly` keeps.
    fn random(g: &mut Lcg, n: usize, syms: usize, top: u32, bits: u32) -> FPoly {
        let z = (0..n)
            .map(|_| {
                let m: Exponents = (0..syms).map(|_| g.next(u64::from(top)) as u32).collect();
                let mut c = BigInt::from(g.next(1 << 20) as i64 - (1 << 19));
                while c.bits() < u64::from(bits) {
                    c = c * BigInt::from(1u64 << 20) + BigInt::from(g.next(1 << 20));
                }
                (Monomial(m).trim(), c)
            })
            .collect();
        FPoly {
            z: merge_terms(z),
            d: BigInt::from(1 + g.next(9)),
        }
    }

    use super::super::Exponents;

    #[test]
    fn every_product_path_agrees_with_the_merged_lists() {
        // the reference is the list product, which shares no code with the packed keys; the
        // cases reach each path: machine integers sorted (few pairs) and hashed (over 1024
        // pairs), big integers hashed (coefficients over 64 bits), and no packing at all
        // (eight symbols to exponents near 2^30, wider than 128 bits)
        let mut g = Lcg(7);
        let cases: [(usize, usize, usize, u32, u32); 6] = [
            (1, 1, 2, 3, 3),
            (3, 2, 5, 4, 8),
            (12, 9, 3, 5, 40),
            (45, 40, 3, 6, 20),
            (20, 30, 5, 4, 130),
            (6, 5, 8, 1 << 30, 10),
        ];
        for (na, nb, syms, top, bits) in cases {
            for _ in 0..5 {
                let a = random(&mut g, na, syms, top, bits);
                let b = random(&mut g, nb, syms, top, bits);
                let fast = a.mul(&b);
                let slow = a.mul_by_lists(&b);
                assert_eq!(
                    fast.z, slow.z,
                    "{na}x{nb} terms over {syms} symbols, {bits} bits"
                );
                assert_eq!(fast.d, slow.d);
                assert!(fast.z.iter().all(|(_, c)| !c.is_zero()));
                assert!(
                    fast.z.windows(2).all(|w| w[0].0 < w[1].0),
                    "sorted, no repeats"
                );
            }
        }
    }

    #[test]
    fn cancelled_terms_are_dropped() {
        // (x + y)(x - y) = x^2 - y^2: the two xy products cancel, in each integer path
        let x = |e: u32| Monomial::var(super::super::Sym(0), e);
        let y = |e: u32| Monomial::var(super::super::Sym(1), e);
        for scale in [BigInt::from(1), BigInt::from(3u8).pow(90)] {
            let mut plus = vec![(x(1), scale.clone()), (y(1), scale.clone())];
            plus.sort();
            let mut minus = vec![(x(1), scale.clone()), (y(1), -scale.clone())];
            minus.sort();
            let p = FPoly {
                z: plus,
                d: BigInt::one(),
            };
            let m = FPoly {
                z: minus,
                d: BigInt::one(),
            };
            let prod = p.mul(&m);
            let sq = &scale * &scale;
            let mut want = vec![(x(2), sq.clone()), (y(2), -sq)];
            want.sort();
            assert_eq!(prod.z, want);
        }
    }

    #[test]
    fn packed_keys_keep_the_monomial_order_and_add_as_products() {
        let mut g = Lcg(11);
        let mons: Vec<(Monomial, BigInt)> = (0..60)
            .map(|_| {
                let m: Exponents = (0..4).map(|_| g.next(5) as u32).collect();
                (Monomial(m).trim(), BigInt::one())
            })
            .collect();
        let p = Packing::of(&mons, &mons).expect("four symbols to degree 8 fit");
        assert_eq!(p.len, 4);
        assert_eq!(p.bits, 4, "the product's exponents reach 8, four bits");
        for (a, _) in &mons {
            assert_eq!(p.unpack(p.pack(a)), *a);
            for (b, _) in &mons {
                assert_eq!(p.pack(a).cmp(&p.pack(b)), a.cmp(b), "{a:?} against {b:?}");
                assert_eq!(p.unpack(p.pack(a) + p.pack(b)), a.mul(b));
            }
        }
        let wide: Vec<(Monomial, BigInt)> =
            vec![(Monomial(smallvec::smallvec![1 << 30; 8]), BigInt::one())];
        assert_eq!(
            Packing::of(&wide, &wide),
            None,
            "8 x 32 bits do not fit 128"
        );
        assert_eq!(Packing::of(&[], &mons), None, "no terms, no packing");
    }

    #[test]
    fn the_key_hasher_tells_keys_apart() {
        use std::hash::Hasher;
        let hash = |k: u128| {
            let mut h = KeyHasher::default();
            h.write_u128(k);
            h.finish()
        };
        let bytes = |b: &[u8]| {
            let mut h = KeyHasher::default();
            h.write(b);
            h.finish()
        };
        let keys = [0u128, 1, 2, 1 << 64, (1 << 64) + 1, u128::MAX];
        let mut seen: Vec<u64> = keys.iter().map(|k| hash(*k)).collect();
        seen.sort();
        seen.dedup();
        assert_eq!(seen.len(), keys.len());
        assert_ne!(bytes(&[1, 2]), bytes(&[2, 1]));
        assert_ne!(bytes(&[0]), bytes(&[]));
    }
}
