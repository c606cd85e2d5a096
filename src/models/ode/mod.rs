//! Any model as text (`model = "ode"`): a paper's equations of motion written in the scene file,
//! integrated like a built-in model.
//!
//! ```toml
//! model = "ode"
//! [parameters]                 # numbers (SI)
//! m = 1.0
//! k = 1.0e6
//! v0 = 1.0
//! [units]                      # every parameter, state and t
//! t = "s"
//! m = "kg"
//! k = "N/m^1.5"
//! v0 = "m/s"
//! z = "m"
//! v = "m/s"
//! [definitions]                # named formulas, expanded where they are used
//! F = "k*max(z, 0)^(3/2)"
//! [state]                      # initial values: numbers or formulas of the parameters
//! z = 0.0
//! v = "v0"
//! [equations]                  # dz/dt, dv/dt
//! z = "v"
//! v = "-F/m"
//! [[event]]
//! name = "contact-end"
//! when = "z"                   # the event is a root of this formula
//! direction = "down"           # "up", "down" or "any"
//! action = "stop"              # "stop" or "record"
//! jump = { v = "-e*v" }        # optional: state updates applied where it fires
//! [outcome]                    # at the end, or at an event's first firing
//! duration = "t@contact-end"
//! [solve]                      # as every model: rtol, atol, method, t_end (required here)
//! t_end = 1.0
//! ```
//!
//! Formulas are the claims files' language ([`crate::algebra::expr`]) with `max`, `min`, `sign`
//! and `heaviside`. Before anything runs, every formula's units are checked against `[units]`:
//! the right side of `[equations].x` must be the unit of `x` per the unit of `t`, an initial value
//! or a jump the unit of its state, and a sum must not mix units (exit 2 naming the equation and
//! the term). Each formula is then compiled once to a flat program ([`program`]); Radau5's
//! Jacobian is the symbolic derivative of the equations, compiled the same way.
//!
//! Events: `when` is any formula of `t`, the states and the parameters; it fires where it
//! crosses zero in `direction` (located on the dense output, as every model's events are). An
//! event with a `jump` stops the integrator, replaces the states it names (every right side is
//! evaluated in the state before the jump) and, with `action = "record"`, restarts from there: an
//! impact map. At most [`MAX_RESTARTS`] jumps per run, so that a Zeno sequence of impacts is an
//! error that says so, not an endless loop.
//!
//! Outcomes: `name = "formula"` is evaluated at the end of the run; `"formula@event"` in the
//! state where `event` first fires (before its jump), `"formula@event[k]"` at its k-th firing
//! (from 1) and `"formula@event[last]"` at its last; `hits@event` is how many times it fired. An
//! outcome whose event never fired is `null` in the JSON, with a warning. Every outcome's unit
//! is derived from the formula and `[units]` (`outcome_units` in the JSON).
use crate::models::doc as d;

pub mod program;

use super::params::{Fields, SceneError, SolveSpec};
use super::{Curves, Model, RunError};
use crate::algebra::expr::{Expr, parse};
use crate::algebra::ratfunc::RatFunc;
use crate::algebra::units::{Unit, dimension};
use crate::integrate::{Direction, Event, Method, OdeSystem, Options, Stats, Stop};
use program::Program;
use std::collections::BTreeMap;
use toml::Value;

/// The most jumps one run may apply.
pub const MAX_RESTARTS: usize = 100_000;
/// The most variables (`t`, states, parameters) a model may have: they are copied to a stack
/// buffer for every evaluation.
pub const MAX_VARS: usize = 256;

/// An event function over the states.
type EventFn<'a> = Box<dyn Fn(f64, &[f64]) -> f64 + 'a>;

/// Which firing of an event an outcome reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Firing {
    /// The k-th (from 0).
    Nth(usize),
    /// The last.
    Last,
    /// How many times it fired (`hits@event`).
    Count,
}

#[derive(Clone, Debug)]
struct EventSpec {
    name: String,
    when: Program,
    direction: Direction,
    stop: bool,
    /// (state index, new value).
    jump: Vec<(usize, Program)>,
}

#[derive(Clone, Debug)]
struct OutcomeSpec {
    name: String,
    text: String,
    program: Program,
    at: Option<(usize, Firing)>,
    /// Its unit, as the JSON writes it.
    unit_text: String,
}

/// What a text model compiles to: fixed once read, shared by the points of a sweep.
#[derive(Debug)]
pub struct Compiled {
    /// States, in order.
    states: Vec<String>,
    /// Parameter names, in the order of [`OdeScene`]'s values.
    param_names: Vec<String>,
    /// Initial values, programs of the parameters.
    init: Vec<Program>,
    /// The right sides.
    rhs: Vec<Program>,
    /// The Jacobian, row-major, when the method uses one.
    jac: Option<Vec<Program>>,
    events: Vec<EventSpec>,
    outcomes: Vec<OutcomeSpec>,
    /// The unit of every state (for the JSON).
    state_units: Vec<String>,
    /// The end of the interval (s).
    t_end: f64,
    /// The initial values and right sides as formulas (definitions expanded), for the exact
    /// Taylor series of the solution ([`OdeScene::taylor`]).
    init_exprs: Vec<Expr>,
    rhs_exprs: Vec<Expr>,
}

