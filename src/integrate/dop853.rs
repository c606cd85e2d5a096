//! DOP853: the explicit Runge-Kutta pair of Dormand and Prince, order 8 with the (5,3) error
//! estimate and a 7th-order dense output (Hairer, Norsett, Wanner, Solving ODEs I, sec. II.10).
//!
//! Step control as in Hairer's code: with $e_5$ and $e_3$ the two error vectors scaled by
//! $s_i = a + r\max(|y_i|, |\hat y_i|)$,
//! $$\mathrm{err} = |h|\,\frac{\|e_5\|^2}{\sqrt{n(\|e_5\|^2 + 0.01\|e_3\|^2)}},\qquad
//!   h_{new} = h / \max(1/6, \min(3, \mathrm{err}^{1/8}/0.9)),$$
//! a rejected step shrinks by $\min(3, \mathrm{err}^{1/8}/0.9)$ and the step after a rejection
//! may not grow. Stiffness: $h|\lambda| \approx |h|\,\|f(\hat y) - f(y_{12})\|/\|\hat y - y_{12}\|
//! > 6.1$ on 15 consecutive tests.
//!
//! Evaluation counts: 2 at start (with the starting step), 12 per accepted and 11 per rejected
//! step, 3 more per step whose dense output is used.

use super::dop853_tableau::{A, C, D, E3, E5};
use super::{IntegrateError, OdeSystem, Options, Stats, Stepper, StiffnessTest, initial_step};

const SAFE: f64 = 0.9;
const FACC1: f64 = 1.0 / 0.333;
const FACC2: f64 = 1.0 / 6.0;

/// The DOP853 stepper; all buffers are allocated in [`Dop853::new`]. `N` is the dimension when
/// it is known at compile time (the stages then live in registers), 0 when it is not.
pub struct Dop853<const N: usize = 0> {
    n: usize,
    t: f64,
    t_old: f64,
    h: f64,
    h_old: f64,
    hmax: f64,
    rtol: f64,
    atol: f64,
    y: Vec<f64>,
    y_old: Vec<f64>,
    y_new: Vec<f64>,
    y_stage: Vec<f64>,
    y12: Vec<f64>,
    /// Stage derivatives, stage `j` at `k[j*n..(j+1)*n]`.
    k: Vec<f64>,
    /// Dense-output coefficients, row `r` at `cont[r*n..(r+1)*n]`.
    cont: Vec<f64>,
    facold: f64,
    reject: bool,
    have_fsal: bool,
    dense_ready: bool,
    stats: Stats,
    stiffness: StiffnessTest,
    fixed: Option<f64>,
}

impl<const N: usize> Dop853<N> {
    /// The dimension: `N` when it is fixed, else the initial state's length.
    #[inline(always)]
    fn dim(&self) -> usize {
        if N == 0 { self.n } else { N }
    }

    /// Prepares a solve from `(t0, y0)`: evaluates $f(t_0, y_0)$ and the starting step.
    pub fn new<S: OdeSystem>(sys: &S, t0: f64, y0: &[f64], t_end: f64, opts: &Options) -> Self {
        let n = y0.len();
        let mut k = vec![0.0; 16 * n];
        sys.rhs(t0, y0, &mut k[..n]);
        let hmax = opts.hmax.unwrap_or(t_end - t0).abs();
        let mut wy = vec![0.0; n];
        let mut wf = vec![0.0; n];
        let h = match opts.fixed_step.or(opts.h0) {
            Some(h) => h,
            None => initial_step(
                sys,
                t0,
                y0,
                &k[..n],
                8,
                hmax,
                opts.rtol,
                opts.atol,
                &mut wy,
                &mut wf,
            ),
        };
        Dop853 {
            n,
            t: t0,
            t_old: t0,
            h,
            h_old: h,
            hmax,
            rtol: opts.rtol,
            atol: opts.atol,
            y: y0.to_vec(),
            y_old: y0.to_vec(),
            y_new: vec![0.0; n],
            y_stage: wy,
            y12: wf,
            k,
            cont: vec![0.0; 7 * n],
            facold: 1e-4,
            reject: false,
            have_fsal: false,
            dense_ready: false,
            stats: Stats {
                rhs_evals: if opts.h0.is_some() { 1 } else { 2 },
                ..Stats::default()
            },
            stiffness: StiffnessTest::default(),
            fixed: opts.fixed_step,
        }
    }
}

