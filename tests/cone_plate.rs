//! The cone-plate model of 000_92d54b11128ea1ec.txt: effects cost states only when named, the
//! elastic limit, energy balance, closed forms and an independent SciPy reference.

use impactcheck::integrate::Method;
use impactcheck::models::cone_plate::{self, ConePlate, Effects, Law, Params, Variant};

fn params() -> Params {
    Params {
        mass: 0.05,
        theta_deg: 60.0,
        v0: 2.0,
        e: 2.0e9,
        nu: 0.3,
        eta: 1.0e6,
        a: 0.2,
        b: 0.2,
        h: 0.002,
        rho: 1200.0,
        kw: Some(1.0e6),
        kg: Some(1.0e3),
        ct: Some(10.0),
        inplane: Some((0.0, 0.0)),
    }
}

fn fx(names: &[&str], modes: &[(u32, u32)]) -> Effects {
    let mut e = Effects::default();
    for n in names {
        assert!(e.switch_on(n), "{n} is not an effect");
    }
    e.modes = modes.to_vec();
    e
}

fn build(names: &[&str], modes: &[(u32, u32)], law: Law) -> ConePlate {
    ConePlate::new(params(), fx(names, modes), Variant::Corrected, law).expect("builds")
}

#[test]
fn effects_that_are_off_cost_no_state() {
    // cone: z, z'. Each effect adds only its own states; energy books only what exists.
    type Case<'a> = (&'a [&'a str], &'a [(u32, u32)], Law, usize);
    let cases: &[Case] = &[
        (&[], &[], Law::ConstantBulk, 2),
        (&["viscoelastic"], &[], Law::ConstantPoisson, 3), // + dissipation
        (&["viscoelastic"], &[], Law::ConstantBulk, 5),    // + u_alpha, u_gamma, operator work
        (&["plate"], &[(1, 1)], Law::ConstantBulk, 5),     // + f, f', injected work
        (
            &["plate", "relative-indentation"],
            &[(1, 1)],
            Law::ConstantBulk,
            4,
        ),
        (
            &["plate", "winkler", "pasternak", "relative-indentation"],
            &[(1, 1)],
            Law::ConstantBulk,
            4,
        ),
        (
            &["plate", "damper", "relative-indentation"],
            &[(1, 1)],
            Law::ConstantBulk,
            5,
        ),
        (
            &["plate", "relative-indentation"],
            &[(1, 1), (1, 3), (3, 1)],
            Law::ConstantBulk,
            8,
        ),
        (
            &["viscoelastic", "plate", "relative-indentation"],
            &[(1, 1)],
            Law::ConstantBulk,
            9,
        ),
        (
            &["viscoelastic", "plate", "relative-indentation"],
            &[(1, 1)],
            Law::ConstantPoisson,
            5,
        ),
    ];
    for (names, modes, law, dim) in cases {
        assert_eq!(
            build(names, modes, *law).state_dim(),
            *dim,
            "{names:?} {modes:?} {law:?}"
        );
    }
}

#[test]
fn elastic_cone_matches_closed_form() {
    // m z'' = -k z^2: z_max = (3 m v0^2/(2k))^(1/3); t_c = 2 z_max/v0 * Gamma(1/3)Gamma(1/2)/(3 Gamma(5/6))
    // (Gamma values from tables: 2.678938534707747, 1.772453850905516, 1.128787029908126).
    let sys = build(&[], &[], Law::ConstantBulk);
    let r = cone_plate::run(&sys, None, &[], 1e-12, 1e-16, Method::Dop853).expect("solves");
    let p = params();
    let k =
        2.0 / (std::f64::consts::PI * p.theta_deg.to_radians().tan()) * p.e / (1.0 - p.nu * p.nu);
    let zmax = (3.0 * p.mass * p.v0 * p.v0 / (2.0 * k)).cbrt();
    let integral = 2.678_938_534_707_747 * 1.772_453_850_905_516 / (3.0 * 1.128_787_029_908_126);
    let tc = 2.0 * zmax / p.v0 * integral;
    assert!(r.ended);
    assert!(
        (r.duration - tc).abs() < 1e-9 * tc,
        "{} vs {tc}",
        r.duration
    );
    assert!((r.max_indentation - zmax).abs() < 1e-10 * zmax);
    assert!(r.balance_error < 1e-10);
}

