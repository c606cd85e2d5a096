//! Exact integrals of products of sines and cosines with integer frequencies.
//!
//! A function on the rectangle $[0,a]\times[0,b]$ is a finite sum of
//! $c\,X(x)\,Y(y)$ with $X$ one of $\cos(k\pi x/a)$, $\sin(k\pi x/a)$, $x^j$ (and likewise $Y$),
//! coefficients [`RatFunc`] with $\pi$ a symbol. Products use the product-to-sum formulas, so
//! derivatives, products and the integrals
//! $\int_0^L \cos(k\pi x/L)\,dx = L\,[k=0]$, $\int_0^L \sin(k\pi x/L)\,dx = L\,(1-(-1)^k)/(k\pi)$
//! are exact. This is what the Galerkin projection of 000_92d54b11128ea1ec.txt (12)-(16) needs.

use super::AlgebraError;
use super::poly::{Poly, Q, q, qi};
use super::ratfunc::RatFunc;
use num_traits::One;
use std::collections::BTreeMap;

/// One factor in one coordinate: $\cos(k\pi x/L)$, $\sin(k\pi x/L)$ or $x^j$.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Basis {
    /// $\cos(k\pi x/L)$; `Cos(0)` is the constant 1.
    Cos(u32),
    /// $\sin(k\pi x/L)$, $k \ge 1$.
    Sin(u32),
    /// $x^j$, $j \ge 1$.
    Pow(u32),
}

fn normal(b: Basis) -> Basis {
    match b {
        Basis::Pow(0) => Basis::Cos(0),
        x => x,
    }
}

/// Product of two factors in one coordinate, as a sum of `(coefficient, factor)`.
pub fn product(x: Basis, y: Basis) -> Result<Vec<(Q, Basis)>, AlgebraError> {
    use Basis::*;
    let half = q(1, 2);
    let sin = |c: Q, k: i64| -> Vec<(Q, Basis)> {
        match k.signum() {
            0 => vec![],
            1 => vec![(c, Sin(k as u32))],
            _ => vec![(-c, Sin((-k) as u32))],
        }
    };
    let (x, y) = (normal(x), normal(y));
    Ok(match (x, y) {
        (Cos(0), o) | (o, Cos(0)) => vec![(Q::one(), o)],
        (Pow(i), Pow(j)) => vec![(Q::one(), Pow(i + j))],
        (Cos(j), Cos(k)) => vec![(half.clone(), Cos(j.abs_diff(k))), (half, Cos(j + k))],
        (Sin(j), Sin(k)) => vec![(half.clone(), Cos(j.abs_diff(k))), (-half, Cos(j + k))],
        (Sin(j), Cos(k)) | (Cos(k), Sin(j)) => {
            let mut v = sin(half.clone(), j as i64 + k as i64);
            v.extend(sin(half, j as i64 - k as i64));
            v
        }
        (Pow(_), _) | (_, Pow(_)) => {
            return Err(AlgebraError::OutOfRange {
                field: "trig product".into(),
                value: format!("{x:?} * {y:?}"),
                allowed: "products of sines and cosines, or of powers".into(),
            });
        }
    })
}

/// A function on the rectangle: `(X, Y) -> coefficient`.
#[derive(Clone, Debug, Default)]
pub struct Field {
    terms: BTreeMap<(Basis, Basis), RatFunc>,
}

/// Which coordinate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// $x \in [0, a]$.
    X,
    /// $y \in [0, b]$.
    Y,
}

impl Axis {
    fn length(self) -> RatFunc {
        match self {
            Axis::X => RatFunc::sym("a"),
            Axis::Y => RatFunc::sym("b"),
        }
    }
}

impl Field {
    /// Zero.
    pub fn zero() -> Self {
        Field::default()
    }

    /// One term `c X(x) Y(y)`.
    pub fn term(c: RatFunc, x: Basis, y: Basis) -> Self {
        let mut f = Field::zero();
        f.add(normal(x), normal(y), c);
        f
    }

