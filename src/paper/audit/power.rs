//! The audit's own power (issue 65), measured as the claims' power is: every relation the audit
//! calls consistent is misprinted the ways unit errors happen, the paper audited again with the
//! misprint in its place, and the misprints called inconsistent counted.
//!
//! The misprints, each of the relation's printed side (its last side, or its first when the last
//! is a bare 0): its last term multiplied by a symbol with a unit (a mass when the paper has
//! one: `... \, m`), the same term divided by it, a factor with a unit dropped from that term,
//! a symbol with a unit squared, and the time `t` for `t^2`. A misprint that leaves the unit of
//! its side as it was (a factor of unit 1) is no unit error and is not made; nor is one that a
//! referee who knew every unit could not see, the relation still holding in units with every
//! symbol's unit as the audit found it (`z(0) = 0` misprinted `z(0) m = 0`: a bare 0 has every
//! unit; `a = b = 0`, both vanish, each in its own unit). A relation whose
//! misprints all survive says why: it defines its symbol (its unit is whatever the relation
//! makes it), or it is the only relation on a symbol.

use super::{AuditRelation, Units, judge_relations};
use crate::algebra::expr::{Expr, Op};
use crate::algebra::units::{Unit, dimension};
use crate::paper::units::{Relation, holds_in_units, unit_name};
use serde::Serialize;

/// The power of the audit on one relation it calls consistent.
#[derive(Clone, Debug, Serialize)]
pub struct RelationPower {
    /// The relation as the audit names it: its number, or its first characters.
    pub relation: String,
    /// Its index among the audit's relations.
    pub index: usize,
    /// How many misprints were made.
    pub misprints: usize,
    /// How many the audit called inconsistent.
    pub caught: usize,
    /// The misprints the audit did not call inconsistent.
    pub survived: Vec<String>,
    /// Why none was caught, when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why: Option<String>,
}

/// The most consistent relations misprinted in one paper: past it, as many spread evenly over
/// the paper, and the report says how many were measured. Each misprint audits again the
/// relations it reaches through symbols of unknown unit (a generated paper of 1,000
/// relations: every one measured in about 3 s, benches/audit_size.py).
pub const MAX_RELATIONS: usize = 1_000;

/// The power of the audit on a paper.
#[derive(Clone, Debug, Serialize)]
pub struct AuditPower {
    /// The consistent relations with a misprint to make.
    pub consistent: usize,
    /// Those misprinted (all of them, or [`MAX_RELATIONS`] spread evenly over the paper).
    pub measured: usize,
    /// Misprints made, over the relations measured.
    pub misprints: usize,
    /// Misprints called inconsistent.
    pub caught: usize,
    /// Per relation.
    pub relations: Vec<RelationPower>,
}

impl AuditPower {
    /// The share caught (1 when nothing was misprinted).
    pub fn share(&self) -> f64 {
        if self.misprints == 0 {
            1.0
        } else {
            self.caught as f64 / self.misprints as f64
        }
    }

    /// The power in a line of words.
    pub fn summary(&self) -> String {
        let of = if self.measured < self.consistent {
            format!(
                "{} of the {} consistent relations (spread evenly over the paper)",
                self.measured, self.consistent
            )
        } else {
            format!("the {} consistent relations", self.measured)
        };
        format!(
            "The audit's power: {} of {} misprints of {of} called inconsistent ({:.1} %).",
            self.caught,
            self.misprints,
            100.0 * self.share()
        )
    }
}

/// The last term of `e` (of a top-level sum) replaced by `f` of it.
fn with_last_term(e: &Expr, f: &dyn Fn(&Expr) -> Option<Expr>) -> Option<Expr> {
    match e {
        Expr::Bin(op @ (Op::Add | Op::Sub), a, b) => {
            Some(Expr::Bin(*op, a.clone(), Box::new(with_last_term(b, f)?)))
        }
        Expr::Neg(a) => Some(Expr::Neg(Box::new(with_last_term(a, f)?))),
        other => f(other),
    }
}

