//! Regression: a flight shorter than the sample spacing of the step it starts in. Found with a
//! ball whose restitution alternates (tests/ode_sequences.rs): after its 23rd impact it left the
//! floor at z = -1.5e-19 with 3.4e-4 m/s, and the first step after the jump, long because the
//! flight is a polynomial DOP853 integrates exactly, held the whole 69 us flight before its first
//! sample: no sample saw z > 0, the landing was missed and the ball fell 313 m through the floor.
//!
//! Reference: free flight z(t) = z0 + v0 t - g t^2/2, whose roots are in closed form. Each case
//! forces a long first step (`h0`) and carries a constant state `c` that keeps the step long.

use impactcheck::integrate::{Direction, Event, Method, OdeSystem, Options, solve};

const G: f64 = 9.81;

/// The times found agree with the closed form to the rounding of the dense output over a step of
/// 0.5 s (eps h = 1.1e-16 s), with a margin of 100.
const DT: f64 = 1e-14;

/// (z, v, c): z'' = -g; c' = 0.
struct Flight;
impl OdeSystem for Flight {
    fn dim(&self) -> usize {
        3
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -G;
        dy[2] = 0.0;
    }
}

/// The later root of z0 + v0 t - g t^2/2 (the landing), written to avoid cancellation.
fn landing(z0: f64, v0: f64) -> f64 {
    let q = v0 + (v0 * v0 + 2.0 * G * z0).sqrt();
    q / G
}

/// The hits of one event on `z` (as a component or through a closure) from (z0, v0).
fn hits(z0: f64, v0: f64, dir: Direction, component: bool, method: Method) -> Vec<f64> {
    let g = |_t: f64, y: &[f64]| y[0];
    let e = Event::new("floor", &g, dir, false);
    let e = if component { e.reading(0) } else { e };
    let opts = Options {
        rtol: 1e-12,
        atol: 1e-14,
        method,
        h0: Some(0.5),
        events: vec![e],
        ..Options::default()
    };
    let sol = solve(&Flight, 0.0, &[z0, v0, 1.0], 1.0, &opts).expect("solves");
    sol.events.iter().map(|h| h.t).collect()
}

#[test]
fn a_landing_before_the_first_sample_is_seen() {
    // z0 just below the floor, moving up: crosses up at about z0/v0 = 1e-15 s, lands at 2 v0/g
    let (z0, v0) = (-1.5e-19, 3.4e-4);
    let t_land = landing(z0, v0);
    assert!((t_land - 2.0 * v0 / G).abs() < 1e-15);
    for component in [true, false] {
        let down = hits(z0, v0, Direction::Falling, component, Method::Dop853);
        assert_eq!(down.len(), 1, "component {component}: {down:?}");
        assert!((down[0] - t_land).abs() < DT, "{} vs {t_land}", down[0]);
        // both ways: the crossing up right after the start, then the landing
        let both = hits(z0, v0, Direction::Both, component, Method::Dop853);
        assert_eq!(both.len(), 2, "{both:?}");
        assert!(both[0] < 1e-13 && (both[1] - t_land).abs() < DT, "{both:?}");
    }
}

#[test]
fn a_landing_after_leaving_an_exact_zero_is_seen() {
    // z0 = 0 exactly (a root at t0 does not fire), up at 1e-4 m/s: lands at 2 v0/g
    let v0 = 1e-4;
    for component in [true, false] {
        let down = hits(0.0, v0, Direction::Falling, component, Method::Dop853);
        assert_eq!(down.len(), 1, "{down:?}");
        assert!((down[0] - 2.0 * v0 / G).abs() < DT, "{down:?}");
    }
}

#[test]
fn a_turn_short_of_the_floor_is_no_crossing() {
    // below the floor by 1e-9 m, up at 1e-4 m/s: the apex is 1e-9 - 5.1e-10 m below it
    let apex = -1e-9 + 1e-8 / (2.0 * G);
    assert!(apex < 0.0);
    for component in [true, false] {
        assert!(hits(-1e-9, 1e-4, Direction::Both, component, Method::Dop853).is_empty());
    }
    // and just over it: two crossings, at the closed-form roots
    let (z0, v0) = (-1e-9, 2e-4);
    let t_up = (v0 - (v0 * v0 + 2.0 * G * z0).sqrt()) / G;
    let both = hits(z0, v0, Direction::Both, true, Method::Dop853);
    assert_eq!(both.len(), 2, "{both:?}");
    assert!((both[0] - t_up).abs() < DT, "{both:?} vs {t_up}");
    assert!((both[1] - landing(z0, v0)).abs() < DT, "{both:?}");
}

#[test]
fn radau_sees_the_landing_too() {
    // RADAU5 has no Hermite interpolant: the slope at the start comes from its dense output
    let (z0, v0) = (-1.5e-19, 3.4e-4);
    let down = hits(z0, v0, Direction::Falling, true, Method::Radau5);
    assert_eq!(down.len(), 1, "{down:?}");
    // (its simplified Newton iteration stops at a fraction of rtol: 1e-12 s here is 1e-8 of
    // the flight)
    assert!((down[0] - landing(z0, v0)).abs() < 1e-12, "{down:?}");
}
