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

use super::{IntegrateError, OdeSystem, Options, Stats, Stepper};
use nalgebra::{Complex, DMatrix};
use num_traits::Zero;
use std::ops::{Mul, Sub};

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

/// A pivot type of [`lu_factor`]: real for $\gamma/h - J$, complex for $(\alpha + i\beta)/h - J$.
trait Pivot: Copy + Zero + Sub<Output = Self> + Mul<Output = Self> {
    /// The size by which the pivot is chosen (Hairer's DECC takes $|re| + |im|$).
    fn mag(&self) -> f64;
    /// $1/x$.
    fn recip(self) -> Self;
}

impl Pivot for f64 {
    #[inline(always)]
    fn mag(&self) -> f64 {
        self.abs()
    }
    #[inline(always)]
    fn recip(self) -> f64 {
        1.0 / self
    }
}

impl Pivot for Complex<f64> {
    #[inline(always)]
    fn mag(&self) -> f64 {
        self.re.abs() + self.im.abs()
    }
    #[inline(always)]
    fn recip(self) -> Self {
        let d = self.re * self.re + self.im * self.im;
        Complex::new(self.re / d, -self.im / d)
    }
}

/// Factors the row-major `n x n` matrix `a` in place with partial pivoting (the row of the
/// largest [`Pivot::mag`] in each column), as LINPACK's DGEFA and Hairer's DEC/DECC: `a` holds
/// `U`, with the reciprocal of each pivot on the diagonal (the factors serve some three steps:
/// [`lu_solve`] multiplies where DEC's SOL divides on every solve), and the multipliers of `L`;
/// `piv[k]` is the row exchanged with row `k` at step `k` (only the columns from `k` on are
/// exchanged, so [`lu_solve`] applies exchange and elimination step by step). False when a pivot
/// is exactly zero (singular). Inlined so that a dimension known at compile time unrolls it.
#[inline(always)]
fn lu_factor<T: Pivot>(a: &mut [T], piv: &mut [usize], n: usize) -> bool {
    let (a, piv) = (&mut a[..n * n], &mut piv[..n]);
    for k in 0..n {
        let (mut p, mut best) = (k, a[k * n + k].mag());
        for i in k + 1..n {
            let m = a[i * n + k].mag();
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
        let inv = a[k * n + k].recip();
        a[k * n + k] = inv;
        for i in k + 1..n {
            let f = a[i * n + k] * inv;
            a[i * n + k] = f;
            for j in k + 1..n {
                a[i * n + j] = a[i * n + j] - f * a[k * n + j];
            }
        }
    }
    true
}

/// Solves `A x = b` in place with the factors of [`lu_factor`].
#[inline(always)]
fn lu_solve<T: Pivot>(a: &[T], piv: &[usize], n: usize, b: &mut [T]) {
    let (a, piv, b) = (&a[..n * n], &piv[..n], &mut b[..n]);
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
        b[k] = s * a[k * n + k];
    }
}

/// $\sqrt{\sum_m (e_m w_m)^2 / n}$ with the reciprocal scales `w`.
#[inline(always)]
fn rms_inv(e: &[f64], w: &[f64]) -> f64 {
    let s: f64 = e.iter().zip(w).map(|(a, w)| (a * w) * (a * w)).sum();
    (s / e.len().max(1) as f64).sqrt()
}

/// The Radau5 stepper. `N` is the dimension when it is known at compile time (the stage loops
/// and the LU of the small systems of impact models then unroll and lose their bounds checks,
/// as in [`super::erk::Erk`]), 0 when it is not.
pub struct Radau5<const N: usize = 0> {
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
    /// The reciprocals of the error scales $a + r|y|$ (the norms multiply by them).
    iscal: Vec<f64>,
    z: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    /// The stage derivatives, then the real Newton increment (row 0).
    fz: [Vec<f64>; 3],
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

impl<const N: usize> Radau5<N> {
    /// The dimension: `N` when it is fixed, else the initial state's length.
    #[inline(always)]
    fn dim(&self) -> usize {
        if N == 0 { self.n } else { N }
    }

