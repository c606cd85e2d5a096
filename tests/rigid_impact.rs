//! Rigid-body impact in the normal impulse (002_b53e4779673eb6ed.txt section 1): closed forms,
//! Proposition 1's bounds, Kelvin's formula and energy over random bodies.

use impactcheck::models::rigid_impact::{Body, Contact, Law, b_matrix, impact};
use nalgebra::{Matrix3, Vector3};
use proptest::prelude::*;

fn sphere(m: f64, rho2: f64, offset: Vector3<f64>) -> Body {
    Body {
        mass: Some(m),
        inertia: Matrix3::identity() * (m * rho2),
        offset,
    }
}

fn ground() -> Body {
    Body {
        mass: None,
        inertia: Matrix3::identity(),
        offset: Vector3::zeros(),
    }
}

#[test]
fn frictionless_central_impact_closed_form() {
    // Closed form: I_n = (1+e)|V_n^-| / (1/m1 + 1/m2) for every law when there is no friction
    // and no rotation coupling.
    let n = Vector3::z();
    let b1 = sphere(2.0, 0.4, -n * 0.1);
    let b2 = sphere(3.0, 0.4, n * 0.1);
    for law in [Law::Newton, Law::Poisson, Law::Energetic] {
        for e in [0.0, 0.25, 0.5, 0.75, 1.0] {
            let r = impact(
                &b1,
                &b2,
                Contact::new(n, Vector3::new(0.0, 0.0, -1.5), 0.0, law, e),
                1e-12,
            )
            .expect("solves");
            let expect = (1.0 + e) * 1.5 / (0.5 + 1.0 / 3.0);
            assert!(
                (r.impulse[2] - expect).abs() < 1e-9,
                "{law:?} e={e}: {} vs {expect}",
                r.impulse[2]
            );
            assert!((r.v_rel_after[2] - e * 1.5).abs() < 1e-9);
        }
    }
}

#[test]
fn oblique_sphere_on_ground_slip_then_stick() {
    // Closed form (planar): dVt/dchi = -mu (1 + R^2/rho^2)/m while sliding, dVn/dchi = 1/m;
    // sliding stops at chi_s = vt m/(mu (1 + R^2/rho^2)) and the ball then sticks (tau = 0).
    let (m, r, rho2) = (0.5, 0.1, 0.4 * 0.01);
    let k = 1.0 + r * r / rho2;
    let b1 = sphere(m, rho2, Vector3::new(0.0, 0.0, -r));
    for (vt, mu, e) in [(0.3, 0.4, 0.5), (3.0, 0.2, 0.8), (0.05, 0.6, 1.0)] {
        let vn = 1.0;
        let res = impact(
            &b1,
            &ground(),
            Contact::new(
                Vector3::z(),
                Vector3::new(vt, 0.0, -vn),
                mu,
                Law::Poisson,
                e,
            ),
            1e-12,
        )
        .expect("solves");
        let chi_end = (1.0 + e) * m * vn;
        let vt_end = (vt - mu * k * chi_end / m).max(0.0);
        assert!(
            (res.v_rel_after[0] - vt_end).abs() < 1e-9,
            "vt={vt}: {:?} vs {vt_end}",
            res.v_rel_after
        );
        assert!((res.impulse[2] - chi_end).abs() < 1e-10);
        let sticks = vt_end == 0.0;
        assert_eq!(
            res.phases.iter().any(|p| p.kind == "stick"),
            sticks,
            "{:?}",
            res.phases
        );
        if sticks {
            let chi_s = vt * m / (mu * k);
            let p = res
                .phases
                .iter()
                .find(|p| p.kind == "stick")
                .expect("stick phase");
            assert!((p.normal_impulse - chi_s).abs() < 1e-9 * chi_s.max(1.0));
        }
    }
}

#[test]
fn b_matrix_of_two_balls_is_printed_3_9() {
    // (3.9): B = (2/m) diag{1, R^2/rho^2 + 1, R^2/rho^2 + 1} for G1C = -G2C = (R, 0, 0).
    let (m, r) = (0.17, 0.03);
    let rho2 = 0.4 * r * r;
    let b = b_matrix(
        &sphere(m, rho2, Vector3::new(r, 0.0, 0.0)),
        &sphere(m, rho2, Vector3::new(-r, 0.0, 0.0)),
    )
    .expect("invertible");
    let expect = Matrix3::from_diagonal(&Vector3::new(1.0, 3.5, 3.5)) * (2.0 / m);
    assert!((b - expect).abs().max() < 1e-9 * expect.abs().max());
}

fn spd(a: [f64; 6]) -> Matrix3<f64> {
    let l = Matrix3::new(a[0], 0.0, 0.0, a[1], a[2], 0.0, a[3], a[4], a[5]);
    l * l.transpose() + Matrix3::identity() * 1e-3
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn energy_bounds_and_kelvin_over_random_bodies(
        m1 in 0.1f64..10.0, m2 in 0.1f64..10.0,
        i1 in prop::array::uniform6(0.05f64..1.0), i2 in prop::array::uniform6(0.05f64..1.0),
        r1 in prop::array::uniform3(-0.5f64..0.5), r2 in prop::array::uniform3(-0.5f64..0.5),
        vt in prop::array::uniform2(-2.0f64..2.0), vn in 0.1f64..3.0,
        mu in 0.0f64..1.5, e in 0.0f64..=1.0, law_i in 0usize..2,
    ) {
        let b1 = Body { mass: Some(m1), inertia: spd(i1), offset: Vector3::from(r1) };
        let b2 = Body { mass: Some(m2), inertia: spd(i2), offset: Vector3::from(r2) };
        let law = [Law::Poisson, Law::Energetic][law_i];
        let v = Vector3::new(vt[0], vt[1], -vn);
        let r = impact(&b1, &b2, Contact::new(Vector3::z(), v, mu, law, e), 1e-10).expect("solves");
        let scale = 0.5 * v.norm_squared() / r.lambda_min;
        // (1.12): energy does not grow under Poisson's and Stronge's laws
        prop_assert!(r.energy_change <= 1e-8 * scale, "dT = {}", r.energy_change);
        // Kelvin (1.10) equals the directly computed change
        prop_assert!((r.energy_change - r.kelvin_energy_change).abs() <= 1e-8 * scale);
        // (1.9) and (1.13)
        let imp = Vector3::from(r.impulse).norm();
        prop_assert!(imp <= r.bound_upper * (1.0 + 1e-9));
        prop_assert!(imp >= r.bound_lower * (1.0 - 1e-9));
        prop_assert!(r.impulse[2] >= 0.0);
    }
}