/// A validated text model: its compiled formulas (shared) and the values a sweep sets.
#[derive(Clone, Debug)]
pub struct OdeScene {
    c: std::sync::Arc<Compiled>,
    /// Parameter values (SI), in the order of the names.
    params: Vec<f64>,
    /// Initial values set by a sweep (`state.x`), over the compiled formulas.
    init_set: Vec<Option<f64>>,
    /// Solver settings.
    pub solve: SolveSpec,
}

impl std::ops::Deref for OdeScene {
    type Target = Compiled;
    fn deref(&self) -> &Compiled {
        &self.c
    }
}

/// What `impact run` prints for an `ode` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct OdeOutcome {
    /// `"ode"`.
    pub model: &'static str,
    /// The named outcomes (`null`: its event never fired).
    pub outcome: BTreeMap<String, Option<f64>>,
    /// Each outcome's unit, derived from its formula.
    pub outcome_units: BTreeMap<String, String>,
    /// Where the run ended (s).
    pub t_end: f64,
    /// The event that stopped it, if one did.
    pub stopped_by: Option<String>,
    /// The states at the end.
    pub state: BTreeMap<String, f64>,
    /// The unit of each state.
    pub state_units: BTreeMap<String, String>,
    /// How many times each event fired.
    pub event_counts: BTreeMap<String, usize>,
    /// Jumps applied.
    pub jumps: usize,
    /// The method.
    pub method: &'static str,
    /// States integrated.
    pub state_size: usize,
    /// What the user should know.
    pub warnings: Vec<String>,
    /// Work done.
    pub stats: Stats,
}

/// The variables every program reads: `t`, the states, the parameters.
struct Vars<'a> {
    m: &'a OdeScene,
}

impl Vars<'_> {
    /// Calls `f` with `[t, y..., parameters...]` in a buffer on the stack sized to the model (a
    /// short model does not clear a long buffer on every evaluation).
    #[inline]
    fn with<R>(&self, t: f64, y: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
        match 1 + y.len() + self.m.params.len() {
            0..=16 => self.fill::<16, R>(t, y, f),
            17..=64 => self.fill::<64, R>(t, y, f),
            _ => self.fill::<MAX_VARS, R>(t, y, f),
        }
    }

    #[inline]
    fn fill<const N: usize, R>(&self, t: f64, y: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
        let n = y.len();
        let total = 1 + n + self.m.params.len();
        let mut buf = [0.0f64; N];
        buf[0] = t;
        buf[1..=n].copy_from_slice(y);
        for (slot, v) in buf[1 + n..total].iter_mut().zip(&self.m.params) {
            *slot = *v;
        }
        f(&buf[..total])
    }
}

impl OdeSystem for OdeScene {
    fn dim(&self) -> usize {
        self.states.len()
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        Vars { m: self }.with(t, y, |v| {
            for (d, p) in dy.iter_mut().zip(&self.rhs) {
                *d = p.eval(v);
            }
        });
    }
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        let Some(progs) = &self.jac else {
            return false;
        };
        let n = self.states.len();
        Vars { m: self }.with(t, y, |v| {
            for i in 0..n {
                for j in 0..n {
                    jac[(i, j)] = progs[i * n + j].eval(v);
                }
            }
        });
        true
    }
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    model: Option<Value>,
    parameters: Option<Value>,
    units: Option<Value>,
    definitions: Option<Value>,
    state: Option<Value>,
    equations: Option<Value>,
    event: Option<Value>,
    outcome: Option<Value>,
    solve: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEvent {
    name: Option<Value>,
    when: Option<Value>,
    direction: Option<Value>,
    action: Option<Value>,
    jump: Option<Value>,
}

/// Reads the text models' tables into a validated model.
struct Reader<'a> {
    f: Fields<'a>,
    units: BTreeMap<String, Unit>,
    /// The unit of each definition, so that a formula is checked as written.
    def_units: BTreeMap<String, Unit>,
    /// Each formula as parsed, before the definitions are expanded.
    raw: std::cell::RefCell<BTreeMap<String, Expr>>,
    defs: BTreeMap<String, Expr>,
    slots: Vec<String>,
}

