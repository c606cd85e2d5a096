//! Conflicts pinned on the relations that make them (issue 65): when the units' equations of all
//! relations have no solution, the smallest sets of relations whose removal leaves the rest
//! consistent (minimal correction sets, as in type-error localisation) carry the blame, all of
//! them, whatever the order of the paper.
//!
//! The search is the implicit hitting-set loop of MaxHS-style solvers: every contradiction met
//! gives an unsatisfiable core (the relations whose rows the elimination combined to reach
//! `0 = a unit`, tracked by [`System`]), shrunk to a minimal one by deletion; a correction set
//! must hit every core, so the smallest hitting sets of the cores found so far are tried; one
//! that leaves the rest consistent is a minimum correction set, one that does not yields a new
//! core. Cores that share no relation are independent conflicts, each solved on its own; within
//! one, every smallest hitting set that corrects is kept, so that two relations that disagree
//! with nothing to decide between them are both blamed, each naming the other. Among sets of
//! one size, those that spare the paper's definitions are kept (a relation that is the only
//! one with a new symbol alone on its left, `a = F/m`, is how the paper states that symbol's
//! unit: another relation on it is blamed before it, and its detail names the definition whose
//! unit it contradicts; a misprinted definition is thus found through the relation it
//! contradicts, which `verify audit --power` counts as a misprint that survives).
//!
//! The search is bounded ([`MAX_CHECKS`] systems solved, hitting sets of at most [`MAX_SIZE`]
//! relations per conflict); past a bound the caller keeps the one-at-a-time judgement and says
//! so.

use super::Status;
use super::system::System;
use super::walk::Constraint;
use num_traits::Zero;
use std::collections::{BTreeMap, BTreeSet};

/// The most systems the search solves before it gives up (a solve of the relations outside the
/// cores found, or of a core while it is shrunk).
pub(super) const MAX_CHECKS: usize = 2_000;
/// The largest correction set tried for one conflict.
pub(super) const MAX_SIZE: usize = 4;
/// The most candidate sets enumerated for one conflict and size.
const MAX_CANDIDATES: usize = 20_000;

/// The system of the relations `set` (each relation's equations, in the order given), or the
/// core of the first contradiction met: the relations whose equations combine to `0 = a unit`.
pub(super) fn system_of(cs: &[Vec<Constraint>], set: &[usize]) -> Result<System, BTreeSet<usize>> {
    let mut system = System::default();
    for &i in set {
        for c in &cs[i] {
            system.add(c, i)?;
        }
    }
    Ok(system)
}

/// A core shrunk to a minimal one: each relation dropped in turn while the rest still
/// contradicts itself.
fn minimized(cs: &[Vec<Constraint>], core: BTreeSet<usize>, checks: &mut usize) -> BTreeSet<usize> {
    let mut core: Vec<usize> = core.into_iter().collect();
    let mut k = 0;
    while k < core.len() && core.len() > 1 {
        let rest: Vec<usize> = core
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != k)
            .map(|(_, &i)| i)
            .collect();
        *checks += 1;
        match system_of(cs, &rest) {
            // still contradicts: the relation is not needed (keep the smaller core found)
            Err(smaller) => core = smaller.into_iter().collect(),
            Ok(_) => k += 1,
        }
    }
    core.into_iter().collect()
}

/// Where the blame lies.
#[derive(Clone, Debug, Default)]
pub(super) struct Blame {
    /// Each blamed relation with the minimum correction set it belongs to (every relation of
    /// every smallest set that corrects its conflict).
    pub blamed: BTreeMap<usize, BTreeSet<usize>>,
    /// The minimal cores found (each a set of relations that cannot all hold).
    pub cores: Vec<BTreeSet<usize>>,
    /// Whether a bound stopped the search (the blame is then not established).
    pub bounded: bool,
}

/// The cores grouped into conflicts that share no relation.
fn conflicts(cores: &[BTreeSet<usize>]) -> Vec<Vec<usize>> {
    let mut groups: Vec<(BTreeSet<usize>, Vec<usize>)> = Vec::new();
    for (k, core) in cores.iter().enumerate() {
        let (mut joined, rest): (Vec<_>, Vec<_>) = std::mem::take(&mut groups)
            .into_iter()
            .partition(|(rels, _)| !rels.is_disjoint(core));
        let mut rels = core.clone();
        let mut members = vec![k];
        for (r, m) in joined.drain(..) {
            rels.extend(r);
            members.extend(m);
        }
        groups = rest;
        groups.push((rels, members));
    }
    groups.into_iter().map(|(_, m)| m).collect()
}

