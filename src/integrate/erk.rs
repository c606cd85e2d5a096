//! One driver for the explicit Runge-Kutta pairs: DOPRI5 ([`super::dopri5`]) and DOP853
//! ([`super::dop853`]) differ only in their tableau (stages and error estimate, [`Tableau::attempt`]),
//! the step-size factor of their controller ([`Tableau::factor`]) and their dense output; the
//! step loop (step-size control, rejection, the stiffness test, first-same-as-last, fixed steps)
//! is written once here, after Hairer's codes (Solving ODEs I, sec. II.4 and II.10).
//!
//! The driver is generic over the tableau, so each method is compiled with its own stages
//! inlined into the loop: one driver costs nothing at run time.

use super::{
    IntegrateError, OdeSystem, Options, Start, Stats, Stepper, StiffnessTest, initial_step,
};
use std::marker::PhantomData;

/// Hairer's safety factor.
const SAFE: f64 = 0.9;

/// The storage one step attempt works in.
pub(crate) struct Work<'a> {
    /// The stage slopes, flat: stage j at `[j n, (j+1) n)`.
    pub k: &'a mut [f64],
    /// The state at the start of the step.
    pub y: &'a [f64],
    /// A stage's input.
    pub y_stage: &'a mut [f64],
    /// The input of the last stage before the solution (kept for the stiffness test).
    pub y_last: &'a mut [f64],
    /// The new solution.
    pub y_new: &'a mut [f64],
}

/// What makes a pair: its tableau, error estimate, controller exponent and dense output.
pub(crate) trait Tableau: Sized {
    /// Slopes stored per step (the stages, f at the new point, the dense-output stages).
    const STORED: usize;
    /// The slot of f at the new solution (first same as last); the slot before it holds f at
    /// [`Work::y_last`], which the stiffness test compares with it.
    const FSAL: usize;
    /// Whether the attempt evaluates f at the new solution (its error estimate uses it) or the
    /// driver does once the step is accepted.
    const FSAL_IN_ATTEMPT: bool;
    /// Evaluations per attempt.
    const EVALS: usize;
    /// The order given to the starting-step heuristic.
    const ORDER: i32;
    /// The largest and smallest factor h / h_new (Hairer's FACC1 and FACC2).
    const FACC1: f64;
    /// See [`Tableau::FACC1`].
    const FACC2: f64;
    /// The stiffness boundary of |h lambda|.
    const STIFF_BOUNDARY: f64;
    /// Rows of the dense output's coefficients.
    const DENSE_ROWS: usize;
    /// The controller's memory at the start ([`Tableau::factor`]).
    const MEMORY0: f64;
    /// Whether event location may use the step's cubic Hermite interpolant
    /// ([`Stepper::hermite_parts`]) before the dense output.
    const HERMITE: bool;
    /// One attempt: the stages, the new solution and the scaled error (NaN if the new solution
    /// is not finite). `N` as in [`Erk`].
    fn attempt<S: OdeSystem, const N: usize>(
        sys: &S,
        t: f64,
        h: f64,
        tol: (f64, f64),
        b: &mut Buffers,
    ) -> f64;
    /// The factor h / h_new before the safety factor and the clamp, from the error and the
    /// controller's memory; and the memory kept if the step is accepted.
    fn factor(err: f64, memory: f64) -> (f64, f64);
    /// The factor on a rejected step (before the safety factor).
    fn reject_factor(err: f64) -> f64;
    /// Whether the stiffness test runs after this accepted step.
    fn stiffness_due(steps: usize, test: &StiffnessTest) -> bool;
    /// Fills the dense output's coefficients of the last step.
    fn prepare_dense<S: OdeSystem, const N: usize>(e: &mut Erk<Self, N>, sys: &S);
    /// The dense output at `t` in the last step.
    fn dense<const N: usize>(e: &Erk<Self, N>, t: f64, out: &mut [f64]);
}

/// The body of [`Tableau::attempt`] for a tableau of `$stages` stages whose attempt on a
/// [`Work`] is the function `$attempt(sys, n, t, h, tol, work)`: on the buffers when the
/// dimension is known only at run time, on local arrays ([`Buffers::on_stack`]) when it is fixed.
macro_rules! attempt_on_stack {
    ($stages:literal, $attempt:ident) => {
        #[inline(always)]
        fn attempt<S: OdeSystem, const M: usize>(
            sys: &S,
            t: f64,
            h: f64,
            tol: (f64, f64),
            b: &mut Buffers,
        ) -> f64 {
            if M == 0 {
                $attempt(sys, b.n, t, h, tol, b.work())
            } else {
                b.on_stack::<M, $stages>(|w| $attempt(sys, M, t, h, tol, w))
            }
        }
    };
}
pub(crate) use attempt_on_stack;

