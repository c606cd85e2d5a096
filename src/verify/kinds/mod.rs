//! The claim kinds of a claims file: a printed formula, written as text in the paper's
//! notation, checked without Rust written for it (and `check`, a named Rust check of a paper).
//!
//! - `identity`: `printed` against `derived` (a formula, or `@name[k=v,...]` for a derivation of
//!   [`crate::algebra`], see [`DERIVATIONS`]), both exact ([`crate::algebra::expr`]); `holds` when
//!   the difference is exactly zero, `fails` with the simplified difference otherwise. With
//!   `corrected`, a failing printed form whose correction holds is `holds-with-correction`.
//! - `dimension`: the unit of `printed` (units from the file's `[symbols]`) against `expect`.
//! - `definition`: a symbol's defining formula, checked for units and against its uses.
//! - `model`: `printed`, with symbols bound to scene fields (`bind`), against an outcome
//!   `quantity` of the model over the grid `vary`; `holds` when the largest relative difference is
//!   at most `rtol`.
//! - `bound`: `require`, an inequality over outcome quantities and bound symbols, on `count`
//!   samples of the scene fields drawn from `sample` (statrs quantiles of a seeded generator);
//!   `holds` when no sample violates it.
//! - `threshold`: where a model's behaviour changes along one parameter, located by bisection
//!   at each point of a grid of the others, against the printed formula for that value.
//! - `probability`, `map`, `not-checkable`, `check`: see their files.
//!
//! Each kind is a type implementing [`Kind`] in a file of its own: its keys are a serde struct
//! with `deny_unknown_fields` (a key the kind does not take is an error naming it), its
//! validation turns them into the checked claim (formulas parsed and expanded once, defaults
//! applied once, scenes read once) that its check runs. [`BUILTIN`] is the registry: a new kind
//! is one file and one line there (a caller may also pass its own table, [`super::run_with`]).
//! Validation reads every formula, unit, scene and quantity before anything runs, so a bad
//! claim stops `verify` with the file, the claim and the key named, and nothing written.

use super::{ClaimSpec, Head, Outcome, PaperClaims, VerifyError};
use crate::algebra::expr::{self, Expr};
use crate::algebra::units::{self, Unit};
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod approximation;
mod bound;
mod check;
mod definition;
mod derivations;
mod dimension;
mod extreme;
mod identity;
mod map;
mod model;
mod not_checkable;
mod probability;
mod rows;
mod scene;
mod threshold;

pub use check::NamedCheck;
pub use derivations::{DERIVATIONS, Derivations};
pub use scene::{clopper_pearson, lookup};

/// One claim kind: its keys, its validation (before anything runs) and its check.
///
/// The checked claim is the implementing type itself: [`Kind::validate`] builds it from the
/// claim's keys, with everything that can be read before a run already read.
pub trait Kind: Sized + Send + Sync + 'static {
    /// The name claims give it (`kind = "identity"`).
    const NAME: &'static str;
    /// The kind's keys besides `id`, `equation`, `quote`, `kind` and `assumption` (a serde
    /// struct with `deny_unknown_fields`).
    type Spec: DeserializeOwned;
    /// The keys that hold the paper's printed side (formulas, inequalities, or lists of them):
    /// what [`super::power`] misprints to measure the check's power.
    const PRINTED: &'static [&'static str] = &[];
    /// What every check of this kind cannot see (a dimension check: a misprint that keeps the
    /// unit); a claim's own `blind` says more.
    const BLIND: Option<&'static str> = None;
    /// Whether the kind judges the printed side's units alone: a function applied in it
    /// (`w(x, y, t)` read from the paper) is then taken as the function's value, whose unit is
    /// the function's, rather than refused as opaque.
    const UNITS_ONLY: bool = false;
    /// Checks the keys, formulas, units and scenes, and builds the checked claim.
    fn validate(cx: &Checked, head: &Head, spec: Self::Spec) -> Result<Self, VerifyError>;
    /// Computes the verdict, its detail and any figures.
    fn check(&self, cx: &Checked, head: &Head, run: &mut Session) -> Result<Outcome, VerifyError>;
    /// The line the report prints under the claim's detail: what was compared with what
    /// (empty: the check writes its own).
    fn report(&self, head: &Head) -> String;
}

