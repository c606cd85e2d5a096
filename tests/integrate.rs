//! The numeric core against closed forms and independent references: convergence orders,
//! Hairer's evaluation counts, event location, stiff problems and automatic switching.

use impactcheck::integrate::{
    Direction, Event, IntegrateError, Method, OdeSystem, Options, Stop, solve,
};

/// y' = y cos t, exact y = exp(sin t).
struct ExpSin;
impl OdeSystem for ExpSin {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[0] * t.cos();
    }
}

#[path = "support/oscillator.rs"]
mod oscillator;
use oscillator::Oscillator;

/// Free fall y'' = -g.
struct Fall;
const G: f64 = 9.81;
impl OdeSystem for Fall {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -G;
    }
}

/// z'' = -max(z, 0)^1.5: the problem of Hairer's published counts.
struct HertzUnit;
impl OdeSystem for HertzUnit {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0].max(0.0).powf(1.5);
    }
}

/// Van der Pol in Hairer's scaling, eps = 1e-6 (mu = 1e3 in unscaled time).
struct VanDerPol {
    eps: f64,
    analytic_jacobian: bool,
}
impl OdeSystem for VanDerPol {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.eps;
    }
    fn jacobian(&self, _t: f64, y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        if !self.analytic_jacobian {
            return false;
        }
        jac[(0, 0)] = 0.0;
        jac[(0, 1)] = 1.0;
        jac[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / self.eps;
        jac[(1, 1)] = (1.0 - y[0] * y[0]) / self.eps;
        true
    }
}

/// Robertson's chemical kinetics.
struct Robertson;
impl OdeSystem for Robertson {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        dy[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
        dy[2] = 3e7 * y[1] * y[1];
    }
}

/// y' = -lambda(t) (y - cos t) with lambda growing from 1 to 1e6: becomes stiff.
struct BecomesStiff;
impl OdeSystem for BecomesStiff {
    fn dim(&self) -> usize {
        1
    }
    fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
        let lambda = 10f64.powf(6.0 * (t / 2.0).min(1.0));
        dy[0] = -lambda * (y[0] - t.cos()) - t.sin();
    }
}

fn opts(method: Method, tol: f64) -> Options<'static> {
    Options {
        rtol: tol,
        atol: tol,
        method,
        ..Options::default()
    }
}

fn observed_order(method: Method, n1: usize) -> f64 {
    let err = |n: usize| {
        let o = Options {
            rtol: 1e-10,
            atol: 1e-10,
            method,
            fixed_step: Some(10.0 / n as f64),
            ..Options::default()
        };
        let s = solve(&ExpSin, 0.0, &[1.0], 10.0, &o).expect("solves");
        (s.y[0] - 10f64.sin().exp()).abs()
    };
    (err(n1) / err(2 * n1)).log2()
}

#[test]
fn convergence_orders_within_0_3_of_nominal() {
    // Exact solution exp(sin t); step counts chosen so errors stay far above round-off.
    let p8 = observed_order(Method::Dop853, 20);
    let p5 = observed_order(Method::Dopri5, 80);
    let pr = observed_order(Method::Radau5, 80);
    assert!((p8 - 8.0).abs() <= 0.6, "DOP853 order {p8}");
    assert!((p5 - 5.0).abs() <= 0.3, "DOPRI5 order {p5}");
    assert!((pr - 5.0).abs() <= 0.3, "Radau5 order {pr}");
}

#[test]
fn evaluation_counts_match_hairers_codes() {
    // Published counts of Hairer's DOP853 (86, 295, 704) and DOPRI5 (110) on
    // z'' = -max(z,0)^1.5, z(0)=0, z'(0)=1, to t = 3.218065459719043, rtol = atol.
    let t_end = 3.218_065_459_719_043;
    for (tol, count) in [(1e-6, 86), (1e-9, 295), (1e-12, 704)] {
        let s = solve(
            &HertzUnit,
            0.0,
            &[0.0, 1.0],
            t_end,
            &opts(Method::Dop853, tol),
        )
        .expect("solves");
        assert_eq!(s.stats.rhs_evals, count, "DOP853 at {tol:e}");
    }
    let s = solve(
        &HertzUnit,
        0.0,
        &[0.0, 1.0],
        t_end,
        &opts(Method::Dopri5, 1e-6),
    )
    .expect("solves");
    assert_eq!(s.stats.rhs_evals, 110);
}

