//! What the kinds that run scenes share (`model`, `map`, `bound`, `probability`): the scene read
//! once with its `set` fields, the grid of `vary`, the seeded samples of `sample`, the
//! inequalities, and the statistics of a sampled claim.

use super::{Checked, Where, claim_err, g4};
use crate::algebra::expr::{self, Expr, Inequality};
use crate::algebra::units::Unit;
use crate::scene::field_value;
use crate::verify::{Head, VerifyError};
use serde::Deserialize;
use serde_json::Value;
use std::collections::BTreeMap;

/// One named run of a claim's scene (`runs = { a = { set = { e = 0.5 } }, b = { set = {...} } }`):
/// the scene fields it sets on top of the claim's `set` and the grid point or sample. With
/// `runs`, the scene runs once per run at every point, and a formula reads each run's outcome
/// under its name (`a.impulse.2 = (1 + e)*b.compression_impulse`).
#[derive(Deserialize, Default, Clone)]
#[serde(deny_unknown_fields)]
pub struct RunSpec {
    /// Scene fields of this run (a number or a string).
    #[serde(default)]
    pub set: BTreeMap<String, toml::Value>,
}

/// The `runs` key of a claim: run name -> its fields.
pub type Runs = BTreeMap<String, RunSpec>;

/// A claim's scene: read once, with the claim's `set` fields applied.
pub(super) struct Scene {
    /// The scene as the claim names it (relative to the claims file).
    pub name: String,
    /// Its path, for messages.
    pub label: String,
    /// The scene with `set` applied.
    pub base: toml::Table,
    /// Formula symbol -> scene field (`a.FIELD`: the field in run `a`).
    pub bind: BTreeMap<String, String>,
    /// The named runs (`runs`): each run's fields, in name order; empty: one run, its outcome
    /// read without a prefix.
    pub runs: Vec<(String, BTreeMap<String, toml::Value>)>,
}

impl Scene {
    /// Reads the scene `name` (relative to the claims file), applies `set` and checks each
    /// run's fields of `runs`.
    pub fn open(
        cx: &Checked,
        c: &Head,
        name: &str,
        set: &BTreeMap<String, toml::Value>,
        bind: BTreeMap<String, String>,
        runs: Runs,
    ) -> Result<Scene, VerifyError> {
        let path = cx.dir.join(name);
        if !path.is_file() {
            return Err(claim_err(
                cx.file,
                c,
                "scene",
                format!("`{name}`: no such file ({})", path.display()),
            ));
        }
        let mut base = crate::scene::read_table(&path)
            .map_err(|e| claim_err(cx.file, c, "scene", e.to_string()))?;
        let label = path.display().to_string();
        for (field, v) in set {
            crate::scene::set_value(&mut base, field, v.clone(), &label)
                .map_err(|e| claim_err(cx.file, c, &format!("set.{field}"), e.to_string()))?;
        }
        if runs.len() == 1 {
            return Err(claim_err(
                cx.file,
                c,
                "runs",
                "one run given; `runs` names two or more runs to compare (one run is the claim's own `set`)".into(),
            ));
        }
        for (run, spec) in &runs {
            let ident = run
                .chars()
                .next()
                .is_some_and(|ch| ch.is_ascii_alphabetic())
                && run
                    .chars()
                    .all(|ch| ch.is_ascii_alphanumeric() || ch == '_');
            if !ident {
                return Err(claim_err(
                    cx.file,
                    c,
                    &format!("runs.{run}"),
                    "a run's name is a letter then letters, digits or _ (formulas read `NAME.quantity`)".into(),
                ));
            }
            let mut t = base.clone();
            for (field, v) in &spec.set {
                crate::scene::set_value(&mut t, field, v.clone(), &label).map_err(|e| {
                    claim_err(
                        cx.file,
                        c,
                        &format!("runs.{run}.set.{field}"),
                        e.to_string(),
                    )
                })?;
            }
        }
        Ok(Scene {
            name: name.to_string(),
            label,
            base,
            bind,
            runs: runs.into_iter().map(|(k, v)| (k, v.set)).collect(),
        })
    }

