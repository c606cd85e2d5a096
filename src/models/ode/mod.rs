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
//! [definitions]                # named formulas, expanded where they are used (any order)
//! F = "k*max(z, 0)^(3/2)"
//! [state]                      # initial values: numbers in the state's unit, or formulas
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
//! stop_after = 3               # optional: the run stops at this firing
//! [outcome]                    # at the end, or at an event's first firing
//! duration = "t@contact-end"
//! rebound = "-v@+contact-end/v0"   # just after the jump
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
//! impact map. Events on the same `when` all fire, in the order written, each jump applied to
//! the state the one before left. `stop_after = N` ends the run at the N-th firing (after its
//! jump). An event with a jump whose last [`ACC_FIRINGS`] firings come at intervals that shrink
//! by one factor q (within 2 %) accumulates: infinitely many firings fit before t* = t_n + d_n
//! q/(1 - q). The run ends there once t* is within [`ACCUMULATED`] of the last firing (or when
//! the integrator cannot resolve the flights left), in the state just after the last firing,
//! with a warning and `accumulation` in the JSON: a bouncing ball or a rocking block comes to
//! rest at t*, and the model as written has nothing to say after it. At most [`MAX_RESTARTS`]
//! jumps per run, so that a sequence that accumulates without shrinking geometrically is an
//! error that says so, not an endless loop.
//!
//! Outcomes: `name = "formula"` is evaluated at the end of the run; `"formula@event"` in the
//! state where `event` first fires (before its jump), `"formula@+event"` just after its jump,
//! `"formula@event[k]"` at its k-th firing (from 1) and `"formula@event[last]"` at its last;
//! `hits@event` is how many times it fired. An outcome may also be a formula of several reads,
//! each `@` applying to the name or (group) just before it (`"(v^2)@+impact[1]/(v^2)@impact[1]"`,
//! `"t@impact[2] - t@impact[1]"`), and of other outcomes by name (`"ke2/ke1"`; [`outcomes`]).
//! An outcome whose event never fired is `null` in the JSON, with a warning. Every outcome's
//! unit is derived from the formula and `[units]` (`outcome_units` in the JSON).
//!
//! Here the model's types, its integration and its run; apart: `scene` (reading the scene's
//! tables in named steps), `outcomes` (reading and evaluating `[outcome]`), `formulas` (parsing a formula with the definitions expanded),
//! `units` (checking every formula's units), `compile` (formulas to [`program`]s, the
//! Jacobian's symbolic derivative), `taylor` (the exact Taylor series of the solution) and
//! `doc` (the model's reference).
use crate::models::doc as d;

mod closures;
mod compile;
mod doc;
mod formulas;
mod outcomes;
pub mod program;
mod scene;
mod shapes;
mod switch;
mod taylor;
mod units;

pub use doc::DOC;

use super::params::{SceneError, SolveSpec};
use super::trace::{Trace, Traced, or_why};
use super::{Curves, Model, RunError};
use crate::algebra::expr::Expr;
use crate::integrate::{Direction, Event, OdeSystem, Options, Stats, Stop};
use program::Program;
use smol_str::SmolStr;
use std::collections::BTreeMap;

/// The most jumps one run may apply.
pub const MAX_RESTARTS: usize = 100_000;
/// The most variables (`t`, states, parameters) a model may have: they are copied to a stack
/// buffer for every evaluation.
pub const MAX_VARS: usize = 256;

/// The run ends at an accumulation of firings when the time left to it, predicted from the
/// geometric shrinking of their intervals, is at most this share of it.
pub const ACCUMULATED: f64 = 1e-9;
/// The firings whose intervals must shrink by one factor (within [`RATIO_SPREAD`]) before an
/// accumulation is predicted.
const ACC_FIRINGS: usize = 8;
/// How far (relative) the ratios of successive intervals may spread.
const RATIO_SPREAD: f64 = 0.02;

/// Where an event's firings accumulate: their intervals shrink geometrically, by `ratio`, so
/// that infinitely many fit before `t` (a bouncing ball, a rocking block coming to rest).
#[derive(Clone, Debug, serde::Serialize)]
pub struct Accumulation {
    /// The event.
    pub event: String,
    /// Its firings.
    pub firings: usize,
    /// The accumulation time (s): the last firing plus the geometric sum of the intervals left.
    pub t: f64,
    /// The ratio of its last two intervals.
    pub ratio: f64,
    /// The state just after the last firing.
    #[serde(skip)]
    state: Vec<f64>,
}