/// The unit of `e` under `unit_of`, `None` when a symbol has none.
fn unit_in(e: &Expr, unit_of: &dyn Fn(&str) -> Option<Unit>) -> Option<Unit> {
    dimension(e, &|s| unit_of(&unit_name(s))).ok()
}

/// The misprints of a relation's printed side, each with what was changed. `by` is the symbol
/// a term is multiplied by.
fn misprints(
    r: &Relation,
    by: Option<&str>,
    unit_of: &dyn Fn(&str) -> Option<Unit>,
) -> Vec<(String, Relation)> {
    let Some(last) = r.sides.len().checked_sub(1) else {
        return Vec::new();
    };
    let at = if crate::algebra::units::every_unit(&r.sides[last]) {
        0
    } else {
        last
    };
    let side = &r.sides[at];
    let has_unit = |e: &Expr| unit_in(e, unit_of).is_some_and(|u| !u.is_one());
    let mut out: Vec<(String, Expr)> = Vec::new();
    if let Some(m) = by {
        let m = Expr::Sym(m.to_string());
        let times = |t: &Expr| Some(Expr::Bin(Op::Mul, Box::new(t.clone()), Box::new(m.clone())));
        let over = |t: &Expr| Some(Expr::Bin(Op::Div, Box::new(t.clone()), Box::new(m.clone())));
        if let Some(e) = with_last_term(side, &times) {
            out.push((format!("its last term times `{m}`"), e));
        }
        if let Some(e) = with_last_term(side, &over) {
            out.push((format!("its last term over `{m}`"), e));
        }
    }
    let drop = |t: &Expr| match t {
        Expr::Bin(Op::Mul | Op::Div, a, b) if has_unit(b) => Some((**a).clone()),
        Expr::Bin(Op::Mul, a, b) if has_unit(a) => Some((**b).clone()),
        _ => None,
    };
    if let Some(e) = with_last_term(side, &drop) {
        out.push(("a factor with a unit dropped from its last term".into(), e));
    }
    let square = |name: &str| {
        side.substitute(&|s: &str| {
            (s == name).then(|| {
                Expr::Bin(
                    Op::Pow,
                    Box::new(Expr::Sym(s.to_string())),
                    Box::new(Expr::Num(crate::algebra::poly::qi(2))),
                )
            })
        })
    };
    if let Some(s) = side
        .symbols()
        .into_iter()
        .find(|s| s != "t" && unit_of(&unit_name(s)).is_some_and(|u| !u.is_one()))
    {
        out.push((format!("`{s}` squared"), square(&s)));
    }
    if side.symbols().iter().any(|s| s == "t") && unit_of("t").is_some_and(|u| !u.is_one()) {
        out.push(("`t^2` for `t`".into(), square("t")));
    }
    out.into_iter()
        .map(|(what, e)| {
            let mut m = r.clone();
            m.sides[at] = e;
            (what, m)
        })
        // with every unit as the audit found it, the misprinted relation no longer holds in
        // units: a unit error a referee who knew every unit could see
        .filter(|(_, m)| !holds_in_units(m, unit_of))
        .collect()
}

/// The symbol a term is multiplied by: a mass when the paper has one, else the first symbol with
/// a unit that is not 1 (declared before inferred).
fn multiplier(a: &super::Audit) -> Option<String> {
    let with_unit = |declared: bool| {
        a.symbols
            .iter()
            .filter(|s| (s.source != "inferred") == declared)
            .filter(|s| s.unit.as_deref().is_some_and(|u| u != "1"))
            .filter(|s| !s.name.starts_with('{'))
            .map(|s| (s.name.clone(), s.unit.clone().unwrap_or_default()))
            .collect::<Vec<_>>()
    };
    let all: Vec<(String, String)> = with_unit(true)
        .into_iter()
        .chain(with_unit(false))
        .collect();
    all.iter()
        .find(|(_, u)| u == "kg")
        .or(all.first())
        .map(|(n, _)| n.clone())
}

