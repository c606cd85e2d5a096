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
//!
//! Here the model's types, its integration and its run; apart: `scene` (reading the scene's
//! tables in named steps), `formulas` (parsing a formula with the definitions expanded),
//! `units` (checking every formula's units), `compile` (formulas to [`program`]s, the
//! Jacobian's symbolic derivative), `taylor` (the exact Taylor series of the solution) and
//! `doc` (the model's reference).
use crate::models::doc as d;

mod compile;
mod doc;
mod formulas;
pub mod program;
mod scene;
mod taylor;
mod units;

pub use doc::DOC;

use super::params::{SceneError, SolveSpec};
use super::{Curves, Model, RunError};
use crate::algebra::expr::Expr;
use crate::integrate::{Direction, Event, OdeSystem, Options, Stats, Stop};
use program::Program;
use std::collections::BTreeMap;

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

impl Model for OdeScene {
    const NAME: &'static str = "ode";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = OdeOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError> {
        scene::read(root, path)
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