impl Accumulation {
    fn warning(&self, err: Option<&crate::integrate::IntegrateError>) -> String {
        let why = match err {
            Some(e) => format!(" (the integrator could not go on: {e})"),
            None => String::new(),
        };
        format!(
            "event {}: its {} firings accumulate, each interval {:.6} times the one before, at t = {:.12e} s; the run ends there, in the state just after the last firing{why} (a bouncing ball or a rocking block comes to rest at that time)",
            self.event, self.firings, self.ratio, self.t
        )
    }
}

/// An event function over the states.
type EventFn<'a> = Box<dyn Fn(f64, &[f64]) -> f64 + 'a>;
/// An event formula at several points in one call ([`Event::batched`]).
type BatchBox<'a> = Box<dyn Fn(&[f64], &[f64], &mut [f64]) + 'a>;

/// Which firing of an event an outcome reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Firing {
    /// The k-th (from 0).
    Nth(usize),
    /// The last.
    Last,
}

#[derive(Clone, Debug)]
struct EventSpec {
    /// Its name (inline: a key of every run's counts).
    name: SmolStr,
    when: Program,
    direction: Direction,
    stop: bool,
    /// Stop the run at this firing (`stop_after = N`).
    stop_after: Option<usize>,
    /// (state index, new value).
    jump: Vec<(usize, Program)>,
}

impl EventSpec {
    /// Whether the integrator stops where it fires: to stop, to jump, or to count.
    fn halts(&self) -> bool {
        self.stop || !self.jump.is_empty() || self.stop_after.is_some()
    }
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
    /// The formulas whose sign the right sides read, held between their zeros.
    switches: Vec<switch::Switch>,
    outcomes: Vec<outcomes::OutcomeSpec>,
    /// The unit of every state and of every outcome, by name (for the JSON: shared by every
    /// run's outcome, not built per run of a sweep).
    state_units: std::sync::Arc<BTreeMap<String, String>>,
    outcome_units: std::sync::Arc<BTreeMap<String, String>>,
    /// The events' names, in order.
    event_names: Vec<String>,
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
    /// Parameter values (SI), in the order of the names (inline: a sweep copies the scene for
    /// every point).
    params: smallvec::SmallVec<[f64; 8]>,
    /// Initial values set by a sweep (`state.x`), over the compiled formulas.
    init_set: smallvec::SmallVec<[Option<f64>; 4]>,
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
    pub outcome: BTreeMap<SmolStr, Option<f64>>,
    /// Each outcome's unit, derived from its formula.
    pub outcome_units: std::sync::Arc<BTreeMap<String, String>>,
    /// Where the run ended (s).
    pub t_end: f64,
    /// The event that stopped it, if one did.
    pub stopped_by: Option<SmolStr>,
    /// The states at the end.
    pub state: BTreeMap<SmolStr, f64>,
    /// The unit of each state.
    pub state_units: std::sync::Arc<BTreeMap<String, String>>,
    /// How many times each event fired.
    pub event_counts: BTreeMap<SmolStr, usize>,
    /// Jumps applied.
    pub jumps: usize,
    /// Zeros of the formulas whose sign the right sides read, crossed ([`switch`]).
    pub switches: usize,
    /// Where an event's firings accumulated and the run ended, if they did.
    pub accumulation: Option<Accumulation>,
    /// The method.
    pub method: &'static str,
    /// States integrated.
    pub state_size: usize,
    /// What the user should know.
    pub warnings: Vec<String>,
    /// Work done.
    pub stats: Stats,
}

/// The variables every program reads: `t`, the states, the parameters, the held values of
/// the switches ([`switch`]; empty for a program that reads none).
struct Vars<'a> {
    m: &'a OdeScene,
    held: &'a [f64],
}

