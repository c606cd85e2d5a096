//! Stable f64 evaluation of exact series terms (000_92d54b11128ea1ec.txt (19)-(22)) at the spots
//! where the closed forms cancel: t from 1e-9 up to the contact time, and alpha within 1e-9
//! relative of gamma.
//!
//! References: (1) the exact Taylor series summed in exact rational arithmetic at the exact
//! binary value of t (for small t, where 30 terms leave a remainder far below 1e-30 relative);
//! (2) the fixed-point big-integer path of the evaluator, itself checked against (1).

use impactcheck::algebra::eval::{Evaluator, Path};
use impactcheck::algebra::expo::Expo;
use impactcheck::algebra::poly::{Q, parse_q};
use impactcheck::algebra::series::{self, SeriesParams, Viscous};
use num_traits::{ToPrimitive, Zero};

fn params(alpha: &str, gamma: &str) -> SeriesParams {
    let mut p = SeriesParams::symbolic();
    for (k, v) in [
        ("alpha", alpha),
        ("gamma", gamma),
        ("v0", "5"),
        ("a8", "14000000"),
        ("a9", "140000"),
    ] {
        p.set(k, parse_q(v).expect("rational"))
            .expect("known symbol");
    }
    p
}

fn exact_taylor_value(e: &Expo, t: f64, terms: u32) -> f64 {
    let tq = Q::from_float(t).expect("finite");
    let mut acc = Q::zero();
    for n in 0..terms {
        let c = e.taylor_coeff(n).as_constant().expect("numeric");
        acc += c * tq.pow(n as i32);
    }
    acc.to_f64().expect("finite")
}

fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

#[test]
fn a1_and_a2_small_t_against_exact_taylor_sum() {
    let p = params("-900", "433");
    let terms = series::adomian_terms(&p, 2, Viscous::TwoZZ);
    for (k, term) in terms.iter().enumerate().skip(1) {
        let ev = Evaluator::new(term).expect("numeric");
        for t in logspace(1e-9, 1e-5, 9) {
            let reference = exact_taylor_value(term, t, 40);
            let v = ev.eval(t).expect("evaluates");
            let hp = ev.high_precision(t).expect("evaluates");
            assert!(
                (v - reference).abs() <= 1e-12 * reference.abs(),
                "a{k}({t}) = {v}, exact Taylor {reference}"
            );
            assert!(
                (hp - reference).abs() <= 1e-14 * reference.abs(),
                "high precision a{k}({t})"
            );
        }
    }
}

#[test]
fn a1_up_to_contact_time_against_high_precision() {
    let p = params("-900", "433");
    let terms = series::adomian_terms(&p, 2, Viscous::TwoZZ);
    let mut paths = std::collections::BTreeSet::new();
    for term in &terms[1..] {
        let ev = Evaluator::new(term).expect("numeric");
        for t in logspace(1e-9, 3e-3, 40) {
            let (v, path) = ev.eval_with_path(t).expect("evaluates");
            paths.insert(format!("{path:?}"));
            let hp = ev.high_precision(t).expect("evaluates");
            assert!(
                (v - hp).abs() <= 1e-12 * hp.abs(),
                "t={t}: {v} vs {hp} via {path:?}"
            );
        }
    }
    // the window crosses from the Taylor regime into the direct one
    assert!(
        paths.contains("Taylor") && paths.contains("Direct"),
        "{paths:?}"
    );
}

#[test]
fn alpha_within_1e_minus_9_of_gamma() {
    // alpha and gamma 1e-9 apart in relative terms: every part of a2 carries 1/(alpha - gamma)^j
    let p = params("1000", "1000.000001");
    let terms = series::adomian_terms(&p, 2, Viscous::TwoZZ);
    for term in &terms[1..] {
        let ev = Evaluator::new(term).expect("numeric");
        for t in logspace(1e-9, 2e-2, 25) {
            let (v, path) = ev.eval_with_path(t).expect("evaluates");
            let hp = ev.high_precision(t).expect("evaluates");
            assert!(
                (v - hp).abs() <= 1e-12 * hp.abs(),
                "t={t}: {v} vs {hp} via {path:?}"
            );
            if t <= 1e-5 {
                let reference = exact_taylor_value(term, t, 40);
                assert!((v - reference).abs() <= 1e-12 * reference.abs());
            }
        }
    }
}

#[test]
fn high_precision_path_is_used_and_right_where_both_fast_paths_cancel() {
    let p = params("1000", "1000.000001");
    let a2 = series::adomian_terms(&p, 2, Viscous::TwoZZ).remove(2);
    let ev = Evaluator::new(&a2).expect("numeric");
    let (_, path) = ev.eval_with_path(1e-2).expect("evaluates");
    assert_eq!(path, Path::HighPrecision);
}
