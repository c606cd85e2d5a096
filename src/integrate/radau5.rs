//! RADAU5: the 3-stage Radau IIA collocation method of order 5 (Hairer and Wanner, Solving ODEs
//! II, sec. IV.8), for stiff systems.
//!
//! The stage increments $Z = (Y_i - y_0)$ solve $Z = h(A\otimes I)F(Z)$ by simplified Newton in
//! the variables $W = (T^{-1}\otimes I)Z$, with $T^{-1}A^{-1}T = \mathrm{diag}(\gamma,
//! \begin{smallmatrix}\alpha&-\beta\\\beta&\alpha\end{smallmatrix})$, so each iteration solves one
//! real system with $\gamma/h - J$ and one complex system with $(\alpha + i\beta)/h - J$ (LU with
//! partial pivoting, factored and solved in place in the stepper's workspace, as Hairer's
//! DEC/DECC and SOL/SOLC do: written by hand because nalgebra's `LU` takes its matrix by value and
//! allocates a permutation per factorisation, and a stiff solve refactors on most steps; no
//! allocation after the stepper is built). Tolerances are used as given (Hairer transforms them to $r' = 0.1 r^{2/3}$, which at
//! tight tolerances lets the global error grow three orders past the request), the Newton stopping
//! criterion is $\theta/(1-\theta)\,\|\Delta W\| \le \kappa$, the error estimate is
//! $(\gamma/h - J)^{-1}[f(y_0) + (d_1 Z_1 + d_2 Z_2 + d_3 Z_3)/h]$ (re-filtered once after a
//! rejection), and the step size follows Gustafsson's predictive controller. Jacobians are reused
//! while Newton converges fast ($\theta \le 0.001$) and, as Hairer's `CALJAC` has it, by every
//! retry of a step for which one was computed; the LU is kept when the step barely changes.
//! Dense output is the collocation polynomial.

use super::{IntegrateError, OdeSystem, Options, Stats, Stepper, rms};
use nalgebra::{Complex, DMatrix};
use num_traits::Zero;
use std::ops::{Div, Mul, Sub};

const NIT: usize = 7;
const SAFE: f64 = 0.9;
const THET: f64 = 0.001;
/// Hairer's RADAU5 default rounding unit (`UROUND = 1.0D-16`), used where his code uses it: the
/// Newton tolerance, the finite-difference increment, the smallest step; with it the counts of
/// evaluations equal his (f64::EPSILON = 2.2e-16 loosened the Newton tolerance at tight rtol).
const UROUND: f64 = 1e-16;
const FACL: f64 = 5.0;
const FACR: f64 = 1.0 / 8.0;
const QUOT1: f64 = 1.0;
const QUOT2: f64 = 1.2;

// T and its inverse (Hairer's RADAU5, 20 digits as published); checked in the tests against
// A^{-1} of Radau IIA.
#[allow(clippy::excessive_precision)]
const T: [[f64; 3]; 3] = [
    [
        9.123_239_487_089_294_3e-2,
        -0.141_255_295_020_954_2,
        -3.002_919_410_514_742_4e-2,
    ],
    [
        0.241_717_932_707_107_02,
        0.204_129_352_293_799_93,
        0.382_942_112_757_261_94,
    ],
    [0.966_048_182_615_092_9, 1.0, 0.0],
];
#[allow(clippy::excessive_precision)]
const TI: [[f64; 3]; 3] = [
    [
        4.325_579_890_063_155,
        0.339_199_251_815_809_87,
        0.541_770_539_935_874_9,
    ],
    [
        -4.178_718_591_551_905,
        -0.327_682_820_761_062_4,
        0.476_623_554_500_550_45,
    ],
    [
        -0.502_872_634_945_786_9,
        2.571_926_949_855_605_4,
        -0.596_039_204_828_224_9,
    ],
];

#[derive(Clone, Copy)]
struct Consts {
    c1: f64,
    c2: f64,
    c1m1: f64,
    c2m1: f64,
    c1mc2: f64,
    dd: [f64; 3],
    u1: f64,
    alph: f64,
    beta: f64,
}

