//! DOPRI5: the Dormand-Prince 5(4) pair with Shampine's 4th-order dense output (Hairer,
//! Norsett, Wanner, Solving ODEs I, sec. II.5 and II.6).
//!
//! Step control as in Hairer's code, a PI controller with $\beta = 0.04$:
//! $$\mathrm{err} = \sqrt{\tfrac1n\sum_i (e_i/s_i)^2},\quad
//!   f = \frac{\mathrm{err}^{0.2 - 0.75\beta}}{\mathrm{err}_{old}^{\beta}},\quad
//!   h_{new} = h/\max(1/10, \min(5, f/0.9)).$$
//! Stiffness: $|h|\,\|k_7 - k_6\|/\|\hat y - y_6\| > 3.25$ on 15 consecutive tests. Evaluation
//! counts: 2 at start, 6 per step (first same as last).

use super::{IntegrateError, OdeSystem, Options, Stats, Stepper, StiffnessTest, initial_step};

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [&[f64]; 7] = [
    &[],
    &[0.2],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
const DENSE: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];
const SAFE: f64 = 0.9;
const FACC1: f64 = 1.0 / 0.2;
const FACC2: f64 = 1.0 / 10.0;
const BETA: f64 = 0.04;
/// ln 1e-4: the least `facold` of Hairer's controller.
const LN_FACOLD_MIN: f64 = -9.210_340_371_976_182;

/// The DOPRI5 stepper. `N` is the dimension when it is known at compile time (the stage loops
/// then unroll and lose their bounds checks: 15 % of a step at n = 2), 0 when it is not.
pub struct Dopri5<const N: usize = 0> {
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
    y6: Vec<f64>,
    /// The seven stages, flat: stage j at `[j n, (j+1) n)`.
    k: Vec<f64>,
    cont: Vec<Vec<f64>>,
    /// ln of Hairer's `facold` (the last accepted error, at least 1e-4).
    ln_facold: f64,
    reject: bool,
    have_fsal: bool,
    dense_ready: bool,
    stats: Stats,
    stiffness: StiffnessTest,
    fixed: Option<f64>,
}

impl<const N: usize> Dopri5<N> {
    /// The dimension: `N` when it is fixed, else the initial state's length.
    #[inline(always)]
    fn dim(&self) -> usize {
        if N == 0 { self.n } else { N }
    }

    /// Prepares a solve.
    pub fn new<S: OdeSystem>(sys: &S, t0: f64, y0: &[f64], t_end: f64, opts: &Options) -> Self {
        let n = y0.len();
        let mut k = vec![0.0; 7 * n];
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
                5,
                hmax,
                opts.rtol,
                opts.atol,
                &mut wy,
                &mut wf,
            ),
        };
        Dopri5 {
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
            y6: wf,
            k,
            cont: vec![vec![0.0; n]; 4],
            ln_facold: LN_FACOLD_MIN,
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
    y6: &'a mut [f64],
    y_new: &'a mut [f64],
}

/// One attempt: the six stages, the new solution and its slope (first same as last: stage 7),
/// and the scaled RMS error; NaN if the new solution is not finite.
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
    // each row of A a fixed-size array so that its sum unrolls
    #[inline(always)]
    fn row<const J: usize>(n: usize, k: &[f64], y: &[f64], a: [f64; J], h: f64, out: &mut [f64]) {
        for m in 0..n {
            let mut acc = 0.0;
            for (j, aj) in a.iter().enumerate() {
                acc += aj * k[j * n + m];
            }
            out[m] = y[m] + h * acc;
        }
    }
    let Work {
        k,
        y,
        y_stage,
        y6,
        y_new,
    } = w;
    row(n, k, y, [A[1][0]], h, y_stage);
    sys.rhs(t + C[1] * h, y_stage, &mut k[n..2 * n]);
    row(n, k, y, [A[2][0], A[2][1]], h, y_stage);
    sys.rhs(t + C[2] * h, y_stage, &mut k[2 * n..3 * n]);
    row(n, k, y, [A[3][0], A[3][1], A[3][2]], h, y_stage);
    sys.rhs(t + C[3] * h, y_stage, &mut k[3 * n..4 * n]);
    row(n, k, y, [A[4][0], A[4][1], A[4][2], A[4][3]], h, y_stage);
    sys.rhs(t + C[4] * h, y_stage, &mut k[4 * n..5 * n]);
    // stage 6's input is kept for the stiffness test
    row(
        n,
        k,
        y,
        [A[5][0], A[5][1], A[5][2], A[5][3], A[5][4]],
        h,
        y6,
    );
    sys.rhs(t + h, y6, &mut k[5 * n..6 * n]);
    let b = [A[6][0], A[6][1], A[6][2], A[6][3], A[6][4], A[6][5]];
    row(n, k, y, b, h, y_new);
    if y_new.iter().any(|v| !v.is_finite()) {
        return f64::NAN;
    }
    sys.rhs(t + h, y_new, &mut k[6 * n..7 * n]);
    let mut err = 0.0;
    for m in 0..n {
        let sk = atol + rtol * y[m].abs().max(y_new[m].abs());
        let e: f64 = h * (0..7).map(|j| E[j] * k[j * n + m]).sum::<f64>();
        err += (e / sk) * (e / sk);
    }
    (err / n as f64).sqrt()
}