/// The vectors of a stepper.
pub(crate) struct Buffers {
    pub n: usize,
    pub y: Vec<f64>,
    pub y_old: Vec<f64>,
    pub y_new: Vec<f64>,
    pub y_stage: Vec<f64>,
    pub y_last: Vec<f64>,
    pub k: Vec<f64>,
}

impl Buffers {
    /// The attempt's storage in the buffers (a dimension known only at run time).
    #[inline(always)]
    pub fn work(&mut self) -> Work<'_> {
        Work {
            k: &mut self.k,
            y: &self.y,
            y_stage: &mut self.y_stage,
            y_last: &mut self.y_last,
            y_new: &mut self.y_new,
        }
    }

    /// Runs `f` on local arrays of `K` stages of dimension `N` (which the compiler keeps in
    /// registers: 15 % of a step at n = 2), copying the step's own state in and out.
    #[inline(always)]
    pub fn on_stack<const N: usize, const K: usize>(
        &mut self,
        f: impl FnOnce(Work<'_>) -> f64,
    ) -> f64 {
        let mut k = [[0.0; N]; K];
        k[0].copy_from_slice(&self.k[..N]);
        let mut y = [0.0; N];
        y.copy_from_slice(&self.y[..N]);
        let (mut ys, mut yl, mut yn) = ([0.0; N], [0.0; N], [0.0; N]);
        let err = f(Work {
            k: k.as_flattened_mut(),
            y: &y,
            y_stage: &mut ys,
            y_last: &mut yl,
            y_new: &mut yn,
        });
        self.k[..K * N].copy_from_slice(k.as_flattened());
        self.y_last[..N].copy_from_slice(&yl);
        self.y_new[..N].copy_from_slice(&yn);
        err
    }
}

/// An explicit Runge-Kutta stepper with the tableau `T`. `N` is the dimension when it is known
/// at compile time (the stage loops then unroll and lose their bounds checks), 0 when it is not.
pub(crate) struct Erk<T: Tableau, const N: usize> {
    pub(super) b: Buffers,
    pub(super) t: f64,
    pub(super) t_old: f64,
    pub(super) h: f64,
    pub(super) h_old: f64,
    hmax: f64,
    rtol: f64,
    atol: f64,
    /// The dense output's coefficients, flat: row r at `[r n, (r+1) n)`.
    pub(super) cont: Vec<f64>,
    /// The controller's memory ([`Tableau::factor`]).
    memory: f64,
    reject: bool,
    have_fsal: bool,
    pub(super) dense_ready: bool,
    pub(super) stats: Stats,
    stiffness: StiffnessTest,
    fixed: Option<f64>,
    tableau: PhantomData<T>,
}

impl<T: Tableau, const N: usize> Erk<T, N> {
    /// The dimension: `N` when it is fixed, else the initial state's length.
    #[inline(always)]
    pub(super) fn dim(&self) -> usize {
        if N == 0 { self.b.n } else { N }
    }

    /// Prepares a solve.
    pub(crate) fn new<S: OdeSystem>(
        sys: &S,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        opts: &Options,
    ) -> Self {
        let n = y0.len();
        let mut k = vec![0.0; T::STORED * n];
        sys.rhs(t0, y0, &mut k[..n]);
        let hmax = opts.hmax.unwrap_or(t_end - t0).abs();
        let mut wy = vec![0.0; n];
        let mut wf = vec![0.0; n];
        let h = match opts.fixed_step.or(opts.h0) {
            Some(h) => h,
            None => {
                let start = Start {
                    t: t0,
                    y: y0,
                    f0: &k[..n],
                    order: T::ORDER,
                    hmax,
                    rtol: opts.rtol,
                    atol: opts.atol,
                };
                initial_step(sys, &start, &mut wy, &mut wf)
            }
        };
        Erk {
            b: Buffers {
                n,
                y: y0.to_vec(),
                y_old: y0.to_vec(),
                y_new: vec![0.0; n],
                y_stage: wy,
                y_last: wf,
                k,
            },
            t: t0,
            t_old: t0,
            h,
            h_old: h,
            hmax,
            rtol: opts.rtol,
            atol: opts.atol,
            cont: vec![0.0; T::DENSE_ROWS * n],
            memory: T::MEMORY0,
            reject: false,
            have_fsal: false,
            dense_ready: false,
            stats: Stats {
                rhs_evals: if opts.h0.is_some() { 1 } else { 2 },
                ..Stats::default()
            },
            stiffness: StiffnessTest::default(),
            fixed: opts.fixed_step,
            tableau: PhantomData,
        }
    }

