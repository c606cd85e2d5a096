//! Units of the claim files: every symbol a formula uses has one (`[symbols]` of
//! `verify/*.toml`), written as SI names and products, quotients and rational powers of them
//! (`"kg"`, `"m/s"`, `"N/m^1.5"`, `"Pa"`, `"J"`, `"1"`). A unit is kept as exact rational exponents
//! of the seven SI base units (kilogram, metre, second, ampere, kelvin, mole, candela), so that $k\,\delta^{3/2}$ with $k$ in N/m^1.5 and $\delta$ in m
//! is a force exactly, and [`dimension`] of a formula either gives its unit or names the first
//! term whose units do not match.

use super::expr::{Calc, Expr, Func, Op};
use num_rational::Rational64;
use num_traits::{ToPrimitive, Zero};
use std::fmt;

/// The SI base units, in the order of a [`Unit`]'s exponents.
pub const BASE: [&str; 7] = ["kg", "m", "s", "A", "K", "mol", "cd"];

/// Exponents of the SI base units (kg, m, s, A, K, mol, cd).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Unit(pub [Rational64; 7]);

impl Unit {
    /// Dimensionless.
    pub fn one() -> Unit {
        Unit::default()
    }

    fn base(kg: i64, m: i64, s: i64) -> Unit {
        let mut u = Unit::default();
        u.0[0] = kg.into();
        u.0[1] = m.into();
        u.0[2] = s.into();
        u
    }

    /// The unit `BASE[k]`.
    fn unit_of_base(k: usize) -> Unit {
        let mut u = Unit::default();
        u.0[k] = 1.into();
        u
    }

    /// `self * o^k`.
    fn times(self, o: Unit, k: Rational64) -> Unit {
        let mut r = self.0;
        for (x, y) in r.iter_mut().zip(o.0) {
            *x += k * y;
        }
        Unit(r)
    }

    /// `self / o`.
    pub fn per(self, o: Unit) -> Unit {
        self.times(o, (-1).into())
    }

    /// Whether the unit is 1.
    pub fn is_one(&self) -> bool {
        self.0.iter().all(Zero::is_zero)
    }

    /// The named SI units a file may use.
    pub fn named(name: &str) -> Option<Unit> {
        Some(match name {
            "kg" => Unit::base(1, 0, 0),
            "m" => Unit::base(0, 1, 0),
            "s" => Unit::base(0, 0, 1),
            "N" => Unit::base(1, 1, -2),
            "Pa" => Unit::base(1, -1, -2),
            "J" => Unit::base(1, 2, -2),
            "W" => Unit::base(1, 2, -3),
            "Hz" => Unit::base(0, 0, -1),
            "rad" => Unit::one(),
            "A" => Unit::unit_of_base(3),
            "K" => Unit::unit_of_base(4),
            "mol" => Unit::unit_of_base(5),
            "cd" => Unit::unit_of_base(6),
            // coulomb, volt, ohm: A s, W/A, V/A
            "C" => Unit::unit_of_base(3).times(Unit::base(0, 0, 1), 1.into()),
            "V" => Unit::base(1, 2, -3).times(Unit::unit_of_base(3), (-1).into()),
            "ohm" => Unit::base(1, 2, -3).times(Unit::unit_of_base(3), (-2).into()),
            _ => return None,
        })
    }

    /// Reads a unit: `"N/m^1.5"`, `"kg*m^2"`, `"kg m^2"` (a space is a product), `"1"`.
    pub fn parse(text: &str) -> Result<Unit, String> {
        let spaced = text.split_whitespace().collect::<Vec<_>>().join("*");
        let e = super::expr::parse(&spaced).map_err(|e| format!("unit `{text}`: {e}"))?;
        dimension(&e, &|s| Unit::named(s)).map_err(|e| match e {
            DimError::Unknown(s) => {
                let near = KNOWN
                    .iter()
                    .map(|k| (edit_distance(&s.to_lowercase(), &k.to_lowercase()), *k))
                    .min()
                    .filter(|(d, k)| *d <= 2 && *d < k.len().max(2))
                    .map(|(_, k)| format!(" (nearest known: `{k}`)"))
                    .unwrap_or_default();
                format!(
                    "unit `{text}`: unknown unit `{s}`{near}; known: {}, 1 (no unit), with * / ^",
                    KNOWN.join(" ")
                )
            }
            other => format!("unit `{text}`: {other}"),
        })
    }
}