fn consts() -> Consts {
    let sq6 = 6f64.sqrt();
    let c1 = (4.0 - sq6) / 10.0;
    let c2 = (4.0 + sq6) / 10.0;
    let cbrt81 = 81f64.cbrt();
    let cbrt9 = 9f64.cbrt();
    let u1 = (6.0 + cbrt81 - cbrt9) / 30.0;
    let alph = (12.0 - cbrt81 + cbrt9) / 60.0;
    let beta = (cbrt81 + cbrt9) * 3f64.sqrt() / 60.0;
    let cno = alph * alph + beta * beta;
    Consts {
        c1,
        c2,
        c1m1: c1 - 1.0,
        c2m1: c2 - 1.0,
        c1mc2: c1 - c2,
        dd: [
            -(13.0 + 7.0 * sq6) / 3.0,
            (-13.0 + 7.0 * sq6) / 3.0,
            -1.0 / 3.0,
        ],
        u1: 1.0 / u1,
        alph: alph / cno,
        beta: beta / cno,
    }
}

/// Factors the row-major `n x n` matrix `a` in place with partial pivoting (the row of the
/// largest `mag` in each column), as LINPACK's DGEFA and Hairer's DEC/DECC: `a` holds `U` and
/// the multipliers of `L`, `piv[k]` the row exchanged with row `k` at step `k` (only the columns
/// from `k` on are exchanged, so [`lu_solve`] applies exchange and elimination step by step).
/// False when a pivot is exactly zero (singular).
fn lu_factor<T>(a: &mut [T], piv: &mut [usize], n: usize, mag: fn(&T) -> f64) -> bool
where
    T: Copy + Zero + Sub<Output = T> + Mul<Output = T> + Div<Output = T>,
{
    for k in 0..n {
        let (mut p, mut best) = (k, mag(&a[k * n + k]));
        for i in k + 1..n {
            let m = mag(&a[i * n + k]);
            if m > best {
                (p, best) = (i, m);
            }
        }
        piv[k] = p;
        if best <= 0.0 || best.is_nan() {
            return false;
        }
        if p != k {
            for j in k..n {
                a.swap(k * n + j, p * n + j);
            }
        }
        let pivot = a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] / pivot;
            a[i * n + k] = f;
            if !f.is_zero() {
                for j in k + 1..n {
                    a[i * n + j] = a[i * n + j] - f * a[k * n + j];
                }
            }
        }
    }
    true
}

/// Solves `A x = b` in place with the factors of [`lu_factor`].
fn lu_solve<T>(a: &[T], piv: &[usize], n: usize, b: &mut [T])
where
    T: Copy + Sub<Output = T> + Mul<Output = T> + Div<Output = T>,
{
    for k in 0..n {
        if piv[k] != k {
            b.swap(k, piv[k]);
        }
        let bk = b[k];
        for i in k + 1..n {
            b[i] = b[i] - a[i * n + k] * bk;
        }
    }
    for k in (0..n).rev() {
        let mut s = b[k];
        for j in k + 1..n {
            s = s - a[k * n + j] * b[j];
        }
        b[k] = s / a[k * n + k];
    }
}

