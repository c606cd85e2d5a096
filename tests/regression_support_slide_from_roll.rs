//! Regression: seeded constrained impacts 8527 and 12955 of `examples/constrained_fail` (a rough
//! support under the second body) failed with "more than 100000 steps needed": the support rolled
//! until its reaction reached the friction cone, then slid from rest, where (4.5)'s rate starts at
//! zero and the slide direction turned ever faster as the slip stayed at its floor. The slide now
//! keeps the direction (4.5) gives until the slip exceeds the velocity tolerance. What must hold:
//! the impact ends, the support rolled and then slid, and the kinetic energy (from the bodies'
//! velocities under both impulses) did not grow.

use impactcheck::models::constrained::{RigidImpactScene, solve_scene};
use impactcheck::models::rigid_impact::{Body, Law, kinetic_change_moving};
use impactcheck::models::support::Support;
use nalgebra::{Matrix3, Vector3};

fn body(mass: f64, inertia: [f64; 3], offset: [f64; 3]) -> Body {
    Body {
        mass: Some(mass),
        inertia: Matrix3::from_diagonal(&Vector3::from(inertia)),
        offset: Vector3::from(offset),
    }
}

fn check(s: &RigidImpactScene) {
    let (r, _, warnings) = solve_scene(s).expect("the impact ends");
    let r = r.expect("integrated");
    let kinds: Vec<&str> = r.support_phases.iter().map(|p| p.kind.as_str()).collect();
    let roll = kinds.iter().position(|k| *k == "roll").expect("rolls");
    assert!(kinds[roll..].contains(&"slide"), "{kinds:?}");
    let sup = s.support.as_ref().expect("support");
    let de = kinetic_change_moving(
        &s.bodies[0],
        &s.bodies[1],
        &s.v_rel,
        &s.v_support,
        &Vector3::from(r.impulse),
        Some((sup.offset, Vector3::from(r.support_impulse))),
    );
    let scale = 0.5 * s.v_rel.norm_squared() / r.lambda_max;
    assert!(de <= 1e-7 * scale, "energy grows by {de:e} J; {warnings:?}");
}

#[test]
fn seed_8527_slides_out_of_rolling() {
    check(&RigidImpactScene {
        bodies: [
            body(
                3.1491259824166487,
                [
                    0.04823134913428509,
                    0.07914619917170584,
                    0.17191083966148923,
                ],
                [
                    0.45093636064454146,
                    0.37176251864163523,
                    0.24756221366423758,
                ],
            ),
            body(
                5.347833637085292,
                [0.1337277310559537, 0.08886938710843521, 0.10884704452492111],
                [0.4506692562021094, 0.23833812464569093, -0.3705192262945216],
            ),
        ],
        normal: Vector3::z(),
        mu: 1.2532888494309324,
        law: Law::Newton,
        e: 0.6161232908698008,
        v_rel: Vector3::new(-0.42816735294298836, 0.4528048871097665, -2.840125526458212),
        rtol: 1e-10,
        support: Some(Support {
            offset: Vector3::new(
                0.16628144801796463,
                -0.021833831952980942,
                -0.26485171233638094,
            ),
            normal: Vector3::new(
                0.12277346322471319,
                -0.04187738032331673,
                0.9915507862661732,
            ),
            mu: 1.451226678649034,
        }),
        v_support: Vector3::zeros(),
        fixed: None,
        method: Default::default(),
    });
}

#[test]
fn seed_12955_slides_out_of_rolling() {
    check(&RigidImpactScene {
        bodies: [
            body(
                5.475987449229863,
                [0.0583815197663041, 0.1322740463081251, 0.11970147777063218],
                [
                    -0.2915456683837926,
                    -0.09258424474489879,
                    0.3644594775249076,
                ],
            ),
            body(
                3.397395855658061,
                [0.1784883656274696, 0.12674106593137263, 0.1872411065206291],
                [0.276112358587552, 0.02489439960587725, 0.1743143819842572],
            ),
        ],
        normal: Vector3::z(),
        mu: 0.7070305749861553,
        law: Law::Newton,
        e: 0.4016303731689286,
        v_rel: Vector3::new(
            0.22210676791391126,
            -0.7841975634509857,
            -0.27839823568120314,
        ),
        rtol: 1e-10,
        support: Some(Support {
            offset: Vector3::new(
                0.04956084553076845,
                -0.41567593704700045,
                -0.5767707845414691,
            ),
            normal: Vector3::new(0.10433006691360162, 0.09037491023623777, 0.9904279947263179),
            mu: 0.5239039925023259,
        }),
        v_support: Vector3::zeros(),
        fixed: None,
        method: Default::default(),
    });
}
