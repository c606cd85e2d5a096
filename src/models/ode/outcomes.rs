//! A text model's `[outcome]`: named formulas read at the end of the run, at an event's firing
//! (before its jump with `@`, just after it with `@+`), or as formulas of several firings and of
//! other outcomes (`KE@+impact[1]/KE@impact[1]`, `ke2/ke1`), each with its unit derived.
//!
//! Two forms. With one `@` followed by nothing but the event (`m*(v0^2 - v^2)/2@contact-end`),
//! the whole formula before it is read at the firing. Otherwise each `@` applies to the name or
//! the parenthesised group just before it, and the other names of the formula are read at the
//! end of the run, or are other outcomes (a name that is no state, parameter or definition);
//! outcomes are computed after the ones they use (a cycle is an error naming its members).

use super::compile::Program;
use super::formulas::{Reader, expand};
use super::{EventSpec, Firing};
use crate::algebra::expr::{Expr, parse};
use crate::algebra::units::{Unit, dimension};
use crate::models::params::SceneError;
use smol_str::SmolStr;
use std::collections::BTreeMap;

/// One read of a formula at a firing: which event, which firing, before or after its jump, and
/// what is read (`None`: the count, `hits@event`).
#[derive(Clone, Debug)]
pub(super) struct AtRef {
    pub(super) event: usize,
    pub(super) firing: Firing,
    pub(super) after: bool,
    pub(super) program: Option<Program>,
}

/// How an outcome is computed.
#[derive(Clone, Debug)]
pub(super) enum Rule {
    /// A formula of the state at the end of the run.
    End(Program),
    /// A formula read at one firing.
    At(AtRef),
    /// A formula of reads at firings (`__at0`, `__at1`, ...), of the end state and of other
    /// outcomes, evaluated once per run.
    Formula { expr: Expr, reads: Vec<AtRef> },
}

#[derive(Clone, Debug)]
pub(super) struct OutcomeSpec {
    /// Its name (inline: a key of every run's outcome).
    pub(super) name: SmolStr,
    pub(super) text: String,
    pub(super) rule: Rule,
    /// Its unit, as the JSON writes it.
    pub(super) unit_text: String,
}

/// One firing: its time and the states before and after its jump (`None`: no jump, the state
/// before; a firing that goes on keeps one copy, not two).
#[derive(Clone, Debug)]
pub(super) struct Hit {
    pub(super) t: f64,
    pub(super) before: Vec<f64>,
    pub(super) jumped: Option<Vec<f64>>,
}

impl Hit {
    /// The state just after the firing's jump.
    pub(super) fn after(&self) -> &[f64] {
        self.jumped.as_deref().unwrap_or(&self.before)
    }
}

const ALLOWED: &str = "allowed: formula, formula@event, formula@+event (just after its jump), formula@event[k] (k >= 1), formula@event[last], hits@event; in a formula, name@event[k] and (group)@event[k] for reads at firings, and other outcomes by name";

/// `[outcome]`, in the order they use each other.
pub(super) fn read_outcomes(
    r: &Reader,
    table: &toml::Table,
    events: &[EventSpec],
) -> Result<Vec<OutcomeSpec>, SceneError> {
    let mut parsed: Vec<(String, String, Parsed)> = Vec::new();
    for (k, v) in table {
        let field = format!("outcome.{k}");
        let text = v
            .as_str()
            .ok_or_else(|| r.bad(&field, &v.to_string(), "a formula, or formula@event"))?;
        let p = split(r, &field, text, events)?;
        parsed.push((k.clone(), text.to_string(), p));
    }
    // the order: an outcome after those its formula names
    let names: Vec<String> = parsed.iter().map(|(k, _, _)| k.clone()).collect();
    let mut done: BTreeMap<String, Unit> = BTreeMap::new();
    let mut out = Vec::new();
    while !parsed.is_empty() {
        let free = parsed.iter().position(|(_, _, p)| {
            p.outcome_names(r, &names)
                .iter()
                .all(|n| done.contains_key(n))
        });
        let Some(i) = free else {
            let members: Vec<String> = parsed.iter().map(|(k, _, _)| k.clone()).collect();
            return Err(r.bad(
                &format!("outcome.{}", members[0]),
                &members.join(", "),
                "outcomes that do not use each other in a cycle",
            ));
        };
        let (k, text, p) = parsed.remove(i);
        let field = format!("outcome.{k}");
        let (rule, unit) = p.finish(r, &field, &text, &done)?;
        done.insert(k.clone(), unit);
        out.push(OutcomeSpec {
            name: k.into(),
            text,
            rule,
            unit_text: unit.to_string(),
        });
    }
    Ok(out)
}

/// An outcome's text taken apart: the formula with each read at a firing replaced by `__atJ`,
/// and the reads (the formula read, its event, firing and side).
struct Parsed {
    /// `None`: the whole formula at the one firing of `reads[0]`.
    outer: Option<Expr>,
    reads: Vec<(Option<Expr>, usize, Firing, bool)>,
}