/// A checked claim of any kind (the object-safe face of [`Kind`]).
pub trait Claim: Send + Sync {
    /// See [`Kind::check`]; the report line of [`Kind::report`] comes first in the outcome's
    /// Markdown, before any figure the check attached.
    fn run(&self, cx: &Checked, head: &Head, run: &mut Session) -> Result<Outcome, VerifyError>;
}

impl<K: Kind> Claim for K {
    fn run(&self, cx: &Checked, head: &Head, run: &mut Session) -> Result<Outcome, VerifyError> {
        let mut o = self.check(cx, head, run)?;
        let line = self.report(head);
        if !line.is_empty() {
            o.extra_md = Some(match o.extra_md.take() {
                Some(figures) => format!("{line}{figures}"),
                None => line,
            });
        }
        Ok(o)
    }
}

/// A kind in a registry: its name and its validation, which reads the claim's keys into the
/// kind's spec and checks them.
#[derive(Clone, Copy)]
pub struct KindEntry {
    /// The name claims give it.
    pub name: &'static str,
    /// The keys holding the printed side ([`Kind::PRINTED`]).
    pub printed: &'static [&'static str],
    /// What no check of the kind can see ([`Kind::BLIND`]).
    pub blind: Option<&'static str>,
    /// Whether it judges units alone ([`Kind::UNITS_ONLY`]).
    pub units_only: bool,
    pub(crate) validate: Validate,
}

/// A kind's validation, its spec type erased.
type Validate = fn(&Checked, &ClaimSpec) -> Result<Box<dyn Claim>, VerifyError>;

/// The registry entry of the kind `K`.
pub const fn kind<K: Kind>() -> KindEntry {
    KindEntry {
        name: K::NAME,
        printed: K::PRINTED,
        blind: K::BLIND,
        units_only: K::UNITS_ONLY,
        validate: validate_as::<K>,
    }
}

fn validate_as<K: Kind>(cx: &Checked, c: &ClaimSpec) -> Result<Box<dyn Claim>, VerifyError> {
    let spec: K::Spec = toml::Value::Table(c.keys.clone())
        .try_into()
        .map_err(|e: toml::de::Error| key_error(cx.file, c, K::NAME, &e.to_string()))?;
    // the claim's own `where`, as written (a kind may add entries of its own, which are not
    // checked here: a definition's printed formula stands for the name it defines)
    if let Some(w) = c
        .keys
        .get("where")
        .and_then(|v| v.clone().try_into::<Where>().ok())
    {
        cx.check_where_units(&c.head, &w)?;
    }
    Ok(Box::new(K::validate(cx, &c.head, spec)?))
}

/// A serde error of a kind's keys as a claim error naming the key.
fn key_error(file: &PaperClaims, c: &ClaimSpec, kind: &str, message: &str) -> VerifyError {
    let message = message.trim().replace('\n', " ");
    let named = |prefix: &str| {
        message
            .strip_prefix(prefix)
            .and_then(|r| r.split('`').next())
            .map(str::to_string)
    };
    if let Some(key) = named("unknown field `") {
        let allowed = message
            .split_once("expected ")
            .map(|(_, a)| a.trim_start_matches("one of ").to_string())
            .unwrap_or_default();
        return claim_err(
            file,
            &c.head,
            &key,
            format!("kind `{kind}` does not take this key; allowed: {allowed}"),
        );
    }
    if let Some(key) = named("missing field `") {
        return claim_err(
            file,
            &c.head,
            &key,
            format!("missing; kind `{kind}` needs it"),
        );
    }
    claim_err(file, &c.head, "kind", format!("kind `{kind}`: {message}"))
}

