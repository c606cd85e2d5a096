//! The report of a conflict: the equation of a rejected relation that the system contradicts,
//! as its two terms and their units.

use super::Status;
use super::system::System;
use super::walk::Constraint;
use num_traits::Zero;
use std::collections::BTreeSet;

/// The first equation of a rejected relation that the final system contradicts, as the two
/// terms and their units (the first that does not hold if none contradicts alone).
pub(super) fn inconsistency(system: &System, cs: &[Constraint]) -> Status {
    let broken = cs
        .iter()
        .find(|c| {
            let (coeffs, rhs) = c.equation();
            let (rest, rhs, _) = system.reduce(coeffs, rhs, BTreeSet::new());
            rest.is_empty() && rhs.iter().any(|x| !x.is_zero())
        })
        .or_else(|| {
            cs.iter().find(|c| {
                let (coeffs, rhs) = c.equation();
                let (rest, rhs, _) = system.reduce(coeffs, rhs, BTreeSet::new());
                !rest.is_empty() || rhs.iter().any(|x| !x.is_zero())
            })
        })
        .or(cs.first());
    match broken {
        Some(c) => Status::Inconsistent {
            left: c.left.0.clone(),
            left_unit: system.show(&c.left.1),
            right: c.right.0.clone(),
            right_unit: system.show(&c.right.1),
            what: c.what.clone(),
        },
        None => Status::Undetermined(vec![]),
    }
}
