//! `verify audit`: the units of every relation of a paper, from its LaTeX and the units of a few
//! symbols ([`crate::paper::units`]), and `verify init`: a claims file to start from.
//!
//! The paper is its LaTeX source (or a text with display math), read as LaTeX numbers it
//! ([`read_document`]), or a displays extract of `%% block N` sections (`verify/tex/*.tex`, the
//! seeds' cache). Every relation of every display, numbered or not, gets a status:
//! `consistent`, `inconsistent` (the two terms whose units disagree, with their units),
//! `undetermined` (the symbols whose units nothing fixes) or `unreadable` (the construct the
//! LaTeX reader lacks). The units file is TOML with `[symbols]` (name = unit) and optionally
//! `[audit_symbols]` (more units, which only the audit reads) and `[tex_symbols]`: a claims
//! file serves as it is.

use crate::algebra::expr::Expr;
use crate::algebra::units::Unit;
use crate::paper::formulas::{TexSymbols, read_formula};
use crate::paper::source::display::read_display;
use crate::paper::source::document::Document;
pub use crate::paper::units::declared::{Units, read_units};
use crate::paper::units::{Inference, Relation, Status, infer_ordered, unit_name};
use crate::paper::words::Words;
use crate::paper::words::vocabulary::Vocabulary;
use serde::Serialize;
use std::collections::BTreeMap;

pub mod init;
pub mod paper;
pub mod power;
pub mod shelf;

/// The units a paper's words give its symbols ([`crate::paper::words`]), its symbols named as the
/// audit of `blocks` names them.
pub fn paper_words(
    text: &str,
    blocks: &[(Option<String>, String)],
    units: &Units,
    vocab: &Vocabulary,
) -> Words {
    let syms = TexSymbols::new(units.tex_symbols.clone())
        .with_functions_of(blocks.iter().map(|(_, tex)| tex.as_str()));
    crate::paper::words::read_words(text, &syms, vocab)
}

/// One relation of the paper and what the audit says of it.
#[derive(Clone, Debug, Serialize)]
pub struct AuditRelation {
    /// Its number as the paper's reader sees it (`"5"`, `"A1"`), `null` when unnumbered.
    pub number: Option<String>,
    /// Its `\label`, if any.
    pub label: Option<String>,
    /// The line where its display opens (`null` for a displays extract): of `file` when the
    /// display is in another file of the paper, else of the paper.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// The file of the paper its display is in, when not the paper's own
    /// (`sections/model.tex`, as the paper's `\input` names it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// The line of the paper's text with its inputs followed (where sections and spans are
    /// counted).
    #[serde(skip)]
    pub at: Option<usize>,
    /// The row's LaTeX.
    pub latex: String,
    /// `consistent`, `inconsistent`, `undetermined` or `unreadable`.
    pub status: &'static str,
    /// Why: the terms and units that disagree, the symbols nothing fixes, the construct the
    /// reader lacks.
    pub detail: String,
    /// The relation as read (the formula language), when read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub read: Option<String>,
    /// Which relation of its row (0 for the first).
    #[serde(skip)]
    pub index_in_row: usize,
    /// Its display's place in the paper (1 for the first), as `printed_from = { display = K }`
    /// names it.
    pub display: usize,
    /// Its place among the formulas of its display (1 for the first), as `relation = k` with
    /// `display` names it.
    pub in_display: usize,
    /// Whether a side reads a function application as an opaque symbol (`{z(0)}`).
    #[serde(skip)]
    pub opaque: bool,
    /// The symbols its sides name.
    #[serde(skip)]
    pub names: Vec<String>,
    /// Its sides as read.
    #[serde(skip)]
    pub sides: Vec<Expr>,
    /// The relations between its sides (`=`, `<=`, ...), one fewer than the sides.
    #[serde(skip)]
    pub rels: Vec<&'static str>,
    /// The unit of its left side, when it has one.
    #[serde(skip)]
    pub side_unit: Option<Unit>,
    /// The unit of its right side, when it has one.
    #[serde(skip)]
    pub right_unit: Option<Unit>,
    /// For a consistent relation, the unit every side shares (`"1"`: it holds only as a
    /// relation of pure numbers, which decides nothing of a physical unit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
}

