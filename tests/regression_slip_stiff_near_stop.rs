//! Seeded random impact #58768 of the sweep benchmark (`examples/rigid_fail`) stopped with "more
//! than 100000 steps needed" at normal impulse 7.6314, h = 1.5e-10: mu = 1.0792 is just above the
//! stick threshold mu* = 1.0787, the slip dies out slowly along a stable ray of slip directions,
//! and the direction's turning rate grows like 1/|V_t| as the slip goes to zero, so the equations
//! turned ever stiffer and the steps collapsed before the stop. Once the slip lies on the ray (its
//! component across the ray under 1e-2 rtol of the velocity scale and 1e-6 rad) the friction
//! direction is now held along the ray, and the slip stops at a simple root.

mod common;

#[test]
fn slow_slip_stop_above_the_stick_threshold_sticks() {
    let r = common::check_case(58_768, &["slip", "stick"]);
    assert!(r.stats.steps < 1000, "{} steps", r.stats.steps);
}
