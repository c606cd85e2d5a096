//! The solution: the relations taken into the system one at a time (definitions first, then the
//! fewest unknowns, or, with units from the words, each chosen against what is fixed so far),
//! a relation that contradicts the system rejected, and every relation and symbol judged.

use super::conflicts::{Blame, inconsistency, localise, system_of};
use super::system::System;
use super::walk::{Constraint, all_constraints, is_local, unknowns};
use super::{Inference, Relation, Status, SymbolUnit, unit_name};
use crate::algebra::expr::Expr;
use crate::algebra::units::{ELLIPSIS, INFINITY, OPERAND, Unit, WRITTEN_UNIT};
use std::collections::{BTreeMap, BTreeSet};

/// Infers the units of every symbol of `relations` from the `declared` ones and judges each
/// relation. `None` relations (unreadable) are passed over and get no status of their own
/// (their index still holds a status, `Undetermined(vec![])`, which the caller replaces).
pub fn infer(relations: &[Option<Relation>], declared: &BTreeMap<String, Unit>) -> Inference {
    infer_ordered(relations, declared, false)
}

/// As [`infer`]; with `anchored_first` (units from a paper's words), the relations are taken
/// one at a time against what is fixed so far: a definition that fixes its symbol and claims
/// nothing else, then the relation with the most terms whose units are all fixed (a governing
/// equation, whose known terms fix each other term's unit, before a two-term definition of a
/// derived constant), then the fewest unknowns, in the paper's order.
pub fn infer_ordered(
    relations: &[Option<Relation>],
    declared: &BTreeMap<String, Unit>,
    anchored_first: bool,
) -> Inference {
    let cs = all_constraints(relations, declared);
    let mut order: Vec<usize> = (0..relations.len())
        .filter(|&i| relations[i].is_some())
        .collect();
    // definitions first (a bare undeclared symbol on the left: the paper's own statement of
    // its unit), then the relations with the fewest unknowns, each group in the paper's order
    let defines = |i: usize| {
        relations[i].as_ref().is_some_and(|r| {
            r.sides.len() == 2
                && matches!(&r.sides[0], Expr::Sym(s) if declared.get(&unit_name(s)).is_none())
        })
    };
    // a dotted symbol or an increment whose base is declared is as good as declared (`\Delta
    // V` with V a velocity): it is no unknown when the relations are ordered
    let as_declared: BTreeSet<String> = relations
        .iter()
        .flatten()
        .flat_map(|r| &r.dots)
        .filter(|(_, base, order)| {
            declared.contains_key(base) && (*order == 0 || declared.contains_key("t"))
        })
        .map(|(dotted, _, _)| dotted.clone())
        .collect();
    let open = |i: usize| unknowns(&cs[i]).difference(&as_declared).count();
    let mut system = System::default();
    let mut rejected = BTreeSet::new();
    let mut take = |i: usize, system: &mut System| {
        // one equation: checked in place (a clone of the system per relation made the pass
        // quadratic); several: on a copy, kept when all hold
        if let [c] = cs[i].as_slice() {
            if system.contradicts(c) {
                rejected.insert(i);
            } else {
                let _ = system.add(c, i);
            }
            return;
        }
        let mut trial = system.clone();
        if cs[i].iter().all(|c| trial.add(c, i).is_ok()) {
            *system = trial;
        } else {
            rejected.insert(i);
        }
    };
    if anchored_first {
        // one at a time, each chosen against what the system fixes so far
        let mut left: Vec<usize> = order.clone();
        while !left.is_empty() {
            let key = |i: usize| {
                // the unknowns nothing fixes yet (an integral's variable is none)
                let open: BTreeSet<String> = unknowns(&cs[i])
                    .into_iter()
                    .filter(|v| {
                        !is_local(v) && !as_declared.contains(v) && system.fixed(v).is_none()
                    })
                    .collect();
                let known = |e: &Expr| e.symbols().iter().all(|s| !open.contains(&unit_name(s)));
                let r = relations[i].as_ref();
                // it fixes every unknown it names, with what is fixed so far (a definition of
                // known things, `L(\delta) = e^{-\delta t}..`): it can contradict nothing else
                let closes = || {
                    let mut trial = system.clone();
                    cs[i].iter().all(|c| trial.add(c, i).is_ok())
                        && open.iter().all(|v| trial.fixed(v).is_some())
                };
                // a definition that fixes its symbol and claims nothing else: one term on the
                // right (or every term known), every unknown fixed by it
                let pure_definition = r.is_some_and(|r| {
                    defines(i)
                        && !known(&r.sides[0])
                        && (r.sides[1].terms().len() == 1
                            || r.sides[1].terms().iter().all(|t| known(t)))
                        && closes()
                });
                let anchored = r.map_or(0, |r| {
                    r.sides
                        .iter()
                        .flat_map(|e| e.terms())
                        .filter(|t| !t.symbols().is_empty() && known(t))
                        .count()
                });
                (!pure_definition, std::cmp::Reverse(anchored), open.len(), i)
            };
            let Some(k) = (0..left.len()).min_by_key(|&k| key(left[k])) else {
                break;
            };
            let i = left.remove(k);
            take(i, &mut system);
        }
    } else {
        order.sort_by_key(|&i| (!defines(i), open(i), i));
        for &i in &order {
            take(i, &mut system);
        }
    }
    // the blame, whatever the order (the one-at-a-time judgement above stands where the search
    // is bounded, and with units from a paper's words)
    let (blame, found, against) = blame_of(relations, declared, &cs, &order, anchored_first);
    if let Some((s, blamed)) = found {
        system = s;
        rejected = blamed;
    }
    let statuses = (0..relations.len())
        .map(|i| {
            if rejected.contains(&i) {
                return match against.get(&i) {
                    Some((s, others)) => inconsistency(s, &cs[i], others.clone()),
                    None => inconsistency(&system, &cs[i], Vec::new()),
                };
            }
            let open: Vec<String> = unknowns(&cs[i])
                .into_iter()
                .filter(|v| !is_local(v) && system.fixed(v).is_none())
                .collect();
            if open.is_empty() && relations[i].is_some() {
                Status::Consistent
            } else {
                Status::Undetermined(open)
            }
        })
        .collect();
    let mut names: BTreeSet<String> = cs
        .iter()
        .flatten()
        .flat_map(|c| {
            c.left
                .1
                .coeffs
                .keys()
                .chain(c.right.1.coeffs.keys())
                .filter(|v| !is_local(v))
                .cloned()
        })
        .collect();
    for r in relations.iter().flatten() {
        for s in &r.sides {
            names.extend(
                s.symbols()
                    .iter()
                    .filter(|x| {
                        !x.is_empty()
                            && ![ELLIPSIS, INFINITY, OPERAND, WRITTEN_UNIT].contains(&x.as_str())
                    })
                    .map(|x| unit_name(x)),
            );
        }
    }
    let symbols = names
        .into_iter()
        .map(|name| {
            if let Some(u) = declared.get(&name) {
                return SymbolUnit {
                    name,
                    unit: Some(*u),
                    declared: true,
                    from: vec![],
                };
            }
            let fixed = system.fixed(&name);
            SymbolUnit {
                unit: fixed.map(|(u, _)| u),
                from: fixed.map_or_else(Vec::new, |(_, f)| f.iter().copied().collect()),
                name,
                declared: false,
            }
        })
        .collect();
    Inference {
        statuses,
        bounded: blame.bounded,
        symbols,
    }
}