/// The Radau5 stepper.
pub struct Radau5 {
    n: usize,
    k: Consts,
    t: f64,
    t_old: f64,
    h: f64,
    h_old: f64,
    hmax: f64,
    rtol: f64,
    atol: f64,
    fnewt: f64,
    y: Vec<f64>,
    f0: Vec<f64>,
    scal: Vec<f64>,
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    cont: [Vec<f64>; 4],
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
    f1: Vec<f64>,
    jac: DMatrix<f64>,
    /// $\gamma/h - J$, factored in place (row-major), and its pivots.
    lu_real: Vec<f64>,
    piv_real: Vec<usize>,
    /// $(\alpha + i\beta)/h - J$, factored in place, and its pivots.
    lu_cplx: Vec<Complex<f64>>,
    piv_cplx: Vec<usize>,
    /// Whether the factors are there (a first decomposition was made).
    factored: bool,
    rhs_cplx: Vec<Complex<f64>>,
    /// Whether the next attempt may use the stored Jacobian as it is.
    jac_current: bool,
    /// Whether a Jacobian was computed since the last accepted step (Hairer's `CALJAC`): a
    /// rejected attempt, or a failed Newton iteration or factorisation, reuses the Jacobian
    /// when it was, and computes a new one when the one it has is from an earlier step.
    caljac: bool,
    lu_h: f64,
    first: bool,
    reject: bool,
    theta: f64,
    faccon: f64,
    hacc: f64,
    erracc: f64,
    nsing: u32,
    /// The step the controller proposed at the last accepted step (before the factorisation is
    /// kept with the old one): Hairer decides the last step to the interval's end with it.
    h_proposed: f64,
    stats: Stats,
    fixed: Option<f64>,
}

impl Radau5 {
    /// Prepares a solve.
    pub fn new<S: OdeSystem>(sys: &S, t0: f64, y0: &[f64], t_end: f64, opts: &Options) -> Self {
        let n = y0.len();
        // the tolerances as given (SciPy's Radau does the same); Hairer's RADAU5 loosens them to
        // 0.1 rtol^(2/3), which at rtol = 1e-12 is an internal 1e-9 and a global error near 1e-7
        // on the long pendulum (issue 17)
        let rtol = opts.rtol;
        let atol = opts.atol;
        let fnewt = (10.0 * UROUND / rtol).max(0.03f64.min(rtol.sqrt()));
        let mut f0 = vec![0.0; n];
        sys.rhs(t0, y0, &mut f0);
        let hmax = opts.hmax.unwrap_or(t_end - t0).abs();
        let h = opts.fixed_step.or(opts.h0).unwrap_or(1e-6).min(hmax);
        let v = || vec![0.0; n];
        Radau5 {
            n,
            k: consts(),
            t: t0,
            t_old: t0,
            h,
            h_old: h,
            hmax,
            rtol,
            atol,
            fnewt,
            y: y0.to_vec(),
            f0,
            scal: y0.iter().map(|v| atol + rtol * v.abs()).collect(),
            z: [v(), v(), v()],
            w: [v(), v(), v()],
            cont: [y0.to_vec(), v(), v(), v()],
            tmp: v(),
            tmp2: v(),
            f1: v(),
            jac: DMatrix::zeros(n, n),
            lu_real: vec![0.0; n * n],
            piv_real: vec![0; n],
            lu_cplx: vec![Complex::new(0.0, 0.0); n * n],
            piv_cplx: vec![0; n],
            factored: false,
            rhs_cplx: vec![Complex::new(0.0, 0.0); n],
            jac_current: false,
            caljac: false,
            lu_h: f64::NAN,
            first: true,
            reject: false,
            theta: 0.0,
            faccon: 1.0,
            hacc: h,
            erracc: 1e-2,
            nsing: 0,
            // Hairer's first test: x + 1.0001 h >= xend
            h_proposed: 1.0001 * QUOT1 * h,
            stats: Stats {
                rhs_evals: 1,
                ..Stats::default()
            },
            fixed: opts.fixed_step,
        }
    }

    fn jacobian<S: OdeSystem>(&mut self, sys: &S) {
        self.stats.jac_evals += 1;
        if !sys.jacobian(self.t, &self.y, &mut self.jac) {
            for i in 0..self.n {
                let ysafe = self.y[i];
                let delt = (UROUND * 1e-5f64.max(ysafe.abs())).sqrt();
                self.y[i] = ysafe + delt;
                sys.rhs(self.t, &self.y, &mut self.tmp);
                for j in 0..self.n {
                    self.jac[(j, i)] = (self.tmp[j] - self.f0[j]) / delt;
                }
                self.y[i] = ysafe;
            }
            self.stats.rhs_evals += self.n;
        }
        self.jac_current = true;
        self.caljac = true;
    }