impl Vars<'_> {
    /// Calls `f` with `[t, y..., parameters...]` in a buffer on the stack sized to the model (a
    /// short model does not clear a long buffer on every evaluation).
    #[inline]
    fn with<R>(&self, t: f64, y: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
        match 1 + y.len() + self.m.params.len() + self.held.len() {
            0..=16 => self.fill::<16, R>(t, y, f),
            17..=64 => self.fill::<64, R>(t, y, f),
            _ => self.fill::<MAX_VARS, R>(t, y, f),
        }
    }

    #[inline]
    fn fill<const N: usize, R>(&self, t: f64, y: &[f64], f: impl FnOnce(&[f64]) -> R) -> R {
        let n = y.len();
        let p = 1 + n + self.m.params.len();
        let total = p + self.held.len();
        let mut buf = [0.0f64; N];
        buf[0] = t;
        // element by element: the slices are a few numbers long, where a call of `memcpy` for
        // each costs more than the copy (a tenth of a text model's sweep)
        for (slot, v) in buf[1..=n].iter_mut().zip(y) {
            *slot = *v;
        }
        for (slot, v) in buf[1 + n..p].iter_mut().zip(&self.m.params) {
            *slot = *v;
        }
        for (slot, v) in buf[p..total].iter_mut().zip(self.held) {
            *slot = *v;
        }
        f(&buf[..total])
    }
}

impl Vars<'_> {
    /// `p` at `(t, y)`: a bare variable read as it is (an outcome's `t@event`, `z@event`: no
    /// buffer filled), any other formula on the variables in one buffer ([`Vars::with`]).
    fn eval(&self, p: &Program, t: f64, y: &[f64]) -> f64 {
        let n = y.len();
        match p.variable() {
            Some(0) => t,
            Some(s) if s <= n => y[s - 1],
            Some(s) if s <= n + self.m.params.len() => self.m.params[s - 1 - n],
            _ => self.with(t, y, |v| p.eval(v)),
        }
    }
}

/// A map of a few entries, inserted one by one (collecting sorts a vector of them first: a
/// sweep builds these for every point).
fn entries<V>(items: impl Iterator<Item = (SmolStr, V)>) -> BTreeMap<SmolStr, V> {
    let mut map = BTreeMap::new();
    for (k, v) in items {
        map.insert(k, v);
    }
    map
}

impl OdeScene {
    /// The held values as `sign` reads them at `(t, y)`: the right sides as written.
    fn signs(&self, t: f64, y: &[f64]) -> Vec<f64> {
        let vars = Vars { m: self, held: &[] };
        self.switches
            .iter()
            .map(|s| vars.with(t, y, |v| s.arg.eval(v)).signum())
            .collect()
    }

    fn rhs_held(&self, held: &[f64], t: f64, y: &[f64], dy: &mut [f64]) {
        Vars { m: self, held }.with(t, y, |v| {
            for (d, p) in dy.iter_mut().zip(&self.rhs) {
                *d = p.eval(v);
            }
        });
    }

    fn jacobian_held(
        &self,
        held: &[f64],
        t: f64,
        y: &[f64],
        jac: &mut nalgebra::DMatrix<f64>,
    ) -> bool {
        let Some(progs) = &self.jac else {
            return false;
        };
        let n = self.states.len();
        Vars { m: self, held }.with(t, y, |v| {
            for i in 0..n {
                for j in 0..n {
                    jac[(i, j)] = progs[i * n + j].eval(v);
                }
            }
        });
        true
    }

    /// The side each switch is on at `(t, y)`, starting from `held` ([`switch::side`]).
    fn sides(&self, t: f64, y: &[f64], held: &mut [f64]) {
        for j in 0..held.len() {
            let sw = &self.switches[j];
            let g = Vars { m: self, held: &[] }.with(t, y, |v| sw.arg.eval(v));
            let rate = |s: f64| {
                let mut h = held.to_vec();
                h[j] = s;
                Vars { m: self, held: &h }.with(t, y, |v| sw.rate.eval(v))
            };
            held[j] = switch::side(t, g, &rate);
        }
    }
}

/// A run of the model, recorded or not: what [`shapes::run_shaped`] calls with the system built.
struct Go<'a> {
    m: &'a OdeScene,
    record: bool,
}

impl shapes::Runner for Go<'_> {
    type Out = Result<(OdeOutcome, Option<Trace>), RunError>;
    fn run<S: shapes::Integrated>(&self, sys: S) -> Self::Out {
        self.m.go_with(self.record, sys)
    }
}

/// A text model with its switches held ([`switch`]): what the run integrates.
struct Held<'a> {
    m: &'a OdeScene,
    held: Vec<f64>,
    /// The right sides as nested closures ([`closures`]), reading `t` and the state in place.
    slopes: Vec<closures::Slope>,
    /// The variables after the states, in slot order: the parameters, then the held values
    /// (written by [`Held::set_held`]).
    rest: Vec<f64>,
}