/// One symbol and its unit.
#[derive(Clone, Debug, Serialize)]
pub struct AuditSymbol {
    /// The symbol.
    pub name: String,
    /// Its unit (`null`: nothing fixes it).
    pub unit: Option<String>,
    /// `declared`, `words` (the paper's prose names it: `quote`, `line`) or `inferred`.
    pub source: &'static str,
    /// The relations that fixed an inferred unit: their numbers, or `display K` for one without.
    pub from: Vec<String>,
    /// For a unit from the words: the quantity named (`density`, or `written` for a unit the
    /// paper writes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quantity: Option<String>,
    /// For a unit from the words: the words, quoted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quote: Option<String>,
    /// For a unit from the words: their line in the paper (in `file`, when given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<usize>,
    /// For a unit from the words in another file of the paper: that file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// For a declared unit the words gave another: what they said, and where.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overrides: Option<String>,
}

impl AuditSymbol {
    /// Where its unit comes from, in words: `declared`, `inferred from (3), (5)`, `words, line
    /// 38: "$\rho$ is the density of plate"`.
    pub fn provenance(&self) -> String {
        let mut s = self.source.to_string();
        if let (Some(l), Some(q)) = (self.line, &self.quote) {
            match &self.file {
                Some(f) => s.push_str(&format!(", {f}:{l}: \"{q}\"")),
                None => s.push_str(&format!(", line {l}: \"{q}\"")),
            }
        }
        if !self.from.is_empty() {
            s.push_str(&format!(" from {}", self.from.join(", ")));
        }
        if let Some(o) = &self.overrides {
            s.push_str(&format!(" (overrides the words: {o})"));
        }
        s
    }
}

/// The audit of a paper.
#[derive(Clone, Debug, Serialize)]
pub struct Audit {
    /// Every relation, in the paper's order.
    pub relations: Vec<AuditRelation>,
    /// Every symbol met, sorted by name.
    pub symbols: Vec<AuditSymbol>,
    /// The consistent relations whose sides share a physical unit (not `1`).
    pub consistent_in_a_unit: usize,
    /// The consistent relations that hold only as relations of pure numbers (every side in `1`).
    pub consistent_pure: usize,
}

impl Audit {
    /// What the consistent relations decide, in words: how many hold in a physical unit and how
    /// many only as relations of pure numbers.
    pub fn decided(&self) -> String {
        format!(
            "Consistent in a physical unit: {}; consistent only as pure numbers (every side in 1): {}.",
            self.consistent_in_a_unit, self.consistent_pure
        )
    }

    /// How many relations have each status.
    pub fn counts(&self) -> BTreeMap<&'static str, usize> {
        let mut c = BTreeMap::new();
        for r in &self.relations {
            *c.entry(r.status).or_insert(0) += 1;
        }
        c
    }
}

/// A paper's displays: from a displays extract (`%% block N` sections) or from its source
/// ([`crate::paper::source::blocks::blocks_of`]).
pub fn paper_blocks(text: &str) -> (Vec<(Option<String>, String)>, Option<Document>) {
    crate::paper::source::blocks::blocks_of(text)
}

/// `(dotted, base, order)` of every `\dot{..}` and `\ddot{..}` of `tex`.
fn dots(tex: &str, syms: &TexSymbols) -> Vec<(String, String, u32)> {
    let mut out = Vec::new();
    for (cmd, order, suffix) in [("\\ddot{", 2, "dd"), ("\\dot{", 1, "d")] {
        let mut rest = tex;
        while let Some(i) = rest.find(cmd) {
            rest = &rest[i + cmd.len()..];
            let Some(end) = rest.find('}') else { break };
            if let Ok(Expr::Sym(s)) = read_formula(&rest[..end], syms) {
                let base = unit_name(&s);
                let d = (format!("{base}{suffix}"), base, order);
                if !out.contains(&d) {
                    out.push(d);
                }
            }
        }
    }
    out
}

/// Audits the relations of `blocks` with the units given.
pub fn audit(blocks: &[(Option<String>, String)], doc: Option<&Document>, units: &Units) -> Audit {
    let (rels, inputs) = read_relations(blocks, doc, units);
    judge_relations(rels, inputs, units)
}

