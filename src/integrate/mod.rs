//! The numeric core: adaptive, event-locating, stiff-capable ODE integration.
//!
//! Every model of the papers ends in $y' = f(t, y)$ integrated to a known accuracy and stopped at a
//! physical event (contact ends when the indentation crosses zero, compression ends at $V_n = 0$,
//! slip stops at zero slip speed). Three methods, each in its own file:
//!
//! - [`dop853`]: Dormand-Prince 8(5,3) with the 7th-order dense output,
//! - [`dopri5`]: Dormand-Prince 5(4) with Shampine's 4th-order dense output,
//! - [`radau5`]: Radau IIA of order 5 (3 stages), simplified Newton with a real and a complex
//!   LU (nalgebra's dense LU), its collocation polynomial as dense output.
//!
//! `Method::Auto` starts with DOP853 and moves to Radau5 when the explicit method's stiffness
//! detection fires. Events ([`events`]) are located by root finding on the dense output.
//!
//! Why in-house: we looked at the Rust ODE crates; on these problems they are 1.3x to 5x slower
//! than Hairer's codes, or lack tight event location (one returns dense output that is wrong at the
//! end point; one reports event states off g = 0 by 1e-6), or spawn threads every step. These
//! methods follow Hairer's published step-size control, starting step, stiffness detection and
//! dense output (DOPRI5, DOP853, RADAU5 in Hairer, Norsett, Wanner, Solving ODEs I and II), so
//! that the evaluation counts match his codes: that match is the strongest regression test there
//! is. Work buffers are allocated once per solve; the step loop itself does not allocate (Radau5's
//! LU factorisations, done only when the step size or Jacobian changes, are nalgebra's).

// The kernels index several state-sized arrays in lockstep; iterator chains would obscure them.
#![allow(clippy::needless_range_loop)]

pub mod dop853;
mod dop853_tableau;
pub mod dopri5;
mod erk;
pub mod events;
pub mod radau5;
pub mod stats;
pub mod workprecision;

pub use events::{Direction, Event, EventHit};
pub use stats::Stats;

use nalgebra::DMatrix;

/// A system $y' = f(t, y)$.
pub trait OdeSystem {
    /// Number of states.
    fn dim(&self) -> usize;
    /// Writes $f(t, y)$ into `dy`.
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Writes $\partial f/\partial y$ into `jac` and returns true, or returns false to ask for
    /// finite differences.
    fn jacobian(&self, _t: f64, _y: &[f64], _jac: &mut DMatrix<f64>) -> bool {
        false
    }
}

/// Which method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Dormand-Prince 5(4).
    Dopri5,
    /// Dormand-Prince 8(5,3).
    Dop853,
    /// Radau IIA order 5.
    Radau5,
    /// DOP853, switching to Radau5 when stiffness is detected.
    Auto,
}

impl Method {
    /// Name as in scenes.
    pub fn name(self) -> &'static str {
        match self {
            Method::Dopri5 => "dopri5",
            Method::Dop853 => "dop853",
            Method::Radau5 => "radau5",
            Method::Auto => "auto",
        }
    }

    /// Parses a scene name.
    pub fn parse(s: &str) -> Option<Method> {
        match s {
            "dopri5" => Some(Method::Dopri5),
            "dop853" => Some(Method::Dop853),
            "radau5" => Some(Method::Radau5),
            "auto" => Some(Method::Auto),
            _ => None,
        }
    }
}

/// Solver options.
pub struct Options<'a> {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Method.
    pub method: Method,
    /// Initial step (None: Hairer's starting-step heuristic).
    pub h0: Option<f64>,
    /// Largest step (default: the whole interval).
    pub hmax: Option<f64>,
    /// Step limit.
    pub max_steps: usize,
    /// Times at which to report the solution (sorted, inside the interval).
    pub dense_times: Vec<f64>,
    /// Record every accepted step.
    pub trajectory: bool,
    /// Event functions.
    pub events: Vec<Event<'a>>,
    /// Constant step size without error control (for convergence-order tests only).
    pub fixed_step: Option<f64>,
}

impl Default for Options<'_> {
    fn default() -> Self {
        Options {
            rtol: 1e-6,
            atol: 1e-6,
            method: Method::Dop853,
            h0: None,
            hmax: None,
            max_steps: 100_000,
            dense_times: vec![],
            trajectory: false,
            events: vec![],
            fixed_step: None,
        }
    }
}