impl fmt::Display for Unit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let parts: Vec<String> = BASE
            .iter()
            .zip(self.0)
            .filter(|(_, e)| !e.is_zero())
            .map(|(n, e)| {
                if e == Rational64::from(1) {
                    n.to_string()
                } else if e.is_integer() {
                    format!("{n}^{e}")
                } else {
                    format!("{n}^({e})")
                }
            })
            .collect();
        if parts.is_empty() {
            f.write_str("1")
        } else {
            f.write_str(&parts.join(" "))
        }
    }
}

/// Why a formula has no single unit.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DimError {
    /// A symbol with no unit.
    #[error("`{0}` has no unit")]
    Unknown(String),
    /// A sum (or comparison) of terms with different units.
    #[error("`{left}` is {left_unit} but `{right}` is {right_unit}, in `{whole}`")]
    Mismatch {
        /// The whole sum.
        whole: String,
        /// One term.
        left: String,
        /// Its unit.
        left_unit: String,
        /// The other term.
        right: String,
        /// Its unit.
        right_unit: String,
    },
    /// A function or power whose argument must be a pure number.
    #[error("`{term}`: {what} must be dimensionless, but is {unit}")]
    NotDimensionless {
        /// The term.
        term: String,
        /// Which part.
        what: String,
        /// Its unit.
        unit: String,
    },
    /// A power of a dimensional base whose exponent is not an exact rational.
    #[error("`{0}`: the exponent of a dimensional base must be a rational number")]
    Exponent(String),
}

/// Whether `e` has every unit: a literal 0 as written, and the ellipsis (`\ldots`) and
/// infinity (`\infty`) a paper's formula may hold, alone or negated.
pub fn every_unit(e: &Expr) -> bool {
    match e {
        Expr::Num(c) => c.is_zero(),
        Expr::Sym(s) => s == ELLIPSIS || s == INFINITY,
        Expr::Neg(a) => every_unit(a),
        _ => false,
    }
}

/// The symbol the LaTeX reader reads a unit written after a number as (`9.8\,\text{m/s}^2`):
/// the number is a value in that unit, which fits any place (the reader does not turn the
/// text into a unit: a prefix, a `km/h`).
pub const WRITTEN_UNIT: &str = "(unit)";

/// The symbol the LaTeX reader reads `\ldots` and `\cdots` as (a term that stands for the
/// terms left out).
pub const ELLIPSIS: &str = "...";

/// The symbol the LaTeX reader reads the operand of an operator written alone as
/// (`\frac{\partial}{\partial r} = \nabla`): the same on every side, so a pure number.
pub const OPERAND: &str = "(operand)";

/// The symbol the LaTeX reader reads `\infty` as.
pub const INFINITY: &str = "infinity";