/// The storage one step attempt works in.
struct Work<'a> {
    k: &'a mut [f64],
    y: &'a [f64],
    y_stage: &'a mut [f64],
    y12: &'a mut [f64],
    y_new: &'a mut [f64],
}

/// `out = base + h * sum_j A[i][j] k_j`.
#[inline(always)]
fn combine(n: usize, k: &[f64], base: &[f64], row: &[(usize, f64)], h: f64, out: &mut [f64]) {
    for m in 0..n {
        let mut acc = 0.0;
        for &(j, a) in row {
            acc += a * k[j * n + m];
        }
        out[m] = base[m] + h * acc;
    }
}

/// One attempt: stages 2..12 (stage 12's input kept in `y12` for the stiffness test), the new
/// solution and Hairer's error; NaN if the new solution is not finite.
#[inline(always)]
fn attempt<S: OdeSystem>(
    sys: &S,
    n: usize,
    t: f64,
    h: f64,
    rtol: f64,
    atol: f64,
    w: Work<'_>,
) -> f64 {
    let Work {
        k,
        y,
        y_stage,
        y12,
        y_new,
    } = w;
    for (i, ci) in C.iter().enumerate().take(11).skip(1) {
        combine(n, k, y, A[i], h, y_stage);
        sys.rhs(t + ci * h, y_stage, &mut k[i * n..(i + 1) * n]);
    }
    combine(n, k, y, A[11], h, y12);
    sys.rhs(t + C[11] * h, y12, &mut k[11 * n..12 * n]);
    // new solution: row 12 of A holds the weights b
    combine(n, k, y, A[12], h, y_new);
    if y_new.iter().any(|v| !v.is_finite()) {
        return f64::NAN;
    }
    let (mut err5, mut err3) = (0.0, 0.0);
    for m in 0..n {
        let sk = atol + rtol * y[m].abs().max(y_new[m].abs());
        let e5: f64 = E5.iter().map(|&(j, e)| e * k[j * n + m]).sum();
        let e3: f64 = E3.iter().map(|&(j, e)| e * k[j * n + m]).sum();
        err5 += (e5 / sk) * (e5 / sk);
        err3 += (e3 / sk) * (e3 / sk);
    }
    let mut deno = err5 + 0.01 * err3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    h.abs() * err5 * (1.0 / (n as f64 * deno)).sqrt()
}

impl<const N: usize> Stepper for Dop853<N> {
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError> {
        let n = self.dim();
        if self.have_fsal {
            self.k.copy_within(12 * n..13 * n, 0);
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
            let t = self.t;
            let err = if N == 0 {
                let ws = Work {
                    k: &mut self.k,
                    y: &self.y,
                    y_stage: &mut self.y_stage,
                    y12: &mut self.y12,
                    y_new: &mut self.y_new,
                };
                attempt(sys, n, t, h, self.rtol, self.atol, ws)
            } else {
                // a fixed dimension: the stages in local arrays, which the compiler keeps in
                // registers (copied in and out: 1 + 12 stages and the step's states)
                let mut k = [[0.0; N]; 12];
                k[0].copy_from_slice(&self.k[..N]);
                let mut y = [0.0; N];
                y.copy_from_slice(&self.y[..N]);
                let (mut ys, mut y12, mut yn) = ([0.0; N], [0.0; N], [0.0; N]);
                let ws = Work {
                    k: k.as_flattened_mut(),
                    y: &y,
                    y_stage: &mut ys,
                    y12: &mut y12,
                    y_new: &mut yn,
                };
                let err = attempt(sys, n, t, h, self.rtol, self.atol, ws);
                self.k[..12 * N].copy_from_slice(k.as_flattened());
                self.y12[..N].copy_from_slice(&y12);
                self.y_new[..N].copy_from_slice(&yn);
                err
            };
            self.stats.rhs_evals += 11;
            if err.is_nan() && self.y_new.iter().any(|v| !v.is_finite()) {
                return Err(IntegrateError::NonFinite { t: self.t + h });
            }
            let err = if self.fixed.is_some() { 0.0 } else { err };
            // err^(1/8) by three square roots: cheaper than powf, same value to an ulp
            let fac11 = err.sqrt().sqrt().sqrt();
            let fac = (fac11 / SAFE).clamp(FACC2, FACC1);
            let mut h_new = h / fac;
            if err <= 1.0 {
                self.facold = err.max(1e-4);
                let (ynew, t_new) = (&self.y_new, self.t + h);
                sys.rhs(t_new, ynew, &mut self.k[12 * n..13 * n]);
                self.stats.rhs_evals += 1;
                self.stats.steps += 1;
                // stiffness test
                let (mut stnum, mut stden) = (0.0, 0.0);
                for m in 0..n {
                    stnum += (self.k[12 * n + m] - self.k[11 * n + m]).powi(2);
                    stden += (self.y_new[m] - self.y12[m]).powi(2);
                }
                self.stiffness.update(stnum, stden, h, 6.1);
                std::mem::swap(&mut self.y_old, &mut self.y);
                std::mem::swap(&mut self.y, &mut self.y_new);
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
                return Ok(());
            }
            h_new = h / FACC1.min(fac11 / SAFE);
            self.reject = true;
            if self.stats.steps >= 1 {
                self.stats.rejected += 1;
            }
            last = false;
            self.h = h_new;
        }
    }