#[test]
fn bouncing_ball_impact_time_to_1e_12() {
    // Closed form: y(t) = 1 - g t^2/2 reaches 0 at sqrt(2/g).
    let ground = |_t: f64, y: &[f64]| y[0];
    for method in [Method::Dop853, Method::Dopri5, Method::Radau5] {
        let o = Options {
            events: vec![Event::new("ground", &ground, Direction::Falling, true)],
            ..opts(method, 1e-12)
        };
        let s = solve(&Fall, 0.0, &[1.0, 0.0], 10.0, &o).expect("solves");
        let exact = (2.0 / G).sqrt();
        assert!(matches!(s.stop, Stop::Event { index: 0, .. }));
        assert!(
            (s.t - exact).abs() < 1e-12,
            "{method:?}: {} vs {exact}",
            s.t
        );
        assert!(s.y[0].abs() < 1e-12);
    }
}

#[test]
fn oscillator_zeros_in_both_directions() {
    // Closed form: cos t = 0 at pi/2 + k pi; falling at pi/2, 5pi/2, ...; rising at 3pi/2, ...
    let g = |_t: f64, y: &[f64]| y[0];
    let o = Options {
        events: vec![
            Event::new("falling", &g, Direction::Falling, false),
            Event::new("rising", &g, Direction::Rising, false),
        ],
        ..opts(Method::Dop853, 1e-13)
    };
    let s = solve(&Oscillator, 0.0, &[1.0, 0.0], 20.0, &o).expect("solves");
    let pi = std::f64::consts::PI;
    let expect: Vec<(f64, usize)> = (0..6).map(|k| (pi / 2.0 + k as f64 * pi, k % 2)).collect();
    assert_eq!(s.events.len(), expect.len());
    for (h, (t, idx)) in s.events.iter().zip(expect) {
        assert_eq!(h.index, idx);
        assert!((h.t - t).abs() < 1e-12, "{} vs {t}", h.t);
    }
}

#[test]
fn two_sign_changes_inside_one_step_are_both_found() {
    // Loose tolerance: steps longer than the half period pi; every zero must still be found.
    let g = |_t: f64, y: &[f64]| y[0];
    let o = Options {
        events: vec![Event::new("zero", &g, Direction::Both, false)],
        ..opts(Method::Dop853, 1e-3)
    };
    let s = solve(&Oscillator, 0.0, &[1.0, 0.0], 30.0, &o).expect("solves");
    let longest = s
        .events
        .windows(2)
        .map(|w| w[1].t - w[0].t)
        .fold(0.0, f64::max);
    assert_eq!(s.events.len(), 10, "zeros of cos t in (0, 30)");
    assert!(longest < 3.5);
    // the steps really were long enough to hold two zeros
    assert!(s.stats.steps < 15, "{}", s.stats);
}

#[test]
fn root_at_t0_does_not_fire_and_root_at_step_end_fires_once() {
    // y = sin t starts on its root: the first event is at pi, not at 0.
    let g = |_t: f64, y: &[f64]| y[0];
    let o = Options {
        events: vec![Event::new("zero", &g, Direction::Both, false)],
        ..opts(Method::Dop853, 1e-12)
    };
    let s = solve(&Oscillator, 0.0, &[0.0, 1.0], 4.0, &o).expect("solves");
    assert_eq!(s.events.len(), 1);
    assert!((s.events[0].t - std::f64::consts::PI).abs() < 1e-12);
    // y' = 1 with fixed steps of 0.5: y - 1 vanishes exactly at a step end
    struct Ramp;
    impl OdeSystem for Ramp {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, _t: f64, _y: &[f64], dy: &mut [f64]) {
            dy[0] = 1.0;
        }
    }
    let g1 = |_t: f64, y: &[f64]| y[0] - 1.0;
    let o = Options {
        events: vec![Event::new("one", &g1, Direction::Rising, false)],
        fixed_step: Some(0.5),
        ..opts(Method::Dop853, 1e-9)
    };
    let s = solve(&Ramp, 0.0, &[0.0], 2.0, &o).expect("solves");
    assert_eq!(s.events.len(), 1);
    assert!((s.events[0].t - 1.0).abs() < 1e-15);
}

