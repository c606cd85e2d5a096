//! Seeded random constrained impacts (002 sections 2-4): two free bodies, one with a fixed point
//! or a fixed axis, or a support (smooth or rough) under the second, the three restitution laws
//! in turn; lists those that fail and counts those only classified (a rough support that
//! slides). Usage: `constrained_fail [COUNT]` (default 20000), or `constrained_fail --case I` to
//! print case I's scene and result.
use impactcheck::models::constrained::{RigidImpactScene, solve_scene};
use impactcheck::models::rigid_impact::{Body, Law};
use nalgebra::{Matrix3, Vector3};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case: Option<u64> = (args.get(1).map(String::as_str) == Some("--case"))
        .then(|| args.get(2).and_then(|s| s.parse().ok()))
        .flatten();
    let n: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20000);
    let range = match case {
        Some(i) => i..i + 1,
        None => 0..n,
    };
    let mut bad = 0;
    let mut classified = 0;
    for i in range {
        let mut r = impactcheck::rng::Rng(i.wrapping_mul(0x2545F4914F6CDD1D) ^ 0x5A5A);
        let body = |r: &mut impactcheck::rng::Rng| Body {
            mass: Some(r.range(0.1, 10.0)),
            inertia: Matrix3::from_diagonal(&Vector3::new(
                r.range(0.01, 0.2),
                r.range(0.01, 0.2),
                r.range(0.01, 0.2),
            )),
            offset: Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5)),
        };
        let b1 = body(&mut r);
        let b2 = body(&mut r);
        let law = [Law::Poisson, Law::Newton, Law::Energetic][(i % 3) as usize];
        let kind = i % 4;
        let fixed = if kind == 1 || kind == 2 {
            let axis = if kind == 2 {
                Some(Vector3::new(r.range(-1., 1.), r.range(-1., 1.), r.range(-1., 1.)).normalize())
            } else {
                None
            };
            Some((
                0usize,
                Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5)),
                axis,
            ))
        } else {
            None
        };
        let support = if kind == 3 {
            Some(impactcheck::models::support::Support {
                offset: Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), -r.range(0.1, 0.6)),
                normal: Vector3::new(r.range(-0.2, 0.2), r.range(-0.2, 0.2), 1.0).normalize(),
                mu: if r.next() < 0.5 {
                    0.0
                } else {
                    r.range(0.0, 1.5)
                },
            })
        } else {
            None
        };
        let v = Vector3::new(r.range(-2., 2.), r.range(-2., 2.), -r.range(0.05, 3.0));
        let s = RigidImpactScene {
            bodies: [b1, b2],
            normal: Vector3::z(),
            mu: r.range(0.0, 1.5),
            law,
            e: r.range(0.0, 1.0),
            v_rel: v,
            rtol: 1e-10,
            support,
            v_support: Vector3::zeros(),
            fixed,
        };
        if case.is_some() {
            println!("{s:#?}");
            println!("{:#?}", solve_scene(&s).map(|r| r.0));
            return;
        }
        match solve_scene(&s) {
            Ok((Some(_), _, _)) => {}
            Ok((None, _, _)) => classified += 1,
            Err(err) => {
                bad += 1;
                if bad <= 8 {
                    println!("{i} kind {kind} {law:?}: {err}");
                }
            }
        }
    }
    println!("{bad} of {n} failed, {classified} classified only");
}