    fn add(&mut self, x: Basis, y: Basis, c: RatFunc) {
        if c.is_zero() {
            return;
        }
        let key = (x, y);
        let v = self.terms.get(&key).map_or(c.clone(), |old| old + &c);
        if v.is_zero() {
            self.terms.remove(&key);
        } else {
            self.terms.insert(key, v);
        }
    }

    /// The terms.
    pub fn terms(&self) -> impl Iterator<Item = (&(Basis, Basis), &RatFunc)> {
        self.terms.iter()
    }

    /// Coefficient of one basis pair.
    pub fn coeff(&self, x: Basis, y: Basis) -> RatFunc {
        self.terms
            .get(&(normal(x), normal(y)))
            .cloned()
            .unwrap_or_else(RatFunc::zero)
    }

    /// Multiplies by a coefficient.
    pub fn scale(&self, c: &RatFunc) -> Field {
        let mut out = Field::zero();
        for ((x, y), v) in &self.terms {
            out.add(*x, *y, v * c);
        }
        out
    }

    /// Sum.
    pub fn plus(&self, o: &Field) -> Field {
        let mut out = self.clone();
        for ((x, y), v) in &o.terms {
            out.add(*x, *y, v.clone());
        }
        out
    }

    /// Difference.
    pub fn minus(&self, o: &Field) -> Field {
        self.plus(&o.scale(&RatFunc::from_q(qi(-1))))
    }

    /// Product.
    pub fn times(&self, o: &Field) -> Result<Field, AlgebraError> {
        let mut out = Field::zero();
        for ((x1, y1), v1) in &self.terms {
            for ((x2, y2), v2) in &o.terms {
                let v = v1 * v2;
                for (cx, bx) in product(*x1, *x2)? {
                    for (cy, by) in product(*y1, *y2)? {
                        out.add(bx, by, v.scale(&(&cx * &cy)));
                    }
                }
            }
        }
        Ok(out)
    }

    /// Partial derivative along an axis.
    pub fn diff(&self, axis: Axis) -> Field {
        let pi = RatFunc::sym("pi");
        let len = axis.length();
        let mut out = Field::zero();
        for ((x, y), v) in &self.terms {
            let b = if axis == Axis::X { *x } else { *y };
            let (c, nb) = match b {
                Basis::Cos(0) => continue,
                Basis::Cos(k) => (
                    pi.scale(&qi(-(k as i64))).div(&len).expect("nz"),
                    Basis::Sin(k),
                ),
                Basis::Sin(k) => (
                    pi.scale(&qi(k as i64)).div(&len).expect("nz"),
                    Basis::Cos(k),
                ),
                Basis::Pow(j) => (RatFunc::from_q(qi(j as i64)), normal(Basis::Pow(j - 1))),
            };
            let (nx, ny) = if axis == Axis::X { (nb, *y) } else { (*x, nb) };
            out.add(nx, ny, v * &c);
        }
        out
    }

    /// $\Delta$.
    pub fn laplacian(&self) -> Field {
        self.diff(Axis::X)
            .diff(Axis::X)
            .plus(&self.diff(Axis::Y).diff(Axis::Y))
    }

    /// $\int_0^a\int_0^b \cdot\,dy\,dx$.
    pub fn integral(&self) -> RatFunc {
        let mut acc = RatFunc::zero();
        for ((x, y), v) in &self.terms {
            acc = &acc + &(&(v * &integral_1d(*x, Axis::X)) * &integral_1d(*y, Axis::Y));
        }
        acc
    }

    /// Value at the centre $(a/2, b/2)$.
    pub fn at_centre(&self) -> RatFunc {
        let mut acc = RatFunc::zero();
        for ((x, y), v) in &self.terms {
            acc = &acc + &(&(v * &centre_1d(*x, Axis::X)) * &centre_1d(*y, Axis::Y));
        }
        acc
    }

