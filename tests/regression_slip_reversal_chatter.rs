//! Seeded random impact #102926 of the sweep benchmark (`examples/rigid_fail`) ended with "more
//! than 10000 stick/slip switches": mu = 1.281 is below the stick threshold mu* = 1.341, so when
//! the slip stops at normal impulse 4.4127 it must reverse and slide along the direction u with
//! P_t B (n - mu u) parallel to u (here u = (0.175, -0.985), growth rate (W, u) = 8.8e-3). The
//! slip was restarted at 2 slip_stop, only 20 absolute tolerances above the stop event, and the
//! integration noise took it back under the stop at once, over and over. The restart is now 20
//! slip_stop (still under 0.2 rtol of the velocity scale), and the root chosen is the stable one.

mod common;

#[test]
fn slip_reversal_below_the_stick_threshold_ends() {
    // one reversal, then slip to the end (no chatter)
    common::check_case(102_926, &["slip", "reversal"]);
}