impl Parsed {
    fn outcome_names(&self, r: &Reader, names: &[String]) -> Vec<String> {
        let Some(e) = &self.outer else {
            return Vec::new();
        };
        e.symbols()
            .into_iter()
            .filter(|s| is_outcome(r, names, s))
            .collect()
    }

    fn finish(
        self,
        r: &Reader,
        field: &str,
        text: &str,
        done: &BTreeMap<String, Unit>,
    ) -> Result<(Rule, Unit), SceneError> {
        let units_err = |e: crate::algebra::units::DimError| {
            r.bad_formula(field, text, format!("the units do not agree: {e}"))
        };
        let mut reads = Vec::new();
        let mut read_units = Vec::new();
        for (body, event, firing, after) in self.reads {
            let (program, unit) = match body {
                None => (None, Unit::one()),
                Some(b) => {
                    let e = expand(&b, &r.defs);
                    if let Some(s) = e.symbols().into_iter().find(|s| !r.slots.contains(s)) {
                        return Err(r.bad_formula(
                            field,
                            text,
                            format!("`{s}` read at a firing is not t, a state, a parameter or a definition"),
                        ));
                    }
                    let u = dimension(&b, &|s| {
                        r.units.get(s).or_else(|| r.def_units.get(s)).copied()
                    })
                    .map_err(units_err)?;
                    (Some(r.compile(&e, field)?), u)
                }
            };
            read_units.push(unit);
            reads.push(AtRef {
                event,
                firing,
                after,
                program,
            });
        }
        let Some(outer) = self.outer else {
            let read = reads.pop().expect("one read");
            return Ok((Rule::At(read), read_units[0]));
        };
        let unit = dimension(&outer, &|s| {
            if let Some(j) = s.strip_prefix("__at").and_then(|j| j.parse::<usize>().ok()) {
                return read_units.get(j).copied();
            }
            r.units
                .get(s)
                .or_else(|| r.def_units.get(s))
                .or_else(|| done.get(s))
                .copied()
        })
        .map_err(units_err)?;
        let expanded = expand(&outer, &r.defs);
        if let Some(s) = expanded
            .symbols()
            .into_iter()
            .find(|s| !r.slots.contains(s) && !done.contains_key(s) && !s.starts_with("__at"))
        {
            return Err(r.bad_formula(
                field,
                text,
                format!(
                    "`{s}` is not t, a state, a parameter, a definition or another outcome; {ALLOWED}"
                ),
            ));
        }
        if reads.is_empty() && expanded.symbols().iter().all(|s| r.slots.contains(s)) {
            return Ok((Rule::End(r.compile(&expanded, field)?), unit));
        }
        Ok((
            Rule::Formula {
                expr: expanded,
                reads,
            },
            unit,
        ))
    }
}

fn is_outcome(r: &Reader, names: &[String], s: &str) -> bool {
    !r.slots.iter().any(|x| x == s) && !r.defs.contains_key(s) && names.iter().any(|n| n == s)
}

/// Reads an event reference at the start of `rest` (`+impact[2]`, `contact-end`): the event,
/// the firing, whether after the jump, and the length read. The longest event name that fits.
fn event_ref(
    r: &Reader,
    field: &str,
    text: &str,
    rest: &str,
    events: &[EventSpec],
) -> Result<(usize, Firing, bool, usize), SceneError> {
    let (after, body) = match rest.strip_prefix('+') {
        Some(b) => (true, b),
        None => (false, rest),
    };
    let lead = body.len() - body.trim_start().len();
    let body = body.trim_start();
    let mut best: Option<usize> = None;
    for (i, e) in events.iter().enumerate() {
        if body.starts_with(e.name.as_str())
            && best.is_none_or(|b| events[b].name.len() < e.name.len())
        {
            best = Some(i);
        }
    }
    let Some(i) = best else {
        let word: String = body
            .chars()
            .take_while(|c| !matches!(c, '[' | ' ' | '*' | '/' | '+' | ')' | '^'))
            .collect();
        let names: Vec<&str> = events.iter().map(|e| e.name.as_str()).collect();
        return Err(r.bad_formula(
            field,
            text,
            format!(
                "`{word}` is not an event; the events of [[event]]: {}",
                names.join(", ")
            ),
        ));
    };
    let mut used = usize::from(after) + lead + events[i].name.len();
    let tail = &body[events[i].name.len()..];
    let firing = match tail.strip_prefix('[') {
        None => Firing::Nth(0),
        Some(t) => {
            let close = t
                .find(']')
                .ok_or_else(|| r.bad_formula(field, text, ALLOWED.into()))?;
            used += close + 2;
            let idx = t[..close].trim();
            if idx == "last" {
                Firing::Last
            } else {
                match idx.parse::<usize>() {
                    Ok(k) if k >= 1 => Firing::Nth(k - 1),
                    _ => return Err(r.bad_formula(field, text, ALLOWED.into())),
                }
            }
        }
    };
    Ok((i, firing, after, used))
}