impl Reader<'_> {
    fn bad(&self, field: &str, value: &str, allowed: &str) -> SceneError {
        self.f.out_of_range(field, value.to_string(), allowed)
    }

    /// An error about the formula `shown` of `field`.
    fn bad_formula(&self, field: &str, shown: &str, message: String) -> SceneError {
        SceneError::Formula {
            path: self.f.path.into(),
            field: field.into(),
            formula: shown.trim_matches('"').into(),
            message,
        }
    }

    /// A formula (a string or a number), parsed, with the definitions expanded and checked to
    /// use only known names; and its text as written (for messages).
    fn formula_text(&self, v: &Value, field: &str) -> Result<(Expr, String), SceneError> {
        let text = match v {
            Value::String(s) => s.clone(),
            Value::Float(x) if x.is_finite() => format!("{x:e}"),
            Value::Integer(i) => i.to_string(),
            other => {
                return Err(self.bad(
                    field,
                    &other.to_string(),
                    "a formula (a string) or a finite number",
                ));
            }
        };
        let parsed = parse(&text)
            .map_err(|e| self.bad_formula(field, &text, format!("not a formula: {e}")))?;
        let e = expand(&parsed, &self.defs);
        self.raw.borrow_mut().insert(field.to_string(), parsed);
        if let Some(s) = e.symbols().into_iter().find(|s| !self.slots.contains(s)) {
            return Err(self.bad_formula(
                field,
                &text,
                format!(
                    "`{s}` is not t, a state, a parameter or a definition (a formula may use those, and pi)"
                ),
            ));
        }
        Ok((e, text))
    }

    /// The unit of `e`, written as `shown`.
    /// The formula of `field` as written (definitions by name), checked with the definitions'
    /// units, so that a message names the terms the user wrote.
    fn unit_of(&self, e: &Expr, field: &str, shown: &str) -> Result<Unit, SceneError> {
        let raw = self
            .raw
            .borrow()
            .get(field)
            .cloned()
            .unwrap_or_else(|| e.clone());
        dimension(&raw, &|s| {
            self.units.get(s).or_else(|| self.def_units.get(s)).copied()
        })
        .map_err(|err| self.bad_formula(field, shown, format!("the units do not agree: {err}")))
    }

    /// Checks that `e` (written as `shown`) is in `want`, the unit of `what`; a literal 0 is
    /// in every unit.
    fn unit_is(
        &self,
        e: &Expr,
        field: &str,
        shown: &str,
        want: Unit,
        what: &str,
    ) -> Result<(), SceneError> {
        let u = self.unit_of(e, field, shown)?;
        // a written 0 is in every unit (`v = 0.0`)
        if u == want || matches!(e, Expr::Num(c) if num_traits::Zero::is_zero(c)) {
            return Ok(());
        }
        Err(self.bad_formula(field, shown, format!("is in {u}, but {what} is in {want}")))
    }

    fn compile(&self, e: &Expr, field: &str) -> Result<Program, SceneError> {
        let slots = &self.slots;
        Program::compile(e, &|s| slots.iter().position(|n| n == s))
            .map_err(|m| self.bad_formula(field, &e.to_string(), m))
    }
}

/// `e` with every defined name replaced by its (expanded) definition.
fn expand(e: &Expr, defs: &BTreeMap<String, Expr>) -> Expr {
    e.substitute(&|s| defs.get(s).cloned())
}

fn table_of<'t>(
    f: &Fields,
    v: Option<&'t Value>,
    name: &str,
) -> Result<&'t toml::Table, SceneError> {
    f.table(v, name)
}

impl OdeScene {
    /// The Taylor polynomial at t = 0 of the solution's `state` to degree `order`, exact, in
    /// the parameters as symbols (their values play no part): the coefficients come from
    /// substituting the partial sums into the right sides, $a_{k+1} = [t^k] f(x(t), t)/(k+1)$,
    /// which is exact when every right side is a polynomial in the states and t with
    /// coefficients rational in the parameters, and every initial value rational in them.
    /// Anything else (a square root of a state, a state in a denominator, `heaviside`) is an
    /// error that says so: such a solution has no Taylor series of this kind at t = 0 in
    /// general.
    pub fn taylor(&self, state: &str, order: u32) -> Result<RatFunc, String> {
        use crate::algebra::poly::{Q, Sym};
        let c = &self.c;
        let which = c.states.iter().position(|s| s == state).ok_or_else(|| {
            format!(
                "`{state}` is not a state of this model; its states: {}",
                c.states.join(", ")
            )
        })?;
        if order > 24 {
            return Err(format!("order {order}: at most 24"));
        }
        let t = Sym::new("t");
        let rational = |e: &Expr, what: &str| -> Result<RatFunc, String> {
            e.lower()
                .ok()
                .and_then(|l| l.to_ratfunc())
                .ok_or_else(|| format!("{what} `{e}` is not rational in the states, t and the parameters: its Taylor series at t = 0 is not computed exactly"))
        };
        let mut x: Vec<RatFunc> = c
            .init_exprs
            .iter()
            .zip(&c.states)
            .map(|(e, s)| rational(e, &format!("the initial value of {s}")))
            .collect::<Result<_, _>>()?;
        let f: Vec<RatFunc> = c
            .rhs_exprs
            .iter()
            .zip(&c.states)
            .map(|(e, s)| rational(e, &format!("the equation of {s}")))
            .collect::<Result<_, _>>()?;
        for (rhs, s) in f.iter().zip(&c.states) {
            let poly_in = |v: Sym| rhs.denom().degree_in(v) == 0;
            if !poly_in(t) || !c.states.iter().all(|x| poly_in(Sym::new(x))) {
                return Err(format!(
                    "the equation of {s} has a state or t in a denominator: its Taylor series at t = 0 is not computed exactly"
                ));
            }
        }
        for k in 0..order {
            // f at the partial sums (degree k), to degree k in t: its t^k coefficient
            let mut next = Vec::with_capacity(x.len());
            for rhs in &f {
                let mut g = rhs.clone();
                for (s, xs) in c.states.iter().zip(&x) {
                    g = g
                        .subst(Sym::new(s), xs)
                        .ok_or_else(|| "a denominator vanishes".to_string())?;
                }
                let coeff = RatFunc::from_poly(g.numer().coeff_of(t, k))
                    .div(&RatFunc::from_poly(g.denom()))
                    .ok_or_else(|| "a denominator vanishes".to_string())?;
                let scale = Q::from_integer((i64::from(k) + 1).into()).recip();
                let power = RatFunc::sym("t")
                    .powi(i32::try_from(k + 1).unwrap_or(i32::MAX))
                    .ok_or_else(|| "a power of t".to_string())?;
                next.push(&coeff.scale(&scale) * &power);
            }
            for (xs, add) in x.iter_mut().zip(next) {
                *xs = &*xs + &add;
            }
        }
        Ok(x.swap_remove(which))
    }
}