/// As [`audit`], with the audit's power on the paper ([`power`]).
pub fn audit_with_power(
    blocks: &[(Option<String>, String)],
    doc: Option<&Document>,
    units: &Units,
) -> (Audit, power::AuditPower) {
    let (rels, inputs) = read_relations(blocks, doc, units);
    let a = judge_relations(rels.clone(), inputs.clone(), units);
    let p = power::measure(&a, &rels, &inputs, units);
    (a, p)
}

/// Every relation of `blocks` as the audit reports it (not yet judged), and as the inference
/// reads it (`None`: unreadable).
pub(super) fn read_relations(
    blocks: &[(Option<String>, String)],
    doc: Option<&Document>,
    units: &Units,
) -> (Vec<AuditRelation>, Vec<Option<Relation>>) {
    let syms = TexSymbols::new(units.tex_symbols.clone())
        .with_dirac(units.dirac.iter().cloned())
        .with_functions_of(blocks.iter().map(|(_, tex)| tex.as_str()));
    let mut rels: Vec<AuditRelation> = Vec::new();
    let mut inputs: Vec<Option<Relation>> = Vec::new();
    for (k, (after, tex)) in blocks.iter().enumerate() {
        let at = doc.and_then(|d| d.displays.get(k)).map(|d| d.line);
        let (file, line) = match (doc, at) {
            (Some(d), Some(l)) => {
                let (f, n) = d.place(l);
                ((!f.is_empty()).then(|| f.to_string()), Some(n))
            }
            _ => (None, at),
        };
        let mut in_display = 0;
        for row in read_display(tex, &syms) {
            let number = row.tag.clone().or_else(|| after.clone());
            let label = number
                .as_deref()
                .and_then(|n| doc.and_then(|d| d.label_of(n)))
                .map(str::to_string);
            let row_dots = dots(&row.tex, &syms);
            for (j, rel) in row.relations.iter().enumerate() {
                in_display += 1;
                let base = AuditRelation {
                    number: number.clone(),
                    label: label.clone(),
                    line,
                    file: file.clone(),
                    at,
                    latex: row.tex.clone(),
                    status: "unreadable",
                    detail: String::new(),
                    read: None,
                    index_in_row: j,
                    display: k + 1,
                    in_display,
                    opaque: false,
                    names: Vec::new(),
                    sides: Vec::new(),
                    rels: Vec::new(),
                    side_unit: None,
                    right_unit: None,
                    unit: None,
                };
                match rel {
                    Err(e) => {
                        let place = match (&file, line) {
                            (Some(f), Some(l)) => format!("{f}:{l}, "),
                            (None, Some(l)) => format!("line {l}, "),
                            _ => String::new(),
                        };
                        rels.push(AuditRelation {
                            detail: format!("the LaTeX reader: {place}{e}"),
                            ..base
                        });
                        inputs.push(None);
                    }
                    // a bare formula is no relation
                    Ok(r) if r.sides.len() < 2 => {}
                    Ok(r) => {
                        let mut read = r.sides[0].to_string();
                        for (rel, side) in r.rels.iter().zip(&r.sides[1..]) {
                            read.push_str(&format!(" {rel} {side}"));
                        }
                        let opaque = r
                            .sides
                            .iter()
                            .any(|s| s.symbols().iter().any(|x| x.starts_with('{')));
                        let special = [
                            crate::algebra::units::ELLIPSIS,
                            crate::algebra::units::INFINITY,
                            crate::algebra::units::OPERAND,
                            crate::algebra::units::WRITTEN_UNIT,
                        ];
                        let names = r
                            .sides
                            .iter()
                            .flat_map(|s| s.symbols())
                            .filter(|s| !s.is_empty() && !special.contains(&s.as_str()))
                            .collect();
                        rels.push(AuditRelation {
                            read: Some(read),
                            opaque,
                            names,
                            sides: r.sides.clone(),
                            rels: r.rels.clone(),
                            ..base
                        });
                        let mut dots = row_dots.clone();
                        dots.extend(r.links.iter().filter(|l| !row_dots.contains(l)).cloned());
                        inputs.push(Some(Relation {
                            sides: r.sides.clone(),
                            dots,
                            rels: r.rels.clone(),
                        }));
                    }
                }
            }
        }
    }
    operator_images(&mut inputs);
    (rels, inputs)
}

