//! Seeded random rigid impacts of two free bodies ([`impactcheck::models::samples::rigid_sample`]: a random
//! B, V-, mu in [0, 1.5) and e; one in three with the textbook degeneracies: planar motion, B
//! diagonal, a symmetric body, the contact point on a principal axis, zero slip, mu at or next to
//! the critical value, e = 0 or 1), the restitution law `i % 3` (Poisson, Newton, energetic),
//! integrated at rtol 1e-10. A failure is an error, or a wrong answer
//! ([`impactcheck::models::samples::wrong_answer`]: a planar impact that differs from the exact planar
//! solution, or energy gained under a law that dissipates there); each is listed with its seed.
//! Usage: `rigid_fail [COUNT]` (default 20000).
use impactcheck::models::rigid_impact::{Contact, impact_with_matrix};
use impactcheck::models::samples::{rigid_sample, wrong_answer};
use std::collections::BTreeMap;

fn main() {
    let n: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20000);
    let t = std::time::Instant::now();
    let (mut errors, mut wrong, mut degenerate, mut planar) = (0u64, 0u64, 0u64, 0u64);
    let mut tags: BTreeMap<&str, u64> = BTreeMap::new();
    let z = nalgebra::Vector3::z();
    for i in 0..n {
        let s = rigid_sample(i);
        degenerate += u64::from(!s.degenerate.is_empty());
        for t in &s.degenerate {
            *tags.entry(t).or_default() += 1;
        }
        let is_planar = impactcheck::models::planar_impact::planar_frame(
            &s.b,
            &z,
            &s.v,
            impactcheck::models::planar_impact::PLANAR_TOL,
        )
        .is_some();
        planar += u64::from(is_planar);
        match impact_with_matrix(&s.b, Contact::new(z, s.v, s.mu, s.law, s.e), 1e-10) {
            Ok(r) => {
                if let Some(why) = wrong_answer(&s.b, Contact::new(z, s.v, s.mu, s.law, s.e), &r) {
                    wrong += 1;
                    println!("{i} ({}, {:?}): wrong: {why}", s.law.name(), s.degenerate);
                }
            }
            Err(err) => {
                errors += 1;
                println!("{i} ({}, {:?}): {err}", s.law.name(), s.degenerate);
            }
        }
    }
    println!(
        "degenerate samples: {degenerate} of {n} ({:.1} %), {planar} planar (compared with the exact planar solution); {tags:?}",
        100.0 * degenerate as f64 / n.max(1) as f64
    );
    println!(
        "{} of {n} failed ({errors} ended in an error, {wrong} ended with a wrong answer); ended {}, agreed {} ({:.2} s)",
        errors + wrong,
        n - errors,
        n - errors - wrong,
        t.elapsed().as_secs_f64()
    );
}
