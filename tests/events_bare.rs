//! Events at bare cost: the counts of the Hertz reference against Hairer's DOP853 without events,
//! the event times against closed forms, no crossing missed that a dense scan of every step finds,
//! and no heap allocation per step.
//!
//! References: Hairer's compiled DOP853 on the Hertz problem (m = k = v0 = 1, t_end at the contact
//! time, rtol = atol) used 86 / 295 / 704 evaluations at 1e-6 / 1e-9 / 1e-12 (measured on this
//! machine, reports/performance.md); the contact time is
//! t_c = 2 (5/4)^(2/5) (2/5) Gamma(2/5) Gamma(1/2)/Gamma(9/10) (the first integral of
//! m z'' = -k z^1.5), evaluated with `libm`'s gamma, independent of the integrator.

use impactcheck::integrate::{Direction, Event, Method, OdeSystem, Options, solve};
use impactcheck::models::hertz::{ContactLaw, Hertz, run};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // per thread: the test threads run side by side
    static ALLOCS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, l: Layout) -> *mut u8 {
        ALLOCS.with(|c| c.set(c.get() + 1));
        // SAFETY: the caller's layout is passed on unchanged.
        unsafe { System.alloc(l) }
    }
    unsafe fn dealloc(&self, p: *mut u8, l: Layout) {
        // SAFETY: `p` came from `System.alloc` with this layout.
        unsafe { System.dealloc(p, l) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn gamma(x: f64) -> f64 {
    // Lanczos (g = 7, 9 terms), about 1e-15 relative for x > 0: an independent evaluation
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return std::f64::consts::PI / ((std::f64::consts::PI * x).sin() * gamma(1.0 - x));
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + 7.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    (2.0 * std::f64::consts::PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * a
}

fn contact_time() -> f64 {
    2.0 * 1.25f64.powf(0.4) * 0.4 * gamma(0.4) * gamma(0.5) / gamma(0.9)
}

fn unit_hertz() -> Hertz {
    Hertz {
        mass: 1.0,
        k: 1.0,
        damping: 0.0,
        law: ContactLaw::Hertz,
    }
}

#[test]
fn hertz_counts_are_near_hairers_bare_counts() {
    // reference: Hairer's DOP853 without events (86 / 295 / 704 evaluations, his own code
    // through SciPy's `ode('dop853')`); the events cost only the 7th-order dense output of the
    // one step that holds the peak (3 evaluations): the steps that hold no crossing (the first,
    // where g leaves its zero at t0, among them) are screened for free
    let tc = contact_time();
    assert!((tc - 3.218_065_459_7).abs() < 1e-10, "{tc}");
    let model = unit_hertz();
    for (tol, hairer) in [(1e-6, 86), (1e-9, 295), (1e-12, 704)] {
        let r = run(&model, 1.0, tol, tol, Method::Dop853, Some(tc)).expect("solves");
        assert!(
            r.stats.rhs_evals <= hairer + 3,
            "rtol {tol}: {} evaluations, Hairer {hairer}",
            r.stats.rhs_evals
        );
    }
}

#[test]
fn hertz_contact_end_to_1e_12() {
    let tc = contact_time();
    // at the tightest setting (the solution's own error is 2e-12 at rtol = atol = 1e-12)
    let r = run(&unit_hertz(), 1.0, 1e-13, 1e-13, Method::Dop853, None).expect("solves");
    assert!(r.ended);
    assert!(
        (r.duration - tc).abs() <= 1e-12 * tc,
        "{} against {tc}: {:e}",
        r.duration,
        (r.duration - tc) / tc
    );
}

#[path = "support/oscillator.rs"]
mod oscillator;
use oscillator::Oscillator;

/// The crossings found with the Hermite screen and with the dense output formed on every step
/// (forced by asking for samples in every step).
fn crossings(level: f64, rtol: f64) -> (Vec<f64>, Vec<f64>) {
    let g = move |_t: f64, y: &[f64]| y[0] - level;
    let run = |dense: bool| {
        let opts = Options {
            rtol,
            atol: rtol,
            method: Method::Dop853,
            events: vec![Event::new("level", &g, Direction::Both, false)],
            dense_times: if dense {
                (1..20_000).map(|i| i as f64 * 1e-3).collect()
            } else {
                vec![]
            },
            ..Options::default()
        };
        let sol = solve(&Oscillator, 0.0, &[1.0, 0.0], 20.0, &opts).expect("solves");
        sol.events.iter().map(|e| e.t).collect::<Vec<f64>>()
    };
    (run(false), run(true))
}

#[test]
fn no_crossing_missed_that_a_dense_scan_finds() {
    // levels near the top of cos t (grazing: the two roots of each hump are close), at zero
    // (simple roots), and a level whose roots fall near step ends by chance
    for level in [0.999_999, 0.9999, 0.99, 0.5, 0.0, -0.999_99] {
        for rtol in [1e-6, 1e-9, 1e-12] {
            let (screened, dense) = crossings(level, rtol);
            assert_eq!(
                screened.len(),
                dense.len(),
                "level {level}, rtol {rtol}: {screened:?} vs {dense:?}"
            );
            for (a, b) in screened.iter().zip(&dense) {
                assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} vs {b}");
            }
            // each found crossing is a root of cos t = level (closed form), to the accuracy of the
            // solution itself
            for t in &screened {
                let r = t.cos() - level;
                assert!(
                    r.abs() < 100.0 * rtol,
                    "level {level}: cos({t}) - level = {r}"
                );
            }
        }
    }
}

#[test]
fn two_roots_in_one_step_and_a_root_at_the_end() {
    // y' = 1 from 0: DOP853's steps grow by up to 6 at a time, so the last ones span most of the
    // interval; g = (y - 1)(y - 3) puts two roots in one step, g = y - 10 its root at the end
    struct Line;
    impl OdeSystem for Line {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&self, _t: f64, _y: &[f64], dy: &mut [f64]) {
            dy[0] = 1.0;
        }
    }
    let two = |_t: f64, y: &[f64]| (y[0] - 1.0) * (y[0] - 3.0);
    let end = |_t: f64, y: &[f64]| y[0] - 10.0;
    let opts = Options {
        rtol: 1e-10,
        atol: 1e-10,
        events: vec![
            Event::new("two", &two, Direction::Both, false),
            Event::new("end", &end, Direction::Both, false),
        ],
        trajectory: true,
        ..Options::default()
    };
    let sol = solve(&Line, 0.0, &[0.0], 10.0, &opts).expect("solves");
    // the step ends: one step holds both roots of the first event
    let ends: Vec<f64> = sol.trajectory.iter().map(|(t, _)| *t).collect();
    assert!(
        ends.windows(2).any(|w| w[0] < 1.0 && w[1] > 3.0),
        "no step holds both roots: {ends:?}"
    );
    let ts: Vec<(usize, f64)> = sol.events.iter().map(|e| (e.index, e.t)).collect();
    assert_eq!(ts.len(), 3, "{ts:?}");
    assert!(
        (ts[0].1 - 1.0).abs() < 1e-12 && (ts[1].1 - 3.0).abs() < 1e-12,
        "{ts:?}"
    );
    assert_eq!(ts[2].0, 1);
    assert!((ts[2].1 - 10.0).abs() < 1e-12, "{ts:?}");
}

#[test]
fn no_allocation_per_step() {
    // the allocations of a solve do not grow with its steps (with an event on that never fires:
    // a located crossing keeps its state, which is an allocation of its own)
    let g = |_t: f64, y: &[f64]| y[0] - 5.0;
    let count = |t_end: f64| {
        let opts = Options {
            rtol: 1e-10,
            atol: 1e-10,
            events: vec![Event::new("level", &g, Direction::Both, false)],
            ..Options::default()
        };
        let before = ALLOCS.with(Cell::get);
        let sol = solve(&Oscillator, 0.0, &[1.0, 0.0], t_end, &opts).expect("solves");
        let after = ALLOCS.with(Cell::get);
        (after - before, sol.stats.steps, sol.events.len())
    };
    let (a1, s1, e1) = count(20.0);
    let (a2, s2, e2) = count(200.0);
    assert!(s2 > 5 * s1, "{s1} {s2}");
    assert_eq!((e1, e2), (0, 0));
    assert_eq!(
        a1, a2,
        "{a1} allocations for {s1} steps, {a2} for {s2} steps"
    );
}

#[test]
fn radau5_allocates_nothing_per_step() {
    // a stiff forced system (rates 1 and 1e4): Radau5 refactors its two matrices on most steps,
    // in its own workspace; the allocations of a solve do not grow with its steps
    struct Stiff;
    impl OdeSystem for Stiff {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&self, t: f64, y: &[f64], dy: &mut [f64]) {
            // y1 follows cos(10 t) on the fast scale, y0 follows y1 slowly: the forcing keeps
            // the steps short all the way
            dy[0] = -y[0] + y[1];
            dy[1] = -1e4 * (y[1] - (10.0 * t).cos());
        }
    }
    let count = |t_end: f64| {
        let opts = Options {
            rtol: 1e-9,
            atol: 1e-12,
            method: Method::Radau5,
            ..Options::default()
        };
        let before = ALLOCS.with(Cell::get);
        let sol = solve(&Stiff, 0.0, &[1.0, 0.0], t_end, &opts).expect("solves");
        let after = ALLOCS.with(Cell::get);
        (after - before, sol.stats.steps, sol.stats.lu_decomps)
    };
    let (a1, s1, d1) = count(2.0);
    let (a2, s2, d2) = count(40.0);
    assert!(s2 > 3 * s1 && d2 > 3 * d1, "{s1} {s2} steps, {d1} {d2} LUs");
    assert_eq!(
        a1, a2,
        "{a1} allocations for {s1} steps ({d1} LUs), {a2} for {s2} steps ({d2} LUs)"
    );
}