    /// Factorises $\gamma/h - J$ and $(\alpha+i\beta)/h - J$; false if singular.
    fn decompose(&mut self, h: f64) -> bool {
        let n = self.n;
        let fac1 = self.k.u1 / h;
        let (alphn, betan) = (self.k.alph / h, self.k.beta / h);
        for i in 0..n {
            for j in 0..n {
                let d = if i == j { 1.0 } else { 0.0 };
                self.lu_real[i * n + j] = d * fac1 - self.jac[(i, j)];
                self.lu_cplx[i * n + j] = Complex::new(d * alphn - self.jac[(i, j)], d * betan);
            }
        }
        self.stats.lu_decomps += 2;
        let ok = lu_factor(&mut self.lu_real, &mut self.piv_real, n, |x| x.abs())
            && lu_factor(&mut self.lu_cplx, &mut self.piv_cplx, n, |z| {
                z.re.abs() + z.im.abs()
            });
        self.factored = true;
        self.lu_h = h;
        ok
    }

    fn solve_real(&mut self, v: &mut [f64]) {
        if self.factored {
            lu_solve(&self.lu_real, &self.piv_real, self.n, v);
        }
    }

    /// One attempt at a step of size `h`; `Ok(Some((err, newton_iterations)))` when Newton
    /// converged, `Ok(None)` when it failed and the step must be retried with the (already
    /// reduced) `self.h`.
    fn attempt<S: OdeSystem>(
        &mut self,
        sys: &S,
        h: f64,
    ) -> Result<Option<(f64, usize)>, IntegrateError> {
        let n = self.n;
        let k = self.k;
        let (c1, c2) = (k.c1, k.c2);
        // starting values
        if self.first {
            for i in 0..3 {
                self.z[i].fill(0.0);
                self.w[i].fill(0.0);
            }
        } else {
            let c3q = h / self.h_old;
            let (c1q, c2q) = (c1 * c3q, c2 * c3q);
            for m in 0..n {
                let (ak1, ak2, ak3) = (self.cont[1][m], self.cont[2][m], self.cont[3][m]);
                let ext = |cq: f64| cq * (ak1 + (cq - k.c2m1) * (ak2 + (cq - k.c1m1) * ak3));
                let zz = [ext(c1q), ext(c2q), ext(c3q)];
                for i in 0..3 {
                    self.z[i][m] = zz[i];
                }
                for i in 0..3 {
                    self.w[i][m] = TI[i][0] * zz[0] + TI[i][1] * zz[1] + TI[i][2] * zz[2];
                }
            }
        }
        let fac1 = k.u1 / h;
        let (alphn, betan) = (k.alph / h, k.beta / h);
        let cs = [c1, c2, 1.0];
        let mut newt = 0;
        self.faccon = self.faccon.max(UROUND).powf(0.8);
        self.theta = THET;
        let (mut dynold, mut thqold) = (0.0f64, 0.0f64);
        // with a fixed step (order tests) Newton may take more iterations instead of a new h
        let nit = if self.fixed.is_some() { 60 } else { NIT };
        loop {
            if newt >= nit {
                return Ok(self.unexpected_rejection(h));
            }
            // stage derivatives, transformed
            let mut fz = [vec![0.0; 0], vec![0.0; 0], vec![0.0; 0]];
            for (i, slot) in fz.iter_mut().enumerate() {
                for m in 0..n {
                    self.tmp[m] = self.y[m] + self.z[i][m];
                }
                let mut out = std::mem::take(&mut self.z[i]);
                sys.rhs(self.t + cs[i] * h, &self.tmp, &mut out);
                *slot = out;
            }
            self.stats.rhs_evals += 3;
            // a stage derivative that is not finite makes the increment's norm not finite
            // (checked once below, on the norm, instead of on every component here)
            let mut dz = fz;
            for m in 0..n {
                let f = [dz[0][m], dz[1][m], dz[2][m]];
                let tf: [f64; 3] =
                    std::array::from_fn(|i| TI[i][0] * f[0] + TI[i][1] * f[1] + TI[i][2] * f[2]);
                dz[0][m] = tf[0] - fac1 * self.w[0][m];
                dz[1][m] = tf[1] - alphn * self.w[1][m] + betan * self.w[2][m];
                dz[2][m] = tf[2] - betan * self.w[1][m] - alphn * self.w[2][m];
            }
            // solve the real and the complex system
            self.solve_real(&mut dz[0]);
            for m in 0..n {
                self.rhs_cplx[m] = Complex::new(dz[1][m], dz[2][m]);
            }
            if self.factored {
                lu_solve(&self.lu_cplx, &self.piv_cplx, n, &mut self.rhs_cplx);
            }
            for m in 0..n {
                dz[1][m] = self.rhs_cplx[m].re;
                dz[2][m] = self.rhs_cplx[m].im;
            }
            newt += 1;
            let mut dyno = 0.0;
            for m in 0..n {
                let s = self.scal[m];
                dyno += (dz[0][m] / s).powi(2) + (dz[1][m] / s).powi(2) + (dz[2][m] / s).powi(2);
            }
            let dyno = (dyno / (3 * n) as f64).sqrt();
            if !dyno.is_finite() {
                self.z = dz;
                return Ok(self.unexpected_rejection(h));
            }
            if newt > 1 && newt < nit {
                let thq = dyno / dynold;
                self.theta = if newt == 2 {
                    thq
                } else {
                    (thq * thqold).sqrt()
                };
                thqold = thq;
                if self.theta < 0.99 {
                    self.faccon = self.theta / (1.0 - self.theta);
                    let dyth =
                        self.faccon * dyno * self.theta.powi((NIT - 1 - newt) as i32) / self.fnewt;
                    if dyth >= 1.0 && self.fixed.is_none() {
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        let hhfac = 0.8 * qnewt.powf(-1.0 / (4.0 + NIT as f64 - 1.0 - newt as f64));
                        self.h = hhfac * h;
                        self.reject = true;
                        self.z = dz;
                        return Ok(None);
                    }
                } else {
                    self.z = dz;
                    return Ok(self.unexpected_rejection(h));
                }
            }
            dynold = dyno.max(UROUND);
            for m in 0..n {
                for i in 0..3 {
                    self.w[i][m] += dz[i][m];
                }
                let w = [self.w[0][m], self.w[1][m], self.w[2][m]];
                for i in 0..3 {
                    dz[i][m] = T[i][0] * w[0] + T[i][1] * w[1] + T[i][2] * w[2];
                }
            }
            self.z = dz;
            if self.faccon * dyno <= self.fnewt {
                break;
            }
        }
        // error estimate
        let hee = [k.dd[0] / h, k.dd[1] / h, k.dd[2] / h];
        for m in 0..n {
            self.tmp2[m] = hee[0] * self.z[0][m] + hee[1] * self.z[1][m] + hee[2] * self.z[2][m];
            self.tmp[m] = self.tmp2[m] + self.f0[m];
        }
        let mut e = std::mem::take(&mut self.tmp);
        self.solve_real(&mut e);
        let mut err = rms(&e, &self.scal).max(1e-10);
        if err >= 1.0 && (self.first || self.reject) {
            for m in 0..n {
                e[m] += self.y[m];
            }
            sys.rhs(self.t, &e, &mut self.f1);
            self.stats.rhs_evals += 1;
            for m in 0..n {
                e[m] = self.f1[m] + self.tmp2[m];
            }
            self.solve_real(&mut e);
            err = rms(&e, &self.scal).max(1e-10);
        }
        self.tmp = e;
        Ok(Some((err, newt)))
    }