impl<'a> Held<'a> {
    fn new(m: &'a OdeScene) -> Self {
        let n = m.states.len();
        let mut rest = m.params.to_vec();
        rest.resize(m.params.len() + m.switches.len(), 0.0);
        Held {
            m,
            held: vec![0.0; m.switches.len()],
            slopes: m.rhs.iter().map(|p| p.slope(n)).collect(),
            rest,
        }
    }

    /// Sets the held values (each switch's side) from `(t, y)` ([`OdeScene::sides`]).
    fn set_held(&mut self, t: f64, y: &[f64]) {
        self.m.sides(t, y, &mut self.held);
        let at = self.rest.len() - self.held.len();
        self.rest[at..].copy_from_slice(&self.held);
    }
}

impl shapes::Integrated for Held<'_> {
    fn set_held(&mut self, t: f64, y: &[f64]) {
        Held::set_held(self, t, y);
    }
    fn solve(
        &self,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        opts: &Options,
    ) -> Result<crate::integrate::Solution, crate::integrate::IntegrateError> {
        crate::integrate::solve(self, t0, y0, t_end, opts)
    }
}

impl OdeSystem for Held<'_> {
    fn dim(&self) -> usize {
        self.m.states.len()
    }
    #[inline(always)]
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        for (d, f) in dy.iter_mut().zip(&self.slopes) {
            *d = f(t, y, &self.rest);
        }
    }
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        self.m.jacobian_held(&self.held, t, y, jac)
    }
}

/// The model as written: each `sign` read where it is evaluated.
impl OdeSystem for OdeScene {
    fn dim(&self) -> usize {
        self.states.len()
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        if self.switches.is_empty() {
            self.rhs_held(&[], t, y, dy);
        } else {
            self.rhs_held(&self.signs(t, y), t, y, dy);
        }
    }
    fn jacobian(&self, t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        let held = if self.switches.is_empty() {
            Vec::new()
        } else {
            self.signs(t, y)
        };
        self.jacobian_held(&held, t, y, jac)
    }
}

impl OdeScene {
    /// The earliest accumulation of the firings of an event with a jump, if the last
    /// [`ACC_FIRINGS`] of one shrink geometrically.
    fn accumulating(&self, hits: &[Vec<outcomes::Hit>]) -> Option<Accumulation> {
        let mut best: Option<Accumulation> = None;
        for (e, list) in self.events.iter().zip(hits) {
            if e.jump.is_empty() || list.len() < ACC_FIRINGS {
                continue;
            }
            let last = &list[list.len() - ACC_FIRINGS..];
            let d: Vec<f64> = last.windows(2).map(|w| w[1].t - w[0].t).collect();
            let q: Vec<f64> = d.windows(2).map(|w| w[1] / w[0]).collect();
            let r = q[q.len() - 1];
            let steady = q
                .iter()
                .all(|x| *x > 0.0 && *x < 1.0 && (x - r).abs() <= RATIO_SPREAD * r);
            if !steady {
                continue;
            }
            let end = list[list.len() - 1].t + d[d.len() - 1] * r / (1.0 - r);
            if end <= self.t_end && best.as_ref().is_none_or(|b| end < b.t) {
                best = Some(Accumulation {
                    event: e.name.to_string(),
                    firings: list.len(),
                    t: end,
                    ratio: r,
                    state: list[list.len() - 1].after().to_vec(),
                });
            }
        }
        best
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
        Ok((self.go(false)?.0, vec![]))
    }

    fn run_traced(&self) -> Result<(OdeOutcome, Traced), RunError> {
        let (out, trace) = self.go(true)?;
        Ok((out, or_why(trace, "nothing was recorded")))
    }
}

impl OdeScene {
    /// The run, its path (every state at every accepted step, every event and switch) recorded
    /// when `record` is set.
    fn go(&self, record: bool) -> Result<(OdeOutcome, Option<Trace>), RunError> {
        let go = Go { m: self, record };
        shapes::run_shaped(self, &go).unwrap_or_else(|| shapes::Runner::run(&go, Held::new(self)))
    }

