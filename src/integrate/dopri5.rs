//! DOPRI5: the Dormand-Prince 5(4) pair with Shampine's 4th-order dense output (Hairer,
//! Norsett, Wanner, Solving ODEs I, sec. II.5 and II.6).
//!
//! Step control as in Hairer's code, a PI controller with $\beta = 0.04$:
//! $$\mathrm{err} = \sqrt{\tfrac1n\sum_i (e_i/s_i)^2},\quad
//!   f = \frac{\mathrm{err}^{0.2 - 0.75\beta}}{\mathrm{err}_{old}^{\beta}},\quad
//!   h_{new} = h/\max(1/10, \min(5, f/0.9)).$$
//! Stiffness: $|h|\,\|k_7 - k_6\|/\|\hat y - y_6\| > 3.25$ on 15 consecutive tests. Evaluation
//! counts: 2 at start, 6 per step (first same as last).

use super::erk::{Buffers, Erk, Tableau, Work};
use super::{OdeSystem, StiffnessTest};

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
const BETA: f64 = 0.04;
/// ln 1e-4: the least `facold` of Hairer's controller.
const LN_FACOLD_MIN: f64 = -9.210_340_371_976_182;

/// The DOPRI5 stepper ([`Erk`] with the Dormand-Prince 5(4) tableau).
pub(crate) type Dopri5<const N: usize = 0> = Erk<Dp5, N>;

/// The Dormand-Prince 5(4) pair.
pub(crate) struct Dp5;

impl Tableau for Dp5 {
    const STORED: usize = 7;
    const FSAL: usize = 6;
    const FSAL_IN_ATTEMPT: bool = true;
    const EVALS: usize = 6;
    const ORDER: i32 = 5;
    const FACC1: f64 = 1.0 / 0.2;
    const FACC2: f64 = 1.0 / 10.0;
    const STIFF_BOUNDARY: f64 = 3.25;
    const DENSE_ROWS: usize = 4;
    const MEMORY0: f64 = LN_FACOLD_MIN;
    const HERMITE: bool = false;

    super::erk::attempt_on_stack!(7, attempt);

    /// Hairer's PI controller: err^(0.2 - 0.75 beta) / facold^beta as one exponential, with ln
    /// facold kept from the last accepted step (one ln and one exp per step, not two powf).
    #[inline(always)]
    fn factor(err: f64, ln_facold: f64) -> (f64, f64) {
        let ln_err = err.ln();
        let fac = ((0.2 - BETA * 0.75) * ln_err - BETA * ln_facold).exp();
        (fac, ln_err.max(LN_FACOLD_MIN))
    }

    fn reject_factor(err: f64) -> f64 {
        ((0.2 - BETA * 0.75) * err.ln()).exp()
    }

    /// Hairer's schedule (NSTIFF = 1000): every 1000th step, and every step once an estimate
    /// has come out stiff (DOPRI5 is not the first stage of Auto, which uses DOP853, so only
    /// the warning's timing depends on it).
    #[inline(always)]
    fn stiffness_due(steps: usize, test: &StiffnessTest) -> bool {
        steps.is_multiple_of(1000) || test.iasti > 0
    }

    fn prepare_dense<S: OdeSystem, const M: usize>(e: &mut Erk<Self, M>, _sys: &S) {
        let (h, n, b) = (e.h_old, e.dim(), &e.b);
        for m in 0..n {
            let dy = b.y[m] - b.y_old[m];
            let bspl = h * b.k[m] - dy;
            e.cont[m] = dy;
            e.cont[n + m] = bspl;
            e.cont[2 * n + m] = dy - h * b.k[6 * n + m] - bspl;
            e.cont[3 * n + m] = h * (0..7).map(|j| DENSE[j] * b.k[j * n + m]).sum::<f64>();
        }
    }

    fn dense<const M: usize>(e: &Erk<Self, M>, t: f64, out: &mut [f64]) {
        let s = (t - e.t_old) / e.h_old;
        let s1 = 1.0 - s;
        let n = e.dim();
        for (m, o) in out.iter_mut().enumerate() {
            let c = |r: usize| e.cont[r * n + m];
            *o = e.b.y_old[m] + s * (c(0) + s1 * (c(1) + s * (c(2) + s1 * c(3))));
        }
    }
}

/// One attempt: the six stages, the new solution and its slope (first same as last: stage 7),
/// and the scaled RMS error; NaN if the new solution is not finite.
#[inline(always)]
fn attempt<S: OdeSystem>(
    sys: &S,
    n: usize,
    t: f64,
    h: f64,
    (rtol, atol): (f64, f64),
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
        y_last: y6,
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