/// Why no misprint of relation `i` was caught.
fn why_none(i: usize, inputs: &[Option<Relation>], units: &Units) -> String {
    let Some(r) = &inputs[i] else {
        return String::new();
    };
    if let (2, Expr::Sym(s)) = (r.sides.len(), &r.sides[0]) {
        let name = unit_name(s);
        let defined_once = inputs
            .iter()
            .flatten()
            .filter(|o| matches!(o.sides.first(), Some(Expr::Sym(x)) if unit_name(x) == name))
            .count()
            == 1;
        if !units.symbols.contains_key(&name) && defined_once {
            return format!(
                "it defines `{name}`: a misprint changes the unit of `{name}` with it, and no other relation or declared unit fixes that unit"
            );
        }
    }
    let mine: std::collections::BTreeSet<String> = r
        .sides
        .iter()
        .flat_map(Expr::symbols)
        .map(|s| unit_name(&s))
        .collect();
    let alone: Vec<String> = mine
        .iter()
        .filter(|s| !units.symbols.contains_key(*s))
        .filter(|s| {
            !inputs.iter().enumerate().any(|(j, o)| {
                j != i
                    && o.as_ref().is_some_and(|o| {
                        o.sides
                            .iter()
                            .flat_map(Expr::symbols)
                            .any(|x| unit_name(&x) == **s)
                    })
            })
        })
        .cloned()
        .collect();
    if alone.is_empty() {
        "its misprints are absorbed by the units of symbols that only the relations fix".into()
    } else {
        format!(
            "it is the only relation on {}: their units are whatever it makes them",
            alone
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// The power of the audit `a` of the relations `rels`/`inputs` (as [`super::read_relations`]
/// gives them) under `units`: each consistent relation misprinted and the paper judged again.
pub fn measure(
    a: &super::Audit,
    rels: &[AuditRelation],
    inputs: &[Option<Relation>],
    units: &Units,
) -> AuditPower {
    let unit_of = |name: &str| -> Option<Unit> {
        a.symbols
            .iter()
            .find(|s| s.name == name)
            .and_then(|s| s.unit.as_deref())
            .and_then(|u| Unit::parse(u).ok())
    };
    let by = multiplier(a);
    let candidates: Vec<(usize, Vec<(String, Relation)>)> = a
        .relations
        .iter()
        .enumerate()
        .filter(|(_, r)| r.status == "consistent")
        .filter_map(|(i, _)| {
            let ms = misprints(inputs[i].as_ref()?, by.as_deref(), &unit_of);
            (!ms.is_empty()).then_some((i, ms))
        })
        .collect();
    let n = candidates.len();
    let step = n.div_ceil(MAX_RELATIONS).max(1);
    let chosen: Vec<(usize, Vec<(String, Relation)>)> =
        candidates.into_iter().step_by(step).collect();
    let mut out = AuditPower {
        consistent: n,
        measured: chosen.len(),
        misprints: 0,
        caught: 0,
        relations: Vec::new(),
    };
    // each relation's misprints judged apart, the relations in parallel
    use rayon::prelude::*;
    let measured: Vec<RelationPower> = chosen
        .into_par_iter()
        .map(|(i, ms)| relation_power(i, &a.relations[i], ms, rels, inputs, units))
        .collect();
    for p in measured {
        out.misprints += p.misprints;
        out.caught += p.caught;
        out.relations.push(p);
    }
    out
}

/// The names of unknown unit in `r` (its symbols' unit names not declared in `units`, and the
/// time when it differentiates by it): what links it to other relations.
fn unknown_names(r: &Relation, units: &Units) -> Vec<String> {
    let mut out: Vec<String> = r
        .sides
        .iter()
        .flat_map(Expr::symbols)
        .chain(
            r.dots
                .iter()
                .flat_map(|(d, b, _)| [d.clone(), b.clone(), "t".into()]),
        )
        .map(|s| unit_name(&s))
        .filter(|n| !units.symbols.contains_key(n))
        .collect();
    out.sort();
    out.dedup();
    out
}

/// The indices of the relations that `m`, relation `i` misprinted, reaches through names of
/// unknown unit shared one with the next, with `i` itself, in order; with units from the
/// words (whose scopes span the paper), every relation.
fn reachable(i: usize, m: &Relation, inputs: &[Option<Relation>], units: &Units) -> Vec<usize> {
    if !units.words.is_empty() {
        return (0..inputs.len()).collect();
    }
    let names: Vec<Vec<String>> = inputs
        .iter()
        .map(|r| {
            r.as_ref()
                .map_or_else(Vec::new, |r| unknown_names(r, units))
        })
        .collect();
    let mut seen = vec![false; inputs.len()];
    seen[i] = true;
    let mut known: std::collections::BTreeSet<String> =
        unknown_names(m, units).into_iter().collect();
    let mut grew = true;
    while grew {
        grew = false;
        for (j, ns) in names.iter().enumerate() {
            if !seen[j] && ns.iter().any(|n| known.contains(n)) {
                seen[j] = true;
                known.extend(ns.iter().cloned());
                grew = true;
            }
        }
    }
    (0..inputs.len()).filter(|&j| seen[j]).collect()
}

/// The power on relation `i` (its audit entry `r`) of its misprints `ms`.
fn relation_power(
    i: usize,
    r: &AuditRelation,
    ms: Vec<(String, Relation)>,
    rels: &[AuditRelation],
    inputs: &[Option<Relation>],
    units: &Units,
) -> RelationPower {
    let mut p = RelationPower {
        relation: r.number.as_ref().map_or_else(
            || format!("`{}`", super::short(&r.latex)),
            |n| format!("({n})"),
        ),
        index: i,
        misprints: ms.len(),
        caught: 0,
        survived: Vec::new(),
        why: None,
    };
    for (what, m) in ms {
        // the relations the misprint can reach through symbols of unknown unit, in order: the
        // others share no unknown with them and cannot change its status (with units from the
        // words, whose scopes span the paper, every relation)
        let reach = reachable(i, &m, inputs, units);
        let at = reach.iter().position(|&j| j == i).unwrap_or(0);
        let mut rels2: Vec<AuditRelation> = reach.iter().map(|&j| rels[j].clone()).collect();
        let mut inputs2: Vec<Option<Relation>> = reach.iter().map(|&j| inputs[j].clone()).collect();
        rels2[at].names = m.sides.iter().flat_map(Expr::symbols).collect();
        inputs2[at] = Some(m);
        let again = judge_relations(rels2, inputs2, units);
        if again.relations[at].status == "inconsistent" {
            p.caught += 1;
        } else {
            p.survived.push(what);
        }
    }
    if p.caught == 0 {
        p.why = Some(why_none(i, inputs, units));
    }
    p
}

/// An audit with its power, as `verify audit --power --format json` prints it: the audit's keys
/// and `power`.
#[derive(Serialize)]
pub struct WithPower<'a> {
    /// The audit.
    #[serde(flatten)]
    pub audit: &'a super::Audit,
    /// Its power.
    pub power: &'a AuditPower,
}

/// The power as text: the share, then each relation with a misprint that survived.
pub fn to_text(p: &AuditPower) -> String {
    let mut s = format!("\n{}\n", p.summary());
    for r in p.relations.iter().filter(|r| r.caught < r.misprints) {
        s.push_str(&format!(
            "  {:<10} {}/{} caught; survived: {}{}\n",
            r.relation,
            r.caught,
            r.misprints,
            r.survived.join("; "),
            r.why
                .as_ref()
                .map_or_else(String::new, |w| format!(" ({w})"))
        ));
    }
    s
}

/// The power as a Markdown section.
pub fn to_markdown(p: &AuditPower) -> String {
    let esc = |t: &str| t.replace('|', "\\|");
    let mut s = format!(
        "\n## Power of the audit\n\n{} Each relation called consistent is misprinted the ways unit errors happen (its last term times or over a symbol with a unit, a factor with a unit dropped, a symbol squared, `t^2` for `t`) and the paper audited again.\n\n",
        p.summary()
    );
    let missed: Vec<&RelationPower> = p
        .relations
        .iter()
        .filter(|r| r.caught < r.misprints)
        .collect();
    if !missed.is_empty() {
        s.push_str("| relation | caught | survived | why |\n|---|---|---|---|\n");
        for r in missed {
            s.push_str(&format!(
                "| {} | {}/{} | {} | {} |\n",
                esc(&r.relation),
                r.caught,
                r.misprints,
                esc(&r.survived.join("; ")),
                esc(r.why.as_deref().unwrap_or(""))
            ));
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::super::tests::units;
    use super::super::{audit_with_power, paper_blocks};
    use super::*;

    /// The power of the audit of `tex` (displays) under the declared `pairs`.
    fn power_of(tex: &str, pairs: &[(&str, &str)]) -> AuditPower {
        let (blocks, doc) = paper_blocks(tex);
        audit_with_power(&blocks, doc.as_ref(), &units(pairs)).1
    }

    const FMA: [(&str, &str); 5] = [
        ("F", "N"),
        ("m", "kg"),
        ("a", "m/s^2"),
        ("k", "N/m"),
        ("x", "m"),
    ];

    #[test]
    fn each_misprint_of_a_relation_of_declared_symbols_is_caught() {
        // by hand: m a times m, over m, without a, with m squared: each kg^2 m s^-2, m s^-2,
        // kg, kg^2 m s^-2, none N
        let p = power_of("\\begin{equation} F = m a \\end{equation}", &FMA);
        assert_eq!((p.consistent, p.misprints, p.caught), (1, 4, 4));
        assert!((p.share() - 1.0).abs() < f64::EPSILON);
        assert!(p.summary().contains("4 of 4 misprints"), "{}", p.summary());
    }

    #[test]
    fn a_side_of_zero_takes_every_unit_so_its_lone_term_has_no_misprint() {
        // `x = 0`: x times m is still equal to a 0 in units; no referee could see it
        let p = power_of("\\begin{equation} x = 0 \\end{equation}", &FMA);
        assert_eq!((p.consistent, p.misprints), (0, 0));
        assert!((p.share() - 1.0).abs() < f64::EPSILON);
    }

    #[test]
    fn a_chain_to_zero_says_each_side_vanishes_so_no_side_has_a_misprint() {
        // `x = F/k = 0`: x and F/k both vanish, each in its unit; x m would vanish as well
        let p = power_of("\\begin{equation} x = F/k = 0 \\end{equation}", &FMA);
        assert_eq!(p.misprints, 0);
        // `x = F/k`, no zero: x m is kg m against m
        let p = power_of("\\begin{equation} x = F/k \\end{equation}", &FMA);
        assert_eq!((p.misprints, p.caught), (4, 4));
    }

    #[test]
    fn a_sum_equal_to_zero_is_misprinted_in_its_last_term() {
        // `m a + k x = 0`: k x times m, over m, without x (k alone, N/m): each term then
        // disagrees with m a (N); m squared changes m a; all four caught
        let p = power_of("\\begin{equation} m a + k x = 0 \\end{equation}", &FMA);
        assert_eq!((p.consistent, p.misprints, p.caught), (1, 4, 4));
    }

    #[test]
    fn a_definition_absorbs_its_misprints_and_says_why() {
        // E has no declared unit and no other relation: whatever E = F x makes it
        let p = power_of(
            "\\begin{equation} F = m a \\end{equation}\n\\begin{equation} E = F x \\end{equation}",
            &FMA,
        );
        let e = &p.relations[1];
        assert_eq!((e.caught, e.survived.len()), (0, e.misprints));
        assert!(e.misprints > 0);
        let why = e.why.as_deref().unwrap_or("");
        assert!(why.contains("it defines `E`"), "{why}");
        assert!(p.share() < 1.0);
    }

    #[test]
    fn a_misprint_reaches_the_relations_that_share_an_unknown_with_it() {
        let (blocks, doc) = paper_blocks(
            "\\begin{equation} u = F x \\end{equation}\n\\begin{equation} u = w \\end{equation}\n\\begin{equation} w = P t \\end{equation}\n\\begin{equation} k = m a \\end{equation}",
        );
        let declared = units(&[("F", "N"), ("x", "m"), ("P", "W"), ("t", "s"), ("m", "kg")]);
        let (_, inputs) = super::super::read_relations(&blocks, doc.as_ref(), &declared);
        let m0 = inputs[0].clone().expect("read");
        // u links (1) to (2), w (2) to (3); k and a are (4)'s alone, F, m declared
        assert_eq!(reachable(0, &m0, &inputs, &declared), vec![0, 1, 2]);
        let m3 = inputs[3].clone().expect("read");
        assert_eq!(reachable(3, &m3, &inputs, &declared), vec![3]);
        // with units from the words, every relation
        let mut words = declared.clone();
        let w = crate::paper::words::WordUnit {
            symbol: "a".into(),
            unit: crate::algebra::units::Unit::parse("m/s^2").expect("a unit"),
            quantity: "acceleration".into(),
            quote: "the acceleration $a$".into(),
            line: 1,
            key: true,
            file: None,
        };
        words.words.insert("a".into(), w);
        assert_eq!(reachable(3, &m3, &inputs, &words), vec![0, 1, 2, 3]);
        // and the misprint of (1) caught through (3), which fixes u = w as W s = J
        let p = power_of(
            "\\begin{equation} u = F x \\end{equation}\n\\begin{equation} u = w \\end{equation}\n\\begin{equation} w = P t \\end{equation}",
            &[("F", "N"), ("x", "m"), ("P", "W"), ("t", "s"), ("m", "kg")],
        );
        assert_eq!(p.relations[0].misprints, p.relations[0].caught);
        assert!(p.relations[0].caught > 0);
    }

    #[test]
    fn the_term_is_multiplied_by_a_mass_when_the_paper_has_one() {
        let (blocks, doc) = paper_blocks("\\begin{equation} F = m a \\end{equation}");
        let a = super::super::audit(&blocks, doc.as_ref(), &units(&FMA));
        assert_eq!(multiplier(&a).as_deref(), Some("m"));
        let no_mass = [("F", "N"), ("a", "m/s^2"), ("x", "m")];
        let (blocks, doc) = paper_blocks("\\begin{equation} F = a x \\end{equation}");
        let a = super::super::audit(&blocks, doc.as_ref(), &units(&no_mass));
        // the first symbol with a unit other than 1, declared first
        assert_eq!(multiplier(&a).as_deref(), Some("F"));
    }

    #[test]
    fn the_text_lists_the_relations_with_a_misprint_that_survived_and_no_other() {
        let rel = |name: &str, misprints: usize, caught: usize| RelationPower {
            relation: name.into(),
            index: 0,
            misprints,
            caught,
            survived: vec!["`m` squared".into(); misprints - caught],
            why: None,
        };
        let p = AuditPower {
            consistent: 2,
            measured: 2,
            misprints: 7,
            caught: 6,
            relations: vec![rel("(1)", 4, 4), rel("(2)", 3, 2)],
        };
        let text = to_text(&p);
        assert!(
            text.contains("(2)        2/3 caught; survived: `m` squared"),
            "{text}"
        );
        assert!(!text.contains("(1) "), "{text}");
    }
}