/// The generic kinds and `check`, by name.
pub const BUILTIN: &[KindEntry] = &[
    kind::<identity::Identity>(),
    kind::<dimension::Dimension>(),
    kind::<model::Model>(),
    kind::<bound::Bound>(),
    kind::<probability::Probability>(),
    kind::<map::Map>(),
    kind::<threshold::Threshold>(),
    kind::<definition::Definition>(),
    kind::<not_checkable::NotCheckable>(),
    kind::<check::Check>(),
];

/// What the checks of one run share: the derivations computed so far and what the papers'
/// named checks need ([`super::Named`]).
pub struct Session<'a> {
    /// The derivations computed in this run.
    pub derivations: Derivations,
    pub(crate) named: super::Named<'a>,
}

pub(crate) fn claim_err(file: &PaperClaims, c: &Head, field: &str, message: String) -> VerifyError {
    VerifyError::Claim {
        file: file.source.display().to_string(),
        id: c.id.clone(),
        field: field.into(),
        message,
    }
}

/// A claim's own definitions (`where`): symbol -> formula.
pub type Where = BTreeMap<String, String>;

/// A claims file with its units and definitions read, and its claims checked.
pub struct Checked<'a> {
    pub(crate) file: &'a PaperClaims,
    units: BTreeMap<String, Unit>,
    /// The file's definitions, each expanded to symbols with units.
    defs: BTreeMap<String, Expr>,
    /// The unit of each definition, or why it has none.
    def_units: BTreeMap<String, Result<Unit, String>>,
    dir: PathBuf,
    /// The checked claims, in the file's order.
    claims: Vec<Box<dyn Claim>>,
    /// The kind of each claim, in the file's order.
    pub(crate) entries: Vec<KindEntry>,
    /// Symbols of the same unit as each symbol (for [`super::power`]'s swaps).
    same_unit: BTreeMap<String, Vec<String>>,
}

fn parse_formula(
    file: &PaperClaims,
    c: &Head,
    field: &str,
    text: &str,
) -> Result<Expr, VerifyError> {
    expr::parse(text).map_err(|e| claim_err(file, c, field, format!("`{text}`: {e}")))
}

