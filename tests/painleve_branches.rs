//! The plane example of 002 section 4 ((4.8)): the second body slides to the right on a rough
//! support with beta of (4.4) < 0 and alpha > 0 (b2 > 0), so (3.6) has two solutions. The scene
//! must say so and integrate both branches (`alternatives`), the detaching one as the result.

use impactcheck::models::constrained::{RigidImpactScene, solve_scene_all};
use impactcheck::models::rigid_impact::{Body, Law};
use impactcheck::models::support::Support;
use nalgebra::{Matrix3, Vector3};

#[test]
fn two_solution_start_integrates_both_branches() {
    // m2 = 1, rho2^2 = 0.25 (rotation about z only matters in the plane), G2C = (a2, b2),
    // G2A = (a3, b3) = (0.5, -0.6), mu* = 3: m2 rho2^2 beta = a3^2 + rho2^2 + mu* a3 b3 = -0.4
    let plate = |offset: Vector3<f64>| Body {
        mass: Some(1.0),
        inertia: Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, 0.25)),
        offset,
    };
    let s = RigidImpactScene {
        bodies: [
            plate(Vector3::new(0.4, 0.1, 0.0)),
            plate(Vector3::new(-0.4, 0.5, 0.0)),
        ],
        normal: Vector3::x(),
        mu: 0.0,
        law: Law::Poisson,
        e: 0.5,
        v_rel: Vector3::new(-1.0, 0.0, 0.0),
        rtol: 1e-10,
        support: Some(Support {
            offset: Vector3::new(0.5, -0.6, 0.0),
            normal: Vector3::y(),
            mu: 3.0,
        }),
        v_support: Vector3::new(1.0, 0.0, 0.0),
        fixed: None,
        method: Default::default(),
    };
    let mut alternatives = Vec::new();
    let (r, cl, warnings) = solve_scene_all(&s, &mut alternatives).expect("classified");
    let cl = cl.expect("a classification");
    assert_eq!(cl.kind, "two", "{cl:?}");
    assert!(cl.beta < 0.0 && cl.alpha > 0.0, "{cl:?}");
    assert!(
        warnings.iter().any(|w| w.contains("Painleve")),
        "{warnings:?}"
    );
    let starts: Vec<&str> = alternatives.iter().map(|a| a.start.as_str()).collect();
    assert!(
        starts.contains(&"detach") && starts.len() == 2,
        "{starts:?}"
    );
    // the result is the detaching branch: the support gives no impulse in it
    let r = r.expect("a result");
    let detach = alternatives
        .iter()
        .find(|a| a.start == "detach")
        .expect("detach");
    assert_eq!(Some(r.impulse), detach.impulse);
    assert!(
        Vector3::from(r.support_impulse).norm() == 0.0,
        "{:?}",
        r.support_impulse
    );
    // the sliding branch: F_N* = -alpha/beta > 0 with (4.3): a support impulse with a positive
    // normal part and Coulomb's tangential part against the slide (to +x), mu* times it; less
    // energy than the detaching branch keeps (friction at A works against the slide)
    let slide = alternatives
        .iter()
        .find(|a| a.start == "slide")
        .expect("slide");
    let si = slide.support_impulse.expect("integrated");
    assert!(si[1] > 0.0, "{si:?}");
    assert!((si[0] + 3.0 * si[1]).abs() <= 1e-9 * si[1], "{si:?}");
    let (ed, es) = (
        detach.energy_change.expect("e"),
        slide.energy_change.expect("e"),
    );
    assert!(es < ed && ed < 0.0, "{es} {ed}");
}

/// Seeded constrained impact 6783 (`impactcheck::models::samples::constrained_scene_generic`): (3.6) admits detach,
/// roll and slide at the start, but the detaching branch ends in a Painleve-type instant. The
/// result must then be a branch that ends (the roll one, the first), the same impulse as that
/// branch's entry in `alternatives`, and the warning must say which (it said "the detaching
/// one" for every two-solution start). Seed 3723: no branch ends, no result, and it says so.
#[test]
fn the_result_names_the_branch_it_is() {
    let s = impactcheck::models::samples::constrained_scene_generic(6783);
    let mut alts = Vec::new();
    let (r, _, warnings) = solve_scene_all(&s, &mut alts).expect("classified");
    let r = r.expect("a branch ends");
    let detach = alts.iter().find(|a| a.start == "detach").expect("detach");
    assert!(detach.error.is_some(), "{alts:?}");
    let roll = alts.iter().find(|a| a.start == "roll").expect("roll");
    assert_eq!(roll.impulse, Some(r.impulse));
    assert!(
        warnings
            .iter()
            .any(|w| w.contains("the result is the roll one")),
        "{warnings:?}"
    );

    let s = impactcheck::models::samples::constrained_scene_generic(3723);
    let mut alts = Vec::new();
    let (r, _, warnings) = solve_scene_all(&s, &mut alts).expect("classified");
    assert!(r.is_none());
    assert!(alts.iter().all(|a| a.error.is_some()), "{alts:?}");
    assert!(
        warnings.iter().any(|w| w.contains("no branch ends")),
        "{warnings:?}"
    );
}