/// The unit of a formula, given each symbol's unit; `pi` and numbers are dimensionless.
pub fn dimension(e: &Expr, unit: &dyn Fn(&str) -> Option<Unit>) -> Result<Unit, DimError> {
    let pure = |x: &Expr, what: &str, term: &Expr| -> Result<(), DimError> {
        let u = dimension(x, unit)?;
        if u.is_one() {
            Ok(())
        } else {
            Err(DimError::NotDimensionless {
                term: term.to_string(),
                what: what.into(),
                unit: u.to_string(),
            })
        }
    };
    match e {
        Expr::Num(_) | Expr::Pi => Ok(Unit::one()),
        Expr::Sym(s) if s == OPERAND => Ok(Unit::one()),
        Expr::Sym(s) => unit(s).ok_or_else(|| DimError::Unknown(s.clone())),
        Expr::Neg(a) => dimension(a, unit),
        Expr::Call(f, a) => match f {
            Func::Sqrt => Ok(Unit::one().times(dimension(a, unit)?, Rational64::new(1, 2))),
            Func::Abs => dimension(a, unit),
            Func::Sign | Func::Heaviside => {
                dimension(a, unit)?;
                Ok(Unit::one())
            }
            _ => {
                pure(a, &format!("the argument of {}", f.name()), e)?;
                Ok(Unit::one())
            }
        },
        Expr::Calc(c, body, x, extra) => {
            let zero = |v: &Expr| every_unit(v);
            // the index of a sum is a pure number; the variable of an integral with bounds has
            // the unit of its bounds (a literal 0 bound has every unit), whatever a symbol of
            // its name has outside it
            let bound = match c {
                Calc::Sum | Calc::Prod => Some(Unit::one()),
                // over an index set the paper does not give: the index's unit does not matter
                Calc::Max | Calc::Min | Calc::Mean | Calc::Marked
                    if x.is_empty() || extra.is_empty() =>
                {
                    Some(Unit::one())
                }
                Calc::Lim => match extra.iter().find(|v| !zero(v)) {
                    Some(v) => Some(dimension(v, unit)?),
                    None => unit(x).or(Some(Unit::one())),
                },
                Calc::Int if !extra.is_empty() => match extra.iter().find(|v| !zero(v)) {
                    Some(v) => Some(dimension(v, unit)?),
                    None => unit(x),
                },
                _ => None,
            };
            let ux = match bound {
                Some(u) => u,
                None => unit(x).ok_or_else(|| DimError::Unknown(x.clone()))?,
            };
            for v in extra.iter().filter(|v| !zero(v)) {
                let uv = dimension(v, unit)?;
                if uv != ux {
                    return Err(DimError::Mismatch {
                        whole: e.to_string(),
                        left: x.clone(),
                        left_unit: ux.to_string(),
                        right: v.to_string(),
                        right_unit: uv.to_string(),
                    });
                }
            }
            let ub = match bound {
                Some(u) => dimension(body, &|s| if s == x { Some(u) } else { unit(s) })?,
                None => dimension(body, unit)?,
            };
            Ok(match c {
                Calc::Diff => ub.times(ux, (-1).into()),
                Calc::Int | Calc::Region => ub.times(ux, 1.into()),
                Calc::At
                | Calc::Sum
                | Calc::Max
                | Calc::Min
                | Calc::Lim
                | Calc::Mean
                | Calc::Marked => ub,
                // a product of n factors: the factor's unit to the n-th, when n is known
                Calc::Prod => match (extra[0].exact_constant(), extra[1].exact_constant()) {
                    _ if ub.is_one() => ub,
                    (Some(lo), Some(hi)) if (&hi - &lo).is_integer() => {
                        let n = (hi - lo).to_integer() + num_bigint::BigInt::from(1);
                        let n: i64 = num_traits::ToPrimitive::to_i64(&n).unwrap_or(0);
                        Unit::one().times(ub, Rational64::from_integer(n))
                    }
                    _ => return Err(DimError::Exponent(e.to_string())),
                },
            })
        }
        Expr::Bin(op, a, b) => match op {
            Op::Add | Op::Sub => {
                // a literal 0 has every unit (`max(z, 0)`, `x + 0`); only the number as
                // written, not a term that happens to vanish (`diff(F, x)` of a constant F
                // keeps the unit of F/x); so have an ellipsis and infinity read from a paper
                if every_unit(a) {
                    return dimension(b, unit);
                }
                if every_unit(b) {
                    return dimension(a, unit);
                }
                let (ua, ub) = (dimension(a, unit)?, dimension(b, unit)?);
                if ua == ub {
                    Ok(ua)
                } else {
                    Err(DimError::Mismatch {
                        whole: e.to_string(),
                        left: a.to_string(),
                        left_unit: ua.to_string(),
                        right: b.to_string(),
                        right_unit: ub.to_string(),
                    })
                }
            }
            Op::Mul => Ok(dimension(a, unit)?.times(dimension(b, unit)?, 1.into())),
            Op::Div => Ok(dimension(a, unit)?.times(dimension(b, unit)?, (-1).into())),
            Op::Pow => {
                pure(b, "the exponent", e)?;
                let ua = dimension(a, unit)?;
                if ua.is_one() {
                    return Ok(ua);
                }
                let k = b
                    .exact_constant()
                    .ok_or_else(|| DimError::Exponent(e.to_string()))?;
                let (n, d) = (k.numer().to_i64(), k.denom().to_i64());
                match (n, d) {
                    (Some(n), Some(d)) => Ok(Unit::one().times(ua, Rational64::new(n, d))),
                    _ => Err(DimError::Exponent(e.to_string())),
                }
            }
        },
    }
}

/// The unit names [`Unit::parse`] knows ([`Unit::named`]).
const KNOWN: [&str; 16] = [
    "kg", "m", "s", "A", "K", "mol", "cd", "N", "Pa", "J", "W", "Hz", "rad", "C", "V", "ohm",
];

