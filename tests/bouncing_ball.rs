//! A stress test of event location: a ball thrown up from the floor (y'' = -1, v0 = 1) bouncing
//! with restitution e = 0.9, each impact located by a terminal event, against the closed form
//! t_n = 2 (1 - e^n)/(1 - e) (the flights last 2 e^k). DifferentialEquations.jl's version of this
//! test ended below the floor once the flights grew short.
//!
//! The scaling choice: the k-th flight has speed e^k, so an absolute tolerance scaled to its height
//! e^(2k)/2 leaves the normal f64 range after about 3,000 bounces (0.9^6700 underflows the speed
//! itself), and near t = 20 a flight of 1e-10 s is a few thousand ulps of t. So each flight is
//! integrated in its own time from 0 (the impact times are summed, compensated); for 3,000
//! bounces in SI lengths with an absolute tolerance scaled to its height; then, up to 10^4
//! bounces, in its own units (time in e^k, length in e^(2k)), which is the same flight, its time
//! summed with the scale factor.

use impactcheck::integrate::{Direction, Event, Method, OdeSystem, Options, Stop, solve};

struct Ball;
impl OdeSystem for Ball {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, _y: &[f64], dy: &mut [f64]) {
        dy[0] = _y[1];
        dy[1] = -1.0;
    }
}

const E: f64 = 0.9;

fn closed_form(n: i32) -> f64 {
    2.0 * (1.0 - E.powi(n)) / (1.0 - E)
}

/// One flight from the floor with upward speed `v`, in its own time: its duration and the state
/// at the impact.
fn flight(v: f64) -> (f64, [f64; 2]) {
    let t0 = 0.0;
    let floor = |_t: f64, y: &[f64]| y[0];
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-14 * v * v,
        method: Method::Dop853,
        events: vec![Event::new("floor", &floor, Direction::Falling, true)],
        ..Options::default()
    };
    let sol = solve(&Ball, t0, &[0.0, v], t0 + 4.0 * v, &opts).expect("flight solves");
    assert!(
        matches!(sol.stop, Stop::Event { .. }),
        "no impact found in the flight at speed {v:e}"
    );
    (sol.t, [sol.y[0], sol.y[1]])
}

/// Kahan's compensated sum, one term at a time.
#[derive(Default)]
struct Sum {
    s: f64,
    c: f64,
}
impl Sum {
    fn add(&mut self, x: f64) -> f64 {
        let y = x - self.c;
        let t = self.s + y;
        self.c = (t - self.s) - y;
        self.s = t;
        t
    }
}

#[test]
fn bounces_in_si_units_until_the_heights_underflow() {
    let (mut t, mut v) = (Sum::default(), 1.0);
    let mut n = 0;
    // while the absolute tolerance 1e-14 v^2 is a normal number
    while v > 1e-140 {
        let (tau, yi) = flight(v);
        let ti = t.add(tau);
        n += 1;
        // never below the floor: the located impact is on the floor to the flight's tolerance
        assert!(
            yi[0] >= -1e-12 * v * v,
            "bounce {n}: y = {:e} at the impact (height scale {:e})",
            yi[0],
            v * v
        );
        let want = closed_form(n);
        assert!(
            (ti - want).abs() <= 1e-10 * want,
            "bounce {n}: t = {ti} against {want} ({:e})",
            (ti - want) / want
        );
        assert!(
            (yi[1] + v).abs() <= 1e-9 * v,
            "bounce {n}: impact speed {}",
            yi[1]
        );
        v = -E * yi[1];
    }
    assert!(n > 3000, "{n} bounces");
}

#[test]
fn ten_thousand_bounces_in_each_flights_units() {
    let mut sum = Sum::default();
    let mut t = 0.0;
    for k in 0..10_000 {
        // the flight in its own units: speed 1, time in e^k
        let (tau, y) = flight(1.0);
        assert!(y[0] >= -1e-12, "bounce {}: y = {:e}", k + 1, y[0]);
        t = sum.add(E.powi(k) * tau);
        let want = closed_form(k + 1);
        assert!(
            (t - want).abs() <= 1e-10 * want,
            "bounce {}: t = {t} against {want}",
            k + 1
        );
    }
    // the ball comes to rest at 2/(1 - e) = 20
    assert!((t - 20.0).abs() <= 1e-10 * 20.0, "{t}");
}