    /// Prepares a solve.
    pub fn new<S: OdeSystem>(sys: &S, t0: f64, y0: &[f64], t_end: f64, opts: &Options) -> Self {
        let n = y0.len();
        assert!(N == 0 || N == n, "Radau5::<{N}> for a state of length {n}");
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
            iscal: y0.iter().map(|v| 1.0 / (atol + rtol * v.abs())).collect(),
            z: [v(), v(), v()],
            w: [v(), v(), v()],
            fz: [v(), v(), v()],
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
        let n = self.dim();
        if !sys.jacobian(self.t, &self.y, &mut self.jac) {
            for i in 0..n {
                let ysafe = self.y[i];
                let delt = (UROUND * 1e-5f64.max(ysafe.abs())).sqrt();
                self.y[i] = ysafe + delt;
                sys.rhs(self.t, &self.y, &mut self.tmp);
                for j in 0..n {
                    self.jac[(j, i)] = (self.tmp[j] - self.f0[j]) / delt;
                }
                self.y[i] = ysafe;
            }
            self.stats.rhs_evals += n;
        }
        self.jac_current = true;
        self.caljac = true;
    }

    /// Factorises $\gamma/h - J$ and $(\alpha+i\beta)/h - J$; false if singular.
    fn decompose(&mut self, h: f64) -> bool {
        let n = self.dim();
        let fac1 = self.k.u1 / h;
        let (alphn, betan) = (self.k.alph / h, self.k.beta / h);
        let (lr, lc) = (&mut self.lu_real[..n * n], &mut self.lu_cplx[..n * n]);
        for i in 0..n {
            for j in 0..n {
                let (d, jij) = (if i == j { 1.0 } else { 0.0 }, self.jac[(i, j)]);
                lr[i * n + j] = d * fac1 - jij;
                lc[i * n + j] = Complex::new(d * alphn - jij, d * betan);
            }
        }
        self.stats.lu_decomps += 2;
        let ok = lu_factor(&mut self.lu_real, &mut self.piv_real, n)
            && lu_factor(&mut self.lu_cplx, &mut self.piv_cplx, n);
        self.factored = true;
        self.lu_h = h;
        ok
    }

    /// The starting values of Newton's iteration for a step of size `h`: zero on the first
    /// step, else the last step's collocation polynomial extrapolated (and transformed to W).
    fn start_values(&mut self, h: f64) {
        let n = self.dim();
        let k = self.k;
        let [z0, z1, z2] = &mut self.z;
        let [w0, w1, w2] = &mut self.w;
        let (z0, z1, z2) = (&mut z0[..n], &mut z1[..n], &mut z2[..n]);
        let (w0, w1, w2) = (&mut w0[..n], &mut w1[..n], &mut w2[..n]);
        if self.first {
            for v in [z0, z1, z2, w0, w1, w2] {
                v.fill(0.0);
            }
            return;
        }
        let c3q = h / self.h_old;
        let (c1q, c2q) = (k.c1 * c3q, k.c2 * c3q);
        let [_, a1, a2, a3] = &self.cont;
        let (a1, a2, a3) = (&a1[..n], &a2[..n], &a3[..n]);
        for m in 0..n {
            let (ak1, ak2, ak3) = (a1[m], a2[m], a3[m]);
            let ext = |cq: f64| cq * (ak1 + (cq - k.c2m1) * (ak2 + (cq - k.c1m1) * ak3));
            let zz = [ext(c1q), ext(c2q), ext(c3q)];
            (z0[m], z1[m], z2[m]) = (zz[0], zz[1], zz[2]);
            w0[m] = TI[0][0] * zz[0] + TI[0][1] * zz[1] + TI[0][2] * zz[2];
            w1[m] = TI[1][0] * zz[0] + TI[1][1] * zz[1] + TI[1][2] * zz[2];
            w2[m] = TI[2][0] * zz[0] + TI[2][1] * zz[1] + TI[2][2] * zz[2];
        }
    }