#[test]
fn kelvin_voigt_cone_matches_scipy_reference() {
    // Reference: SciPy 1.17 LSODA, Radau and DOP853 at rtol 1e-12 on the same equations written
    // independently in Python (m z'' = -A7 E/(1-nu^2)(z^2 + 2 tau z z')); they agree to 1e-12:
    // contact end 7.717951829916e-4 s, z(1e-4) = 1.8939285245731e-4 m, z(3e-4) = 3.9399813726992e-4 m.
    let sys = build(&["viscoelastic"], &[], Law::ConstantPoisson);
    let r =
        cone_plate::run(&sys, None, &[1e-4, 3e-4], 1e-12, 1e-16, Method::Dop853).expect("solves");
    assert!(r.ended);
    assert!(
        (r.duration - 7.717_951_829_916e-4).abs() < 1e-9 * 7.7e-4,
        "{}",
        r.duration
    );
    assert!((r.samples[0].z - 1.893_928_524_573_1e-4).abs() < 1e-9 * 1.9e-4);
    assert!((r.samples[1].z - 3.939_981_372_699_2e-4).abs() < 1e-9 * 3.9e-4);
    assert!(
        r.dissipated > 0.0 && r.warnings.is_empty(),
        "{:?}",
        r.warnings
    );
}

#[test]
fn viscous_limit_is_the_elastic_model() {
    // eta -> 0 in the constant-Poisson law must give the elastic cone.
    let mut p = params();
    p.eta = 1e-6;
    let kv = ConePlate::new(
        p,
        fx(&["viscoelastic"], &[]),
        Variant::Corrected,
        Law::ConstantPoisson,
    )
    .expect("builds");
    let el = build(&[], &[], Law::ConstantBulk);
    let a = cone_plate::run(&kv, None, &[], 1e-12, 1e-16, Method::Dop853).expect("solves");
    let b = cone_plate::run(&el, None, &[], 1e-12, 1e-16, Method::Dop853).expect("solves");
    assert!((a.duration - b.duration).abs() < 1e-9 * b.duration);
    assert!(
        (a.max_indentation - b.max_indentation).abs() < 1e-9 * b.max_indentation,
        "{} vs {}",
        a.max_indentation,
        b.max_indentation
    );
}

#[test]
fn energy_balance_closes_with_every_effect() {
    let all = [
        "viscoelastic",
        "plate",
        "winkler",
        "pasternak",
        "damper",
        "membrane",
        "relative-indentation",
    ];
    for law in [Law::ConstantPoisson, Law::ConstantBulk] {
        for names in [&all[..], &all[1..], &["plate", "membrane"][..]] {
            let sys = build(names, &[(1, 1), (1, 3)], law);
            let r =
                cone_plate::run(&sys, Some(2e-4), &[], 1e-11, 1e-16, Method::Auto).expect("solves");
            assert!(
                r.balance_error < 1e-7,
                "{names:?} {law:?}: {}",
                r.balance_error
            );
        }
    }
}

#[test]
fn constant_bulk_law_is_reported_not_passive() {
    let sys = build(&["viscoelastic"], &[], Law::ConstantBulk);
    let (alpha, gamma) = sys.rates();
    // alpha = -2(1+nu) lambda/(1-2nu) = -13000 1/s, gamma = 7000 1/s for E/eta = 2000 1/s
    assert!((alpha + 13000.0).abs() < 1e-9 && (gamma - 7000.0).abs() < 1e-9);
    let r = cone_plate::run(&sys, Some(3e-4), &[], 1e-10, 1e-16, Method::Auto).expect("solves");
    assert!(
        r.warnings.iter().any(|w| w.contains("not passive")),
        "{:?}",
        r.warnings
    );
    assert!(
        r.warnings.iter().any(|w| w.contains("tensile")),
        "{:?}",
        r.warnings
    );
    assert!(r.operator_work_min < 0.0);
}

#[test]
fn elliptic_integrals_near_k_one_match_asymptotics() {
    // Independent reference: K = ln(4/k') + (k'^2/4)(ln(4/k') - 1) + O(k'^4 ln k'),
    // E = 1 + (k'^2/2)(ln(4/k') - 1/2) + O(k'^4 ln k'), k' = sqrt((1-k)(1+k)).
    use impactcheck::models::disk_friction::k_e;
    for kp in [1e-4f64, 1e-6, 1e-7] {
        let k = (1.0 - kp * kp).sqrt();
        let l = (4.0 / kp).ln();
        let (kk, ee) = k_e(k);
        let kref = l + kp * kp / 4.0 * (l - 1.0);
        let eref = 1.0 + kp * kp / 2.0 * (l - 0.5);
        // k is rounded to a double: compare with the k' the double actually has
        let kp_actual = ((1.0 - k) * (1.0 + k)).sqrt();
        let la = (4.0 / kp_actual).ln();
        let kref_a = la + kp_actual * kp_actual / 4.0 * (la - 1.0);
        assert!(
            (kk - kref_a).abs() < 1e-12 * kref,
            "K at k' = {kp}: {kk} vs {kref_a}"
        );
        assert!((ee - eref).abs() < 1e-12, "E at k' = {kp}: {ee} vs {eref}");
    }
    // K(1/2) = 1.685750354812596 (tables)
    assert!((k_e(0.5).0 - 1.685_750_354_812_596).abs() < 1e-14);
}