    /// [`OdeScene::go`] with the system `sys`.
    fn go_with<S: shapes::Integrated>(
        &self,
        record: bool,
        mut sys: S,
    ) -> Result<(OdeOutcome, Option<Trace>), RunError> {
        let n = self.states.len();
        let mut y = self.initial_state()?;
        let user = self.events.len();
        let formulas = || {
            self.events
                .iter()
                .map(|e| &e.when)
                .chain(self.switches.iter().map(|s| &s.arg))
        };
        // each formula's closure: a bare state read as it is, a formula of a known shape as
        // its own closure ([`shapes`]), any other as nested closures reading t, the state and
        // the parameters where they live ([`closures`]: no buffer written per evaluation);
        // and the same formula at several points in one call where the program allows it and
        // no closure of its shape does better
        let mut batches: Vec<Option<BatchBox>> = Vec::new();
        let gs: Vec<EventFn> = formulas()
            .map(|p| {
                let (g, batch) = match (p.variable(), shapes::event_fn(p, n, &self.params)) {
                    (Some(slot), _) if (1..=n).contains(&slot) => (
                        Box::new(move |_t: f64, y: &[f64]| y[slot - 1]) as EventFn,
                        false,
                    ),
                    (_, Some(g)) => (g, false),
                    _ => {
                        let (f, rest) = (p.slope(n), self.params.clone());
                        let g = Box::new(move |t: f64, y: &[f64]| f(t, y, &rest)) as EventFn;
                        (g, p.batchable())
                    }
                };
                batches.push(batch.then(|| {
                    let mut base = vec![0.0; 1 + n + self.params.len()];
                    base[1 + n..].copy_from_slice(&self.params);
                    Box::new(move |ts: &[f64], ys: &[f64], out: &mut [f64]| {
                        p.eval_batch(&base, n, ts, ys, out)
                    }) as BatchBox
                }));
                g
            })
            .collect();
        // the user's events, then each switch's zero (stopping, either way)
        let events: Vec<Event> = gs
            .iter()
            .enumerate()
            .map(|(i, g)| {
                let (name, when, direction, halts) = match self.events.get(i) {
                    Some(e) => (
                        std::borrow::Cow::Borrowed(e.name.as_str()),
                        &e.when,
                        e.direction,
                        e.halts(),
                    ),
                    None => {
                        let sw = &self.switches[i - user];
                        (
                            std::borrow::Cow::Owned(format!("switch of sign({})", sw.text)),
                            &sw.arg,
                            Direction::Both,
                            true,
                        )
                    }
                };
                let event = Event::new(name, g.as_ref(), direction, halts);
                // a bare state (`when = "z"`, slot 1 + i after t) is read without a call
                match (when.variable(), &batches[i]) {
                    (Some(slot), _) if (1..=n).contains(&slot) => event.reading(slot - 1),
                    (_, Some(b)) => event.batched(b.as_ref()),
                    _ => event,
                }
            })
            .collect();
        let opts = Options {
            rtol: self.solve.rtol,
            atol: self.solve.atol,
            method: self.solve.method,
            events,
            trajectory: record,
            ..Options::default()
        };
        let mut trace = record.then(|| {
            let names: Vec<(&str, &str)> = self
                .states
                .iter()
                .map(|s| {
                    (
                        s.as_str(),
                        self.state_units.get(s).map_or("1", String::as_str),
                    )
                })
                .collect();
            Trace::new(("t", "s"), &names)
        });
        sys.set_held(0.0, &y);
        let mut r = Runs {
            t: 0.0,
            hits: vec![Vec::new(); user],
            stats: Stats::default(),
            stopped_by: None,
            jumps: 0,
            switches: 0,
            warnings: Vec::new(),
            accumulation: None,
        };
        while r.t < self.t_end {
            let sol = match sys.solve(r.t, &y, self.t_end, &opts) {
                Ok(sol) => sol,
                Err(err) => {
                    // impacts that accumulate: the integrator cannot resolve the last flights
                    if let Some(acc) = self.accumulating(&r.hits) {
                        (r.t, y) = (acc.t, acc.state.clone());
                        r.warnings.push(acc.warning(Some(&err)));
                        r.accumulation = Some(acc);
                        break;
                    }
                    return Err(err.into());
                }
            };
            if let Some(tr) = trace.as_mut() {
                tr.extend(&sol.trajectory);
                for h in &sol.events {
                    tr.event(&opts.events[h.index].name, h.t, &h.y);
                }
            }
            r.stats = r.stats + sol.stats;
            r.t = sol.t;
            y = sol.y;
            let stop_t = match sol.stop {
                Stop::Event { t, .. } => Some(t),
                Stop::End => None,
            };
            // the firings that go on (no jump, no stop), as located; those at the stop below
            let mut halting: Vec<usize> = Vec::new();
            for h in sol.events {
                let halts = self.events.get(h.index).is_none_or(EventSpec::halts);
                if stop_t.is_some_and(|s| s.to_bits() == h.t.to_bits()) && halts {
                    halting.push(h.index);
                } else if h.index < user {
                    r.hits[h.index].push(outcomes::Hit {
                        t: h.t,
                        before: h.y,
                        jumped: None,
                    });
                }
            }
            if stop_t.is_none() {
                break;
            }
            halting.sort_unstable();
            halting.dedup();
            r.switches += halting.iter().filter(|i| **i >= user).count();
            let stop = self.fire(&mut r, &mut y, &halting)?;
            // the state after the jumps, at the same time
            if let Some(tr) = trace.as_mut() {
                tr.extend(&[(r.t, y.clone())]);
            }
            if stop {
                break;
            }
            // every switch on the side the motion goes into, after the jumps
            sys.set_held(r.t, &y);
            if let Some(acc) = self.accumulating(&r.hits)
                && acc.t - r.t <= ACCUMULATED * acc.t.abs()
            {
                (r.t, y) = (acc.t, acc.state.clone());
                r.warnings.push(acc.warning(None));
                r.accumulation = Some(acc);
                break;
            }
            if r.jumps >= MAX_RESTARTS {
                return Err(RunError::BadArgument {
                    arg: format!("event {}", self.events[halting[0]].name),
                    message: format!(
                        "{MAX_RESTARTS} jumps by t = {:e} s without reaching t_end = {:e} s: the impacts accumulate (a Zeno sequence) but not geometrically; stop at an event (stop_after) or shorten t_end",
                        r.t, self.t_end
                    ),
                });
            }
        }
        if let (Some(tr), Some(acc)) = (trace.as_mut(), r.accumulation.as_ref()) {
            tr.extend(&[(acc.t, acc.state.clone())]);
        }
        Ok((self.outcome(r, y), trace))
    }
}