impl Model for OdeScene {
    const NAME: &'static str = "ode";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = OdeOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError> {
        let f = Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let _ = raw.model;
        let params_t = table_of(&f, raw.parameters.as_ref(), "parameters")?;
        let units_t = table_of(&f, raw.units.as_ref(), "units")?;
        let state_t = table_of(&f, raw.state.as_ref(), "state")?;
        let eq_t = table_of(&f, raw.equations.as_ref(), "equations")?;
        let empty = toml::Table::new();
        let defs_t = match raw.definitions.as_ref() {
            None => &empty,
            v => table_of(&f, v, "definitions")?,
        };
        let out_t = match raw.outcome.as_ref() {
            None => &empty,
            v => table_of(&f, v, "outcome")?,
        };
        let name_ok = |n: &str| {
            n.chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                && n != "t"
                && n != "pi"
                && n != "hits"
                && !crate::algebra::expr::FUNCTIONS.contains(&n)
        };
        // parameters
        let mut params = Vec::new();
        for (k, v) in params_t {
            let field = format!("parameters.{k}");
            if !name_ok(k) {
                return Err(f.out_of_range(
                    &field,
                    k.clone(),
                    "a name of letters, digits and _ (not t, pi, hits or a function)",
                ));
            }
            params.push((
                k.clone(),
                f.num(Some(v), &field, None, |_| true, "a finite number (SI)")?,
            ));
        }
        // states: the order of [state]
        let states: Vec<String> = state_t.keys().cloned().collect();
        if states.is_empty() {
            return Err(SceneError::Missing {
                path: path.into(),
                field: "state".into(),
                allowed: "at least one state with its initial value".into(),
            });
        }
        for s in &states {
            if !name_ok(s) || params.iter().any(|(p, _)| p == s) {
                return Err(f.out_of_range(&format!("state.{s}"), s.clone(), "a name of letters, digits and _, not a parameter's, not t, pi, hits or a function"));
            }
            if !eq_t.contains_key(s) {
                return Err(SceneError::Missing {
                    path: path.into(),
                    field: format!("equations.{s}"),
                    allowed: format!("the derivative of the state {s}, a formula"),
                });
            }
        }
        if let Some(k) = eq_t.keys().find(|k| !states.contains(k)) {
            return Err(f.out_of_range(
                &format!("equations.{k}"),
                k.clone(),
                &format!(
                    "an equation for each state of [state]: {}",
                    states.join(", ")
                ),
            ));
        }
        let mut slots = vec!["t".to_string()];
        slots.extend(states.iter().cloned());
        slots.extend(params.iter().map(|(p, _)| p.clone()));
        if slots.len() > MAX_VARS {
            return Err(f.out_of_range(
                "parameters",
                format!("{} states and parameters", slots.len() - 1),
                &format!("at most {} states and parameters", MAX_VARS - 1),
            ));
        }
        // units: every parameter, state and t
        let mut units = BTreeMap::new();
        for (k, v) in units_t {
            let field = format!("units.{k}");
            let text = v
                .as_str()
                .ok_or_else(|| f.out_of_range(&field, v.to_string(), "a unit, e.g. \"m/s\""))?;
            let u =
                Unit::parse(text).map_err(|m| f.out_of_range(&field, format!("\"{text}\""), &m))?;
            if !slots.contains(k) {
                return Err(f.out_of_range(
                    &field,
                    k.clone(),
                    &format!(
                        "units of t, the states and the parameters: {}",
                        slots.join(", ")
                    ),
                ));
            }
            units.insert(k.clone(), u);
        }
        if let Some(s) = slots.iter().find(|s| !units.contains_key(*s)) {
            return Err(SceneError::Missing {
                path: path.into(),
                field: format!("units.{s}"),
                allowed: "the unit of every parameter, state and t, e.g. \"m/s\"".into(),
            });
        }
        let mut r = Reader {
            f,
            units,
            def_units: BTreeMap::new(),
            raw: Default::default(),
            defs: BTreeMap::new(),
            slots,
        };
        // definitions, expanded in the order written; a definition may use earlier ones
        for (k, v) in defs_t {
            let field = format!("definitions.{k}");
            if !name_ok(k) || r.slots.contains(k) {
                return Err(r.bad(
                    &field,
                    k,
                    "a new name (not a parameter, state, t or a function)",
                ));
            }
            let (e, text) = r.formula_text(v, &field)?;
            let u = r.unit_of(&e, &field, &text)?;
            r.def_units.insert(k.clone(), u);
            r.defs.insert(k.clone(), e);
        }
        // initial values: formulas of the parameters
        let mut init = Vec::new();
        let mut init_exprs = Vec::new();
        for s in &states {
            let field = format!("state.{s}");
            let (e, text) = r.formula_text(&state_t[s], &field)?;
            if let Some(x) = e
                .symbols()
                .into_iter()
                .find(|x| !params.iter().any(|(p, _)| p == x))
            {
                return Err(r.bad_formula(&field, &text, format!("an initial value is a number or a formula of the parameters; `{x}` is not a parameter")));
            }
            r.unit_is(
                &e,
                &field,
                &text,
                r.units[s],
                &format!("the initial value of {s}"),
            )?;
            init.push(r.compile(&e, &field)?);
            init_exprs.push(e);
        }
        // equations
        let ut = r.units["t"];
        let mut rhs_exprs = Vec::new();
        for s in &states {
            let field = format!("equations.{s}");
            let (e, text) = r.formula_text(&eq_t[s], &field)?;
            let want = r.units[s].per(ut);
            r.unit_is(
                &e,
                &field,
                &text,
                want,
                &format!("d{s}/dt (the unit of {s} per the unit of t)"),
            )?;
            rhs_exprs.push(e);
        }
        let rhs = rhs_exprs
            .iter()
            .zip(&states)
            .map(|(e, s)| r.compile(e, &format!("equations.{s}")))
            .collect::<Result<Vec<_>, _>>()?;
        let solve = r.f.solve(raw.solve.as_ref(), "", false)?;
        let t_end = solve.t_end.ok_or_else(|| SceneError::Missing {
            path: path.into(),
            field: "solve.t_end".into(),
            allowed: "a time > 0 in s (an event with action = \"stop\" may end the run sooner)"
                .into(),
        })?;
        let jac = if matches!(solve.method, Method::Radau5 | Method::Auto) {
            let mut progs = Vec::new();
            for (e, s) in rhs_exprs.iter().zip(&states) {
                let field = format!("equations.{s}");
                let lowered = e
                    .lower()
                    .map_err(|m| r.bad_formula(&field, &e.to_string(), m))?;
                for x in &states {
                    let d = crate::algebra::calculus::derivative(&lowered, x).map_err(|m| {
                        r.bad_formula(
                            &field,
                            &e.to_string(),
                            format!("Radau5 needs its Jacobian, and {m} (use method = \"dop853\")"),
                        )
                    })?;
                    progs.push(r.compile(&d, &field)?);
                }
            }
            Some(progs)
        } else {
            None
        };
        // events
        let mut events = Vec::new();
        if let Some(v) = &raw.event {
            let list = v
                .as_array()
                .ok_or_else(|| r.bad("event", &v.to_string(), "[[event]] tables"))?;
            for (i, ev) in list.iter().enumerate() {
                let at = format!("event.{i}");
                let t = ev
                    .as_table()
                    .ok_or_else(|| r.bad(&at, &ev.to_string(), "a table"))?;
                let re: RawEvent = r.f.raw(t, &at)?;
                let name = match &re.name {
                    Some(Value::String(s)) if !s.is_empty() && !s.contains(['@', '[', ']']) => {
                        s.clone()
                    }
                    Some(other) => {
                        return Err(r.bad(
                            &format!("{at}.name"),
                            &other.to_string(),
                            "a name (no @, [ or ])",
                        ));
                    }
                    None => {
                        return Err(SceneError::Missing {
                            path: path.into(),
                            field: format!("{at}.name"),
                            allowed: "the event's name, e.g. \"contact-end\"".into(),
                        });
                    }
                };
                if events.iter().any(|e: &EventSpec| e.name == name) {
                    return Err(r.bad(&format!("{at}.name"), &name, "a name no other event has"));
                }
                let when_v = re.when.as_ref().ok_or_else(|| SceneError::Missing {
                    path: path.into(),
                    field: format!("{at}.when"),
                    allowed: "a formula whose root is the event".into(),
                })?;
                let (when, text) = r.formula_text(when_v, &format!("{at}.when"))?;
                r.unit_of(&when, &format!("{at}.when"), &text)?;
                let dir = r.f.choice(
                    re.direction.as_ref(),
                    &format!("{at}.direction"),
                    &["up", "down", "any"],
                    "any",
                )?;
                let direction = match dir.as_str() {
                    "up" => Direction::Rising,
                    "down" => Direction::Falling,
                    _ => Direction::Both,
                };
                let action = r.f.choice(
                    re.action.as_ref(),
                    &format!("{at}.action"),
                    &["stop", "record"],
                    "record",
                )?;
                let mut jump = Vec::new();
                if let Some(j) = &re.jump {
                    let jt = j.as_table().ok_or_else(|| {
                        r.bad(
                            &format!("{at}.jump"),
                            &j.to_string(),
                            "a table of state updates, { v = \"-e*v\" }",
                        )
                    })?;
                    for (s, formula) in jt {
                        let field = format!("{at}.jump.{s}");
                        let k = states.iter().position(|x| x == s).ok_or_else(|| {
                            r.bad(&field, s, &format!("a state: {}", states.join(", ")))
                        })?;
                        let (e, text) = r.formula_text(formula, &field)?;
                        r.unit_is(
                            &e,
                            &field,
                            &text,
                            r.units[s],
                            &format!("the new value of {s}"),
                        )?;
                        jump.push((k, r.compile(&e, &field)?));
                    }
                }
                events.push(EventSpec {
                    name,
                    when: r.compile(&when, &format!("{at}.when"))?,
                    direction,
                    stop: action == "stop",
                    jump,
                });
            }
        }
        // outcomes
        let mut outcomes = Vec::new();
        for (k, v) in out_t {
            let field = format!("outcome.{k}");
            let text = v
                .as_str()
                .ok_or_else(|| r.bad(&field, &v.to_string(), "a formula, or formula@event"))?;
            let (body, at) = match text.rsplit_once('@') {
                None => (text.to_string(), None),
                Some((body, ev)) => {
                    let (ev_name, firing) = match ev.trim().split_once('[') {
                        None => (ev.trim().to_string(), Firing::Nth(0)),
                        Some((n, rest)) => {
                            let idx = rest.trim_end_matches(']').trim();
                            let firing = if idx == "last" {
                                Firing::Last
                            } else {
                                match idx.parse::<usize>() {
                                    Ok(k) if k >= 1 => Firing::Nth(k - 1),
                                    _ => return Err(r.bad_formula(&field, text, "allowed: formula, formula@event, formula@event[k] (k >= 1), formula@event[last], hits@event".into())),
                                }
                            };
                            (n.trim().to_string(), firing)
                        }
                    };
                    let i = events
                        .iter()
                        .position(|e| e.name == ev_name)
                        .ok_or_else(|| {
                            let names: Vec<&str> = events.iter().map(|e| e.name.as_str()).collect();
                            r.bad_formula(
                                &field,
                                text,
                                format!(
                                    "`{ev_name}` is not an event; the events of [[event]]: {}",
                                    names.join(", ")
                                ),
                            )
                        })?;
                    let firing = if body.trim() == "hits" {
                        Firing::Count
                    } else {
                        firing
                    };
                    (body.to_string(), Some((i, firing)))
                }
            };
            let (program, unit) = if matches!(at, Some((_, Firing::Count))) {
                (Program::from_constant(0.0), Unit::one())
            } else {
                let (e, text) = r.formula_text(&Value::String(body.clone()), &field)?;
                let u = r.unit_of(&e, &field, &text)?;
                (r.compile(&e, &field)?, u)
            };
            outcomes.push(OutcomeSpec {
                name: k.clone(),
                text: text.to_string(),
                program,
                at,
                unit_text: unit.to_string(),
            });
        }
        let state_units = states.iter().map(|s| r.units[s].to_string()).collect();
        let n = states.len();
        Ok(OdeScene {
            c: std::sync::Arc::new(Compiled {
                states,
                param_names: params.iter().map(|(p, _)| p.clone()).collect(),
                init,
                rhs,
                jac,
                events,
                outcomes,
                state_units,
                t_end,
                init_exprs,
                rhs_exprs,
            }),
            params: params.iter().map(|(_, v)| *v).collect(),
            init_set: vec![None; n],
            solve,
        })
    }

    fn set_number(&mut self, field: &str, v: f64, path: &str) -> Option<Result<(), SceneError>> {
        let bad = |allowed: &str| SceneError::OutOfRange {
            path: path.into(),
            field: field.into(),
            value: v.to_string(),
            allowed: allowed.into(),
        };
        if let Some(name) = field.strip_prefix("parameters.") {
            let i = self.param_names.iter().position(|p| p == name)?;
            if !v.is_finite() {
                return Some(Err(bad("a finite number (SI)")));
            }
            self.params[i] = v;
            return Some(Ok(()));
        }
        if let Some(name) = field.strip_prefix("state.") {
            let i = self.states.iter().position(|s| s == name)?;
            if !v.is_finite() {
                return Some(Err(bad("a finite number (SI)")));
            }
            self.init_set[i] = Some(v);
            return Some(Ok(()));
        }
        None
    }

    fn run(&self) -> Result<(OdeOutcome, Curves), RunError> {
        let n = self.states.len();
        let vars = Vars { m: self };
        let mut y: Vec<f64> = vars.with(0.0, &vec![0.0; n], |v| {
            self.init
                .iter()
                .zip(&self.init_set)
                .map(|(p, set)| set.unwrap_or_else(|| p.eval(v)))
                .collect()
        });
        if let Some(i) = y.iter().position(|x| !x.is_finite()) {
            return Err(RunError::BadArgument {
                arg: format!("state.{}", self.states[i]),
                message: format!(
                    "the initial value is {} (not finite) with these parameters",
                    y[i]
                ),
            });
        }
        let gs: Vec<EventFn> = self
            .events
            .iter()
            .map(|e| {
                let vars = Vars { m: self };
                Box::new(move |t: f64, y: &[f64]| vars.with(t, y, |v| e.when.eval(v))) as EventFn
            })
            .collect();
        let events: Vec<Event> = self
            .events
            .iter()
            .zip(&gs)
            .map(|(e, g)| {
                let event = Event::new(
                    &e.name,
                    g.as_ref(),
                    e.direction,
                    e.stop || !e.jump.is_empty(),
                );
                // a bare state (`when = "z"`, slot 1 + i after t) is read without a call
                match e.when.variable() {
                    Some(slot) if (1..=y.len()).contains(&slot) => event.reading(slot - 1),
                    _ => event,
                }
            })
            .collect();
        let opts = Options {
            rtol: self.solve.rtol,
            atol: self.solve.atol,
            method: self.solve.method,
            events,
            ..Options::default()
        };
        let mut t = 0.0;
        let mut hits: Vec<Vec<(f64, Vec<f64>)>> = vec![Vec::new(); self.events.len()];
        let mut stats = Stats::default();
        let mut stopped_by = None;
        let mut jumps = 0usize;
        let mut warnings = Vec::new();
        while t < self.t_end {
            let sol = crate::integrate::solve(self, t, &y, self.t_end, &opts)?;
            stats = stats + sol.stats;
            for h in &sol.events {
                hits[h.index].push((h.t, h.y.clone()));
            }
            t = sol.t;
            y = sol.y;
            let Stop::Event { index, .. } = sol.stop else {
                break;
            };
            let ev = &self.events[index];
            if !ev.jump.is_empty() {
                let new: Vec<(usize, f64)> = vars.with(t, &y, |v| {
                    ev.jump.iter().map(|(k, p)| (*k, p.eval(v))).collect()
                });
                for (k, x) in new {
                    y[k] = x;
                }
                jumps += 1;
                if let Some(i) = y.iter().position(|x| !x.is_finite()) {
                    return Err(RunError::BadArgument {
                        arg: format!("event {}: jump of {}", ev.name, self.states[i]),
                        message: format!("at t = {t:e} s the jump gives {} (not finite)", y[i]),
                    });
                }
            }
            if ev.stop {
                stopped_by = Some(ev.name.clone());
                break;
            }
            if jumps >= MAX_RESTARTS {
                return Err(RunError::BadArgument {
                    arg: format!("event {}", ev.name),
                    message: format!(
                        "{MAX_RESTARTS} jumps by t = {t:e} s without reaching t_end = {:e} s: the impacts accumulate (a Zeno sequence); stop at an event or shorten t_end",
                        self.t_end
                    ),
                });
            }
        }
        let mut outcome = BTreeMap::new();
        let mut outcome_units = BTreeMap::new();
        for o in &self.outcomes {
            let value = match o.at {
                None => Some(vars.with(t, &y, |v| o.program.eval(v))),
                Some((e, Firing::Count)) => Some(hits[e].len() as f64),
                Some((e, firing)) => {
                    let list = &hits[e];
                    let hit = match firing {
                        Firing::Nth(k) => list.get(k),
                        _ => list.last(),
                    };
                    match hit {
                        Some((th, yh)) => Some(vars.with(*th, yh, |v| o.program.eval(v))),
                        None => {
                            warnings.push(format!(
                                "outcome.{} = \"{}\": the event {} fired {} time(s), so it has no value",
                                o.name,
                                o.text,
                                self.events[e].name,
                                list.len()
                            ));
                            None
                        }
                    }
                }
            };
            outcome.insert(o.name.clone(), value);
            outcome_units.insert(o.name.clone(), o.unit_text.clone());
        }
        let out = OdeOutcome {
            model: Self::NAME,
            outcome,
            outcome_units,
            t_end: t,
            stopped_by,
            state: self.states.iter().cloned().zip(y.iter().copied()).collect(),
            state_units: self
                .states
                .iter()
                .cloned()
                .zip(self.state_units.iter().cloned())
                .collect(),
            event_counts: self
                .events
                .iter()
                .zip(&hits)
                .map(|(e, h)| (e.name.clone(), h.len()))
                .collect(),
            jumps,
            method: self.solve.method.name(),
            state_size: n,
            warnings,
            stats,
        };
        Ok((out, vec![]))
    }
}