#[test]
fn nan_event_is_an_error_not_a_loop() {
    let g = |t: f64, _y: &[f64]| if t > 0.5 { f64::NAN } else { 1.0 };
    let o = Options {
        events: vec![Event::new("bad", &g, Direction::Both, true)],
        ..opts(Method::Dop853, 1e-8)
    };
    let e = solve(&Oscillator, 0.0, &[1.0, 0.0], 10.0, &o).unwrap_err();
    assert!(matches!(e, IntegrateError::EventNonFinite { .. }), "{e:?}");
}

#[test]
fn dense_output_matches_closed_form() {
    let times: Vec<f64> = (1..40).map(|i| i as f64 * 0.25).collect();
    for (method, tol) in [
        (Method::Dop853, 1e-12),
        (Method::Dopri5, 1e-12),
        (Method::Radau5, 1e-12),
    ] {
        let o = Options {
            dense_times: times.clone(),
            ..opts(method, tol)
        };
        let s = solve(&Oscillator, 0.0, &[1.0, 0.0], 10.0, &o).expect("solves");
        assert_eq!(s.dense.len(), times.len());
        for (t, y) in &s.dense {
            // dense output is a lower-order interpolant: allow 1e3 x tol; both components (the
            // second is where an index slip between components shows)
            for (got, want) in [(y[0], t.cos()), (y[1], -t.sin())] {
                assert!(
                    (got - want).abs() < 1e3 * tol.max(1e-12) * 10.0,
                    "{method:?} t={t}: {}",
                    got - want
                );
            }
        }
    }
}

#[test]
fn dense_output_between_large_steps_is_near_the_tolerance() {
    // loose tolerances, large steps: the interpolant between steps is as good as the steps (10x
    // the tolerance against the closed form cos t, -sin t), in each component
    let times: Vec<f64> = (1..80).map(|i| i as f64 * 0.123).collect();
    for (method, tol, slack) in [
        (Method::Dop853, 1e-7, 10.0),
        (Method::Dopri5, 1e-7, 10.0),
        (Method::Radau5, 1e-7, 10.0),
    ] {
        let o = Options {
            dense_times: times.clone(),
            ..opts(method, tol)
        };
        let s = solve(&Oscillator, 0.0, &[1.0, 0.0], 10.0, &o).expect("solves");
        let worst = s
            .dense
            .iter()
            .map(|(t, y)| (y[0] - t.cos()).abs().max((y[1] + t.sin()).abs()))
            .fold(0.0, f64::max);
        let at_steps = (s.y[0] - 10f64.cos())
            .abs()
            .max((s.y[1] + 10f64.sin()).abs());
        assert!(
            worst < slack * tol.max(at_steps),
            "{method:?}: dense error {worst:e}, end error {at_steps:e}"
        );
    }
}

#[test]
fn a_state_that_becomes_nan_is_an_error_that_says_so() {
    // the right side is NaN after t = 0.5: every method stops with NonFinite there, never with
    // a step-size or step-count error, never with an answer
    struct GoesNan;
    impl OdeSystem for GoesNan {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = if t > 0.5 { f64::NAN } else { -y[0] };
        }
    }
    for method in [Method::Dop853, Method::Dopri5] {
        let e = solve(&GoesNan, 0.0, &[1.0], 2.0, &opts(method, 1e-8)).unwrap_err();
        assert!(
            matches!(e, IntegrateError::NonFinite { t } if t > 0.5 && t <= 2.0),
            "{method:?}: {e:?}"
        );
    }
}