/// What a run has gathered so far.
struct Runs {
    t: f64,
    hits: Vec<Vec<outcomes::Hit>>,
    stats: Stats,
    stopped_by: Option<SmolStr>,
    jumps: usize,
    switches: usize,
    warnings: Vec<String>,
    accumulation: Option<Accumulation>,
}

impl OdeScene {
    /// The initial values, each a number set by a sweep or its formula of the parameters.
    fn initial_state(&self) -> Result<Vec<f64>, RunError> {
        let n = self.states.len();
        let y: Vec<f64> = Vars { m: self, held: &[] }.with(0.0, &vec![0.0; n], |v| {
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
                    "the initial value is {} (not finite) with {}",
                    y[i],
                    self.parameters_text()
                ),
            });
        }
        Ok(y)
    }

    /// `name = value` of each of `names`, for a message.
    fn named_text(&self, names: &[String], values: &[f64]) -> String {
        let pairs: Vec<String> = names
            .iter()
            .zip(values)
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        if pairs.is_empty() {
            "no values".into()
        } else {
            pairs.join(", ")
        }
    }

    /// The parameters and their values, for a message on a value that is not finite.
    fn parameters_text(&self) -> String {
        if self.param_names.is_empty() {
            return "no parameters".into();
        }
        format!(
            "the parameters {}",
            self.named_text(&self.param_names, &self.params)
        )
    }

    /// Every user event that fires at the stop, in the order written, each jump applied to the
    /// state the one before left; whether the run stops here.
    fn fire(&self, r: &mut Runs, y: &mut [f64], halting: &[usize]) -> Result<bool, RunError> {
        let t = r.t;
        let mut stop = false;
        for &index in halting.iter().filter(|i| **i < self.events.len()) {
            let ev = &self.events[index];
            let before = y.to_vec();
            if !ev.jump.is_empty() {
                let new: Vec<(usize, f64)> = Vars { m: self, held: &[] }.with(t, y, |v| {
                    ev.jump.iter().map(|(k, p)| (*k, p.eval(v))).collect()
                });
                for (k, x) in new {
                    y[k] = x;
                }
                r.jumps += 1;
                if let Some(i) = y.iter().position(|x| !x.is_finite()) {
                    return Err(RunError::BadArgument {
                        arg: format!("event {}: jump of {}", ev.name, self.states[i]),
                        message: format!(
                            "at t = {t:e} s the jump gives {} (not finite) from the state {} with {}",
                            y[i],
                            self.named_text(&self.states, &before),
                            self.parameters_text()
                        ),
                    });
                }
            }
            r.hits[index].push(outcomes::Hit {
                t,
                before,
                jumped: (!ev.jump.is_empty()).then(|| y.to_vec()),
            });
            if ev.stop || ev.stop_after == Some(r.hits[index].len()) {
                stop = true;
                r.stopped_by.get_or_insert_with(|| ev.name.clone());
            }
        }
        Ok(stop)
    }

    /// The run's outcome: the named outcomes, the end state, the counts.
    fn outcome(&self, r: Runs, y: Vec<f64>) -> OdeOutcome {
        let Runs {
            t,
            hits,
            stats,
            stopped_by,
            jumps,
            switches,
            mut warnings,
            accumulation,
        } = r;
        let n = self.states.len();
        let vars = Vars { m: self, held: &[] };
        let param = |s: &str| {
            self.param_names
                .iter()
                .position(|p| p == s)
                .map(|i| self.params[i])
        };
        let state = |s: &str| self.states.iter().position(|x| x == s).map(|i| y[i]);
        let outcome = outcomes::evaluate(
            &self.outcomes,
            &hits,
            &self.event_names,
            &|p| vars.eval(p, t, &y),
            &|p, th, yh| vars.eval(p, th, yh),
            &|s| {
                if s == "t" {
                    Some(t)
                } else {
                    state(s).or_else(|| param(s))
                }
            },
            &mut warnings,
        );
        for (name, v) in &outcome {
            if let Some(v) = v.filter(|v| !v.is_finite()) {
                warnings.push(format!(
                    "outcome.{name} is {v} (not finite; written null) with {}",
                    self.parameters_text()
                ));
            }
        }
        OdeOutcome {
            model: <Self as Model>::NAME,
            outcome,
            outcome_units: self.outcome_units.clone(),
            t_end: t,
            stopped_by,
            state: entries(self.states.iter().map(SmolStr::new).zip(y.iter().copied())),
            state_units: self.state_units.clone(),
            event_counts: entries(
                self.events
                    .iter()
                    .zip(&hits)
                    .map(|(e, h)| (e.name.clone(), h.len())),
            ),
            jumps,
            switches,
            accumulation,
            method: self.solve.method.name(),
            state_size: n,
            warnings,
            stats,
        }
    }
}

