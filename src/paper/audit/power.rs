//! The audit's own power (issue 65), measured as the claims' power is: every relation the audit
//! calls consistent is misprinted the ways unit errors happen, the paper audited again with the
//! misprint in its place, and the misprints called inconsistent counted.
//!
//! The misprints, each of the relation's printed side (its last side, or its first when the last
//! is a bare 0): its last term multiplied by a symbol with a unit (a mass when the paper has
//! one: `... \, m`), the same term divided by it, a factor with a unit dropped from that term,
//! a symbol with a unit squared, and the time `t` for `t^2`. A misprint that leaves the unit of
//! its side as it was (a factor of unit 1) is no unit error and is not made. A relation whose
//! misprints all survive says why: it defines its symbol (its unit is whatever the relation
//! makes it), or it is the only relation on a symbol.

use super::{AuditRelation, Units, judge_relations};
use crate::algebra::expr::{Expr, Op};
use crate::algebra::units::{Unit, dimension};
use crate::paper::units::{Relation, unit_name};
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
/// the paper (each misprint audits the whole paper again; a paper of 1,000 relations would take
/// minutes), and the report says how many were measured.
pub const MAX_RELATIONS: usize = 100;

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
    let Some(before) = unit_in(side, unit_of) else {
        return Vec::new();
    };
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
        // a unit error changes the side's unit
        .filter(|(_, e)| unit_in(e, unit_of).is_some_and(|u| u != before))
        .map(|(what, e)| {
            let mut m = r.clone();
            m.sides[at] = e;
            (what, m)
        })
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
        let mut rels2 = rels.to_vec();
        rels2[i].names = m.sides.iter().flat_map(Expr::symbols).collect();
        let mut inputs2 = inputs.to_vec();
        inputs2[i] = Some(m);
        let again = judge_relations(rels2, inputs2, units);
        if again.relations[i].status == "inconsistent" {
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