/// Takes an outcome's text apart ([`Parsed`]).
fn split(r: &Reader, field: &str, text: &str, events: &[EventSpec]) -> Result<Parsed, SceneError> {
    let not_formula =
        |m: String| r.bad_formula(field, text, format!("not a formula: {m}; {ALLOWED}"));
    if text.contains("__at") {
        return Err(r.bad_formula(
            field,
            text,
            "names starting `__at` are the reader's own".into(),
        ));
    }
    // one `@` and nothing after the event: the whole formula at the firing
    if let Some((body, rest)) = text.split_once('@')
        && !rest.contains('@')
        && let Ok((i, firing, after, used)) = event_ref(r, field, text, rest, events)
        && rest[used..].trim().is_empty()
    {
        let read = if body.trim() == "hits" {
            None
        } else {
            Some(parse(body).map_err(|e| not_formula(e.to_string()))?)
        };
        return Ok(Parsed {
            outer: None,
            reads: vec![(read, i, firing, after)],
        });
    }
    // each `@` reads the name or group before it
    let mut outer = String::new();
    let mut reads = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find('@') {
        let before = rest[..at].trim_end();
        let start = operand_start(before).ok_or_else(|| {
            r.bad_formula(
                field,
                text,
                format!("`@` needs a name or a (group) before it; {ALLOWED}"),
            )
        })?;
        let operand = &before[start..];
        let (i, firing, after, used) = event_ref(r, field, text, &rest[at + 1..], events)?;
        let read = if operand == "hits" {
            None
        } else {
            Some(parse(operand).map_err(|e| not_formula(e.to_string()))?)
        };
        outer.push_str(&before[..start]);
        outer.push_str(&format!("__at{}", reads.len()));
        reads.push((read, i, firing, after));
        rest = &rest[at + 1 + used..];
    }
    outer.push_str(rest);
    let outer = parse(&outer).map_err(|e| not_formula(e.to_string()))?;
    Ok(Parsed {
        outer: Some(outer),
        reads,
    })
}

/// Where the operand of an `@` starts in `before`: a name (letters, digits, `_`, `.`) or a
/// parenthesised group ending it.
fn operand_start(before: &str) -> Option<usize> {
    let bytes = before.as_bytes();
    if before.ends_with(')') {
        let mut depth = 0i32;
        for (i, b) in bytes.iter().enumerate().rev() {
            match b {
                b')' => depth += 1,
                b'(' => {
                    depth -= 1;
                    if depth == 0 {
                        return Some(i);
                    }
                }
                _ => {}
            }
        }
        return None;
    }
    let start = before
        .char_indices()
        .rev()
        .take_while(|(_, c)| c.is_ascii_alphanumeric() || *c == '_' || *c == '.')
        .last()
        .map(|(i, _)| i)?;
    Some(start)
}

/// Every outcome's value, in the order read (each after those it uses), with a warning for each
/// read at a firing that did not happen. `end` evaluates a program at the end of the run,
/// `at` at a firing's time and state; `value` gives the end of the run's `t`, states and
/// parameters by name.
pub(super) fn evaluate(
    outcomes: &[OutcomeSpec],
    hits: &[Vec<Hit>],
    event_names: &[String],
    end: &dyn Fn(&Program) -> f64,
    at: &dyn Fn(&Program, f64, &[f64]) -> f64,
    value: &dyn Fn(&str) -> Option<f64>,
    warnings: &mut Vec<String>,
) -> BTreeMap<SmolStr, Option<f64>> {
    let mut out: BTreeMap<SmolStr, Option<f64>> = BTreeMap::new();
    for o in outcomes {
        let mut read = |a: &AtRef| -> Option<f64> {
            let list = &hits[a.event];
            let Some(p) = &a.program else {
                return Some(list.len() as f64);
            };
            let hit = match a.firing {
                Firing::Nth(k) => list.get(k),
                _ => list.last(),
            };
            match hit {
                Some(h) => Some(at(p, h.t, if a.after { h.after() } else { &h.before })),
                None => {
                    warnings.push(format!(
                        "outcome.{} = \"{}\": the event {} fired {} time(s), so it has no value",
                        o.name,
                        o.text,
                        event_names[a.event],
                        list.len()
                    ));
                    None
                }
            }
        };
        let v = match &o.rule {
            Rule::End(p) => Some(end(p)),
            Rule::At(a) => read(a),
            Rule::Formula { expr, reads } => {
                let vals: Vec<Option<f64>> = reads.iter().map(&mut read).collect();
                if vals.iter().any(Option::is_none) {
                    None
                } else {
                    let known = |s: &str| {
                        if let Some(j) =
                            s.strip_prefix("__at").and_then(|j| j.parse::<usize>().ok())
                        {
                            return vals.get(j).copied().flatten();
                        }
                        value(s).or_else(|| out.get(s).copied().flatten())
                    };
                    // an outcome it uses without a value has none either
                    expr.eval(&known).ok()
                }
            }
        };
        out.insert(o.name.clone(), v);
    }
    out
}
