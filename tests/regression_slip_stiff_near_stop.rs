//! Seeded random impact #58768 of the sweep benchmark (`examples/rigid_fail`) stopped with "more
//! than 100000 steps needed" at normal impulse 7.6314, h = 1.5e-10: mu = 1.0792 is just above the
//! stick threshold mu* = 1.0787, the slip dies out slowly along a stable ray of slip directions,
//! and the direction's turning rate grows like 1/|V_t| as the slip goes to zero, so the equations
//! turned ever stiffer and the steps collapsed before the stop. Once the slip lies on the ray (its
//! component across the ray under 1e-2 rtol of the velocity scale and 1e-6 rad) the friction
//! direction is now held along the ray, and the slip stops at a simple root.

#[test]
fn slow_slip_stop_above_the_stick_threshold_sticks() {
    let (_, v, _, e) = impactcheck::perf::rigid_inputs(58_768);
    let r = impactcheck::perf::rigid_case(58_768).expect("the impact ends");
    let kinds: Vec<&str> = r.phases.iter().map(|p| p.kind.as_str()).collect();
    assert_eq!(kinds, ["slip", "stick"], "{kinds:?}");
    let chi_end = (1.0 + e) * r.compression_impulse;
    assert!(
        (r.impulse[2] - chi_end).abs() <= 1e-8 * chi_end,
        "{} vs {chi_end}",
        r.impulse[2]
    );
    assert!(r.energy_change <= 1e-9 * v.norm_squared());
    assert!(nalgebra::Vector3::from(r.impulse).norm() <= r.bound_upper * (1.0 + 1e-9));
    assert!(r.stats.steps < 1000, "{} steps", r.stats.steps);
}
