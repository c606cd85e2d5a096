//! The exact term algebra: no floats here.
//!
//! Rationals ([`poly::Q`] = `BigRational`), polynomials and rational functions in the papers'
//! symbols ([`poly`], [`ratfunc`]), exponential polynomials with the operator
//! $\tilde L(\delta)$ of 000_92d54b11128ea1ec.txt ([`expo`]), identity (21) ([`identity21`]), the
//! Adomian series (18)-(23) ([`series`]), the viscoelastic operator of section 2 ([`operator`]),
//! physical dimensions ([`dims`]), exact trigonometric integrals ([`trig`]) and the Galerkin
//! coefficients (12)-(16) ([`galerkin`]). Crossing to `f64` happens in one place, [`eval`].

pub mod dims;
pub mod eval;
pub mod expo;
pub mod expr;
pub mod galerkin;
pub mod identity21;
pub mod operator;
pub mod poly;
pub mod ratfunc;
pub mod series;
pub mod trig;
pub mod units;

/// Why an exact computation could not be done.
#[derive(Debug, thiserror::Error, Clone, PartialEq, Eq)]
pub enum AlgebraError {
    /// A denominator is exactly zero at the given values.
    #[error("division by zero: {what}")]
    DivisionByZero {
        /// Which quantity vanished.
        what: String,
    },
    /// A symbol name that the computation does not know.
    #[error("unknown symbol `{name}`; allowed: {allowed}")]
    UnknownSymbol {
        /// The name given.
        name: String,
        /// The names allowed.
        allowed: String,
    },
    /// A value that is not an exact rational (`3/2`, `-13`, `0.25`, `2e9`).
    #[error("`{text}` is not an exact rational number (write e.g. 3/2, -13, 0.25, 2e9)")]
    BadRational {
        /// The text given.
        text: String,
    },
    /// A mode number outside its allowed range.
    #[error("{field} = {value} is not allowed; allowed: {allowed}")]
    OutOfRange {
        /// The field.
        field: String,
        /// The value given.
        value: String,
        /// The allowed range.
        allowed: String,
    },
}