#[test]
fn radau5_recovers_from_a_step_whose_newton_iterates_leave_the_domain() {
    // y' = -sqrt(y), y(0) = 1: y = (1 - t/2)^2 until t = 2 (closed form). A first step of 1.9
    // puts Newton's iterates below 0, where the right side is NaN: the step must be halved and
    // retried (Hairer's "unexpected step rejection"), not accepted
    struct Sqrt;
    impl OdeSystem for Sqrt {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = -y[0].sqrt();
        }
    }
    let o = Options {
        h0: Some(1.9),
        ..opts(Method::Radau5, 1e-9)
    };
    let s = solve(&Sqrt, 0.0, &[1.0], 1.5, &o).expect("solves");
    let exact = (1.0f64 - 0.75).powi(2);
    assert!((s.y[0] - exact).abs() < 1e-7, "{} vs {exact}", s.y[0]);
}

#[test]
fn radau5_keeps_its_lu_while_the_step_size_is_kept() {
    // Hairer's RADAU5 keeps h (and so the factorisation of I/h - J) when the proposed step ratio
    // lies in [1, 1.2] and the Jacobian is reused: on a smooth problem over many steps some LU
    // decompositions must be saved
    let s = solve(
        &Oscillator,
        0.0,
        &[1.0, 0.0],
        50.0,
        &opts(Method::Radau5, 1e-9),
    )
    .expect("solves");
    assert!(
        s.stats.lu_decomps < s.stats.steps + s.stats.rejected,
        "{} LU decompositions for {} attempts",
        s.stats.lu_decomps,
        s.stats.steps + s.stats.rejected
    );
}

#[test]
fn work_precision_reports_the_error_against_the_reference() {
    // the reported error is |y - y_ref| (floored relative): against the closed form of the
    // oscillator at t = 10 it is small; against a reference shifted by 1e-3 it is 1e-3
    let exact = [10f64.cos(), -10f64.sin()];
    let shifted = [exact[0] + 1e-3, exact[1]];
    for (reference, lo, hi) in [(exact, 0.0, 1e-8), (shifted, 0.9e-3, 1.1e-3)] {
        let p = impactcheck::integrate::workprecision::work_precision(
            &Oscillator,
            (0.0, &[1.0, 0.0], 10.0),
            &reference,
            &[Method::Dop853, Method::Radau5],
            &[1e-10],
            1,
        )
        .expect("runs");
        for (w, method) in p.iter().zip([Method::Dop853, Method::Radau5]) {
            assert_eq!(w.method, method, "the point says its method");
            assert!(
                w.error >= lo && w.error <= hi,
                "{method:?}: error {} not in [{lo}, {hi}]",
                w.error
            );
        }
        // each method did its own work: Radau5 evaluates a Jacobian, DOP853 does not
        assert!(p[0].stats.jac_evals == 0 && p[1].stats.jac_evals > 0);
    }
}

#[test]
fn van_der_pol_stiff_reference() {
    // Reference: SciPy 1.17 solve_ivp LSODA (rtol=atol=1e-12) and Radau (1e-10) agree on
    // y(2) = (1.7061674375, -0.8928100166) to 4e-11.
    for analytic in [true, false] {
        let sys = VanDerPol {
            eps: 1e-6,
            analytic_jacobian: analytic,
        };
        let s = solve(&sys, 0.0, &[2.0, -0.66], 2.0, &opts(Method::Radau5, 1e-9)).expect("solves");
        assert!((s.y[0] - 1.706_167_437_5).abs() < 1e-6, "{:?}", s.y);
        assert!((s.y[1] + 0.892_810_016_6).abs() < 1e-5, "{:?}", s.y);
        // tolerances as given (not Hairer's 0.1 rtol^(2/3)): about 4,800 steps
        assert!(s.stats.steps < 6000, "{}", s.stats);
    }
}