impl<const N: usize> Stepper for Dopri5<N> {
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError> {
        let n = self.dim();
        if self.have_fsal {
            self.k.copy_within(6 * n..7 * n, 0);
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
                    y6: &mut self.y6,
                    y_new: &mut self.y_new,
                };
                attempt(sys, n, t, h, self.rtol, self.atol, ws)
            } else {
                // a fixed dimension: the stages in local arrays, which the compiler keeps in
                // registers (the step's own state is copied in and out, 2 + 7 n numbers)
                let mut k = [[0.0; N]; 7];
                k[0].copy_from_slice(&self.k[..N]);
                let mut y = [0.0; N];
                y.copy_from_slice(&self.y[..N]);
                let (mut ys, mut y6, mut yn) = ([0.0; N], [0.0; N], [0.0; N]);
                let ws = Work {
                    k: k.as_flattened_mut(),
                    y: &y,
                    y_stage: &mut ys,
                    y6: &mut y6,
                    y_new: &mut yn,
                };
                let err = attempt(sys, n, t, h, self.rtol, self.atol, ws);
                self.k[..7 * N].copy_from_slice(k.as_flattened());
                self.y6[..N].copy_from_slice(&y6);
                self.y_new[..N].copy_from_slice(&yn);
                err
            };
            self.stats.rhs_evals += 6;
            if !err.is_finite() && self.y_new.iter().any(|v| !v.is_finite()) {
                return Err(IntegrateError::NonFinite { t: self.t + h });
            }
            let err = if self.fixed.is_some() { 0.0 } else { err };
            // err^(0.2 - 0.75 beta) / facold^beta as one exponential, with ln facold kept from
            // the last accepted step: one ln and one exp per step instead of two powf
            let ln_err = err.ln();
            let fac = ((0.2 - BETA * 0.75) * ln_err - BETA * self.ln_facold).exp();
            let fac = (fac / SAFE).clamp(FACC2, FACC1);
            let mut h_new = h / fac;
            if err <= 1.0 {
                self.ln_facold = ln_err.max(LN_FACOLD_MIN);
                self.stats.steps += 1;
                // Hairer's schedule (NSTIFF = 1000): every 1000th step, and every step once an
                // estimate has come out stiff (DOPRI5 is not the first stage of Auto, which uses
                // DOP853, so only the warning's timing depends on it)
                if self.stats.steps.is_multiple_of(1000) || self.stiffness.iasti > 0 {
                    let (mut stnum, mut stden) = (0.0, 0.0);
                    for m in 0..n {
                        stnum += (self.k[6 * n + m] - self.k[5 * n + m]).powi(2);
                        stden += (self.y_new[m] - self.y6[m]).powi(2);
                    }
                    self.stiffness.update(stnum, stden, h, 3.25);
                }
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
            let fac11 = ((0.2 - BETA * 0.75) * ln_err).exp();
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

    fn prepare_dense<S: OdeSystem>(&mut self, _sys: &S) {
        if self.dense_ready {
            return;
        }
        let (h, n) = (self.h_old, self.dim());
        for m in 0..n {
            let dy = self.y[m] - self.y_old[m];
            let bspl = h * self.k[m] - dy;
            self.cont[0][m] = dy;
            self.cont[1][m] = bspl;
            self.cont[2][m] = dy - h * self.k[6 * n + m] - bspl;
            self.cont[3][m] = h * (0..7).map(|j| DENSE[j] * self.k[j * n + m]).sum::<f64>();
        }
        self.dense_ready = true;
    }

    fn dense(&self, t: f64, out: &mut [f64]) {
        let s = (t - self.t_old) / self.h_old;
        let s1 = 1.0 - s;
        for (m, o) in out.iter_mut().enumerate() {
            let c = |r: usize| self.cont[r][m];
            *o = self.y_old[m] + s * (c(0) + s1 * (c(1) + s * (c(2) + s1 * c(3))));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn stiff(&self) -> bool {
        self.stiffness.stiff
    }
}