/// The `ode` model's reference (`impact describe ode`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "ode",
    summary: "Any model as text: a paper's equations of motion written in the scene (parameters, units, states, equations, events with impact maps, outcomes), integrated like a built-in model. Units are checked equation by equation before anything runs; formulas are compiled once to flat programs; Radau5's Jacobian is their symbolic derivative. The format is in the module doc of src/models/ode/mod.rs.",
    conventions: &[
        "the signs and axes are the scene's own: the formulas say them",
        "an outcome `formula@event` is evaluated where the event fires, before its jump; `@event[k]` at its k-th firing (from 1), `@event[last]` at its last; `hits@event` counts firings; an event that never fired gives null and a warning",
        "a literal 0 has every unit (`max(z, 0)`)",
    ],
    example: "scenes/hertz_ode.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"ode\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "parameters.*",
            unit: "as [units] says",
            range: "finite numbers; names of letters, digits and _ (not t, pi, hits or a function)",
            default: "required",
            meaning: "the parameters",
        },
        d::Key {
            key: "units.*",
            unit: "-",
            range: "a unit of SI names (\"N/m^1.5\", \"m/s\", \"1\") for every parameter, state and t",
            default: "required",
            meaning: "the unit of each name",
        },
        d::Key {
            key: "definitions.*",
            unit: "derived",
            range: "formulas of t, the states, the parameters and earlier definitions",
            default: "none",
            meaning: "named formulas, expanded where used",
        },
        d::Key {
            key: "state.*",
            unit: "as [units] says",
            range: "numbers or formulas of the parameters",
            default: "required (at least one)",
            meaning: "the states, in order, with their initial values",
        },
        d::Key {
            key: "equations.*",
            unit: "state per t",
            range: "a formula for each state: its derivative",
            default: "required",
            meaning: "the equations of motion",
        },
        d::Key {
            key: "event[].name",
            unit: "-",
            range: "unique, no @ [ ]",
            default: "required",
            meaning: "the event's name",
        },
        d::Key {
            key: "event[].when",
            unit: "any",
            range: "a formula",
            default: "required",
            meaning: "the event fires where it crosses zero",
        },
        d::Key {
            key: "event[].direction",
            unit: "-",
            range: "\"up\", \"down\", \"any\"",
            default: "\"any\"",
            meaning: "which crossings count",
        },
        d::Key {
            key: "event[].action",
            unit: "-",
            range: "\"stop\", \"record\"",
            default: "\"record\"",
            meaning: "stop the run there, or record it and go on",
        },
        d::Key {
            key: "event[].jump.*",
            unit: "the state's",
            range: "formulas, evaluated in the state before the jump",
            default: "none",
            meaning: "state updates where it fires: an impact map (at most 100,000 jumps per run)",
        },
        d::Key {
            key: "outcome.*",
            unit: "derived",
            range: "formula, formula@event, formula@event[k], formula@event[last], hits@event",
            default: "none",
            meaning: "named results",
        },
        d::Key {
            key: "solve.rtol",
            unit: "1",
            range: "0 < rtol < 1",
            default: "1e-9",
            meaning: "relative tolerance",
        },
        d::Key {
            key: "solve.atol",
            unit: "as the states",
            range: "atol > 0",
            default: "1e-12",
            meaning: "absolute tolerance",
        },
        d::Key {
            key: "solve.method",
            unit: "-",
            range: "\"dop853\", \"dopri5\", \"radau5\", \"auto\"",
            default: "\"dop853\"",
            meaning: "the integrator (Radau5 with the symbolic Jacobian)",
        },
        d::Key {
            key: "solve.t_end",
            unit: "s",
            range: "a time > 0",
            default: "required",
            meaning: "the end of the run (an event with action = \"stop\" may end it sooner)",
        },
    ]],
    outcomes: &[
        d::COMMON,
        &[
            d::Out {
                path: "outcome.*",
                unit: "outcome_units.*",
                meaning: "the named outcomes (null: its event never fired)",
            },
            d::Out {
                path: "outcome_units.*",
                unit: "-",
                meaning: "each outcome's unit, derived from its formula and [units]",
            },
            d::Out {
                path: "state.*",
                unit: "state_units.*",
                meaning: "the states at the end",
            },
            d::Out {
                path: "state_units.*",
                unit: "-",
                meaning: "each state's unit",
            },
            d::Out {
                path: "event_counts.*",
                unit: "-",
                meaning: "how many times each event fired",
            },
            d::Out {
                path: "stopped_by",
                unit: "-",
                meaning: "the event that stopped the run, or null",
            },
            d::Out {
                path: "t_end",
                unit: "s",
                meaning: "where the run ended",
            },
            d::Out {
                path: "jumps",
                unit: "-",
                meaning: "jumps applied",
            },
            d::Out {
                path: "method",
                unit: "-",
                meaning: "the integrator",
            },
            d::Out {
                path: "state_size",
                unit: "-",
                meaning: "states integrated",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the user should know",
            },
        ],
        d::STATS,
    ],
};