    /// Runs the scene table `t` (a grid point or sample applied): its outcome, or with `runs`
    /// an object of each run's outcome under its name.
    /// An error names the claim's key it comes from (`scene`, or `runs.NAME` for a run).
    fn run_all(&self, t: &toml::Table) -> Result<Value, (String, String)> {
        if self.runs.is_empty() {
            return run_table(t, &self.label).map_err(|m| ("scene".to_string(), m));
        }
        let mut all = serde_json::Map::new();
        for (run, set) in &self.runs {
            let out = self
                .run_table(t, set)
                .and_then(|t| run_table(&t, &self.label))
                .map_err(|m| (format!("runs.{run}"), format!("run `{run}`: {m}")))?;
            all.insert(run.clone(), out);
        }
        Ok(Value::Object(all))
    }

    /// `t` with one run's fields set.
    fn run_table(
        &self,
        t: &toml::Table,
        set: &BTreeMap<String, toml::Value>,
    ) -> Result<toml::Table, String> {
        let mut t = t.clone();
        for (field, v) in set {
            crate::scene::set_value(&mut t, field, v.clone(), &self.label)
                .map_err(|e| e.to_string())?;
        }
        Ok(t)
    }

    /// The value of a bound scene field in `t` (`a.FIELD`: in run `a`).
    fn field(&self, t: &toml::Table, field: &str) -> Option<f64> {
        if let Some((run, rest)) = field.split_once('.')
            && let Some((_, set)) = self.runs.iter().find(|(r, _)| r == run)
        {
            return field_value(&self.run_table(t, set).ok()?, rest);
        }
        field_value(t, field)
    }

    /// Runs the scene with the fields of `pt` set: the table run and its outcome.
    pub fn run_point(&self, pt: &[(String, f64)]) -> Result<(toml::Table, Value), String> {
        let mut t = self.base.clone();
        for (fields, v) in pt {
            set_fields(&mut t, fields, *v, &self.label)?;
        }
        let out = self.run_all(&t).map_err(|(_, m)| m)?;
        Ok((t, out))
    }

    /// The value of a formula of bound symbols only at the grid point `pt`, without a run.
    pub fn bound_value(&self, pt: &[(String, f64)], e: &Expr) -> Result<f64, String> {
        let mut t = self.base.clone();
        for (fields, v) in pt {
            set_fields(&mut t, fields, *v, &self.label)?;
        }
        e.eval(&|s: &str| self.bind.get(s).and_then(|f| self.field(&t, f)))
    }

    /// The value of a formula's symbol at a run: its bound field of `t` (`bind`), else the
    /// number of the outcome `out` it names.
    pub fn value(&self, t: &toml::Table, out: &Value, s: &str) -> Option<f64> {
        match self.bind.get(s) {
            Some(field) => self.field(t, field),
            None => lookup(out, s),
        }
    }

    /// One run of the scene at `probe` (the first grid point, or the samples' medians), to know
    /// that the bound fields are numbers and that every symbol of `formulas` (key, formula) is
    /// bound or a number the model produces; returns the outcome.
    pub fn probe(
        &self,
        cx: &Checked,
        c: &Head,
        probe: &[(String, String, f64)],
        formulas: &[(&str, &Expr)],
    ) -> Result<Value, VerifyError> {
        let mut table = self.base.clone();
        for (key, fields, v) in probe {
            set_fields(&mut table, fields, *v, "scene")
                .map_err(|m| claim_err(cx.file, c, key, m))?;
        }
        for (sym, field) in &self.bind {
            if self.field(&table, field).is_none() {
                let why = match crate::scene::field_raw(&table, field) {
                    Some(v) => format!("is {v}, not a number"),
                    // a model's default is not in the scene: the claim binds what it states
                    None if !self
                        .runs
                        .iter()
                        .any(|(r, _)| field.starts_with(&format!("{r}."))) =>
                    {
                        "is missing (a field a claim binds is written in the scene, not left to \
                         the model's default)"
                            .to_string()
                    }
                    None => "is missing or not a number".to_string(),
                };
                return Err(claim_err(
                    cx.file,
                    c,
                    &format!("bind.{sym}"),
                    format!("scene field `{field}` {why} in {}", self.label),
                ));
            }
        }
        let at = if probe.is_empty() {
            String::new()
        } else {
            let pt: Vec<(String, f64)> = probe.iter().map(|(_, f, v)| (f.clone(), *v)).collect();
            format!(" (the claim's first point: {})", exact_point_text(&pt))
        };
        let outcome = self
            .run_all(&table)
            .map_err(|(key, m)| claim_err(cx.file, c, &key, format!("{m}{at}")))?;
        for (field, e) in formulas {
            for s in e.free_symbols() {
                if !self.bind.contains_key(&s) && lookup(&outcome, &s).is_none() {
                    return Err(claim_err(
                        cx.file,
                        c,
                        field,
                        format!(
                            "`{s}` is neither bound to a scene field (bind) nor a number the model produces ({})",
                            numeric_paths(&outcome).join(", ")
                        ),
                    ));
                }
            }
            self.declared_against_model(cx, c, field, e, &outcome)?;
            cx.units_of_in(c, field, e, &[], &self.model_units(&outcome))?;
        }
        Ok(outcome)
    }