/// The audit of relations read by [`read_relations`]: the units inferred, each relation judged.
pub(super) fn judge_relations(
    mut rels: Vec<AuditRelation>,
    mut inputs: Vec<Option<Relation>>,
    units: &Units,
) -> Audit {
    let original_words = &units.words;
    // a symbol named in passing is that quantity in its own section only
    let lines: Vec<Option<usize>> = rels.iter().map(|r| r.at).collect();
    let mut names: Vec<Vec<String>> = rels.iter().map(|r| r.names.clone()).collect();
    let scoped =
        crate::paper::units::with_words::scope_passing(&mut inputs, &lines, &mut names, units);
    // a letter the words name, defined anew in a later section: that section's own
    crate::paper::units::with_words::scope_redefined(&mut inputs, &lines, &mut names, units);
    // a part the paper says is dimensionless: its letters its own
    crate::paper::units::with_words::scope_dimensionless(&mut inputs, &lines, &mut names, units);
    // a thesis's chapters: each its own notation
    let scoped =
        crate::paper::units::with_words::scope_chapters(&mut inputs, &lines, &mut names, &scoped);
    let units = &scoped;
    let (inf, weak, aside) = if units.words.is_empty() {
        (
            infer_ordered(&inputs, &units.symbols, false),
            Default::default(),
            BTreeMap::new(),
        )
    } else {
        // a key to a display is never set aside, a mention in passing may be
        let words = units
            .words
            .iter()
            .filter(|(_, w)| !w.key)
            .map(|(n, _)| n.clone())
            .collect();
        crate::paper::units::with_words::infer_with_words(&inputs, &names, &units.symbols, &words)
    };
    // a unit of the words set aside is no anchor
    let mut kept = units.clone();
    for n in aside.keys() {
        kept.symbols.remove(n);
        kept.words.remove(n);
    }
    let units = &kept;
    // with units from the words, a relation that names none of them contradicts only what
    // other relations gave: no finding
    let mut weak = weak;
    if !units.words.is_empty() {
        weak.extend((0..names.len()).filter(|&i| {
            !names[i]
                .iter()
                .any(|n| units.words.contains_key(&unit_name(n)))
        }));
    }
    judge(&mut rels, &inputs, &inf, units, &weak);
    let place = |i: usize| {
        rels[i].number.as_ref().map_or_else(
            || format!("unnumbered: {}", short(&rels[i].latex)),
            |n| n.clone(),
        )
    };
    let symbols = inf
        .symbols
        .iter()
        .map(|s| {
            let words = units.words.get(&s.name);
            AuditSymbol {
                name: s.name.clone(),
                unit: s.unit.map(|u| u.to_string()),
                source: match (s.declared, words) {
                    (true, Some(_)) => "words",
                    (true, None) => "declared",
                    _ => "inferred",
                },
                from: {
                    let mut f: Vec<String> = s.from.iter().map(|&i| place(i)).collect();
                    f.dedup();
                    f
                },
                quantity: words.map(|w| w.quantity.clone()),
                quote: words.map(|w| w.quote.clone()),
                line: words.map(|w| w.file.as_ref().map_or(w.line, |f| f.1)),
                file: words.and_then(|w| w.file.as_ref().map(|f| f.0.clone())),
                overrides: units
                    .overridden
                    .get(&s.name)
                    .filter(|_| s.declared)
                    .map(|w| format!("{} ({})", w.unit, w.source()))
                    .or_else(|| {
                        let (against, holds) = aside.get(&s.name)?;
                        let w = original_words.get(&s.name)?;
                        Some(format!(
                            "the words' {} ({}) set aside: {against} relations contradict it, {holds} hold with it",
                            w.unit,
                            w.source()
                        ))
                    }),
            }
        })
        .collect();
    let consistent_pure = rels
        .iter()
        .filter(|r| r.status == "consistent" && r.unit.as_deref() == Some("1"))
        .count();
    let consistent_in_a_unit = rels
        .iter()
        .filter(|r| r.status == "consistent" && r.unit.as_deref().is_some_and(|u| u != "1"))
        .count();
    Audit {
        relations: rels,
        symbols,
        consistent_in_a_unit,
        consistent_pure,
    }
}