#[test]
fn robertson_reference() {
    // Reference: SciPy LSODA at rtol 1e-12 and 1e-11 (agree to 3e-11 relative).
    let s = solve(
        &Robertson,
        0.0,
        &[1.0, 0.0, 0.0],
        40.0,
        &Options {
            atol: 1e-14,
            ..opts(Method::Radau5, 1e-10)
        },
    )
    .expect("solves");
    let r40 = [
        0.715_827_068_723_457_6,
        9.185_534_764_715_265e-6,
        0.284_163_745_741_777_6,
    ];
    for (a, r) in s.y.iter().zip(r40) {
        assert!((a - r).abs() <= 1e-7 * r, "{a} vs {r}");
    }
    let s = solve(
        &Robertson,
        0.0,
        &[1.0, 0.0, 0.0],
        1e5,
        &Options {
            atol: 1e-14,
            ..opts(Method::Radau5, 1e-10)
        },
    )
    .expect("solves");
    let r5 = [
        0.017_865_921_143_060_74,
        7.274_751_468_834_791e-8,
        0.982_134_006_109_421_1,
    ];
    for (a, r) in s.y.iter().zip(r5) {
        assert!((a - r).abs() <= 1e-6 * r, "{a} vs {r}");
    }
    // tolerances as given (not Hairer's 0.1 rtol^(2/3)): about 1,700 steps
    assert!(s.stats.steps < 2500, "{}", s.stats);
}

#[test]
fn auto_switches_when_the_problem_becomes_stiff() {
    // Reference: the solution tracks cos t to O(1/lambda) once lambda is large.
    let s = solve(&BecomesStiff, 0.0, &[1.0], 4.0, &opts(Method::Auto, 1e-8)).expect("solves");
    let ts = s.switched_at.expect("switched to Radau5");
    assert!(ts > 0.0 && ts < 2.0, "switched at {ts}");
    assert!((s.y[0] - 4f64.cos()).abs() < 1e-6);
    let auto_evals = s.stats.rhs_evals;
    // DOP853 alone says it should have switched, and pays for not doing so
    let s = solve(&BecomesStiff, 0.0, &[1.0], 2.0, &opts(Method::Dop853, 1e-8)).expect("solves");
    assert!(s.stiffness_detected_at.is_some());
    assert!(s.switched_at.is_none());
    assert!(
        s.stats.rhs_evals > 10 * auto_evals,
        "{} vs auto {auto_evals}",
        s.stats.rhs_evals
    );
}

#[test]
fn too_many_steps_says_where() {
    let o = Options {
        max_steps: 50,
        ..opts(Method::Dop853, 1e-10)
    };
    let e = solve(&BecomesStiff, 0.0, &[1.0], 4.0, &o).unwrap_err();
    match e {
        IntegrateError::TooManySteps { t, h, max_steps } => {
            assert_eq!(max_steps, 50);
            assert!(t > 0.0 && h > 0.0);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn bad_options_are_rejected() {
    let e = solve(
        &Oscillator,
        0.0,
        &[1.0, 0.0],
        1.0,
        &opts(Method::Dop853, -1.0),
    )
    .unwrap_err();
    assert!(matches!(e, IntegrateError::BadOption { field: "rtol", .. }));
    let e = solve(
        &Oscillator,
        0.0,
        &[f64::NAN, 0.0],
        1.0,
        &opts(Method::Dop853, 1e-6),
    )
    .unwrap_err();
    assert!(matches!(e, IntegrateError::BadOption { field: "y0", .. }));
}

#[test]
fn the_limits_of_the_options_are_exact() {
    // the boundaries themselves (found by mutation testing: `atol > 0` read as `>= 0` passed):
    // rtol = 0, rtol = 1, atol = 0 and t_end = t0 are refused; values inside the limits run
    let run = |rtol: f64, atol: f64, t_end: f64| {
        let mut o = opts(Method::Dop853, 1e-6);
        o.rtol = rtol;
        o.atol = atol;
        solve(&Oscillator, 0.0, &[1.0, 0.0], t_end, &o)
    };
    for (rtol, atol, t_end, field) in [
        (0.0, 1e-9, 1.0, "rtol"),
        (1.0, 1e-9, 1.0, "rtol"),
        (1e-6, 0.0, 1.0, "atol"),
        (1e-6, 1e-9, 0.0, "t_end"),
    ] {
        let e = run(rtol, atol, t_end).unwrap_err();
        assert!(
            matches!(e, IntegrateError::BadOption { field: f, .. } if f == field),
            "rtol {rtol}, atol {atol}, t_end {t_end}: {e}"
        );
    }
    assert!(run(1e-3, 1e-12, 1.0).is_ok());
    assert!(run(0.5, 1e-6, 1.0).is_ok());
}