    /// Solves $\Delta^2 F = $ `self` for a trigonometric `self` without a constant term.
    pub fn solve_biharmonic(&self) -> Result<Field, AlgebraError> {
        let pi = RatFunc::sym("pi");
        let mut out = Field::zero();
        for ((x, y), v) in &self.terms {
            let freq = |b: Basis, axis: Axis| -> Result<RatFunc, AlgebraError> {
                let k = match b {
                    Basis::Cos(k) | Basis::Sin(k) => k,
                    Basis::Pow(_) => {
                        return Err(AlgebraError::OutOfRange {
                            field: "biharmonic right side".into(),
                            value: format!("{b:?}"),
                            allowed: "sines and cosines".into(),
                        });
                    }
                };
                Ok(pi.scale(&qi(k as i64)).div(&axis.length()).expect("nz"))
            };
            let (kx, ky) = (freq(*x, Axis::X)?, freq(*y, Axis::Y)?);
            let s = &(&kx * &kx) + &(&ky * &ky);
            let mult = &s * &s;
            let c = v.div(&mult).ok_or(AlgebraError::DivisionByZero {
                what: "constant term in the biharmonic right side".into(),
            })?;
            out.add(*x, *y, c);
        }
        Ok(out)
    }
}

fn integral_1d(b: Basis, axis: Axis) -> RatFunc {
    let len = axis.length();
    match b {
        Basis::Cos(0) => len,
        Basis::Cos(_) => RatFunc::zero(),
        Basis::Sin(k) if k % 2 == 0 => RatFunc::zero(),
        Basis::Sin(k) => len
            .scale(&qi(2))
            .div(&RatFunc::sym("pi").scale(&qi(k as i64)))
            .expect("nz"),
        Basis::Pow(j) => len
            .powi(j as i32 + 1)
            .expect("power")
            .scale(&q(1, j as i64 + 1)),
    }
}

fn centre_1d(b: Basis, axis: Axis) -> RatFunc {
    // sin(k pi/2), cos(k pi/2) exactly
    let c = |v: i64| RatFunc::from_q(qi(v));
    match b {
        Basis::Cos(k) => c([1, 0, -1, 0][(k % 4) as usize]),
        Basis::Sin(k) => c([0, 1, 0, -1][(k % 4) as usize]),
        Basis::Pow(j) => axis.length().scale(&q(1, 2)).powi(j as i32).expect("power"),
    }
}

/// A constant polynomial in `Poly` form, for callers building coefficients.
pub fn constant(c: Q) -> RatFunc {
    RatFunc::from_poly(Poly::constant(c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrals_of_single_sines() {
        // closed form: int_0^a sin(k pi x/a) dx = a (1 - cos k pi)/(k pi): 2a/(k pi) for odd k,
        // 0 for even k; over y, int_0^b dy = b
        for k in 1..=6u32 {
            let f = Field::term(RatFunc::one(), Basis::Sin(k), Basis::Cos(0));
            let want = if k % 2 == 1 {
                (&RatFunc::sym("a") * &RatFunc::sym("b"))
                    .scale(&q(2, i64::from(k)))
                    .div(&RatFunc::sym("pi"))
                    .expect("nz")
            } else {
                RatFunc::zero()
            };
            assert_eq!(f.integral(), want, "k = {k}");
        }
    }

    #[test]
    fn orthogonality_of_sines() {
        // Closed form: int_0^a sin(j pi x/a) sin(k pi x/a) dx = a/2 [j == k].
        for j in 1..=5u32 {
            for k in 1..=5u32 {
                let f = Field::term(RatFunc::one(), Basis::Sin(j), Basis::Cos(0));
                let g = Field::term(RatFunc::one(), Basis::Sin(k), Basis::Cos(0));
                let i = f.times(&g).expect("trig").integral();
                let expect = if j == k {
                    (&RatFunc::sym("a") * &RatFunc::sym("b")).scale(&q(1, 2))
                } else {
                    RatFunc::zero()
                };
                assert_eq!(i, expect, "j={j} k={k}");
            }
        }
    }

    #[test]
    fn biharmonic_inverts() {
        let f = Field::term(RatFunc::sym("h"), Basis::Cos(2), Basis::Cos(0));
        let sol = f.solve_biharmonic().expect("solvable");
        let back = sol.laplacian().laplacian();
        assert_eq!(back.coeff(Basis::Cos(2), Basis::Cos(0)), RatFunc::sym("h"));
    }
}