/// An application whose arguments name fields (`L(w, F)`, where `w` is applied elsewhere as
/// `w(x, y, t)`) is an operator's image: its unit depends on its arguments, so each spelling is
/// an unknown of its own (`{op L(w,F)}`), where `P(t)` and `P(0)` share the unit of `P`.
fn operator_images(inputs: &mut [Option<Relation>]) {
    let apps = |r: &Relation| -> Vec<String> {
        r.sides
            .iter()
            .flat_map(|e| e.symbols())
            .filter(|s| s.starts_with('{') && unit_name(s) != *s)
            .collect()
    };
    let fields: std::collections::BTreeSet<String> = inputs
        .iter()
        .flatten()
        .flat_map(apps)
        .map(|s| unit_name(&s))
        .collect();
    let args_of = |s: &str| -> Vec<String> {
        let inner = s.trim_start_matches('{').trim_end_matches('}');
        inner
            .split_once('(')
            .map(|(_, a)| a.trim_end_matches(')'))
            .unwrap_or_default()
            .split(',')
            .map(|a| a.trim().to_string())
            .collect()
    };
    for r in inputs.iter_mut().flatten() {
        for side in r.sides.iter_mut() {
            *side = side.substitute(&|s: &str| {
                (s.starts_with('{') && args_of(s).iter().any(|a| fields.contains(a)))
                    .then(|| Expr::Sym(format!("{{op {}", &s[1..])))
            });
        }
    }
}

/// The first 40 characters of a relation's LaTeX.
fn short(tex: &str) -> String {
    let t: String = tex.chars().take(40).collect();
    if t.len() < tex.len() {
        format!("{t}...")
    } else {
        t
    }
}

/// Each readable relation's status and detail from the inference.
fn judge(
    rels: &mut [AuditRelation],
    inputs: &[Option<Relation>],
    inf: &Inference,
    units: &Units,
    weak: &std::collections::BTreeSet<usize>,
) {
    // each relation as the details name it: its number, or its display's first characters
    let places: Vec<String> = rels
        .iter()
        .map(|r| {
            r.number
                .as_ref()
                .map_or_else(|| format!("`{}`", short(&r.latex)), |n| format!("({n})"))
        })
        .collect();
    let unit_of = |name: &str| {
        units.symbols.get(name).copied().or_else(|| {
            inf.symbols
                .iter()
                .find(|s| s.name == name)
                .and_then(|s| s.unit)
        })
    };
    for (i, r) in rels.iter_mut().enumerate() {
        let Some(input) = &inputs[i] else { continue };
        let [left, right] = [input.sides.first(), input.sides.last()].map(|e| {
            e.and_then(|e| crate::algebra::units::dimension(e, &|s| unit_of(&unit_name(s))).ok())
        });
        r.side_unit = left;
        r.right_unit = right;
        // the unit the sides share: of the first that is not a bare 0 (or infinity)
        let shared = input
            .sides
            .iter()
            .filter(|e| !crate::algebra::units::every_unit(e))
            .find_map(|e| crate::algebra::units::dimension(e, &|s| unit_of(&unit_name(s))).ok());
        match &inf.statuses[i] {
            Status::Consistent => {
                r.status = "consistent";
                r.detail = shared.map_or_else(String::new, |u| format!("every side in {u}"));
                r.unit = shared.map(|u| u.to_string());
            }
            Status::Inconsistent {
                left,
                left_unit,
                right,
                right_unit,
                what,
                against,
            } => {
                r.status = "inconsistent";
                r.detail = match term_groups(input, &unit_of) {
                    Some(groups) => groups,
                    None => {
                        format!("`{left}` is {left_unit} but `{right}` is {right_unit} ({what})")
                    }
                };
                // with no unit declared, a relation can only contradict the units other
                // relations gave (one letter, two quantities in a long text; alone, its unit
                // equations are homogeneous and every unknown dimensionless solves them): no
                // finding, nothing says which of them is right
                let from_words: Vec<String> = r
                    .names
                    .iter()
                    .map(|n| unit_name(n))
                    .collect::<std::collections::BTreeSet<_>>()
                    .iter()
                    .filter_map(|n| units.words.get(n))
                    .map(|w| format!("`{}` in {} ({})", w.symbol, w.unit, w.source()))
                    .collect();
                if !from_words.is_empty() {
                    r.detail.push_str(&format!(
                        "; units from the paper's words: {}",
                        from_words.join(", ")
                    ));
                }
                if !against.is_empty() {
                    let (doubt, fixed): (Vec<usize>, Vec<usize>) = against
                        .iter()
                        .partition(|&&j| matches!(inf.statuses[j], Status::Inconsistent { .. }));
                    let names = |v: &[usize]| {
                        v.iter()
                            .map(|&j| places[j].clone())
                            .collect::<Vec<_>>()
                            .join(", ")
                    };
                    let mut parts = Vec::new();
                    if !doubt.is_empty() {
                        parts.push(format!(
                            "it and {} cannot both hold: one of them is wrong",
                            names(&doubt)
                        ));
                    }
                    if !fixed.is_empty() {
                        parts.push(format!(
                            "it contradicts the units that {} fix",
                            names(&fixed)
                        ));
                    }
                    r.detail.push_str(&format!("; {}", parts.join("; ")));
                }
                if inf.bounded {
                    r.detail.push_str(
                        "; the search for the relations to blame was bounded: this one was rejected taken one at a time",
                    );
                }
                if weak.contains(&i) {
                    r.status = "undetermined";
                    r.detail = format!(
                        "its units conflict with those other relations give ({}); the units declared or named in the paper's words do not decide, through its definitions, which is right",
                        r.detail
                    );
                } else if units.symbols.is_empty() {
                    r.status = "undetermined";
                    r.detail = format!(
                        "its units conflict with those other relations give ({}); no declared unit decides",
                        r.detail
                    );
                }
            }
            Status::Undetermined(open) => {
                r.status = "undetermined";
                r.detail = format!("nothing fixes the unit of {}", open.join(", "));
            }
        }
    }
}