/// Levenshtein distance, for near-miss suggestions (an unknown unit here, an unknown scene key
/// in `models::params`).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur.push(sub.min(prev[j + 1] + 1).min(cur[j] + 1));
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    #[test]
    fn units_parse_to_si_exponents() {
        // N/m^1.5 = kg m^-1/2 s^-2 (by hand)
        let u = Unit::parse("N/m^1.5").unwrap();
        assert_eq!(u.0[..3], [1.into(), Rational64::new(-1, 2), (-2).into()]);
        assert!(u.0[3..].iter().all(|e| *e == Rational64::from(0)));
        assert_eq!(
            Unit::parse("kg m^2").unwrap(),
            Unit::parse("J*s^2").unwrap()
        );
        assert!(Unit::parse("1").unwrap().is_one());
        assert!(
            Unit::parse("furlong")
                .unwrap_err()
                .contains("unknown unit `furlong`")
        );
    }

    #[test]
    fn the_seven_base_units_and_the_electrical_ones() {
        // by hand: V A = W, C/s = A, ohm A = V, K and mol apart from the rest
        assert_eq!(Unit::parse("V*A").unwrap(), Unit::parse("W").unwrap());
        assert_eq!(Unit::parse("C/s").unwrap(), Unit::parse("A").unwrap());
        assert_eq!(Unit::parse("ohm*A").unwrap(), Unit::parse("V").unwrap());
        assert_eq!(
            Unit::parse("J/(mol*K)").unwrap().to_string(),
            "kg m^2 s^-2 K^-1 mol^-1"
        );
        assert_eq!(Unit::parse("cd").unwrap().0[6], Rational64::from(1));
        assert_ne!(Unit::parse("K").unwrap(), Unit::parse("mol").unwrap());
    }

    #[test]
    fn only_a_written_zero_has_every_unit() {
        let units = |s: &str| match s {
            "z" => Unit::parse("m").ok(),
            "x" => Unit::parse("m").ok(),
            "F" => Unit::parse("N").ok(),
            _ => None,
        };
        // max(z, 0) is (z + 0 + abs(z - 0))/2: metres
        let u = dimension(&parse("max(z, 0)").unwrap(), &units).unwrap();
        assert_eq!(u, Unit::named("m").unwrap());
        // diff(F, x) vanishes for a constant F but is N/m, not any unit
        assert!(dimension(&parse("diff(F, x) + z").unwrap(), &units).is_err());
    }

    #[test]
    fn bound_variables_take_the_unit_of_their_bounds() {
        let units = |s: &str| match s {
            "x" => Unit::parse("m").ok(),
            "t" => Unit::parse("s").ok(),
            "v" => Unit::parse("m/s").ok(),
            _ => None,
        };
        // int_0^t v(x) dx with x a time here (x is metres outside): metres; a sum's index is
        // pure inside it
        let u = dimension(&parse("int(v*x/x, x, 0, t)").unwrap(), &units).unwrap();
        assert_eq!(u, Unit::named("m").unwrap());
        let u = dimension(&parse("sum(t^2*i, i, 0, 3)").unwrap(), &units).unwrap();
        assert_eq!(u, Unit::parse("s^2").unwrap());
        // a bound of another unit than the other is still a mismatch
        assert!(dimension(&parse("int(v, x, x, t)").unwrap(), &units).is_err());
        // and a derivative keeps the symbol's own unit
        let u = dimension(&parse("diff(x, t)").unwrap(), &units).unwrap();
        assert_eq!(u, Unit::parse("m/s").unwrap());
    }

    #[test]
    fn hertz_force_is_a_force_and_a_sum_that_mixes_units_is_named() {
        let units = |s: &str| match s {
            "k" => Unit::parse("N/m^1.5").ok(),
            "z" => Unit::parse("m").ok(),
            "t" => Unit::parse("s").ok(),
            _ => None,
        };
        let f = dimension(&parse("k*z^(3/2)").unwrap(), &units).unwrap();
        assert_eq!(f, Unit::named("N").unwrap());
        let err = dimension(&parse("k*z^(3/2) + z").unwrap(), &units).unwrap_err();
        assert!(err.to_string().contains("`z` is m"), "{err}");
        let err = dimension(&parse("exp(t)").unwrap(), &units).unwrap_err();
        assert!(err.to_string().contains("argument of exp"), "{err}");
    }
}