/// Why a solve stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// Reached the end of the interval.
    End,
    /// A terminal event fired.
    Event {
        /// Time of the event (s).
        t: f64,
        /// Which event.
        index: usize,
    },
}

/// The result of a solve.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Final time.
    pub t: f64,
    /// Final state.
    pub y: Vec<f64>,
    /// Why it stopped.
    pub stop: Stop,
    /// Work done.
    pub stats: Stats,
    /// Every event that fired, in time order.
    pub events: Vec<EventHit>,
    /// The solution at the requested `dense_times`.
    pub dense: Vec<(f64, Vec<f64>)>,
    /// Every accepted step, if requested.
    pub trajectory: Vec<(f64, Vec<f64>)>,
    /// Where the explicit method's stiffness test fired, if it did.
    pub stiffness_detected_at: Option<f64>,
    /// Where `Auto` switched to Radau5, if it did.
    pub switched_at: Option<f64>,
}

/// Why a solve could not finish (never a silently wrong answer).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IntegrateError {
    /// The step size fell below what the time's precision allows.
    #[error("step size too small: h = {h:e} at t = {t:e}")]
    StepSizeTooSmall {
        /// Time (s).
        t: f64,
        /// Step (s).
        h: f64,
    },
    /// The step limit was reached.
    #[error("more than {max_steps} steps needed; stopped at t = {t:e} (h = {h:e})")]
    TooManySteps {
        /// Time (s).
        t: f64,
        /// Last step (s).
        h: f64,
        /// The limit.
        max_steps: usize,
    },
    /// Newton's iteration of the implicit method failed repeatedly.
    #[error("Newton iteration failed at t = {t:e} with h = {h:e} (singular matrix or divergence)")]
    NewtonFailure {
        /// Time (s).
        t: f64,
        /// Step (s).
        h: f64,
    },
    /// The state became NaN or infinite.
    #[error("non-finite state at t = {t:e}")]
    NonFinite {
        /// Time (s).
        t: f64,
    },
    /// An event function returned NaN or infinity.
    #[error("event {index} returned a non-finite value at t = {t:e}")]
    EventNonFinite {
        /// Time (s).
        t: f64,
        /// Which event.
        index: usize,
    },
    /// An option is out of range.
    #[error("option {field} = {value} is not allowed; allowed: {allowed}")]
    BadOption {
        /// Field.
        field: &'static str,
        /// Value.
        value: String,
        /// Allowed range.
        allowed: &'static str,
    },
}

/// What a method provides to the driver.
pub(crate) trait Stepper {
    /// Takes one accepted step toward `t_end` (never past it).
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError>;
    /// Time and state at the start of the last accepted step.
    fn t_old(&self) -> f64;
    /// Time at the end of the last accepted step.
    fn t(&self) -> f64;
    /// State at `t()`.
    fn y(&self) -> &[f64];
    /// Last step size.
    fn h(&self) -> f64;
    /// Makes dense output of the last step available (may cost evaluations).
    fn prepare_dense<S: OdeSystem>(&mut self, sys: &S);
    /// Dense output at `t` in the last step.
    fn dense(&self, t: f64, out: &mut [f64]);
    /// Whether [`Stepper::hermite_parts`] is available.
    fn has_hermite(&self) -> bool {
        false
    }
    /// The cubic Hermite interpolant of the last step (end values and derivatives, no
    /// evaluation) as four vectors of the state's length in `parts`: $y_0$, $\Delta y$, $c_1$,
    /// $c_2$, so that at $s = (t - t_0)/h$ its quadratic part is
    /// $q = y_0 + s(\Delta y + (1 - s) c_1)$ and the interpolant $q + s^2 (1 - s) c_2$ (see
    /// [`hermite_at`]); returns the step $h$ that defines $s$. Only called when
    /// [`Stepper::has_hermite`].
    fn hermite_parts(&self, _parts: &mut [f64]) -> f64 {
        f64::NAN
    }
    /// Work done.
    fn stats(&self) -> Stats;
    /// True if the stiffness test has fired.
    fn stiff(&self) -> bool {
        false
    }
}