/// The top-level terms of a relation's sides grouped by unit, when they fall in more than one
/// group (`in N: A3*f, P; in kg m: A1*(..)*f`): the terms whose units disagree, each with its
/// unit. `None` when every top-level term has one unit (the fault is inside a term).
fn term_groups(r: &Relation, unit_of: &dyn Fn(&str) -> Option<Unit>) -> Option<String> {
    fn terms(e: &Expr, out: &mut Vec<Expr>) {
        match e {
            Expr::Bin(crate::algebra::expr::Op::Add | crate::algebra::expr::Op::Sub, a, b) => {
                terms(a, out);
                terms(b, out);
            }
            Expr::Neg(a) => terms(a, out),
            // a literal 0 has every unit
            Expr::Num(c) if num_traits::Zero::is_zero(c) => {}
            other => out.push(other.clone()),
        }
    }
    let mut all = Vec::new();
    for s in &r.sides {
        terms(s, &mut all);
    }
    let mut groups: Vec<(String, Vec<String>)> = Vec::new();
    for t in &all {
        let u = crate::algebra::units::dimension(t, &|s| unit_of(&unit_name(s)))
            .map_or_else(|_| "a unit nothing fixes".to_string(), |u| u.to_string());
        match groups.iter_mut().find(|(g, _)| *g == u) {
            Some((_, v)) => v.push(format!("`{t}`")),
            None => groups.push((u, vec![format!("`{t}`")])),
        }
    }
    if groups
        .iter()
        .filter(|(u, _)| u != "a unit nothing fixes")
        .count()
        < 2
    {
        return None;
    }
    Some(
        groups
            .iter()
            .map(|(u, ts)| format!("in {u}: {}", ts.join(", ")))
            .collect::<Vec<_>>()
            .join("; "),
    )
}

/// The audit as text: a line per relation, then the symbols.
pub fn to_text(a: &Audit) -> String {
    let mut s = String::new();
    for r in &a.relations {
        s.push_str(&format!(
            "{:<10} {:<13} {}  {}\n",
            r.number
                .as_deref()
                .map_or("-".to_string(), |n| format!("({n})")),
            r.status,
            short(&r.latex),
            r.detail
        ));
    }
    s.push_str("\nsymbols:\n");
    for y in &a.symbols {
        s.push_str(&format!(
            "  {:<16} {:<22} {}\n",
            y.name,
            y.unit.as_deref().unwrap_or("?"),
            y.provenance()
        ));
    }
    let counts: Vec<String> = a.counts().iter().map(|(k, v)| format!("{v} {k}")).collect();
    s.push_str(&format!(
        "\n{} relations: {}\n{}\n",
        a.relations.len(),
        counts.join(", "),
        a.decided()
    ));
    s
}