    /// Takes the accepted step of size `h` (the last one to `t_end` if `last`), whose solution
    /// is in the buffers, with `h_new` the next step size proposed.
    fn accept<S: OdeSystem>(&mut self, sys: &S, h: f64, mut h_new: f64, last: bool, t_end: f64) {
        let n = self.dim();
        let (fsal, b) = (T::FSAL * n, &mut self.b);
        if !T::FSAL_IN_ATTEMPT {
            sys.rhs(self.t + h, &b.y_new, &mut b.k[fsal..fsal + n]);
            self.stats.rhs_evals += 1;
        }
        self.stats.steps += 1;
        if T::stiffness_due(self.stats.steps, &self.stiffness) {
            let (mut stnum, mut stden) = (0.0, 0.0);
            for m in 0..n {
                stnum += (b.k[fsal + m] - b.k[fsal - n + m]).powi(2);
                stden += (b.y_new[m] - b.y_last[m]).powi(2);
            }
            self.stiffness.update(stnum, stden, h, T::STIFF_BOUNDARY);
        }
        std::mem::swap(&mut b.y_old, &mut b.y);
        std::mem::swap(&mut b.y, &mut b.y_new);
        self.t_old = self.t;
        self.t = if last { t_end } else { self.t + h };
        self.h_old = h;
        if h_new.abs() > self.hmax {
            h_new = self.hmax;
        }
        if self.reject {
            h_new = h_new.min(h);
        }
        if let Some(hf) = self.fixed {
            h_new = hf;
        }
        self.reject = false;
        self.have_fsal = true;
        self.dense_ready = false;
        self.h = h_new;
    }
}

impl<T: Tableau, const N: usize> Stepper for Erk<T, N> {
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError> {
        let n = self.dim();
        if self.have_fsal {
            self.b.k.copy_within(T::FSAL * n..(T::FSAL + 1) * n, 0);
        }
        let mut last = false;
        loop {
            let mut h = self.h;
            if 0.1 * h.abs() <= self.t.abs() * f64::EPSILON {
                return Err(IntegrateError::StepSizeTooSmall { t: self.t, h });
            }
            if self.t + 1.01 * h - t_end > 0.0 {
                h = t_end - self.t;
                last = true;
            }
            let err = T::attempt::<S, N>(sys, self.t, h, (self.rtol, self.atol), &mut self.b);
            self.stats.rhs_evals += T::EVALS;
            if !err.is_finite() && self.b.y_new.iter().any(|v| !v.is_finite()) {
                return Err(IntegrateError::NonFinite { t: self.t + h });
            }
            let err = if self.fixed.is_some() { 0.0 } else { err };
            let (fac, memory) = T::factor(err, self.memory);
            let fac = (fac / SAFE).clamp(T::FACC2, T::FACC1);
            if err <= 1.0 {
                self.memory = memory;
                self.accept(sys, h, h / fac, last, t_end);
                return Ok(());
            }
            self.h = h / T::FACC1.min(T::reject_factor(err) / SAFE);
            self.reject = true;
            if self.stats.steps >= 1 {
                self.stats.rejected += 1;
            }
            last = false;
        }
    }

    fn t_old(&self) -> f64 {
        self.t_old
    }
    fn t(&self) -> f64 {
        self.t
    }
    fn y(&self) -> &[f64] {
        &self.b.y
    }
    fn h(&self) -> f64 {
        self.h
    }

    fn prepare_dense<S: OdeSystem>(&mut self, sys: &S) {
        if !self.dense_ready {
            T::prepare_dense(self, sys);
            self.dense_ready = true;
        }
    }

    fn has_hermite(&self) -> bool {
        T::HERMITE
    }

    fn hermite_parts(&self, parts: &mut [f64]) -> f64 {
        let (n, h, b) = (self.dim(), self.h_old, &self.b);
        let (y0, rest) = parts.split_at_mut(n);
        let (dy, rest) = rest.split_at_mut(n);
        let (c1, c2) = rest.split_at_mut(n);
        for m in 0..n {
            y0[m] = b.y_old[m];
            dy[m] = b.y[m] - b.y_old[m];
            c1[m] = h * b.k[m] - dy[m];
            c2[m] = dy[m] - h * b.k[T::FSAL * n + m] - c1[m];
        }
        h
    }

    fn dense(&self, t: f64, out: &mut [f64]) {
        T::dense(self, t, out);
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn stiff(&self) -> bool {
        self.stiffness.stiff
    }
}