/// The cubic Hermite interpolant of [`Stepper::hermite_parts`] at the fraction `s` of the step
/// in `out`, and in `quad` the same without its cubic term.
#[inline(always)]
pub(crate) fn hermite_at(parts: &[f64], s: f64, out: &mut [f64], quad: &mut [f64]) {
    let n = out.len();
    let (y0, rest) = parts.split_at(n);
    let (dy, rest) = rest.split_at(n);
    let (c1, c2) = rest.split_at(n);
    let s1 = 1.0 - s;
    for m in 0..n.min(quad.len()).min(c2.len()) {
        let q = y0[m] + s * (dy[m] + s1 * c1[m]);
        quad[m] = q;
        out[m] = q + s * s1 * s * c2[m];
    }
}

fn check_options(
    opts: &Options,
    n: usize,
    y0: &[f64],
    t0: f64,
    t_end: f64,
) -> Result<(), IntegrateError> {
    let bad = |field, value: String, allowed| {
        Err(IntegrateError::BadOption {
            field,
            value,
            allowed,
        })
    };
    if !(opts.rtol.is_finite() && opts.rtol > 0.0 && opts.rtol < 1.0) {
        return bad("rtol", opts.rtol.to_string(), "0 < rtol < 1");
    }
    if !(opts.atol.is_finite() && opts.atol > 0.0) {
        return bad("atol", opts.atol.to_string(), "atol > 0");
    }
    if y0.len() != n {
        return bad(
            "y0",
            format!("length {}", y0.len()),
            "the system's dimension",
        );
    }
    if y0.iter().any(|v| !v.is_finite()) {
        return bad("y0", format!("{y0:?}"), "finite numbers");
    }
    if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
        return bad("t_end", t_end.to_string(), "finite and > t0");
    }
    let mut prev = t0;
    for &t in &opts.dense_times {
        if !(t >= prev && t <= t_end) {
            return bad("dense_times", t.to_string(), "sorted, inside [t0, t_end]");
        }
        prev = t;
    }
    Ok(())
}

/// Integrates `sys` from `(t0, y0)` to `t_end` (or a terminal event).
pub fn solve<S: OdeSystem>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    opts: &Options,
) -> Result<Solution, IntegrateError> {
    let n = sys.dim();
    check_options(opts, n, y0, t0, t_end)?;
    match opts.method {
        Method::Dopri5 if n == 2 => {
            let st = dopri5::Dopri5::<2>::new(sys, t0, y0, t_end, opts);
            drive(sys, st, (t0, y0, t_end), opts, None)
        }
        Method::Dopri5 => {
            let st = dopri5::Dopri5::<0>::new(sys, t0, y0, t_end, opts);
            drive(sys, st, (t0, y0, t_end), opts, None)
        }
        Method::Dop853 => drive_dop853(sys, (t0, y0, t_end), opts, None),
        Method::Radau5 => drive_radau5(sys, (t0, y0, t_end), opts),
        Method::Auto => {
            let first = drive_dop853(sys, (t0, y0, t_end), opts, Some(()))?;
            if first.switched_at.is_none() {
                return Ok(first);
            }
            // continue with Radau5 from where stiffness was detected
            let ts = first.t;
            let mut rest_opts = Options {
                rtol: opts.rtol,
                atol: opts.atol,
                method: Method::Radau5,
                h0: None,
                hmax: opts.hmax,
                max_steps: opts.max_steps,
                dense_times: opts
                    .dense_times
                    .iter()
                    .copied()
                    .filter(|t| *t > ts)
                    .collect(),
                trajectory: opts.trajectory,
                events: vec![],
                fixed_step: opts.fixed_step,
            };
            // the events carry borrowed closures: re-borrow them for the second leg
            let events: Vec<Event> = opts.events.iter().map(|e| e.reborrow()).collect();
            rest_opts.events = events;
            let mut second = drive_radau5(sys, (ts, &first.y, t_end), &rest_opts)?;
            let mut merged = first;
            merged.stats = merged.stats + second.stats;
            merged.t = second.t;
            merged.y = std::mem::take(&mut second.y);
            merged.stop = second.stop;
            merged.events.append(&mut second.events);
            merged.dense.append(&mut second.dense);
            merged.trajectory.append(&mut second.trajectory);
            Ok(merged)
        }
    }
}

/// [`solve`] with DOP853 for a system of two states, that one stepper instantiated: a caller
/// that builds many systems the compiler sees whole (a text model's right sides of a known shape)
/// pays one stepper for each, not every method's. The same solution as [`solve`], to the bit;
/// any other method or size is refused.
pub fn solve_dop853_pair<S: OdeSystem>(
    sys: &S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    opts: &Options,
) -> Result<Solution, IntegrateError> {
    let n = sys.dim();
    check_options(opts, n, y0, t0, t_end)?;
    if n != 2 || opts.method != Method::Dop853 {
        return Err(IntegrateError::BadOption {
            field: "method",
            value: format!("{} for {n} states", opts.method.name()),
            allowed: "dop853 for 2 states",
        });
    }
    let st = dop853::Dop853::<2>::new(sys, t0, y0, t_end, opts);
    drive(sys, st, (t0, y0, t_end), opts, None)
}

