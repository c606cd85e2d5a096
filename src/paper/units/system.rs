//! The system of the units' equations: kept in reduced echelon form over the rationals, each row
//! with the relations it came from, so that a unit it fixes can name them.

use super::walk::{Constraint, Form};
use crate::algebra::poly::Q;
use crate::algebra::units::Unit;
use num_traits::{One, ToPrimitive, Zero};
use std::collections::{BTreeMap, BTreeSet};

/// A row of the eliminated system: `pivot + sum coeffs_v v = rhs`, with the relations it came
/// from.
#[derive(Clone, Debug)]
pub(super) struct Row {
    pub(super) coeffs: BTreeMap<String, Q>,
    pub(super) rhs: [Q; 7],
    pub(super) from: BTreeSet<usize>,
}

/// The system in reduced echelon form: no pivot appears in another row.
#[derive(Clone, Debug, Default)]
pub(super) struct System {
    pub(super) rows: BTreeMap<String, Row>,
}

impl System {
    /// The equation reduced by the pivots: what is left, its right side and its relations.
    pub(super) fn reduce(
        &self,
        mut coeffs: BTreeMap<String, Q>,
        mut rhs: [Q; 7],
        mut from: BTreeSet<usize>,
    ) -> (BTreeMap<String, Q>, [Q; 7], BTreeSet<usize>) {
        let pivots: Vec<String> = coeffs
            .keys()
            .filter(|v| self.rows.contains_key(*v))
            .cloned()
            .collect();
        for p in pivots {
            let Some(c) = coeffs.remove(&p) else { continue };
            let row = &self.rows[&p];
            for (v, a) in &row.coeffs {
                let e = coeffs.entry(v.clone()).or_insert_with(Q::zero);
                *e -= &c * a;
                if e.is_zero() {
                    coeffs.remove(v);
                }
            }
            for (x, y) in rhs.iter_mut().zip(&row.rhs) {
                *x -= &c * y;
            }
            from.extend(row.from.iter().copied());
        }
        (coeffs, rhs, from)
    }

    /// Whether an equation contradicts the system (it reduces to 0 = a non-zero unit), which
    /// [`System::add`] would then refuse.
    pub(super) fn contradicts(&self, c: &Constraint) -> bool {
        let (coeffs, rhs) = c.equation();
        let (rest, rhs, _) = self.reduce(coeffs, rhs, BTreeSet::new());
        rest.is_empty() && rhs.iter().any(|x| !x.is_zero())
    }

    /// Adds an equation of the relation `rel`; `Err` with the relations whose equations
    /// combine to the contradiction (0 = a non-zero unit), `rel` among them.
    pub(super) fn add(&mut self, c: &Constraint, rel: usize) -> Result<(), BTreeSet<usize>> {
        let (coeffs, rhs) = c.equation();
        let (mut coeffs, mut rhs, from) = self.reduce(coeffs, rhs, [rel].into());
        let Some((pivot, a)) = coeffs.iter().next().map(|(v, a)| (v.clone(), a.clone())) else {
            return if rhs.iter().all(Zero::is_zero) {
                Ok(())
            } else {
                Err(from)
            };
        };
        coeffs.remove(&pivot);
        for v in coeffs.values_mut() {
            *v /= &a;
        }
        for x in rhs.iter_mut() {
            *x /= &a;
        }
        // the new pivot leaves every other row
        for row in self.rows.values_mut() {
            let Some(k) = row.coeffs.remove(&pivot) else {
                continue;
            };
            for (v, b) in &coeffs {
                let e = row.coeffs.entry(v.clone()).or_insert_with(Q::zero);
                *e -= &k * b;
                if e.is_zero() {
                    row.coeffs.remove(v);
                }
            }
            for (x, y) in row.rhs.iter_mut().zip(&rhs) {
                *x -= &k * y;
            }
            row.from.extend(from.iter().copied());
        }
        self.rows.insert(pivot, Row { coeffs, rhs, from });
        Ok(())
    }

    /// The unit of `v` when the system fixes it, with the relations that did.
    pub(super) fn fixed(&self, v: &str) -> Option<(Unit, &BTreeSet<usize>)> {
        let row = self.rows.get(v)?;
        if !row.coeffs.is_empty() {
            return None;
        }
        Some((to_unit(&row.rhs)?, &row.from))
    }

    /// A form's unit under the system, or the form written with its unknowns.
    pub(super) fn show(&self, f: &Form) -> String {
        let (coeffs, rhs, _) = self.reduce(
            f.coeffs.clone(),
            f.konst.clone().map(|c| -c),
            BTreeSet::new(),
        );
        let konst = rhs.map(|c| -c);
        let base = to_unit(&konst).map_or("?".to_string(), |u| u.to_string());
        if coeffs.is_empty() {
            return base;
        }
        let mut parts: Vec<String> = coeffs
            .iter()
            .map(|(v, a)| {
                if a.is_one() {
                    format!("[{v}]")
                } else {
                    format!("[{v}]^({a})")
                }
            })
            .collect();
        if base != "1" {
            parts.insert(0, base);
        }
        parts.join(" ")
    }
}

pub(super) fn to_unit(x: &[Q; 7]) -> Option<Unit> {
    let r = |q: &Q| {
        Some(num_rational::Rational64::new(
            q.numer().to_i64()?,
            q.denom().to_i64()?,
        ))
    };
    let mut u = Unit::default();
    for (e, q) in u.0.iter_mut().zip(x) {
        *e = r(q)?;
    }
    Some(u)
}
