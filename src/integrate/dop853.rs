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
use super::erk::{Buffers, Erk, Tableau, Work};
use super::{OdeSystem, StiffnessTest};

/// The DOP853 stepper ([`Erk`] with the Dormand-Prince 8(5,3) tableau); all buffers are
/// allocated in [`Erk::new`]. `N` is the dimension when it is known at compile time (the
/// stages then live in registers), 0 when it is not.
pub(crate) type Dop853<const N: usize = 0> = Erk<Dp8, N>;

/// The Dormand-Prince 8(5,3) pair.
pub(crate) struct Dp8;

impl Tableau for Dp8 {
    const STORED: usize = 16;
    const FSAL: usize = 12;
    const FSAL_IN_ATTEMPT: bool = false;
    const EVALS: usize = 11;
    const ORDER: i32 = 8;
    const FACC1: f64 = 1.0 / 0.333;
    const FACC2: f64 = 1.0 / 6.0;
    const STIFF_BOUNDARY: f64 = 6.1;
    const DENSE_ROWS: usize = 7;
    const MEMORY0: f64 = 1e-4;
    const HERMITE: bool = true;

    super::erk::attempt_on_stack!(12, attempt);

    /// err^(1/8), no memory (Hairer's DOP853 has no PI term).
    #[inline(always)]
    fn factor(err: f64, memory: f64) -> (f64, f64) {
        (Self::reject_factor(err), memory)
    }

    #[inline(always)]
    fn reject_factor(err: f64) -> f64 {
        err.sqrt().sqrt().sqrt()
    }

    /// Every accepted step.
    #[inline(always)]
    fn stiffness_due(_steps: usize, _test: &StiffnessTest) -> bool {
        true
    }

    /// The three extra stages of the 7th-order dense output, then its coefficients.
    fn prepare_dense<S: OdeSystem, const M: usize>(e: &mut Erk<Self, M>, sys: &S) {
        let (n, h) = (e.dim(), e.h_old);
        let b = &mut e.b;
        for i in 13..16 {
            combine(n, &b.k, &b.y_old, A[i], h, &mut b.y_stage);
            let t = e.t_old + C[i] * h;
            sys.rhs(t, &b.y_stage, &mut b.k[i * n..(i + 1) * n]);
        }
        e.stats.rhs_evals += 3;
        let k = &b.k;
        for m in 0..n {
            let dy = b.y[m] - b.y_old[m];
            let bspl = h * k[m] - dy;
            e.cont[m] = dy;
            e.cont[n + m] = bspl;
            e.cont[2 * n + m] = dy - h * k[12 * n + m] - bspl;
            for (r, row) in D.iter().enumerate() {
                e.cont[(3 + r) * n + m] =
                    h * row.iter().map(|&(j, d)| d * k[j * n + m]).sum::<f64>();
            }
        }
    }