    /// One simplified Newton iteration from the stages in `z`: the stage derivatives, the
    /// transformed residual, the real and the complex solve; the increment of W is left in
    /// `fz[0]` (real) and `rhs_cplx` (the complex pair). Returns its scaled norm.
    #[inline(always)]
    fn newton_increment<S: OdeSystem>(&mut self, sys: &S, h: f64) -> f64 {
        let n = self.dim();
        let k = self.k;
        let fac1 = k.u1 / h;
        let (alphn, betan) = (k.alph / h, k.beta / h);
        let cs = [k.c1, k.c2, 1.0];
        let (y, tmp) = (&self.y[..n], &mut self.tmp[..n]);
        for i in 0..3 {
            let zi = &self.z[i][..n];
            for m in 0..n {
                tmp[m] = y[m] + zi[m];
            }
            sys.rhs(self.t + cs[i] * h, tmp, &mut self.fz[i][..n]);
        }
        self.stats.rhs_evals += 3;
        let [f0, f1, f2] = &mut self.fz;
        let (f0, f1, f2) = (&mut f0[..n], &f1[..n], &f2[..n]);
        let [w0, w1, w2] = &self.w;
        let (w0, w1, w2) = (&w0[..n], &w1[..n], &w2[..n]);
        let rc = &mut self.rhs_cplx[..n];
        for m in 0..n {
            let (a, b, c) = (f0[m], f1[m], f2[m]);
            let t0 = TI[0][0] * a + TI[0][1] * b + TI[0][2] * c;
            let t1 = TI[1][0] * a + TI[1][1] * b + TI[1][2] * c;
            let t2 = TI[2][0] * a + TI[2][1] * b + TI[2][2] * c;
            f0[m] = t0 - fac1 * w0[m];
            rc[m] = Complex::new(
                t1 - alphn * w1[m] + betan * w2[m],
                t2 - betan * w1[m] - alphn * w2[m],
            );
        }
        lu_solve(&self.lu_real, &self.piv_real, n, f0);
        lu_solve(&self.lu_cplx, &self.piv_cplx, n, rc);
        let is = &self.iscal[..n];
        let mut dyno = 0.0;
        for m in 0..n {
            let (a, b, c) = (f0[m] * is[m], rc[m].re * is[m], rc[m].im * is[m]);
            dyno += a * a + b * b + c * c;
        }
        (dyno / (3 * n) as f64).sqrt()
    }

    /// Adds the Newton increment to W and maps W back to the stages Z = (T x I) W.
    #[inline(always)]
    fn apply_increment(&mut self) {
        let n = self.dim();
        let [w0, w1, w2] = &mut self.w;
        let (w0, w1, w2) = (&mut w0[..n], &mut w1[..n], &mut w2[..n]);
        let [z0, z1, z2] = &mut self.z;
        let (z0, z1, z2) = (&mut z0[..n], &mut z1[..n], &mut z2[..n]);
        let (d0, dc) = (&self.fz[0][..n], &self.rhs_cplx[..n]);
        for m in 0..n {
            w0[m] += d0[m];
            w1[m] += dc[m].re;
            w2[m] += dc[m].im;
            let (a, b, c) = (w0[m], w1[m], w2[m]);
            z0[m] = T[0][0] * a + T[0][1] * b + T[0][2] * c;
            z1[m] = T[1][0] * a + T[1][1] * b + T[1][2] * c;
            // T's last row is (T31, 1, 0), as Hairer's RADCOR writes it
            z2[m] = T[2][0] * a + b;
        }
    }