/// The system of the relations taken without the blamed ones and the blamed set (`None` when
/// no conflict, or the search bounded), and for each blamed relation the system it contradicts
/// (that of every relation but its correction set) and the other relations of its core.
#[allow(clippy::type_complexity)]
fn blame_of(
    relations: &[Option<Relation>],
    declared: &BTreeMap<String, Unit>,
    cs: &[Vec<Constraint>],
    order: &[usize],
    anchored_first: bool,
) -> (
    Blame,
    Option<(System, BTreeSet<usize>)>,
    BTreeMap<usize, (System, Vec<usize>)>,
) {
    let readable: Vec<usize> = order_all(relations);
    // a definition: the only relation with its new symbol alone on the left, the paper's
    // statement of that symbol's unit (blamed last among sets of one size)
    let left_symbol = |i: usize| match relations[i].as_ref().map(|r| (r.sides.len(), &r.sides[0])) {
        Some((2, Expr::Sym(s))) if declared.get(&unit_name(s)).is_none() => Some(unit_name(s)),
        _ => None,
    };
    let lefts: Vec<Option<String>> = (0..relations.len()).map(left_symbol).collect();
    let definitions: BTreeSet<usize> = (0..relations.len())
        .filter(|&i| lefts[i].is_some() && lefts.iter().filter(|l| **l == lefts[i]).count() == 1)
        .collect();
    // units from a paper's words keep the one-at-a-time judgement, whose weak conflicts the
    // audit sets apart, until a letter's roles are told apart
    let blame = if anchored_first {
        Blame::default()
    } else {
        localise(cs, &readable, &definitions)
    };
    let taken = |without: &BTreeSet<usize>| -> Vec<usize> {
        order
            .iter()
            .copied()
            .filter(|i| !without.contains(i))
            .collect()
    };
    let mut against: BTreeMap<usize, (System, Vec<usize>)> = BTreeMap::new();
    if blame.bounded || blame.blamed.is_empty() {
        return (blame, None, against);
    }
    let blamed: BTreeSet<usize> = blame.blamed.keys().copied().collect();
    let Ok(rest) = system_of(cs, &taken(&blamed)) else {
        return (blame, None, against);
    };
    for (&i, set) in &blame.blamed {
        let Ok(s) = system_of(cs, &taken(set)) else {
            continue;
        };
        let others = blame
            .cores
            .iter()
            .filter(|c| c.contains(&i))
            .min_by_key(|c| c.len())
            .map_or_else(Vec::new, |c| {
                c.iter().copied().filter(|&j| j != i).collect()
            });
        against.insert(i, (s, others));
    }
    (blame, Some((rest, blamed)), against)
}

/// The readable relations, in the paper's order.
fn order_all(relations: &[Option<Relation>]) -> Vec<usize> {
    (0..relations.len())
        .filter(|&i| relations[i].is_some())
        .collect()
}

/// Whether `r` alone holds in units when each symbol has the unit `unit_of` gives its unit name
/// (a symbol with none stays free): the equations the audit draws from it have a solution. A
/// misprint is a unit error a referee could see when, with every unit known, it makes this
/// false (`verify audit --power`).
pub fn holds_in_units(r: &Relation, unit_of: &dyn Fn(&str) -> Option<Unit>) -> bool {
    let cs = super::walk::constraints(r, unit_of, 0);
    super::conflicts::system_of(&[cs], &[0]).is_ok()
}
