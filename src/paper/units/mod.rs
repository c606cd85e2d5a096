//! Units inferred across a paper's relations from the units of a few symbols, the way unit
//! checkers for programs infer them across a code base (CamFort's units-of-measure for Fortran,
//! Phriky-Units for ROS C++), and the relations that break consistency named.
//!
//! A unit is a vector of rational exponents of the seven SI base units ([`Unit`]). The exponents are
//! linear in the formula: a product adds them, a quotient subtracts them, a rational power
//! scales them, the terms of a sum and the sides of a relation are equal, and the argument of
//! `exp`, `sin`, `ln` (and a symbolic exponent) is a pure number. So every formula's unit is an
//! affine form $\sum_s a_s u_s + c$ in the unknown units $u_s$ of the undeclared symbols, with
//! one rational coefficient $a_s$ for all seven dimensions, and each relation gives equations
//! $\sum_s a_s u_s = -c$: a linear system over the rationals with seven right sides, solved
//! exactly by elimination.
//!
//! One bad relation must not poison the rest: relations are added one at a time, those with
//! the fewest undeclared symbols first (a relation of declared symbols only is a plain check),
//! then in the order of the paper; a relation whose equations contradict what the system
//! already fixes is `inconsistent` and adds nothing. A symbol's unit is determined when the
//! system fixes it; a relation with a symbol nothing fixes is `undetermined`.
//!
//! Names: a function application read as an opaque symbol (`{w(x,y,t)}`) has the unit of its
//! function (`w`); a dotted symbol (`zd`, `zdd` from `\dot{z}`, `\ddot{z}`) the unit of its
//! base per second (per second squared), given as [`Relation::dots`]. A letter in an index
//! exponent (`\lambda^m`, `x^{n+1}`) is a count there, an unknown of its own, not the quantity
//! the same letter names elsewhere (m a mass); so is the variable of a sum or an integral.
//!
//! Written by hand: the system is small (tens of unknowns), must stay exact, and must say which
//! relations fixed each unit; no crate does the bookkeeping.
//!
//! The parts: `walk` (a formula's unit as an affine form, a relation's equations), `system`
//! (the exact elimination), `solve` (the relations taken in, every status and unit decided),
//! `conflicts` (the report of a rejected relation); apart: [`declared`] (the units an audit
//! starts from: a units file, the paper's words) and [`with_words`] (the conflicts that the
//! words decide, and a letter scoped per section).

mod conflicts;
pub mod declared;
mod solve;
pub mod suggest;
mod system;
mod walk;
pub mod with_words;

pub use solve::{holds_in_units, infer, infer_ordered};

use crate::algebra::expr::Expr;
use crate::algebra::units::Unit;

/// A relation of the paper as the inference reads it.
#[derive(Clone, Debug, Default)]
pub struct Relation {
    /// Its sides, left to right (each pair equal in unit).
    pub sides: Vec<Expr>,
    /// `(dotted, base, order)`: the symbol `dotted` is the `order`-th time derivative of `base`
    /// (`("zd", "z", 1)` from `\dot{z}`); order 0: an increment, in the unit of its base
    /// (`("Deltat", "t", 0)` from `\Delta t`).
    pub dots: Vec<(String, String, u32)>,
    /// The relation signs between the sides (`=`, `<=`, `propto`); a pair of sides joined by
    /// `propto` or `sim` claims no unit of the factor between them and is not linked. Empty:
    /// every pair is linked.
    pub rels: Vec<&'static str>,
}

/// Whether a relation sign claims its two sides are in one unit (all but a proportionality
/// `\propto` and a scaling `\sim`).
pub fn links_units(rel: &str) -> bool {
    !matches!(rel, "propto" | "sim" | "in")
}

/// What the inference says of one relation.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Every side and term agrees, every unit fixed.
    Consistent,
    /// The relation contradicts what the declared units and the other relations fix: the two
    /// terms that disagree and the unit of each.
    Inconsistent {
        /// One term (or side), as text.
        left: String,
        /// Its unit under the inference (or the unit it would need).
        left_unit: String,
        /// The other term.
        right: String,
        /// Its unit.
        right_unit: String,
        /// What must agree: "the sides", "the terms of a sum", "the argument of exp".
        what: String,
        /// The other relations of its conflict (indices into the input): together with it
        /// they cannot all hold, and without it they do. Empty when it contradicts the
        /// declared units alone, or when the search for the blame was bounded.
        against: Vec<usize>,
    },
    /// Consistent so far, but these symbols' units are fixed by nothing.
    Undetermined(Vec<String>),
}

/// The unit found for a symbol.
#[derive(Clone, Debug, PartialEq)]
pub struct SymbolUnit {
    /// The symbol.
    pub name: String,
    /// Its unit, `None` when nothing fixes it.
    pub unit: Option<Unit>,
    /// Whether it was declared (else inferred).
    pub declared: bool,
    /// The relations (indices into the input) that fixed an inferred unit.
    pub from: Vec<usize>,
}

/// The inference over a paper: a status per relation (in input order) and every symbol met.
#[derive(Clone, Debug)]
pub struct Inference {
    /// One per relation given.
    pub statuses: Vec<Status>,
    /// Whether the search for the relations to blame hit its bound: the relations called
    /// inconsistent are then those the one-at-a-time judgement rejected.
    pub bounded: bool,
    /// Every symbol of the relations, declared or not, sorted by name.
    pub symbols: Vec<SymbolUnit>,
}

/// The symbol a name's unit is that of: an opaque application `{w(x,y,t)}` is its function `w`.
pub fn unit_name(s: &str) -> String {
    if let Some(inner) = s.strip_prefix('{')
        && let Some(k) = inner.find('(')
        && k > 0
        && inner[..k].chars().all(|c| c.is_alphanumeric() || c == '_')
    {
        return inner[..k].to_string();
    }
    s.to_string()
}

#[cfg(test)]
mod tests;
