//! What every regression test of a seeded random impact checks once it ends: the phases it went
//! through, Poisson's normal impulse (1 + e) times the compression impulse (independent of the
//! stick/slip history), energy never gained, and Proposition 1's bound |I| <= 2|V-|/lambda_min.

/// Runs generic seeded impact `case` (`models::samples::rigid_inputs_generic`, Poisson's law) and checks the above; `phases` as expected.
pub fn check_case(case: u64, phases: &[&str]) -> impactcheck::models::rigid_impact::ImpactResult {
    let (b, v, mu, e) = impactcheck::models::samples::rigid_inputs_generic(case);
    let r = impactcheck::models::rigid_impact::impact_with_matrix(
        &b,
        impactcheck::models::rigid_impact::Contact::new(
            nalgebra::Vector3::z(),
            v,
            mu,
            impactcheck::models::rigid_impact::Law::Poisson,
            e,
        ),
        1e-10,
    )
    .unwrap_or_else(|err| panic!("case {case}: {err}"));
    let kinds: Vec<&str> = r.phases.iter().map(|p| p.kind.as_str()).collect();
    assert_eq!(kinds, phases, "case {case}");
    let chi_end = (1.0 + e) * r.compression_impulse;
    assert!(
        (r.impulse[2] - chi_end).abs() <= 1e-8 * chi_end,
        "case {case}: {} vs {chi_end}",
        r.impulse[2]
    );
    assert!(r.energy_change <= 1e-9 * v.norm_squared(), "case {case}");
    assert!(
        nalgebra::Vector3::from(r.impulse).norm() <= r.bound_upper * (1.0 + 1e-9),
        "case {case}"
    );
    r
}
