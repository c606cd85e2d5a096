//! Seeded random impacts #272964, #425771, #474652 and #954222 of the sweep benchmark
//! (`examples/rigid_fail 1000000`) ended with "more than 10000 stick/slip switches": mu is just
//! below the stick threshold (0.2 % under mu* for #474652), the slip reverses, and the event that
//! stops a slip dying along its ray, (V_t, u) - slip_stop, fired where the slip only crossed the
//! ray's normal line away from zero; the stage restarted at the root and the event fired again
//! at once, 10000 times. It is now disarmed after such a crossing until the slip settles on the
//! ray or stops.

mod common;

#[test]
fn slip_crossing_the_ray_line_away_from_zero_goes_on() {
    for case in [272_964u64, 425_771, 474_652, 954_222] {
        common::check_case(case, &["slip", "reversal"]);
    }
}
