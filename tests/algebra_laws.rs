//! Laws of the exact algebra, by proptest over random exponential polynomials: ring axioms,
//! the fundamental theorem of calculus, and the operator L(delta) of 000_92d54b11128ea1ec.txt
//! solving y' + delta y = g with y(0) = 0 (including the resonant rate delta == beta).

use impactcheck::algebra::expo::Expo;
use impactcheck::algebra::poly::{Poly, Q};
use impactcheck::algebra::ratfunc::RatFunc;
use proptest::prelude::*;

fn rate(i: u8) -> Poly {
    let a = Poly::sym("alpha");
    let g = Poly::sym("gamma");
    match i % 6 {
        0 => Poly::zero(),
        1 => a,
        2 => g,
        3 => &a + &g,
        4 => &a + &a,
        _ => &g - &a,
    }
}

fn coeff(n: i32, d: u8, sym: u8) -> RatFunc {
    let c = RatFunc::from_q(Q::new(n.into(), (d as i32 + 1).into()));
    match sym % 3 {
        0 => c,
        1 => &c * &RatFunc::sym("v0"),
        _ => &c * &RatFunc::sym("a8"),
    }
}

fn expo() -> impl Strategy<Value = Expo> {
    prop::collection::vec((-5i32..=5, 0u8..4, 0u8..3, 0u32..3, 0u8..6), 0..4).prop_map(|parts| {
        let mut e = Expo::zero();
        for (n, d, s, k, r) in parts {
            e = &e + &Expo::part(coeff(n, d, s), k, rate(r));
        }
        e
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn addition_is_associative_and_commutative(a in expo(), b in expo(), c in expo()) {
        prop_assert_eq!(&(&a + &b) + &c, &a + &(&b + &c));
        prop_assert_eq!(&a + &b, &b + &a);
        prop_assert!((&a - &a).is_zero());
    }

    #[test]
    fn multiplication_distributes(a in expo(), b in expo(), c in expo()) {
        prop_assert_eq!(&a * &(&b + &c), &(&a * &b) + &(&a * &c));
        prop_assert_eq!(&a * &b, &b * &a);
        prop_assert_eq!(&(&a * &b) * &c, &a * &(&b * &c));
    }

    #[test]
    fn derivative_of_integral_is_identity(g in expo()) {
        prop_assert_eq!(g.integral().deriv(), g.clone());
        // and the integral vanishes at t = 0
        prop_assert!(g.integral().taylor_coeff(0).is_zero());
    }

    #[test]
    fn product_rule(a in expo(), b in expo()) {
        prop_assert_eq!((&a * &b).deriv(), &(&a.deriv() * &b) + &(&a * &b.deriv()));
    }

    #[test]
    fn operator_l_solves_its_ode(g in expo(), r in 0u8..6) {
        let delta = rate(r);
        let y = g.op_l(&delta);
        let residual = &(&y.deriv() + &y.scale(&RatFunc::from_poly(delta.clone()))) - &g;
        prop_assert!(residual.is_zero(), "y' + delta y - g = {}", residual.to_text());
        prop_assert!(y.taylor_coeff(0).is_zero());
    }

    #[test]
    fn taylor_coefficients_of_derivative_shift(g in expo(), n in 0u32..6) {
        // [t^n] g' = (n+1) [t^(n+1)] g
        let lhs = g.deriv().taylor_coeff(n);
        let rhs = g.taylor_coeff(n + 1).scale(&Q::from_integer((n as i64 + 1).into()));
        prop_assert_eq!(lhs, rhs);
    }
}

#[test]
fn ratfunc_field_laws_on_fixed_cases() {
    let a = RatFunc::sym("alpha");
    let g = RatFunc::sym("gamma");
    let x = (&a - &g).inv().expect("non-zero");
    let y = (&(&a * &a) + &g).inv().expect("non-zero");
    assert_eq!(&(&x + &y) - &y, x);
    assert_eq!(&x * &x.inv().expect("non-zero"), RatFunc::one());
    assert_ne!(x, y);
}