/// The smallest sets of the relations of `cores` that hit every core, or `None` past the
/// bounds.
fn smallest_hitting_sets(
    cores: &[&BTreeSet<usize>],
    definitions: &BTreeSet<usize>,
) -> Option<Vec<BTreeSet<usize>>> {
    let rels: Vec<usize> = cores
        .iter()
        .flat_map(|c| c.iter().copied())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    for size in 1..=MAX_SIZE.min(rels.len()) {
        let mut found = Vec::new();
        let mut pick: Vec<usize> = (0..size).collect();
        let mut tried = 0;
        loop {
            tried += 1;
            if tried > MAX_CANDIDATES {
                return None;
            }
            let set: BTreeSet<usize> = pick.iter().map(|&j| rels[j]).collect();
            if cores.iter().all(|c| !c.is_disjoint(&set)) {
                found.push(set);
            }
            // the next combination of `size` of the relations, in lexicographic order
            let Some(j) = (0..size).rev().find(|&j| pick[j] < rels.len() - size + j) else {
                break;
            };
            pick[j] += 1;
            for m in j + 1..size {
                pick[m] = pick[m - 1] + 1;
            }
        }
        if !found.is_empty() {
            let spared = |h: &BTreeSet<usize>| h.intersection(definitions).count();
            let least = found.iter().map(spared).min().unwrap_or(0);
            found.retain(|h| spared(h) == least);
            return Some(found);
        }
    }
    None
}

/// The blame for the relations `all` (indices into `cs`): empty when they hold together.
/// `definitions` are blamed last among sets of one size.
pub(super) fn localise(
    cs: &[Vec<Constraint>],
    all: &[usize],
    definitions: &BTreeSet<usize>,
) -> Blame {
    let mut checks = 0;
    let mut cores: Vec<BTreeSet<usize>> = Vec::new();
    checks += 1;
    match system_of(cs, all) {
        Ok(_) => return Blame::default(),
        Err(core) => cores.push(minimized(cs, core, &mut checks)),
    }
    'search: loop {
        if checks > MAX_CHECKS {
            return Blame {
                cores,
                bounded: true,
                ..Blame::default()
            };
        }
        // the relations of no core found so far, solved once: each candidate adds the rest
        let union: BTreeSet<usize> = cores.iter().flatten().copied().collect();
        let outside: Vec<usize> = all.iter().copied().filter(|i| !union.contains(i)).collect();
        checks += 1;
        let base = match system_of(cs, &outside) {
            Ok(s) => s,
            Err(core) => {
                cores.push(minimized(cs, core, &mut checks));
                continue 'search;
            }
        };
        let holds_without = |set: &BTreeSet<usize>| -> Result<(), BTreeSet<usize>> {
            let mut s = base.clone();
            for &i in all.iter().filter(|i| union.contains(i) && !set.contains(i)) {
                for c in &cs[i] {
                    s.add(c, i)?;
                }
            }
            Ok(())
        };
        let groups = conflicts(&cores);
        let mut choices: Vec<Vec<BTreeSet<usize>>> = Vec::new();
        for g in &groups {
            let members: Vec<&BTreeSet<usize>> = g.iter().map(|&k| &cores[k]).collect();
            match smallest_hitting_sets(&members, definitions) {
                Some(h) => choices.push(h),
                None => {
                    return Blame {
                        cores,
                        bounded: true,
                        ..Blame::default()
                    };
                }
            }
        }
        // the first choice of every conflict, then each other choice of one conflict with the
        // first of the others: every one must leave the rest consistent
        let first: BTreeSet<usize> = choices.iter().flat_map(|c| c[0].iter().copied()).collect();
        let mut blamed: BTreeMap<usize, BTreeSet<usize>> = BTreeMap::new();
        for (g, options) in choices.iter().enumerate() {
            for (k, h) in options.iter().enumerate() {
                if k > 0 || g == 0 {
                    let mut set: BTreeSet<usize> =
                        first.difference(&choices[g][0]).copied().collect();
                    set.extend(h.iter().copied());
                    checks += 1;
                    if let Err(core) = holds_without(&set) {
                        cores.push(minimized(cs, core, &mut checks));
                        continue 'search;
                    }
                }
                for &r in h {
                    let mut set: BTreeSet<usize> =
                        first.difference(&choices[g][0]).copied().collect();
                    set.extend(h.iter().copied());
                    blamed.entry(r).or_insert(set);
                }
            }
        }
        return Blame {
            blamed,
            cores,
            bounded: false,
        };
    }
}

/// The first equation of a relation that `system` contradicts, as the two terms and their
/// units (the first that does not hold if none contradicts alone), with the relations `against`
/// it contradicts and whether they are themselves in doubt.
pub(super) fn inconsistency(system: &System, cs: &[Constraint], against: Vec<usize>) -> Status {
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
            against,
        },
        None => Status::Undetermined(vec![]),
    }
}
