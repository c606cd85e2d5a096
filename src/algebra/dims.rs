//! Physical dimensions of the papers' symbols, as exponents of mass, length and time.
//!
//! A sum is dimensionally consistent only if every term has the same dimension; a rational function
//! only if its numerator and each denominator factor are. [`dimension`] returns that common
//! dimension or says which part is inhomogeneous, so that a coefficient such as the printed
//! $E\zeta(1/\alpha - 1/\gamma)$ (dimension of $E$ times time squared, where $E/(1-\nu^2)$ needs
//! the dimension of $E$) is reported as computed, not asserted.

use super::poly::{Poly, Sym};
use super::ratfunc::RatFunc;
use std::fmt;

/// Exponents of (mass, length, time).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Dim(pub [i32; 3]);

impl Dim {
    /// Dimensionless.
    pub const NONE: Dim = Dim([0, 0, 0]);
    /// Pascal, M L^-1 T^-2.
    pub const PRESSURE: Dim = Dim([1, -1, -2]);
    /// Newton, M L T^-2.
    pub const FORCE: Dim = Dim([1, 1, -2]);

    fn add(self, o: Dim, times: i32) -> Dim {
        let mut r = self.0;
        for (x, y) in r.iter_mut().zip(o.0) {
            *x += times * y;
        }
        Dim(r)
    }
}

impl fmt::Display for Dim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names = ["kg", "m", "s"];
        let parts: Vec<String> = names
            .iter()
            .zip(self.0)
            .filter(|(_, e)| *e != 0)
            .map(|(n, e)| {
                if e == 1 {
                    n.to_string()
                } else {
                    format!("{n}^{e}")
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

/// The SI dimension of a known symbol; `None` for an unknown one.
pub fn of_symbol(s: Sym) -> Option<Dim> {
    let d = match s.name().as_str() {
        "D" | "alpha" | "gamma" | "lambda" => Dim([0, 0, -1]),
        "zeta" | "t" => Dim([0, 0, 1]),
        "E" | "Et" | "Eop" => Dim::PRESSURE,
        "eta" => Dim([1, -1, -1]),
        "nu" | "pi" | "tan_theta" | "m" | "n" => Dim::NONE,
        "v0" => Dim([0, 1, -1]),
        "a" | "b" | "h" | "f" | "x" | "y" => Dim([0, 1, 0]),
        "rho" => Dim([1, -3, 0]),
        "Kw" => Dim([1, -2, -2]),
        "KG" | "p1" | "p2" => Dim([1, 0, -2]),
        "CT" => Dim([1, -2, -1]),
        "m_s" => Dim([1, 0, 0]),
        "P" => Dim::FORCE,
        _ => return None,
    };
    Some(d)
}

/// Why an expression has no single dimension.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DimIssue {
    /// A symbol without a known dimension.
    Unknown(String),
    /// Terms of different dimensions are added: the two dimensions and the polynomial.
    Inhomogeneous {
        /// One term's dimension.
        first: Dim,
        /// Another term's dimension.
        second: Dim,
        /// Where.
        poly: String,
    },
}

impl fmt::Display for DimIssue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DimIssue::Unknown(s) => write!(f, "symbol `{s}` has no known dimension"),
            DimIssue::Inhomogeneous {
                first,
                second,
                poly,
            } => {
                write!(f, "`{poly}` adds terms of dimension {first} and {second}")
            }
        }
    }
}

fn poly_dim(p: &Poly) -> Result<Dim, DimIssue> {
    let mut found: Option<Dim> = None;
    for (m, _) in p.terms() {
        let mut d = Dim::NONE;
        for (s, e) in m.factors() {
            let ds = of_symbol(s).ok_or_else(|| DimIssue::Unknown(s.name()))?;
            d = d.add(ds, e as i32);
        }
        match found {
            None => found = Some(d),
            Some(f) if f != d => {
                return Err(DimIssue::Inhomogeneous {
                    first: f,
                    second: d,
                    poly: p.to_text(),
                });
            }
            _ => {}
        }
    }
    Ok(found.unwrap_or(Dim::NONE))
}

/// The dimension of a rational function, or why it has none.
pub fn dimension(r: &RatFunc) -> Result<Dim, DimIssue> {
    let mut d = poly_dim(r.numer())?;
    for (f, e) in r.denom_factors() {
        d = d.add(poly_dim(f)?, -(*e as i32));
    }
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_symbols_dimensions_are_their_si_units() {
        // the reference: each symbol's unit as 000 defines it, read by the units module (kg, m,
        // s exponents of the named SI units), not this table
        for (name, unit) in [
            ("E", "Pa"),
            ("eta", "Pa s"),
            ("alpha", "1/s"),
            ("zeta", "s"),
            ("v0", "m/s"),
            ("h", "m"),
            ("rho", "kg/m^3"),
            ("Kw", "N/m^3"),
            ("KG", "N/m"),
            ("CT", "N s/m^3"),
            ("m_s", "kg"),
            ("P", "N"),
        ] {
            let u = crate::algebra::units::Unit::parse(unit).expect("unit");
            let want: Vec<i32> = u.0[..3].iter().map(|e| *e.numer() as i32).collect();
            let got = of_symbol(Sym::new(name)).expect("known").0;
            assert_eq!(got.to_vec(), want, "{name} ({unit})");
        }
    }

    #[test]
    fn detects_inhomogeneous_sum() {
        let e = RatFunc::sym("E");
        let z = RatFunc::sym("zeta");
        assert_eq!(dimension(&e), Ok(Dim::PRESSURE));
        assert!(matches!(
            dimension(&(&e + &(&e * &z))),
            Err(DimIssue::Inhomogeneous { .. })
        ));
    }
}