fn g4(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor();
    if (-3.0..5.0).contains(&e) {
        let digits = (3.0 - e).max(0.0) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

impl<'a> Checked<'a> {
    /// Reads the file's units and definitions and validates every claim with the kinds of
    /// [`BUILTIN`].
    pub fn validate(file: &'a PaperClaims) -> Result<Self, VerifyError> {
        Self::validate_with(file, BUILTIN)
    }

    /// Reads the file's units and definitions and validates every claim (its keys, formulas,
    /// scenes and quantities, running each named scene once) with the kinds of `kinds`, before
    /// any claim runs.
    pub fn validate_with(file: &'a PaperClaims, kinds: &[KindEntry]) -> Result<Self, VerifyError> {
        super::check_names(file)?;
        let mut me = Self::read(file)?;
        for c in &file.claim {
            let Some(k) = kinds.iter().find(|k| k.name == c.kind) else {
                let names: Vec<&str> = kinds.iter().map(|k| k.name).collect();
                return Err(claim_err(
                    file,
                    &c.head,
                    "kind",
                    format!("unknown kind `{}`; allowed: {}", c.kind, names.join(", ")),
                ));
            };
            let claim = (k.validate)(&me, c)?;
            me.claims.push(claim);
            me.entries.push(*k);
        }
        Ok(me)
    }

    /// The file's units and definitions (each expanded until no defined name is left; a cycle
    /// is refused).
    fn read(file: &'a PaperClaims) -> Result<Self, VerifyError> {
        let mut units = BTreeMap::new();
        for (name, text) in &file.symbols {
            let u = Unit::parse(text).map_err(|message| VerifyError::BadClaims {
                path: file.source.clone(),
                message: format!("symbols.{name}: {message}"),
            })?;
            units.insert(name.clone(), u);
        }
        // the units only the audit uses are checked here too: a bad one is a bad file
        for (name, text) in &file.audit_symbols {
            Unit::parse(text).map_err(|message| VerifyError::BadClaims {
                path: file.source.clone(),
                message: format!("audit_symbols.{name}: {message}"),
            })?;
        }
        let dir = file
            .source
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        let bad_def = |name: &str, message: String| VerifyError::BadClaims {
            path: file.source.clone(),
            message: format!("definitions.{name}: {message}"),
        };
        let mut raw = BTreeMap::new();
        for (name, text) in &file.definitions {
            let e = expr::parse(text).map_err(|e| bad_def(name, format!("`{text}`: {e}")))?;
            raw.insert(name.clone(), e);
        }
        let mut defs = BTreeMap::new();
        for (name, e) in &raw {
            let mut cur = e.clone();
            for round in 0.. {
                if !cur.symbols().iter().any(|s| raw.contains_key(s)) {
                    break;
                }
                if round == 50 {
                    return Err(bad_def(
                        name,
                        "refers to itself (through other definitions)".into(),
                    ));
                }
                cur = cur.substitute(&|s: &str| raw.get(s).cloned());
            }
            for s in cur.symbols() {
                if !units.contains_key(&s) && !matches!(s.as_str(), "m" | "n") {
                    return Err(bad_def(
                        name,
                        format!("unknown symbol `{s}`: give its unit in [symbols]"),
                    ));
                }
            }
            defs.insert(name.clone(), cur);
        }
        let mut me = Checked {
            file,
            units,
            defs,
            def_units: BTreeMap::new(),
            dir,
            claims: Vec::new(),
            entries: Vec::new(),
            same_unit: BTreeMap::new(),
        };
        me.same_unit = same_unit_table(&me.units);
        let def_units = me
            .defs
            .iter()
            .map(|(k, e)| {
                let u = units::dimension(e, &me.unit_fn()).map_err(|e| e.to_string());
                (k.clone(), u)
            })
            .collect();
        me.def_units = def_units;
        Ok(me)
    }

    /// The outcome of a claim of this file with `verdict` and `detail` (for a kind's check).
    pub fn outcome(&self, head: &Head, verdict: super::Verdict, detail: String) -> Outcome {
        super::outcome(self.file, head, verdict, detail)
    }

    /// Runs every claim of the file, in its order.
    pub fn check_all(&self, run: &mut Session) -> Result<Vec<Outcome>, VerifyError> {
        self.check_all_ticking(run, &|_| {})
    }

    /// [`Checked::check_all`], calling `tick` with each claim's id once its verdict is in (a
    /// progress bar).
    pub fn check_all_ticking(
        &self,
        run: &mut Session,
        tick: &dyn Fn(&str),
    ) -> Result<Vec<Outcome>, VerifyError> {
        self.file
            .claim
            .iter()
            .zip(&self.claims)
            .map(|(c, k)| {
                let mut o = k.run(self, &c.head, run)?;
                if o.kind.is_empty() {
                    o.kind = c.kind.clone();
                }
                o.finding = c.head.finding.clone();
                o.printed = c
                    .keys
                    .get("printed")
                    .and_then(|v| v.as_str())
                    .map(str::to_string);
                o.extends = c.head.extends.clone();
                if let Some(tex) = &c.head.tex {
                    o.printed_latex = Some(tex.clone());
                } else if let Some(tex) = self.definitions_latex_in(c) {
                    o.printed_latex = Some(tex);
                }
                if let Some(x) = &c.head.extends {
                    o.detail = format!("extends the paper ({x}): {}", o.detail);
                }
                tick(&c.id);
                Ok(super::with_assumption(o, &c.head))
            })
            .collect()
    }

    /// The LaTeX of the file's definitions read from the paper (`[definitions_from]`) that the
    /// claim's `printed` uses, one row each.
    fn definitions_latex_in(&self, c: &super::ClaimSpec) -> Option<String> {
        let printed = c.keys.get("printed").and_then(|v| v.as_str())?;
        let used = crate::algebra::expr::parse(printed).ok()?.symbols();
        let rows: Vec<&str> = self
            .file
            .definitions_latex
            .iter()
            .filter(|(name, _)| used.contains(*name))
            .map(|(_, tex)| tex.as_str())
            .collect();
        (!rows.is_empty()).then(|| rows.join(" \\\\ "))
    }

    /// The file's symbols of the same unit as `s`.
    pub(crate) fn same_unit(&self, s: &str) -> Vec<String> {
        self.same_unit.get(s).cloned().unwrap_or_default()
    }

    /// The file's definitions expanded in `e` (for misprints inside them).
    pub(crate) fn expand_defs(&self, e: &Expr) -> Expr {
        let mut cur = e.clone();
        for _ in 0..20 {
            let next = self.expand(&cur);
            if next == cur {
                break;
            }
            cur = next;
        }
        cur
    }

    /// Every symbol of `e` has a unit (or is a definition, or one of `also`).
    fn units_of(&self, c: &Head, field: &str, e: &Expr, also: &[&str]) -> Result<(), VerifyError> {
        self.units_of_in(c, field, e, also, &BTreeMap::new())
    }

    /// [`Checked::units_of`], where the numbers a model produces have the model's units
    /// (`model`, [`scene::Scene::model_units`]).
    fn units_of_in(
        &self,
        c: &Head,
        field: &str,
        e: &Expr,
        also: &[&str],
        model: &BTreeMap<String, Unit>,
    ) -> Result<(), VerifyError> {
        for s in e.symbols() {
            if self.declared(&s).is_none()
                && !model.contains_key(&s)
                && !self.defs.contains_key(&s)
                && !also.contains(&s.as_str())
                && !s.starts_with("at_ref_")
                // infinity, read from a paper (a limit, a bound): it has whatever unit its
                // place needs, as a literal 0 has
                && s != crate::algebra::units::INFINITY
            {
                let known = if self.units.is_empty() {
                    String::new()
                } else {
                    let names: Vec<_> = self.units.keys().cloned().collect();
                    format!("; known: {}", names.join(", "))
                };
                return Err(claim_err(
                    self.file,
                    c,
                    field,
                    format!(
                        "unknown symbol `{s}`: give its unit in [symbols] (e.g. {s} = \"m\"){known}"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// [`Checked::unit_fn`], where the numbers a model produces have the model's units first.
    fn unit_fn_in<'m>(
        &'m self,
        model: &'m BTreeMap<String, Unit>,
    ) -> impl Fn(&str) -> Option<Unit> + 'm {
        let file = self.unit_fn();
        move |s: &str| model.get(s).copied().or_else(|| file(s))
    }

    fn unit_fn(&self) -> impl Fn(&str) -> Option<Unit> + '_ {
        |s: &str| {
            if let Some(Ok(u)) = self.def_units.get(s) {
                return Some(*u);
            }
            if s == "m" || s == "n" {
                self.units.get(s).copied().or(Some(Unit::one()))
            } else {
                self.declared(s)
            }
        }
    }

    /// The unit `[symbols]` gives `s`; a run's quantity (`a.impulse.2`, a claim with `runs`)
    /// has the unit of the quantity (`impulse.2`).
    fn declared(&self, s: &str) -> Option<Unit> {
        self.units.get(s).copied().or_else(|| {
            let (_, rest) = s.split_once('.')?;
            self.units.get(rest).copied()
        })
    }

    /// A formula of a claim, with the claim's `where` and then the file's definitions expanded.
    fn formula(&self, c: &Head, w: &Where, field: &str, text: &str) -> Result<Expr, VerifyError> {
        let e = parse_formula(self.file, c, field, text)?;
        self.expand_all(c, w, &e)
    }

    /// The claim's and the file's definitions expanded in `e` until none is left (a local
    /// definition may use a file definition that uses another local one).
    fn expand_all(&self, c: &Head, w: &Where, e: &Expr) -> Result<Expr, VerifyError> {
        let mut cur = e.clone();
        for _ in 0..20 {
            let next = self.expand(&self.expand_local(c, w, &cur)?);
            if next == cur {
                return Ok(next);
            }
            cur = next;
        }
        Ok(cur)
    }

    /// A `where` name that has a unit in [symbols] must be given a formula in that unit
    /// (`where = { a = "P" }` with a in m and P in N is refused); a number is a value in the
    /// name's own unit.
    fn check_where_units(&self, c: &Head, w: &Where) -> Result<(), VerifyError> {
        let local: BTreeMap<String, Expr> = w
            .iter()
            .map(|(k, v)| {
                parse_formula(self.file, c, &format!("where.{k}"), v).map(|x| (k.clone(), x))
            })
            .collect::<Result<_, _>>()?;
        for (k, v) in &local {
            let Some(want) = self.units.get(k) else {
                continue;
            };
            let mut full = v.clone();
            for _ in 0..50 {
                let next = self.expand(&full.substitute(&|s: &str| {
                    (s != k)
                        .then(|| local.get(s).filter(|x| !x.symbols().is_empty()).cloned())
                        .flatten()
                }));
                if next == full {
                    break;
                }
                full = next;
            }
            // a number is a value in the name's own unit (`where = { a = "1" }`: 1 m)
            let zero = full.symbols().is_empty();
            if let Ok(u) = crate::algebra::units::dimension(&full, &self.unit_fn())
                && u != *want
                && !zero
            {
                return Err(claim_err(
                    self.file,
                    c,
                    &format!("where.{k}"),
                    format!(
                        "`{}` is {u}, but `{k}` is {want} in [symbols]",
                        w.get(k).map(String::as_str).unwrap_or_default()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The claim's own definitions (`where`) expanded in `e`, repeatedly (they may use each
    /// other; a cycle is refused).
    fn expand_local(&self, c: &Head, w: &Where, e: &Expr) -> Result<Expr, VerifyError> {
        if w.is_empty() {
            return Ok(e.clone());
        }
        let local: BTreeMap<String, Expr> = w
            .iter()
            .map(|(k, v)| {
                parse_formula(self.file, c, &format!("where.{k}"), v).map(|x| (k.clone(), x))
            })
            .collect::<Result<_, _>>()?;
        let mut cur = e.clone();
        for _ in 0..50 {
            if !cur.symbols().iter().any(|s| local.contains_key(s)) {
                return Ok(cur);
            }
            cur = cur.substitute(&|s: &str| local.get(s).cloned());
        }
        Err(claim_err(
            self.file,
            c,
            "where",
            "a definition refers to itself".into(),
        ))
    }

    /// `w` for a unit: without the entries that give a number to a name with a unit in
    /// [symbols], so that the name keeps that unit (`where = { x = "2" }` with x in m is 2 m, as
    /// a number in a text model's `[state]` is a value in the state's unit).
    fn where_for_units(&self, w: &Where) -> Where {
        w.iter()
            .filter(|(k, v)| {
                !self.units.contains_key(*k)
                    || expr::parse(v).map_or(true, |e| !e.symbols().is_empty())
            })
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect()
    }

    /// The file's definitions expanded in `e`.
    fn expand(&self, e: &Expr) -> Expr {
        e.substitute(&|s: &str| self.defs.get(s).cloned())
    }
}

/// Symbols of the same unit, by unit (for the swaps).
pub(crate) fn same_unit_table(units: &BTreeMap<String, Unit>) -> BTreeMap<String, Vec<String>> {
    let mut out = BTreeMap::new();
    for (s, u) in units {
        let others: Vec<String> = units
            .iter()
            .filter(|(t, v)| *t != s && *v == u)
            .map(|(t, _)| t.clone())
            .take(3)
            .collect();
        out.insert(s.clone(), others);
    }
    out
}