    /// An axis title for a scene field: the field and its unit as the model documents it (a
    /// text model's parameter: its `[units]`), e.g. `impactor.v0 (m s^-1)`.
    pub fn field_label(&self, field: &str) -> String {
        let unit = self.field_unit(field);
        match unit.as_deref() {
            Some("1") => format!("{field} (dimensionless)"),
            Some(u) => format!("{field} ({u})"),
            None => field.to_string(),
        }
    }

    fn field_unit(&self, field: &str) -> Option<String> {
        // fields varied together (`solve.samples.0 solve.t_end`) hold one value: the unit of
        // the first that has one
        if field.contains(' ') {
            return field.split_whitespace().find_map(|f| self.field_unit(f));
        }
        let (table, field) = match field.split_once('.') {
            Some((run, rest)) if self.runs.iter().any(|(r, _)| r == run) => (None, rest),
            _ => (Some(&self.base), field),
        };
        let base = table.unwrap_or(&self.base);
        if let Some(name) = field.strip_prefix("parameters.")
            && let Some(u) = base
                .get("units")
                .and_then(|u| u.get(name))
                .and_then(|u| u.as_str())
        {
            return Unit::parse(u).ok().map(|u| u.to_string());
        }
        let doc = base
            .get("model")
            .and_then(|m| m.as_str())
            .and_then(|m| crate::scene::describe(m).ok())?;
        let key = doc
            .keys
            .iter()
            .flat_map(|g| g.iter())
            .find(|k| k.key == field)?;
        // a unit that depends on a law (`s/m (hertz), N s/m (linear)`): the one of the law the
        // scene names beside the field (`contact.law`), or of the law's default
        let mut unit = key.unit;
        if let Some((table, _)) = field.split_once('.')
            && unit.contains(" (")
        {
            let law_key = format!("{table}.law");
            let law = base
                .get(table)
                .and_then(|t| t.get("law"))
                .and_then(|v| v.as_str())
                .map(str::to_string)
                .or_else(|| {
                    doc.keys
                        .iter()
                        .flat_map(|g| g.iter())
                        .find(|k| k.key == law_key)
                        .map(|k| k.default.trim_matches('"').to_string())
                });
            if let Some(law) = law
                && let Some(one) = unit
                    .split(", ")
                    .find_map(|alt| alt.strip_suffix(&format!(" ({law})")))
            {
                unit = one;
            }
        }
        (unit != "-").then(|| {
            Unit::parse(unit)
                .map(|u| u.to_string())
                .unwrap_or_else(|_| unit.to_string())
        })
    }

    /// An axis title for a number the model produces: its path and unit (from one run of the
    /// base scene), e.g. `contact.max_indentation (m)`.
    pub fn quantity_label(&self, quantity: &str) -> String {
        let unit = self
            .run_point(&[])
            .ok()
            .and_then(|(_, out)| self.model_units(&out).get(quantity).map(|u| u.to_string()));
        labelled(
            quantity,
            unit.as_deref(),
            self.scaled_unit(quantity).as_deref(),
        )
    }

    /// The scale of a number the model states as a pure number in units of its own (`1 (f N)`
    /// gives `f N`).
    fn scaled_unit(&self, quantity: &str) -> Option<String> {
        let doc = self
            .base
            .get("model")
            .and_then(|m| m.as_str())
            .and_then(|m| crate::scene::describe(m).ok())?;
        let out = doc
            .all_outcomes()
            .find(|o| crate::models::doc::covers(o.path, quantity))?;
        let scale = out.unit.strip_prefix("1 (")?.strip_suffix(')')?;
        Some(scale.to_string())
    }