    /// The error estimate of the step just computed:
    /// $(\gamma/h - J)^{-1}[f(y_0) + (d_1 Z_1 + d_2 Z_2 + d_3 Z_3)/h]$, re-filtered through one
    /// more evaluation when it fails on a first or rejected step.
    fn error_estimate<S: OdeSystem>(&mut self, sys: &S, h: f64) -> f64 {
        let n = self.dim();
        let k = self.k;
        let hee = [k.dd[0] / h, k.dd[1] / h, k.dd[2] / h];
        {
            let [z0, z1, z2] = &self.z;
            let (z0, z1, z2) = (&z0[..n], &z1[..n], &z2[..n]);
            let (f0, t2, e) = (&self.f0[..n], &mut self.tmp2[..n], &mut self.tmp[..n]);
            for m in 0..n {
                t2[m] = hee[0] * z0[m] + hee[1] * z1[m] + hee[2] * z2[m];
                e[m] = t2[m] + f0[m];
            }
        }
        lu_solve(&self.lu_real, &self.piv_real, n, &mut self.tmp);
        let mut err = rms_inv(&self.tmp[..n], &self.iscal[..n]).max(1e-10);
        if err >= 1.0 && (self.first || self.reject) {
            let e = &mut self.tmp[..n];
            for m in 0..n {
                e[m] += self.y[m];
            }
            sys.rhs(self.t, e, &mut self.f1[..n]);
            self.stats.rhs_evals += 1;
            for m in 0..n {
                e[m] = self.f1[m] + self.tmp2[m];
            }
            lu_solve(&self.lu_real, &self.piv_real, n, &mut self.tmp);
            err = rms_inv(&self.tmp[..n], &self.iscal[..n]).max(1e-10);
        }
        err
    }

    /// One attempt at a step of size `h`; `Ok(Some((err, newton_iterations)))` when Newton
    /// converged, `Ok(None)` when it failed and the step must be retried with the (already
    /// reduced) `self.h`.
    fn attempt<S: OdeSystem>(
        &mut self,
        sys: &S,
        h: f64,
    ) -> Result<Option<(f64, usize)>, IntegrateError> {
        self.start_values(h);
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
            // a stage derivative that is not finite makes the increment's norm not finite
            // (checked once, on the norm, instead of on every component)
            let dyno = self.newton_increment(sys, h);
            newt += 1;
            if !dyno.is_finite() {
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
                        return Ok(None);
                    }
                } else {
                    return Ok(self.unexpected_rejection(h));
                }
            }
            dynold = dyno.max(UROUND);
            self.apply_increment();
            if self.faccon * dyno <= self.fnewt {
                break;
            }
        }
        Ok(Some((self.error_estimate(sys, h), newt)))
    }

    fn unexpected_rejection(&mut self, h: f64) -> Option<(f64, usize)> {
        self.h = 0.5 * h;
        self.reject = true;
        None
    }

    /// Takes the accepted step: the new state, the collocation polynomial for the dense output
    /// and the next start, the error scales.
    fn accept_state(&mut self) {
        let n = self.dim();
        let kk = self.k;
        let [z0, z1, z2] = &self.z;
        let (z0, z1, z2) = (&z0[..n], &z1[..n], &z2[..n]);
        let [c0, c1, c2, c3] = &mut self.cont;
        let (c0, c1, c2, c3) = (&mut c0[..n], &mut c1[..n], &mut c2[..n], &mut c3[..n]);
        let (y, is) = (&mut self.y[..n], &mut self.iscal[..n]);
        for m in 0..n {
            y[m] += z2[m];
            c1[m] = (z1[m] - z2[m]) / kk.c2m1;
            let ak = (z0[m] - z1[m]) / kk.c1mc2;
            let acont3 = (ak - z0[m] / kk.c1) / kk.c2;
            c2[m] = (ak - c1[m]) / kk.c1m1;
            c3[m] = c2[m] - acont3;
            c0[m] = y[m];
            is[m] = 1.0 / (self.atol + self.rtol * y[m].abs());
        }
    }
}