    fn dense<const M: usize>(e: &Erk<Self, M>, t: f64, out: &mut [f64]) {
        let h = e.h_old;
        let s = (t - e.t_old) / h;
        let s1 = 1.0 - s;
        let n = e.dim();
        for (m, o) in out.iter_mut().enumerate() {
            let c = |r: usize| e.cont[r * n + m];
            let inner = c(3) + s * (c(4) + s1 * (c(5) + s * c(6)));
            *o = e.b.y_old[m] + s * (c(0) + s1 * (c(1) + s * (c(2) + s1 * inner)));
        }
    }
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
    (rtol, atol): (f64, f64),
    w: Work<'_>,
) -> f64 {
    let Work {
        k,
        y,
        y_stage,
        y_last: y12,
        y_new,
    } = w;
    // stages 2..11, one by one: each row of A is then a constant the compiler folds into the
    // combination (a loop over the rows costs a tenth of the step in row bookkeeping at n = 2)
    macro_rules! stage {
        ($($i:literal)*) => {$(
            combine(n, k, y, A[$i], h, y_stage);
            sys.rhs(t + C[$i] * h, y_stage, &mut k[$i * n..($i + 1) * n]);
        )*};
    }
    stage!(1 2 3 4 5 6 7 8 9 10);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::{OdeSystem, Stats, step_to_end};

    /// Two coupled oscillators (4 states) with a nonlinear coupling, and the unit Hertz impact
    /// (2 states).
    struct Coupled;
    impl OdeSystem for Coupled {
        fn dim(&self) -> usize {
            4
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] + 0.3 * (y[1] - y[0]).powi(3);
            dy[3] = -2.0 * y[1] - 0.3 * (y[1] - y[0]).powi(3);
        }
    }
    struct Hertz;
    impl OdeSystem for Hertz {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            let z = y[0].max(0.0);
            dy[0] = y[1];
            dy[1] = -z * z.sqrt();
        }
    }

    fn run<const N: usize, S: OdeSystem>(sys: &S, y0: &[f64], t_end: f64) -> (Vec<f64>, Stats) {
        step_to_end(sys, 1e-10, t_end, |o| {
            Dop853::<N>::new(sys, 0.0, y0, t_end, o)
        })
    }

    /// The stages of a fixed size (2 and 4 states) do the arithmetic of the run-time size in the
    /// same order: the same steps, rejections and end state to the bit (the reference is the
    /// run-time-size stepper, which tests/integrate.rs checks against closed forms and orders).
    #[test]
    fn fixed_size_stages_take_the_steps_of_the_run_time_size() {
        let y0 = [1.0, -0.5, 0.0, 0.8];
        let (yf, sf) = run::<4, _>(&Coupled, &y0, 20.0);
        let (yd, sd) = run::<0, _>(&Coupled, &y0, 20.0);
        assert!(sf.steps > 50, "{sf}");
        assert_eq!((yf, format!("{sf}")), (yd, format!("{sd}")));
        let (yf, sf) = run::<2, _>(&Hertz, &[0.0, 1.0], 3.2);
        let (yd, sd) = run::<0, _>(&Hertz, &[0.0, 1.0], 3.2);
        assert!(sf.rejected > 0, "a run with rejections: {sf}");
        assert_eq!((yf, format!("{sf}")), (yd, format!("{sd}")));
    }

    /// [`crate::integrate::solve_dop853_pair`] is [`crate::integrate::solve`]'s DOP853 to the
    /// bit on two states, events included (the Hertz impact to its contact end), and refuses
    /// another size or method with the field named.
    #[test]
    fn the_pairs_solve_is_the_solve() {
        use crate::integrate::{Direction, Event, Method, Options, solve, solve_dop853_pair};
        let gap = |_t: f64, y: &[f64]| y[0];
        let opts = Options {
            rtol: 1e-10,
            atol: 1e-12,
            method: Method::Dop853,
            events: vec![Event::new("end", &gap, Direction::Falling, true).reading(0)],
            ..Options::default()
        };
        let pair = solve_dop853_pair(&Hertz, 0.0, &[0.0, 1.0], 10.0, &opts).expect("solves");
        let all = solve(&Hertz, 0.0, &[0.0, 1.0], 10.0, &opts).expect("solves");
        assert!(
            pair.t > 3.0 && pair.t < 4.0 && pair.events.len() == 1,
            "{}",
            pair.t
        );
        assert_eq!(
            (pair.t.to_bits(), &pair.y, format!("{}", pair.stats)),
            (all.t.to_bits(), &all.y, format!("{}", all.stats))
        );
        let four = solve_dop853_pair(&Coupled, 0.0, &[1.0, 0.0, 0.0, 0.0], 1.0, &opts);
        let radau = Options {
            method: Method::Radau5,
            ..Options::default()
        };
        let implicit = solve_dop853_pair(&Hertz, 0.0, &[0.0, 1.0], 1.0, &radau);
        for r in [four, implicit] {
            let e = r.expect_err("refused").to_string();
            assert!(
                e.contains("method") && e.contains("dop853 for 2 states"),
                "{e}"
            );
        }
    }
}