/// The audit as a Markdown report: the inconsistent relations first, with their LaTeX and the
/// terms that disagree; then every relation; then the symbols.
pub fn to_markdown(a: &Audit, title: &str) -> String {
    let esc = |t: &str| t.replace('|', "\\|").replace('\n', " ");
    let counts: Vec<String> = a.counts().iter().map(|(k, v)| format!("{v} {k}")).collect();
    let mut s = format!(
        "# Units audit: {title}\n\n{} relations: {}. {} Units of the symbols not declared are inferred from the relations (`verify audit`); a relation is inconsistent when it contradicts what the declared units and the other relations fix.\n\n",
        a.relations.len(),
        counts.join(", "),
        a.decided()
    );
    let bad: Vec<&AuditRelation> = a
        .relations
        .iter()
        .filter(|r| r.status == "inconsistent")
        .collect();
    s.push_str("## Inconsistent relations\n\n");
    if bad.is_empty() {
        s.push_str("None.\n\n");
    }
    for r in bad {
        s.push_str(&format!(
            "- **{}**: $${}$$\n  {}\n",
            r.number
                .as_deref()
                .map_or("unnumbered".to_string(), |n| format!("({n})")),
            r.latex.trim(),
            r.detail
        ));
    }
    s.push_str("\n## Every relation\n\n| number | status | LaTeX | detail |\n|---|---|---|---|\n");
    for r in &a.relations {
        s.push_str(&format!(
            "| {} | {} | `{}` | {} |\n",
            r.number
                .as_deref()
                .map_or("-".to_string(), |n| format!("({n})")),
            r.status,
            esc(&short(&r.latex)),
            esc(&r.detail)
        ));
    }
    s.push_str("\n## Symbols\n\n| symbol | unit | source | from |\n|---|---|---|---|\n");
    for y in &a.symbols {
        let source = match (&y.quote, y.line, &y.file) {
            (Some(q), Some(l), Some(f)) => format!("words, {f}:{l}: \"{q}\""),
            (Some(q), Some(l), None) => format!("words, line {l}: \"{q}\""),
            _ => y.source.to_string(),
        };
        let source = match &y.overrides {
            Some(o) => format!("{source} (overrides the words: {o})"),
            None => source,
        };
        s.push_str(&format!(
            "| `{}` | {} | {} | {} |\n",
            esc(&y.name),
            y.unit.as_deref().unwrap_or("not fixed"),
            esc(&source),
            esc(&y.from.join(", "))
        ));
    }
    s
}