impl<const N: usize> Stepper for Radau5<N> {
    fn step<S: OdeSystem>(&mut self, sys: &S, t_end: f64) -> Result<(), IntegrateError> {
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
            // err^(1/4) as two square roots (a third of pow's time; the same value to rounding)
            let mut quot = FACR.max(FACL.min(err.sqrt().sqrt() / fac));
            let mut h_new = h / quot;
            if err < 1.0 {
                self.first = false;
                self.stats.steps += 1;
                if self.stats.steps > 1 {
                    let facgus = (self.hacc / h) * (err * err / self.erracc).sqrt().sqrt() / SAFE;
                    let facgus = FACR.max(FACL.min(facgus));
                    quot = quot.max(facgus);
                    h_new = h / quot;
                }
                self.hacc = h;
                self.erracc = err.max(1e-2);
                self.t_old = self.t;
                self.h_old = h;
                self.t = if last { t_end } else { self.t + h };
                self.accept_state();
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
    use crate::integrate::step_to_end;

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

    /// $y' = \lambda y$ with its Jacobian, $\lambda$ set after the stepper is made.
    struct Growth(std::cell::Cell<f64>);
    impl OdeSystem for Growth {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = self.0.get() * y[0];
        }
        fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) -> bool {
            jac[(0, 0)] = self.0.get();
            true
        }
    }

    /// Hairer's NSING rule: a singular iteration matrix halves the step, and the fifth in one
    /// solve ends it with a Newton failure at the step that met it. The matrix u1/h - lambda
    /// is made exactly singular for the first step (lambda = u1/h0, computed as the stepper
    /// computes it); the count is the stepper's own, so four earlier ones are set by hand.
    #[test]
    fn the_fifth_singular_matrix_ends_the_solve() {
        let opts = Options {
            h0: Some(0.01),
            ..Options::default()
        };
        let sys = Growth(std::cell::Cell::new(1.0));
        let mut st = Radau5::<0>::new(&sys, 0.0, &[1.0], 100.0, &opts);
        sys.0.set(st.k.u1 / st.h);
        let h0 = st.h;
        // the first singular matrix: the step is halved and taken
        st.step(&sys, 100.0)
            .expect("one singular matrix halves the step");
        assert_eq!(st.nsing, 1);
        assert!(st.h_old <= 0.5 * h0, "h = {}", st.h_old);
        // the fifth: the solve ends where it met it
        let mut st = Radau5::<0>::new(&sys, 0.0, &[1.0], 100.0, &opts);
        st.nsing = 4;
        match st.step(&sys, 100.0) {
            Err(IntegrateError::NewtonFailure { t, h }) => {
                assert_eq!((t, h), (0.0, h0));
            }
            other => panic!("expected a Newton failure, got {other:?}"),
        }
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
        let mut st = Radau5::<0>::new(&sys, 0.0, &y0, t_end, &opts);
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

    /// A stiff linear system of 4 states (the pendulum on the wall of 002 (2.15) with
    /// rho = 0.5 and sigma = 1e-4), with its Jacobian.
    struct Pendulum4;
    impl OdeSystem for Pendulum4 {
        fn dim(&self) -> usize {
            4
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            let (r2, s) = (4.0, 1e-4);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] * (1.0 + r2) - s * y[1] * (1.0 - r2);
            dy[3] = -y[0] * (1.0 - r2) - s * y[1] * (1.0 + r2);
        }
    }

    fn run<const N: usize, S: OdeSystem>(sys: &S, y0: &[f64], t_end: f64) -> (Vec<f64>, Stats) {
        step_to_end(sys, 1e-9, t_end, |o| {
            Radau5::<N>::new(sys, 0.0, y0, t_end, o)
        })
    }