    /// The unit of each number the model produced in `outcome` (a run's JSON, or with `runs`
    /// each run's under its name), as the model states it ([`crate::models::doc::outcome_units`]).
    pub fn model_units(&self, outcome: &Value) -> BTreeMap<String, Unit> {
        let Some(doc) = self
            .base
            .get("model")
            .and_then(|m| m.as_str())
            .and_then(|m| crate::scene::describe(m).ok())
        else {
            return BTreeMap::new();
        };
        if self.runs.is_empty() {
            return crate::models::doc::outcome_units(doc, outcome);
        }
        let mut all = BTreeMap::new();
        for (run, _) in &self.runs {
            if let Some(out) = outcome.get(run) {
                for (path, u) in crate::models::doc::outcome_units(doc, out) {
                    all.insert(format!("{run}.{path}"), u);
                }
            }
        }
        all
    }

    /// A unit `[symbols]` gives to a number the model produces must be the model's own: the
    /// model knows what it computes; a contradiction is an error naming both.
    pub fn declared_against_model(
        &self,
        cx: &Checked,
        c: &Head,
        field: &str,
        e: &Expr,
        outcome: &Value,
    ) -> Result<(), VerifyError> {
        let model = self.model_units(outcome);
        for s in e.free_symbols() {
            if self.bind.contains_key(&s) {
                continue;
            }
            if let (Some(declared), Some(own)) = (cx.units.get(&s), model.get(&s))
                && declared != own
            {
                return Err(claim_err(
                    cx.file,
                    c,
                    field,
                    format!(
                        "`{s}`: [symbols] gives it in {declared}, but the model computes it in {own}; remove `{s}` from [symbols] (the model's unit is taken) or correct it"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Runs the scene with the fields of one grid point or sample set, and evaluates two
    /// formulas there: a symbol is a bound scene field (`bind`) or a number the model produces.
    fn point(&self, pt: &[(String, f64)], sides: (&Expr, &Expr)) -> Result<(f64, f64), String> {
        let (t, out) = self.run_point(pt)?;
        let value = |s: &str| self.value(&t, &out, s);
        let why = |e: String| match model_warnings(&out) {
            w if w.is_empty() => e,
            w => format!("{e} (the model: {w})"),
        };
        Ok((
            sides.0.eval(&value).map_err(why)?,
            sides.1.eval(&value).map_err(why)?,
        ))
    }
}

/// The warnings of a run (or of each run of `runs`), joined, for a value the model did not give.
fn model_warnings(out: &Value) -> String {
    let mut all = Vec::new();
    let mut take = |v: &Value| {
        if let Some(ws) = v.get("warnings").and_then(Value::as_array) {
            all.extend(ws.iter().filter_map(Value::as_str).map(str::to_string));
        }
    };
    take(out);
    if let Some(m) = out.as_object() {
        m.values().for_each(&mut take);
    }
    all.join("; ")
}

/// The model's quantity is in the outcome, else an error listing what the model produces.
pub(super) fn check_quantity(
    cx: &Checked,
    c: &Head,
    outcome: &Value,
    q: &str,
) -> Result<(), VerifyError> {
    if lookup(outcome, q).is_none() {
        return Err(claim_err(
            cx.file,
            c,
            "quantity",
            format!(
                "`{q}`: the model does not produce this number; it produces: {}",
                numeric_paths(outcome).join(", ")
            ),
        ));
    }
    Ok(())
}

/// A relative tolerance >= 0.
pub(super) fn check_rtol(cx: &Checked, c: &Head, rtol: f64) -> Result<(), VerifyError> {
    if !(rtol.is_finite() && rtol >= 0.0) {
        return Err(claim_err(
            cx.file,
            c,
            "rtol",
            format!("{rtol} is not a tolerance >= 0"),
        ));
    }
    Ok(())
}

/// One grid axis or sampled field.
#[derive(Clone, Debug)]
pub(super) struct Axis {
    pub field: String,
    pub values: Vec<f64>,
    pub log: bool,
}

/// Scene fields set for a probe run: (the claim's key, the field(s), the value).
pub(super) type Probe = Vec<(String, String, f64)>;

/// The axes of `vary` (at least one), and the probe at the grid's first point.
pub(super) fn axes(
    cx: &Checked,
    c: &Head,
    vary: &[String],
) -> Result<(Vec<Axis>, Probe), VerifyError> {
    if vary.is_empty() {
        return Err(claim_err(
            cx.file,
            c,
            "vary",
            "missing; give at least one FIELD=START:STOP:COUNT[:log]".into(),
        ));
    }
    let axes: Vec<Axis> = vary
        .iter()
        .map(|s| parse_axis(s).map_err(|m| claim_err(cx.file, c, "vary", m)))
        .collect::<Result<_, _>>()?;
    let probe = axes
        .iter()
        .map(|a| ("vary".to_string(), a.field.clone(), a.values[0]))
        .collect();
    Ok((axes, probe))
}

fn parse_axis(spec: &str) -> Result<Axis, String> {
    let (spec, log) = match spec.strip_suffix(":log") {
        Some(s) => (s, true),
        None => (spec, false),
    };
    let sv = crate::scene::sweep::parse_vary(spec, log).map_err(|e| e.to_string())?;
    Ok(Axis {
        field: sv.param,
        values: sv.values,
        log,
    })
}

/// A grid's points (first axis slowest) and, at each, the two sides compared (or why the point
/// did not run).
pub(super) type GridRows = (Vec<Vec<(String, f64)>>, Vec<Result<(f64, f64), String>>);

/// Runs the scene at every point of the grid of `axes`.
pub(super) fn grid(scene: &Scene, axes: &[Axis], sides: (&Expr, &Expr)) -> GridRows {
    use rayon::prelude::*;
    let points = grid_points(axes);
    let rows = points.par_iter().map(|pt| scene.point(pt, sides)).collect();
    (points, rows)
}

/// The points of the grid of `axes` (first axis slowest); one empty point without axes.
pub(super) fn grid_points(axes: &[Axis]) -> Vec<Vec<(String, f64)>> {
    let mut points: Vec<Vec<(String, f64)>> = vec![vec![]];
    for a in axes {
        points = points
            .into_iter()
            .flat_map(|p| {
                a.values.iter().map(move |v| {
                    let mut q = p.clone();
                    q.push((a.field.clone(), *v));
                    q
                })
            })
            .collect();
    }
    points
}

/// A distribution of `sample`.
#[derive(Clone, Copy, Debug)]
pub(super) enum Dist {
    Uniform(f64, f64),
    LogUniform(f64, f64),
    Normal(f64, f64),
}

fn parse_dist(text: &str) -> Result<Dist, String> {
    let help = "expected uniform(a, b), loguniform(a, b) with 0 < a < b, or normal(mu, sigma) with sigma > 0";
    let t = text.trim();
    let open = t.find('(').ok_or_else(|| format!("`{text}`: {help}"))?;
    let inner = t[open + 1..]
        .strip_suffix(')')
        .ok_or_else(|| format!("`{text}`: {help}"))?;
    let args: Vec<f64> = inner
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{text}`: {help}"))?;
    let [a, b] = args[..] else {
        return Err(format!("`{text}`: two numbers are needed; {help}"));
    };
    if !a.is_finite() || !b.is_finite() {
        return Err(format!("`{text}`: {help}"));
    }
    match &t[..open] {
        "uniform" if a < b => Ok(Dist::Uniform(a, b)),
        "loguniform" if 0.0 < a && a < b => Ok(Dist::LogUniform(a, b)),
        "normal" if b > 0.0 => Ok(Dist::Normal(a, b)),
        _ => Err(format!("`{text}`: {help}")),
    }
}

impl Dist {
    /// The quantile at `u` in (0, 1) (statrs' inverse CDFs).
    fn quantile(self, u: f64) -> f64 {
        use statrs::distribution::{ContinuousCDF, Normal, Uniform};
        match self {
            Dist::Uniform(a, b) => Uniform::new(a, b).map_or(f64::NAN, |d| d.inverse_cdf(u)),
            Dist::LogUniform(a, b) => Uniform::new(a.ln(), b.ln())
                .map_or(f64::NAN, |d| d.inverse_cdf(u))
                .exp(),
            Dist::Normal(m, s) => Normal::new(m, s).map_or(f64::NAN, |d| d.inverse_cdf(u)),
        }
    }
}

/// The seeded draws of a sampled claim: `sample`, `count` (1 to 10^6) and `seed`.
pub(super) struct Samples {
    /// Scene field(s) (or symbol) -> distribution, as written.
    pub text: BTreeMap<String, String>,
    dists: Vec<(String, Dist)>,
    pub count: usize,
    pub seed: u64,
}

impl Samples {
    /// Reads `sample`, `count` and `seed`.
    pub fn read(
        cx: &Checked,
        c: &Head,
        text: BTreeMap<String, String>,
        count: usize,
        seed: u64,
    ) -> Result<Samples, VerifyError> {
        if !(1..=1_000_000).contains(&count) {
            return Err(claim_err(
                cx.file,
                c,
                "count",
                format!("{count} is out of range; allowed: 1..=1000000"),
            ));
        }
        if text.is_empty() {
            return Err(claim_err(
                cx.file,
                c,
                "sample",
                "missing; give at least one FIELD = \"uniform(a, b)\"".into(),
            ));
        }
        let dists = text
            .iter()
            .map(|(k, v)| {
                parse_dist(v)
                    .map(|d| (k.clone(), d))
                    .map_err(|m| claim_err(cx.file, c, &format!("sample.{k}"), m))
            })
            .collect::<Result<_, _>>()?;
        Ok(Samples {
            text,
            dists,
            count,
            seed,
        })
    }

    /// The medians, as a probe of the scene ([`Scene::probe`]).
    pub fn probe(&self) -> Probe {
        self.dists
            .iter()
            .map(|(k, d)| (format!("sample.{k}"), k.clone(), d.quantile(0.5)))
            .collect()
    }

    /// `field ~ distribution, ...` for the report.
    pub fn described(&self) -> String {
        self.text
            .iter()
            .map(|(k, v)| format!("{k} ~ {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The draws and, for each, both sides of `ineq` (or why it did not run): with a scene,
    /// runs of it; without one, the draws are the symbols' values.
    pub fn run(&self, scene: Option<&Scene>, ineq: &Inequality) -> GridRows {
        use rayon::prelude::*;
        let draws: Vec<Vec<(String, f64)>> =
            self.unit_draws().iter().map(|u| self.point_at(u)).collect();
        let rows = match scene {
            None => {
                // the sides' derivatives taken once, not at every draw
                let ineq = Inequality {
                    lhs: ineq.lhs.prepared(),
                    rel: ineq.rel,
                    rhs: ineq.rhs.prepared(),
                };
                draws
                    .iter()
                    .map(|pt| Self::sides(None, &ineq, pt))
                    .collect()
            }
            Some(_) => draws
                .par_iter()
                .map(|pt| Self::sides(scene, ineq, pt))
                .collect(),
        };
        (draws, rows)
    }

    /// The seeded draws in the unit cube: each coordinate the probability of its field's
    /// distribution below the value drawn.
    pub fn unit_draws(&self) -> Vec<Vec<f64>> {
        let mut rng = crate::rng::Rng(self.seed);
        let half = 0.5 / (1u64 << 53) as f64;
        (0..self.count)
            .map(|_| self.dists.iter().map(|_| rng.next() + half).collect())
            .collect()
    }

    /// The values of the fields at a point of the unit cube (each coordinate clamped into
    /// [1e-9, 1 - 1e-9], so a normal stays finite).
    pub fn point_at(&self, u: &[f64]) -> Vec<(String, f64)> {
        self.dists
            .iter()
            .zip(u)
            .map(|((k, d), u)| (k.clone(), d.quantile(u.clamp(1e-9, 1.0 - 1e-9))))
            .collect()
    }

    /// Both sides of `ineq` at one point: a run of the scene, or the symbols' values.
    pub fn sides(
        scene: Option<&Scene>,
        ineq: &Inequality,
        pt: &[(String, f64)],
    ) -> Result<(f64, f64), String> {
        match scene {
            Some(scene) => scene.point(pt, (&ineq.lhs, &ineq.rhs)),
            None => {
                let value = |s: &str| pt.iter().find(|(k, _)| k == s).map(|(_, v)| *v);
                Ok((ineq.lhs.eval(&value)?, ineq.rhs.eval(&value)?))
            }
        }
    }
}

/// A claim's inequality (`require` or `event`, named by `field`), definitions expanded.
pub(super) fn inequality(
    cx: &Checked,
    c: &Head,
    w: &Where,
    field: &str,
    text: &str,
) -> Result<Inequality, VerifyError> {
    let mut ineq: Inequality = expr::parse_inequality(text)
        .map_err(|e| claim_err(cx.file, c, field, format!("`{text}`: {e}")))?;
    ineq.lhs = cx.expand_all(c, w, &ineq.lhs)?;
    ineq.rhs = cx.expand_all(c, w, &ineq.rhs)?;
    Ok(ineq)
}

/// The value at a dotted path of a run's JSON (a number after an array is its index).
pub(super) fn at_path<'v>(v: &'v Value, path: &str) -> Option<&'v Value> {
    let mut cur = v;
    for part in path.split('.') {
        cur = match cur {
            Value::Object(m) => m.get(part)?,
            Value::Array(a) => a.get(part.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// The number at a dotted path of a model's outcome (`contact.duration`, `impulse.2`).
pub fn lookup(v: &Value, path: &str) -> Option<f64> {
    match at_path(v, path)? {
        Value::Number(n) => n.as_f64(),
        Value::Bool(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    }
}

/// Sets every field of a `sample` key (one or more fields, separated by spaces, that share one
/// draw: the two off-diagonal entries of a symmetric inertia).
fn set_fields(t: &mut toml::Table, fields: &str, v: f64, label: &str) -> Result<(), String> {
    for field in fields.split_whitespace() {
        crate::scene::set_field(t, field, v, label).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn run_table(t: &toml::Table, label: &str) -> Result<Value, String> {
    let scene = crate::scene::parse_table(t, label).map_err(|e| e.to_string())?;
    scene.run().map(|(v, _)| v).map_err(|e| e.to_string())
}

/// A claim on a probability: `<= 0.15`, `< 0.15`, `>= 0.9`, `> 0.9`.
pub(super) fn parse_expectation(text: &str) -> Result<(expr::Rel, f64), String> {
    let t = text.trim();
    let help = "expected <= p, < p, >= p or > p with 0 <= p <= 1, e.g. \"<= 0.15\"";
    let (rel, rest) = if let Some(r) = t.strip_prefix("<=") {
        (expr::Rel::Le, r)
    } else if let Some(r) = t.strip_prefix(">=") {
        (expr::Rel::Ge, r)
    } else if let Some(r) = t.strip_prefix('<') {
        (expr::Rel::Lt, r)
    } else if let Some(r) = t.strip_prefix('>') {
        (expr::Rel::Gt, r)
    } else {
        return Err(format!("`{text}`: {help}"));
    };
    let p: f64 = rest
        .trim()
        .parse()
        .map_err(|_| format!("`{text}`: {help}"))?;
    if !(0.0..=1.0).contains(&p) {
        return Err(format!("`{text}`: {help}"));
    }
    Ok((rel, p))
}

/// The Clopper-Pearson interval of a binomial proportion: `k` successes in `n` trials at
/// `confidence` (the exact interval from the Beta quantiles, statrs):
/// $[B^{-1}(\alpha/2; k, n-k+1),\ B^{-1}(1-\alpha/2; k+1, n-k)]$, with 0 and 1 at the ends.
pub fn clopper_pearson(k: usize, n: usize, confidence: f64) -> (f64, f64) {
    use statrs::distribution::{Beta, ContinuousCDF};
    let alpha = 1.0 - confidence;
    let (kf, nf) = (k as f64, n as f64);
    let lo = if k == 0 {
        0.0
    } else {
        Beta::new(kf, nf - kf + 1.0).map_or(f64::NAN, |b| b.inverse_cdf(alpha / 2.0))
    };
    let hi = if k >= n {
        1.0
    } else {
        Beta::new(kf + 1.0, nf - kf).map_or(f64::NAN, |b| b.inverse_cdf(1.0 - alpha / 2.0))
    };
    (lo, hi)
}

/// The points of a grid that did not run, for a verdict: how many, and the first named by its
/// place in the grid and every varied value, with its error (a NaN names the formula, event or
/// outcome that gave it).
pub(super) fn failed_points(
    points: &[Vec<(String, f64)>],
    rows: &[Result<(f64, f64), String>],
) -> Option<String> {
    let failed: Vec<(usize, &String)> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| r.as_ref().err().map(|e| (i, e)))
        .collect();
    let (i, e) = failed.first()?;
    Some(format!(
        "{} of {} grid point(s) did not run; the first, point {} ({}): {e}",
        failed.len(),
        points.len(),
        i + 1,
        exact_point_text(&points[*i])
    ))
}

/// `field = value, ...` with each value to ten digits (a point to rerun, without the noise of
/// a grid's arithmetic: 10000, not 10000.00000000001).
pub(super) fn exact_point_text(pt: &[(String, f64)]) -> String {
    let ten = |v: f64| {
        format!("{v:.9e}")
            .parse::<f64>()
            .map_or_else(|_| v.to_string(), |r| r.to_string())
    };
    pt.iter()
        .map(|(k, v)| format!("{k} = {}", ten(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

pub(super) fn point_text(pt: &[(String, f64)]) -> String {
    pt.iter()
        .map(|(k, v)| format!("{k} = {}", g4(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `sym = field, ...` of `bind`, for the report.
pub(super) fn bind_text(bind: &BTreeMap<String, String>) -> String {
    if bind.is_empty() {
        return String::new();
    }
    let pairs: Vec<String> = bind.iter().map(|(k, v)| format!("{k} = {v}")).collect();
    format!(" with {}", pairs.join(", "))
}

/// Every dotted path of `v` that holds a number, for error messages.
pub(super) fn numeric_paths(v: &Value) -> Vec<String> {
    fn go(prefix: &str, v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Number(_) | Value::Bool(_) => out.push(prefix.to_string()),
            Value::Object(m) => {
                for (k, x) in m {
                    let p = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    go(&p, x, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    go("", v, &mut out);
    out
}

/// An axis title: the quantity and its unit, or its scale for a number the model gives in units
/// of its own (`1 (f N)`: |F|/(f N)).
fn labelled(quantity: &str, unit: Option<&str>, scale: Option<&str>) -> String {
    match (unit, scale) {
        (Some("1"), _) => format!("{quantity} (dimensionless)"),
        (Some(u), _) => format!("{quantity} ({u})"),
        (None, Some(scale)) => format!("{quantity} / ({scale}) (dimensionless)"),
        (None, None) => quantity.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::{Scene, labelled};

    #[test]
    fn an_axis_title_gives_the_unit_or_the_scale() {
        assert_eq!(labelled("v", Some("m s^-1"), None), "v (m s^-1)");
        assert_eq!(labelled("e", Some("1"), None), "e (dimensionless)");
        assert_eq!(
            labelled("force", None, Some("f N")),
            "force / (f N) (dimensionless)"
        );
        assert_eq!(labelled("q", None, None), "q");
    }

    fn scene(model: &str) -> Scene {
        Scene {
            name: "t".into(),
            label: "t".into(),
            base: toml::from_str(&format!("model = \"{model}\"")).unwrap(),
            bind: Default::default(),
            runs: Vec::new(),
        }
    }

    #[test]
    fn fields_varied_together_have_the_unit_of_the_one_that_has_one() {
        // by the models' documentation: solve.t_end is a time, impactor.v0 a speed
        let s = scene("hertz");
        assert_eq!(
            s.field_label("solve.samples.0 solve.t_end"),
            "solve.samples.0 solve.t_end (s)"
        );
        assert_eq!(s.field_label("impactor.v0"), "impactor.v0 (m s^-1)");
        assert_eq!(s.field_label("no.such"), "no.such");
    }

    #[test]
    fn a_unit_that_depends_on_the_law_is_the_scene_laws() {
        // by the Hertz model's documentation: the damping is c in s/m for the Hertz law (the
        // default), a dashpot in N s/m for the linear one
        let mut s = scene("hertz");
        assert_eq!(s.field_label("contact.damping"), "contact.damping (m^-1 s)");
        s.base = toml::from_str("model = \"hertz\"\n[contact]\nlaw = \"linear\"").unwrap();
        assert_eq!(
            s.field_label("contact.damping"),
            "contact.damping (kg s^-1)"
        );
    }

    #[test]
    fn a_number_in_units_of_its_own_is_labelled_by_its_scale() {
        // the disk model gives |F|/(f N) and |M|/(f N a) (its documentation: `1 (f N)`)
        let s = scene("disk-friction");
        assert_eq!(s.scaled_unit("force").as_deref(), Some("f N"));
        assert_eq!(s.scaled_unit("moment").as_deref(), Some("f N a"));
        assert_eq!(s.scaled_unit("k"), None);
    }
}