/// The `\title{..}` of a LaTeX source, on one line.
pub fn title_of(text: &str) -> Option<String> {
    let at = text.find("\\title")?;
    let rest = &text[at + 6..];
    let rest = rest.trim_start().strip_prefix('{')?;
    let mut depth = 1;
    for (i, c) in rest.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some(rest[..i].split_whitespace().collect::<Vec<_>>().join(" "));
                }
            }
            _ => {}
        }
    }
    None
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    #[test]
    fn a_symbols_provenance_names_its_relations_only_when_it_has_some() {
        let y = AuditSymbol {
            name: "v".into(),
            unit: Some("m s^-1".into()),
            source: "inferred",
            from: vec![],
            quantity: None,
            quote: None,
            line: None,
            file: None,
            overrides: None,
        };
        assert_eq!(y.provenance(), "inferred");
        let y = AuditSymbol {
            from: vec!["(3)".into(), "(5)".into()],
            ..y
        };
        assert_eq!(y.provenance(), "inferred from (3), (5)");
        let y = AuditSymbol {
            source: "words",
            from: vec![],
            quote: Some("the speed $v$".into()),
            line: Some(4),
            file: Some("a.tex".into()),
            ..y
        };
        assert_eq!(y.provenance(), "words, a.tex:4: \"the speed $v$\"");
        let y = AuditSymbol { file: None, ..y };
        assert_eq!(y.provenance(), "words, line 4: \"the speed $v$\"");
    }

    pub(super) fn units(pairs: &[(&str, &str)]) -> Units {
        let texts: BTreeMap<String, String> = pairs
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect();
        Units {
            symbols: texts
                .iter()
                .map(|(k, v)| (k.clone(), Unit::parse(v).unwrap()))
                .collect(),
            texts,
            ..Units::default()
        }
    }

    #[test]
    fn a_zero_side_is_no_term_of_its_own() {
        // a + b = 0 with a in m, b in s: the literal 0 has every unit and joins no group
        let (blocks, doc) = paper_blocks("\\begin{equation} a + b = 0 \\end{equation}");
        let a = audit(&blocks, doc.as_ref(), &units(&[("a", "m"), ("b", "s")]));
        assert_eq!(a.relations[0].detail, "in m: `a`; in s: `b`");
        assert_eq!(a.relations[0].read.as_deref(), Some("a + b = 0"));
    }

    #[test]
    fn a_dimensionless_section_takes_no_unit_from_the_words_or_from_outside() {
        // sec. 1 names v a speed and x a length, and v = x/t holds; sec. 2 says it is
        // non-dimensional and writes v = x + 1 and x = 2, which in SI units would be alarms
        let text = "\\section{Model}\nThe speed $v$, the displacement $x$ and the time $t$ obey\n\\begin{equation} v = x/t \\end{equation}\n\\section{Scaled}\nIn non-dimensional form, with $\\lambda$ the period,\n\\begin{equation} v = x + 1 \\end{equation}\n\\begin{equation} \\lambda = x v \\end{equation}\n";
        let (blocks, doc) = paper_blocks(text);
        let vocab = Vocabulary::builtin().expect("vocabulary");
        let words = paper_words(text, &blocks, &Units::default(), &vocab);
        assert_eq!(words.dimensionless, vec![(5, usize::MAX)]);
        let u = Units::default().with_words(words);
        // the period of the scaled section gives no unit
        assert!(u.words.contains_key("v") && !u.words.contains_key("lambda"));
        let a = audit(&blocks, doc.as_ref(), &u);
        let st: Vec<&str> = a.relations.iter().map(|r| r.status).collect();
        assert_eq!(
            st,
            vec!["consistent", "consistent", "consistent"],
            "{:?}",
            a.relations
        );
        // the second section's letters are its own
        assert!(
            a.symbols.iter().any(|s| s.name == "v_dim5"),
            "{:?}",
            a.symbols
        );
        assert_eq!(a.relations[0].detail, "every side in m s^-1");
    }

    #[test]
    fn a_letter_the_words_define_and_a_later_section_defines_anew_is_that_sections_own() {
        // sec. 1: u = 2 c, where c is the speed of sound (a key); sec. 2 defines c = cos(x) for
        // short, an alarm if c were still the speed there
        let sec1 = "\\section{Waves}\n\\begin{equation} u = 2 c \\end{equation}\nwhere $c$ is the speed of sound.\n";
        let text = format!(
            "{sec1}\\section{{Testing}}\nFor shorthand\n\\begin{{equation}} c = \\cos x \\end{{equation}}\n"
        );
        let (blocks, doc) = paper_blocks(&text);
        let vocab = Vocabulary::builtin().expect("vocabulary");
        let words = paper_words(&text, &blocks, &Units::default(), &vocab);
        let u = Units::default().with_words(words);
        assert!(u.words.get("c").is_some_and(|w| w.key), "{:?}", u.words);
        let a = audit(&blocks, doc.as_ref(), &u);
        let st: Vec<&str> = a.relations.iter().map(|r| r.status).collect();
        assert_eq!(st, vec!["consistent", "consistent"], "{:?}", a.relations);
        assert_eq!(a.relations[0].detail, "every side in m s^-1");
        assert!(
            a.symbols.iter().any(|s| s.name == "c_sec2"),
            "{:?}",
            a.symbols
        );
        // in the key's own section the same display is checked against the speed
        let text = format!("{sec1}\\begin{{equation}} c = \\cos x \\end{{equation}}\n");
        let (blocks, doc) = paper_blocks(&text);
        let words = paper_words(&text, &blocks, &Units::default(), &vocab);
        let a = audit(&blocks, doc.as_ref(), &Units::default().with_words(words));
        assert_eq!(a.relations[1].status, "inconsistent", "{:?}", a.relations);
    }

    #[test]
    fn the_title_on_one_line() {
        assert_eq!(
            title_of("x \\title{The  impact\n of {a} body} y").as_deref(),
            Some("The impact of {a} body")
        );
        assert_eq!(title_of("no title"), None);
        assert_eq!(title_of("\\title{unclosed"), None);
    }
}