    fn unexpected_rejection(&mut self, h: f64) -> Option<(f64, usize)> {
        self.h = 0.5 * h;
        self.reject = true;
        None
    }
}

impl Stepper for Radau5 {
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError> {
        let n = self.n;
        let mut last = false;
        let mut newt_failures = 0;
        // the last step is decided as Hairer's RADAU5 decides it, once per step with the step
        // the controller proposed (x + h_new/quot1 >= xend), not with the step kept for its
        // factorisation; a retry after a rejection checks its own, smaller step
        let mut probe = self.h_proposed;
        loop {
            let mut h = self.h;
            if 0.1 * h.abs() <= self.t.abs() * UROUND {
                return Err(IntegrateError::StepSizeTooSmall { t: self.t, h });
            }
            if self.t + probe.max(h) / QUOT1 - t_end >= 0.0 {
                h = t_end - self.t;
                last = true;
            }
            probe = 0.0;
            let fresh_jacobian = !self.jac_current;
            if fresh_jacobian {
                self.jacobian(sys);
            }
            let needs_lu = fresh_jacobian || (self.lu_h - h).abs() > 0.0 || !self.factored;
            if needs_lu && !self.decompose(h) {
                self.jac_current = self.caljac;
                self.nsing += 1;
                if self.nsing >= 5 {
                    return Err(IntegrateError::NewtonFailure { t: self.t, h });
                }
                self.h = 0.5 * h;
                self.reject = true;
                continue;
            }
            let (err, newt) = match self.attempt(sys, h)? {
                Some(e) => e,
                None if self.fixed.is_some() => {
                    return Err(IntegrateError::NewtonFailure { t: self.t, h });
                }
                None => {
                    // a Jacobian from an earlier step may be what failed: recompute it
                    self.jac_current = self.caljac;
                    newt_failures += 1;
                    if newt_failures > 50 {
                        return Err(IntegrateError::NewtonFailure { t: self.t, h });
                    }
                    last = false;
                    continue;
                }
            };
            let err = if self.fixed.is_some() { 0.5 } else { err };
            let fac = SAFE.min(SAFE * (1.0 + 2.0 * NIT as f64) / (newt as f64 + 2.0 * NIT as f64));
            let mut quot = FACR.max(FACL.min(err.powf(0.25) / fac));
            let mut h_new = h / quot;
            if err < 1.0 {
                self.first = false;
                self.stats.steps += 1;
                if self.stats.steps > 1 {
                    let facgus = (self.hacc / h) * (err * err / self.erracc).powf(0.25) / SAFE;
                    let facgus = FACR.max(FACL.min(facgus));
                    quot = quot.max(facgus);
                    h_new = h / quot;
                }
                self.hacc = h;
                self.erracc = err.max(1e-2);
                self.t_old = self.t;
                self.h_old = h;
                self.t = if last { t_end } else { self.t + h };
                let kk = &self.k;
                for m in 0..n {
                    self.y[m] += self.z[2][m];
                    let (z1, z2, z3) = (self.z[0][m], self.z[1][m], self.z[2][m]);
                    self.cont[1][m] = (z2 - z3) / kk.c2m1;
                    let ak = (z1 - z2) / kk.c1mc2;
                    let acont3 = (ak - z1 / kk.c1) / kk.c2;
                    self.cont[2][m] = (ak - self.cont[1][m]) / kk.c1m1;
                    self.cont[3][m] = self.cont[2][m] - acont3;
                    self.cont[0][m] = self.y[m];
                    self.scal[m] = self.atol + self.rtol * self.y[m].abs();
                }
                if self.y.iter().any(|v| !v.is_finite()) {
                    return Err(IntegrateError::NonFinite { t: self.t });
                }
                sys.rhs(self.t, &self.y, &mut self.f0);
                self.stats.rhs_evals += 1;
                h_new = h_new.min(self.hmax);
                if self.reject {
                    h_new = h_new.min(h);
                }
                self.reject = false;
                self.h_proposed = h_new;
                let qt = h_new / h;
                if self.theta <= THET && (QUOT1..=QUOT2).contains(&qt) {
                    // keep h and the factorisation
                    self.h = h;
                } else {
                    self.h = h_new;
                }
                if let Some(hf) = self.fixed {
                    self.h = hf;
                }
                // reuse the Jacobian while Newton converges fast
                self.jac_current = self.theta <= THET;
                self.caljac = false;
                return Ok(());
            }
            self.reject = true;
            last = false;
            self.jac_current = self.caljac;
            if self.first {
                self.h = 0.1 * h;
            } else {
                self.h = h_new;
            }
            if self.stats.steps >= 1 {
                self.stats.rejected += 1;
            }
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
    fn prepare_dense<S: OdeSystem>(&mut self, _sys: &S) {}

    fn dense(&self, t: f64, out: &mut [f64]) {
        let s = (t - self.t) / self.h_old;
        let k = self.k;
        for (m, o) in out.iter_mut().enumerate() {
            *o = self.cont[0][m]
                + s * (self.cont[1][m]
                    + (s - k.c2m1) * (self.cont[2][m] + (s - k.c1m1) * self.cont[3][m]));
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transformation_block_diagonalises_inverse_radau_matrix() {
        // Reference: the Radau IIA coefficients in closed form (Hairer-Wanner II, Table 5.6).
        let s6 = 6f64.sqrt();
        let a = nalgebra::Matrix3::new(
            (88.0 - 7.0 * s6) / 360.0,
            (296.0 - 169.0 * s6) / 1800.0,
            (-2.0 + 3.0 * s6) / 225.0,
            (296.0 + 169.0 * s6) / 1800.0,
            (88.0 + 7.0 * s6) / 360.0,
            (-2.0 - 3.0 * s6) / 225.0,
            (16.0 - s6) / 36.0,
            (16.0 + s6) / 36.0,
            1.0 / 9.0,
        );
        let t = nalgebra::Matrix3::from_fn(|i, j| T[i][j]);
        let ti = nalgebra::Matrix3::from_fn(|i, j| TI[i][j]);
        let m = ti * a.try_inverse().expect("invertible") * t;
        let k = consts();
        let expect =
            nalgebra::Matrix3::new(k.u1, 0.0, 0.0, 0.0, k.alph, -k.beta, 0.0, k.beta, k.alph);
        assert!((m - expect).abs().max() < 1e-12, "{m}");
        assert!((ti * t - nalgebra::Matrix3::identity()).abs().max() < 1e-14);
    }

    /// Van der Pol's oscillator, $\mu y_2' = (1 - y_1^2) y_2 - y_1$, stiff for small $\mu$.
    struct VanDerPol(f64);
    impl OdeSystem for VanDerPol {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.0;
        }
    }

    /// Hairer's CALJAC rule (radau5.f, RADCOR: a rejected step goes to label 20, the old
    /// Jacobian, when one was computed since the last accepted step, else to label 10): a first
    /// step that is far too large is rejected again and again, and every retry reuses the one
    /// Jacobian computed at its start; after the step is accepted with slow Newton convergence
    /// the next step computes a new one.
    #[test]
    fn retries_of_one_step_reuse_the_jacobian_computed_for_it() {
        let sys = VanDerPol(1e-6);
        let opts = Options {
            rtol: 1e-8,
            atol: 1e-8,
            h0: Some(0.5),
            ..Options::default()
        };
        let (t_end, y0) = (2.0, [2.0, -0.66]);
        let mut st = Radau5::new(&sys, 0.0, &y0, t_end, &opts);
        let evals0 = st.stats().rhs_evals;
        st.step(&sys, t_end).expect("a first step");
        let stats = st.stats();
        // at least three attempts (a Newton iteration takes three evaluations), so at least
        // two retries, each of which would have recomputed the Jacobian under a rule per attempt
        assert!(
            st.h_old < 0.5e-2,
            "the first step was cut twice: h = {}",
            st.h_old
        );
        assert!(stats.rhs_evals - evals0 >= 9, "{stats}");
        assert_eq!(stats.jac_evals, 1, "{stats}");
        assert!(!st.caljac, "an accepted step resets CALJAC");
    }
}
