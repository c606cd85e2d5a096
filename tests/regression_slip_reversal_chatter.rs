//! Seeded random impact #102926 of the sweep benchmark (`examples/rigid_fail`) ended with "more
//! than 10000 stick/slip switches": mu = 1.281 is below the stick threshold mu* = 1.341, so when
//! the slip stops at normal impulse 4.4127 it must reverse and slide along the direction u with
//! P_t B (n - mu u) parallel to u (here u = (0.175, -0.985), growth rate (W, u) = 8.8e-3). The
//! slip was restarted at 2 slip_stop, only 20 absolute tolerances above the stop event, and the
//! integration noise took it back under the stop at once, over and over. The restart is now 20
//! slip_stop (still under 0.2 rtol of the velocity scale), and the root chosen is the stable one.

#[test]
fn slip_reversal_below_the_stick_threshold_ends() {
    let (_, v, _, e) = impactcheck::perf::rigid_inputs(102_926);
    let r = impactcheck::perf::rigid_case(102_926).expect("the impact ends");
    // one reversal, then slip to the end (no chatter)
    let kinds: Vec<&str> = r.phases.iter().map(|p| p.kind.as_str()).collect();
    assert_eq!(kinds, ["slip", "reversal"], "{kinds:?}");
    // Poisson's law: the normal impulse ends at (1 + e) times the compression impulse, and the
    // impulse's normal component is the normal impulse (independent of the stick/slip history)
    let chi_end = (1.0 + e) * r.compression_impulse;
    assert!(
        (r.impulse[2] - chi_end).abs() <= 1e-8 * chi_end,
        "{} vs {chi_end}",
        r.impulse[2]
    );
    // energy never grows, and |I| stays within Proposition 1's bound 2|V-|/lambda_min
    assert!(r.energy_change <= 1e-9 * v.norm_squared());
    assert!(nalgebra::Vector3::from(r.impulse).norm() <= r.bound_upper * (1.0 + 1e-9));
}