    /// The stages and matrices of a fixed size do the same arithmetic in the same order as the
    /// ones of a size known at run time: the same steps, evaluations, rejections and the same
    /// end state to the bit (the reference is the run-time-size stepper, which the order and
    /// peer tests of tests/integrate.rs check against closed forms).
    #[test]
    fn fixed_size_stages_take_the_steps_of_the_run_time_size() {
        let vdp = VanDerPol(1e-3);
        let (yf, sf) = run::<2, _>(&vdp, &[2.0, -0.66], 1.5);
        let (yd, sd) = run::<0, _>(&vdp, &[2.0, -0.66], 1.5);
        assert!(
            sf.rejected > 0 && sf.jac_evals > 1,
            "a run with rejections: {sf}"
        );
        assert_eq!((yf, format!("{sf}")), (yd, format!("{sd}")));
        let y0 = [0.0, 0.0, 0.0, 1.0];
        let (yf, sf) = run::<4, _>(&Pendulum4, &y0, 50.0);
        let (yd, sd) = run::<0, _>(&Pendulum4, &y0, 50.0);
        assert!(sf.steps > 100, "{sf}");
        assert_eq!((yf, format!("{sf}")), (yd, format!("{sd}")));
    }

    /// A small deterministic generator of matrix entries in [-1, 1).
    fn entries(seed: u64, count: usize) -> Vec<f64> {
        let mut x = seed;
        (0..count)
            .map(|_| {
                x = x
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    /// The in-place LU with reciprocal pivots solves as nalgebra's LU does (an independent
    /// implementation), real and complex, for n = 1..6, with a zero first pivot that forces a
    /// row exchange; an exactly singular matrix is reported.
    #[test]
    fn lu_with_reciprocal_pivots_solves_as_nalgebra_does() {
        for n in 1..=6 {
            let e = entries(n as u64, 4 * n * n + 2 * n);
            let mut a: Vec<f64> = e[..n * n].to_vec();
            a[0] = 0.0;
            let b: Vec<f64> = e[n * n..n * n + n].to_vec();
            let m = nalgebra::DMatrix::from_row_slice(n, n, &a);
            if n > 1 {
                let expect = m
                    .clone()
                    .lu()
                    .solve(&nalgebra::DVector::from_vec(b.clone()));
                let expect = expect.expect("regular");
                let (mut lu, mut piv, mut x) = (a.clone(), vec![0; n], b.clone());
                assert!(lu_factor(&mut lu, &mut piv, n));
                lu_solve(&lu, &piv, n, &mut x);
                for i in 0..n {
                    assert!((x[i] - expect[i]).abs() <= 1e-11 * expect.amax(), "n = {n}");
                }
            } else {
                let (mut lu, mut piv) = (a.clone(), vec![0; 1]);
                assert!(!lu_factor(&mut lu, &mut piv, 1), "a zero 1x1 is singular");
            }
            let c: Vec<Complex<f64>> = (0..n * n)
                .map(|k| Complex::new(e[2 * n * n + k], e[3 * n * n + k]))
                .collect();
            let bc: Vec<Complex<f64>> = (0..n)
                .map(|k| Complex::new(e[4 * n * n + k], e[4 * n * n + n + k]))
                .collect();
            let mc = nalgebra::DMatrix::from_row_slice(n, n, &c);
            let expect = mc.lu().solve(&nalgebra::DVector::from_vec(bc.clone()));
            let expect = expect.expect("regular");
            let (mut lu, mut piv, mut x) = (c.clone(), vec![0; n], bc.clone());
            assert!(lu_factor(&mut lu, &mut piv, n));
            lu_solve(&lu, &piv, n, &mut x);
            let scale = expect.iter().map(|z| z.norm()).fold(0.0, f64::max);
            for i in 0..n {
                assert!(
                    (x[i] - expect[i]).norm() <= 1e-11 * scale,
                    "complex, n = {n}"
                );
            }
        }
        // rank 1: the second pivot is exactly zero
        let (mut a, mut piv) = (vec![1.0, 2.0, 2.0, 4.0], vec![0; 2]);
        assert!(!lu_factor(&mut a, &mut piv, 2));
    }
}