#[cfg(test)]
mod tests {
    /// A right side with a switch: `z'' = -a sign(z)` from `z = 1` at rest reaches `z = 0` at
    /// `t = sqrt(2/a)` with `v = -sqrt(2 a)` (by hand: `z = 1 - a t^2/2` while `z > 0`); the
    /// sign's held value sits after the parameter among the variables the right sides read.
    #[test]
    fn a_held_sign_is_read_after_the_parameters() {
        let text = r#"model = "ode"
[parameters]
a = 2.0
[units]
t = "s"
a = "m/s^2"
z = "m"
v = "m/s"
[state]
z = 1.0
v = 0.0
[equations]
z = "v"
v = "-a*sign(z)"
[[event]]
name = "crossing"
when = "z"
direction = "down"
action = "stop"
[outcome]
t1 = "t@crossing"
v1 = "v@crossing"
[solve]
rtol = 1e-10
atol = 1e-12
t_end = 5.0
"#;
        use crate::models::Model;
        let table: toml::Table = toml::from_str(text).expect("toml");
        let scene = super::OdeScene::from_table(&table, "s.toml").expect("a valid scene");
        let (out, _) = scene.run().expect("runs");
        let t1 = out.outcome["t1"].expect("t1");
        let v1 = out.outcome["v1"].expect("v1");
        assert!((t1 - 1.0).abs() < 1e-9, "{out:?}");
        assert!((v1 + 2.0).abs() < 1e-9, "{out:?}");
        assert_eq!(out.switches, 1, "{out:?}");
    }
}