/// Makes a stepper with rtol = atol = `tol` and steps it to `t_end`: its end state and work
/// (the tests that compare a stepper of a fixed size with the one of the run-time size).
#[cfg(test)]
pub(crate) fn step_to_end<S: OdeSystem, St: Stepper>(
    sys: &S,
    tol: f64,
    t_end: f64,
    make: impl FnOnce(&Options) -> St,
) -> (Vec<f64>, Stats) {
    let opts = Options {
        rtol: tol,
        atol: tol,
        ..Options::default()
    };
    let mut st = make(&opts);
    while st.t() < t_end {
        st.step(sys, t_end).expect("solves");
    }
    (st.y().to_vec(), st.stats())
}

/// Evaluates `$body` with the constant `$N` set to the state's length `$n` where a stepper has
/// stages of that fixed size (2 and 4 states: one or two contact coordinates and their rates, the
/// small systems of impact models), to 0 (a size known at run time) otherwise.
macro_rules! with_fixed_dim {
    ($n:expr, $N:ident => $body:expr) => {
        match $n {
            2 => {
                const $N: usize = 2;
                $body
            }
            4 => {
                const $N: usize = 4;
                $body
            }
            _ => {
                const $N: usize = 0;
                $body
            }
        }
    };
}

/// DOP853 from `(t0, y0)` to `t_end` (returning at stiffness when `auto`).
fn drive_dop853<S: OdeSystem>(
    sys: &S,
    (t0, y0, t_end): (f64, &[f64], f64),
    opts: &Options,
    auto: Option<()>,
) -> Result<Solution, IntegrateError> {
    with_fixed_dim!(y0.len(), N => {
        let st = dop853::Dop853::<N>::new(sys, t0, y0, t_end, opts);
        drive(sys, st, (t0, y0, t_end), opts, auto)
    })
}

/// Radau5 from `(t0, y0)` to `t_end`.
fn drive_radau5<S: OdeSystem>(
    sys: &S,
    (t0, y0, t_end): (f64, &[f64], f64),
    opts: &Options,
) -> Result<Solution, IntegrateError> {
    with_fixed_dim!(y0.len(), N => {
        let st = radau5::Radau5::<N>::new(sys, t0, y0, t_end, opts);
        drive(sys, st, (t0, y0, t_end), opts, None)
    })
}

