//! `verify audit --suggest`: the fewest symbols whose units, once given, decide every relation
//! (CamFort's critical variables). The relations the inference keeps form a linear system in
//! the unknown units; each symbol given fixes one dimension of its solutions, so the number of
//! symbols needed is the dimension left free, whichever symbols are chosen. They are chosen one
//! at a time, each the symbol left open in the most undetermined relations (ties by name), and
//! given in turn until the system fixes every unknown.

use super::conflicts::system_of;
use super::walk::{Constraint, Form, all_constraints, is_local, unknowns};
use super::{Relation, Status, infer, unit_name};
use crate::algebra::units::Unit;
use std::collections::{BTreeMap, BTreeSet};

/// The fewest undeclared symbols whose units decide every relation of `relations` that the
/// inference does not call inconsistent, each with the relations (indices) it appears in.
pub fn critical_symbols(
    relations: &[Option<Relation>],
    declared: &BTreeMap<String, Unit>,
) -> Vec<(String, Vec<usize>)> {
    let inf = infer(relations, declared);
    let cs = all_constraints(relations, declared);
    let kept: Vec<usize> = (0..relations.len())
        .filter(|&i| relations[i].is_some())
        .filter(|&i| !matches!(inf.statuses[i], Status::Inconsistent { .. }))
        .collect();
    let Ok(mut system) = system_of(&cs, &kept) else {
        return Vec::new();
    };
    // a symbol that a units file can name: no bound variable, no opaque application
    let nameable = |v: &String| !is_local(v) && !v.starts_with('{');
    let mut open_in: BTreeMap<String, BTreeSet<usize>> = BTreeMap::new();
    for &i in &kept {
        for v in unknowns(&cs[i]).into_iter().filter(nameable) {
            open_in.entry(v).or_default().insert(i);
        }
    }
    let mut out = Vec::new();
    loop {
        let open: Vec<&String> = open_in
            .keys()
            .filter(|v| system.fixed(v).is_none())
            .collect();
        // the symbol open in the most relations that are still undetermined
        let undetermined = |v: &String| {
            open_in[v]
                .iter()
                .filter(|&&i| {
                    unknowns(&cs[i])
                        .iter()
                        .filter(|u| nameable(u))
                        .any(|u| system.fixed(u).is_none())
                })
                .count()
        };
        let Some(pick) = open
            .iter()
            .max_by(|a, b| undetermined(a).cmp(&undetermined(b)).then(b.cmp(a)))
            .map(|v| (*v).clone())
        else {
            break;
        };
        let given = Constraint::new(
            (pick.clone(), Form::var(&pick)),
            ("a unit given".into(), Form::constant(Unit::default())),
            "a unit given",
        );
        if system.add(&given, usize::MAX).is_err() {
            break;
        }
        let mut at: Vec<usize> = open_in[&pick].iter().copied().collect();
        at.sort_unstable();
        out.push((unit_name(&pick), at));
    }
    out
}