    fn t_old(&self) -> f64 {
        self.t_old
    }
    fn t(&self) -> f64 {
        self.t
    }
    fn y(&self) -> &[f64] {
        &self.y
    }
    fn h(&self) -> f64 {
        self.h
    }

    fn prepare_dense<S: OdeSystem>(&mut self, sys: &S) {
        if self.dense_ready {
            return;
        }
        let n = self.dim();
        let h = self.h_old;
        // extra stages 13..15 from the old state
        for i in 13..16 {
            combine(n, &self.k, &self.y_old, A[i], h, &mut self.y_stage);
            let t = self.t_old + C[i] * h;
            sys.rhs(t, &self.y_stage, &mut self.k[i * n..(i + 1) * n]);
        }
        self.stats.rhs_evals += 3;
        let k = &self.k;
        for m in 0..n {
            let dy = self.y[m] - self.y_old[m];
            let bspl = h * k[m] - dy;
            self.cont[m] = dy;
            self.cont[n + m] = bspl;
            self.cont[2 * n + m] = dy - h * k[12 * n + m] - bspl;
            for (r, row) in D.iter().enumerate() {
                self.cont[(3 + r) * n + m] =
                    h * row.iter().map(|&(j, d)| d * k[j * n + m]).sum::<f64>();
            }
        }
        self.dense_ready = true;
    }

    fn has_hermite(&self) -> bool {
        true
    }

    fn hermite(&self, t: f64, out: &mut [f64], quad: &mut [f64]) {
        // the first three rows of the dense output: y_old + s(dy + s1(h f_old - dy + s(...)))
        let (n, h) = (self.dim(), self.h_old);
        let s = (t - self.t_old) / h;
        let s1 = 1.0 - s;
        for (m, (o, q)) in out.iter_mut().zip(quad.iter_mut()).enumerate() {
            let dy = self.y[m] - self.y_old[m];
            let c1 = h * self.k[m] - dy;
            let c2 = dy - h * self.k[12 * n + m] - c1;
            *q = self.y_old[m] + s * (dy + s1 * c1);
            *o = *q + s * s1 * s * c2;
        }
    }

    fn dense(&self, t: f64, out: &mut [f64]) {
        let h = self.h_old;
        let s = (t - self.t_old) / h;
        let s1 = 1.0 - s;
        for (m, o) in out.iter_mut().enumerate() {
            let n = self.n;
            let c = |r: usize| self.cont[r * n + m];
            // y = y_old + s(c0 + s1(c1 + s(c2 + s1(c3 + s(c4 + s1(c5 + s c6))))))
            let inner = c(3) + s * (c(4) + s1 * (c(5) + s * c(6)));
            *o = self.y_old[m] + s * (c(0) + s1 * (c(1) + s * (c(2) + s1 * inner)));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn stiff(&self) -> bool {
        self.stiffness.stiff
    }
}