/// The common loop: steps, dense output, events, trajectory. With `auto = Some(())` it returns
/// early (with `switched_at` set) when the stepper reports stiffness.
fn drive<S: OdeSystem, St: Stepper>(
    sys: &S,
    mut st: St,
    (t0, y0, t_end): (f64, &[f64], f64),
    opts: &Options,
    auto: Option<()>,
) -> Result<Solution, IntegrateError> {
    let n = sys.dim();
    let mut sol = Solution {
        t: t0,
        // set where the solve ends (the loop runs at least once: t_end > t0)
        y: Vec::new(),
        stop: Stop::End,
        stats: Stats::default(),
        events: vec![],
        dense: vec![],
        trajectory: vec![],
        stiffness_detected_at: None,
        switched_at: None,
    };
    if opts.trajectory {
        sol.trajectory.push((t0, y0.to_vec()));
    }
    let mut tracker = events::Tracker::new(&opts.events, t0, y0, n)?;
    let mut next_dense = 0usize;
    // dense times at t0 itself
    while next_dense < opts.dense_times.len() && opts.dense_times[next_dense] <= t0 {
        sol.dense.push((t0, y0.to_vec()));
        next_dense += 1;
    }
    // the dense output's scratch, for events and dense times only (no allocation without them)
    let mut buf = if opts.events.is_empty() && opts.dense_times.is_empty() {
        Vec::new()
    } else {
        vec![0.0; n]
    };
    let mut steps = 0usize;
    while st.t() < t_end {
        if steps >= opts.max_steps {
            return Err(IntegrateError::TooManySteps {
                t: st.t(),
                h: st.h(),
                max_steps: opts.max_steps,
            });
        }
        st.step(sys, t_end)?;
        steps += 1;
        let (ta, tb) = (st.t_old(), st.t());
        let samples_due = next_dense < opts.dense_times.len() && opts.dense_times[next_dense] <= tb;
        // events: the dense output only on a step that may hold a crossing
        let scan = !opts.events.is_empty()
            && (samples_due || tracker.may_cross(&st, ta, tb, &mut buf)? != Some(false));
        if samples_due || scan {
            st.prepare_dense(sys);
        }
        let hit = if scan {
            tracker.scan(&st, ta, tb, &mut buf)?
        } else {
            None
        };
        let stop_at = hit.as_ref().and_then(|h| h.terminal.then_some(h.t));
        let limit = stop_at.unwrap_or(tb);
        while next_dense < opts.dense_times.len() && opts.dense_times[next_dense] <= limit {
            let t = opts.dense_times[next_dense];
            st.dense(t, &mut buf);
            sol.dense.push((t, buf.clone()));
            next_dense += 1;
        }
        for h in tracker.take_hits() {
            sol.events.push(h);
        }
        if let Some(te) = stop_at {
            st.dense(te, &mut buf);
            let index = sol.events.last().map_or(0, |e| e.index);
            sol.t = te;
            sol.y = buf.clone();
            sol.stop = Stop::Event { t: te, index };
            if opts.trajectory {
                sol.trajectory.push((te, buf.clone()));
            }
            sol.stats = st.stats();
            sol.stats.events = sol.events.len();
            return Ok(sol);
        }
        if opts.trajectory {
            sol.trajectory.push((tb, st.y().to_vec()));
        }
        if st.stiff() && sol.stiffness_detected_at.is_none() {
            sol.stiffness_detected_at = Some(tb);
            if auto.is_some() {
                sol.switched_at = Some(tb);
                break;
            }
        }
    }
    sol.t = st.t();
    sol.y = st.y().to_vec();
    sol.stats = st.stats();
    sol.stats.events = sol.events.len();
    Ok(sol)
}

/// Hairer's stiffness test for the explicit pairs: $h|\lambda|$ estimated from the last stage,
/// stiff after 15 consecutive estimates above the stability boundary, reset after 6 below it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct StiffnessTest {
    iasti: u32,
    nonsti: u32,
    /// The test has fired.
    pub stiff: bool,
}

impl StiffnessTest {
    /// One test: `hlamb` $= |h|\,\|f(\hat y) - f(y_s)\|/\|\hat y - y_s\|$ against `boundary`.
    pub fn update(&mut self, stnum: f64, stden: f64, h: f64, boundary: f64) {
        if stden <= 0.0 {
            return;
        }
        if h.abs() * (stnum / stden).sqrt() > boundary {
            self.nonsti = 0;
            self.iasti += 1;
            if self.iasti >= 15 {
                self.stiff = true;
            }
        } else {
            self.nonsti += 1;
            if self.nonsti == 6 {
                self.iasti = 0;
            }
        }
    }
}

/// Where a solve starts, for [`initial_step`]: the time, state and slope there, the method's
/// order, the largest step and the tolerances.
pub(crate) struct Start<'a> {
    pub t: f64,
    pub y: &'a [f64],
    pub f0: &'a [f64],
    pub order: i32,
    pub hmax: f64,
    pub rtol: f64,
    pub atol: f64,
}

/// Hairer's starting step (HINIT): one extra evaluation of `f`, in the work vectors.
pub(crate) fn initial_step<S: OdeSystem>(
    sys: &S,
    start: &Start,
    work_y: &mut [f64],
    work_f: &mut [f64],
) -> f64 {
    let &Start {
        t,
        y,
        f0,
        order,
        hmax,
        rtol,
        atol,
    } = start;
    // sums, not means, as in Hairer's HINIT
    let sk = |i: usize| atol + rtol * y[i].abs();
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..y.len() {
        dnf += (f0[i] / sk(i)).powi(2);
        dny += (y[i] / sk(i)).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(hmax);
    for i in 0..y.len() {
        work_y[i] = y[i] + h * f0[i];
    }
    sys.rhs(t + h, work_y, work_f);
    let der2 = (0..y.len())
        .map(|i| ((work_f[i] - f0[i]) / sk(i)).powi(2))
        .sum::<f64>()
        .sqrt()
        / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / order as f64)
    };
    (100.0 * h).min(h1).min(hmax)
}
