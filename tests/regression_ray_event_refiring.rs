//! Seeded random impacts #272964, #425771, #474652 and #954222 of the sweep benchmark
//! (`examples/rigid_fail 1000000`) ended with "more than 10000 stick/slip switches": mu is just
//! below the stick threshold (0.2 % under mu* for #474652), the slip reverses, and the event that
//! stops a slip dying along its ray, (V_t, u) - slip_stop, fired where the slip only crossed the
//! ray's normal line away from zero; the stage restarted at the root and the event fired again
//! at once, 10000 times. It is now disarmed after such a crossing until the slip settles on the
//! ray or stops.

#[test]
fn slip_crossing_the_ray_line_away_from_zero_goes_on() {
    for case in [272_964u64, 425_771, 474_652, 954_222] {
        let (_, v, _, e) = impactcheck::perf::rigid_inputs(case);
        let r =
            impactcheck::perf::rigid_case(case).unwrap_or_else(|err| panic!("case {case}: {err}"));
        let kinds: Vec<&str> = r.phases.iter().map(|p| p.kind.as_str()).collect();
        assert_eq!(kinds, ["slip", "reversal"], "case {case}: {kinds:?}");
        let chi_end = (1.0 + e) * r.compression_impulse;
        assert!(
            (r.impulse[2] - chi_end).abs() <= 1e-8 * chi_end,
            "case {case}"
        );
        assert!(r.energy_change <= 1e-9 * v.norm_squared(), "case {case}");
    }
}
