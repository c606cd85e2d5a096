//! Seeded random impact #72793 of the sweep benchmark (`examples/rigid_fail`) stopped with "more
//! than 100000 steps needed" at normal impulse 0.8819, h = 1.9e-11: the slip dies out along a
//! stable ray of slip directions (P_t B (n - mu u) parallel to u, the speed falling at a constant
//! rate), so |V_t| reaches zero with a corner; within one step the integrator overshot zero by more
//! than the stop threshold, |V_t| - slip_stop was never seen negative, and the steps collapsed in
//! the chatter around V_t = 0. The speed along the ray, (V_t, u) - slip_stop, falls through zero at
//! a simple root: that event now stops the slip (mu = 0.88 allows sticking there).

mod common;

#[test]
fn slip_that_dies_on_its_ray_sticks() {
    common::check_case(72_793, &["slip", "stick"]);
}
