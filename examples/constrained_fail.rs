//! Seeded random constrained impacts (002 sections 2-4, [`impactcheck::models::samples::constrained_scene_tagged`]):
//! two free bodies, one with a fixed point or a fixed axis, or a support (smooth or rough) under
//! the second, the three restitution laws in turn; one in three with the textbook degeneracies
//! (planar motion, symmetric bodies, the contact point on a principal axis, zero slip, mu at or
//! next to the critical value, e = 0 or 1). Every case is integrated (`[solve] method =
//! "integrate"`). A failure is an error, or a wrong answer: without a support, an impact that is
//! planar and differs from the exact planar solution with B or B* ([`impactcheck::models::samples::wrong_answer`]),
//! or energy gained under a law that dissipates there; with a support, energy gained under the
//! energetic law. Failures are listed with their seeds; cases only classified (Painleve-type, said
//! so) are counted apart (`CLASSIFIED=1` lists them). Usage: `constrained_fail [COUNT]` (default
//! 20000), or `constrained_fail --case I` to print case I's scene and result.
use impactcheck::models::constrained::{ImpactMethod, scene_matrix, solve_scene, solve_scene_all};
use impactcheck::models::rigid_impact::{Contact, Law};
use impactcheck::models::samples::{AGREE, constrained_scene_tagged, wrong_answer};
use std::collections::BTreeMap;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case: Option<u64> = (args.get(1).map(String::as_str) == Some("--case"))
        .then(|| args.get(2).and_then(|s| s.parse().ok()))
        .flatten();
    if let Some(i) = case {
        let (mut s, tags) = constrained_scene_tagged(i);
        s.method = ImpactMethod::Integrate;
        println!("{s:#?}\ndegenerate: {tags:?}");
        println!("{:#?}", solve_scene(&s).map(|r| (r.0, r.2)));
        return;
    }
    let n: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20000);
    // CLASSIFIED=1 lists the classified cases with their reasons too
    let verbose = std::env::var_os("CLASSIFIED").is_some();
    let start = std::time::Instant::now();
    let (mut errors, mut wrong, mut classified, mut degenerate, mut compared) = (0, 0, 0, 0, 0);
    let mut tag_counts: BTreeMap<&str, u64> = BTreeMap::new();
    // branches of two-solution starts that end in an error other than a Painleve-type instant
    // (the case is then classified by its other branches; the branch says why in `alternatives`)
    let mut branch_errors = 0;
    for i in 0..n {
        let (mut s, tags) = constrained_scene_tagged(i);
        s.method = ImpactMethod::Integrate;
        degenerate += u64::from(!tags.is_empty());
        for t in &tags {
            *tag_counts.entry(t).or_default() += 1;
        }
        let mut alternatives = Vec::new();
        let outcome = solve_scene_all(&s, &mut alternatives);
        for a in &alternatives {
            if let Some(err) = a.error.as_ref().filter(|e| !e.contains("Painleve")) {
                branch_errors += 1;
                if verbose {
                    println!("{i} branch {}: {err}", a.start);
                }
            }
        }
        match outcome {
            Ok((Some(r), _, _)) => {
                let why = match scene_matrix(&s) {
                    Some(b) => {
                        let planar = impactcheck::models::planar_impact::planar_frame(
                            &b,
                            &s.normal,
                            &s.v_rel,
                            impactcheck::models::planar_impact::PLANAR_TOL,
                        )
                        .is_some();
                        compared += u64::from(planar);
                        wrong_answer(&b, Contact::new(s.normal, s.v_rel, s.mu, s.law, s.e), &r)
                    }
                    // a support: the energetic law dissipates (the support's impulse does no
                    // positive work: it pushes only while A is at rest along N, and its friction
                    // opposes A's slip)
                    None => (s.law == Law::Energetic
                        && r.energy_change
                            > AGREE * s.v_rel.norm() * nalgebra::Vector3::from(r.impulse).norm())
                    .then(|| {
                        format!(
                            "the kinetic energy grew by {:.6e} J under the energetic law with a support",
                            r.energy_change
                        )
                    }),
                };
                if let Some(why) = why {
                    wrong += 1;
                    println!("{i} kind {} {:?} {tags:?}: wrong: {why}", i % 4, s.law);
                }
            }
            Ok((None, _, warnings)) => {
                classified += 1;
                if verbose {
                    println!("{i} classified: {}", warnings.join("; "));
                }
            }
            Err(err) => {
                errors += 1;
                println!("{i} kind {} {:?} {tags:?}: {err}", i % 4, s.law);
            }
        }
    }
    println!(
        "degenerate samples: {degenerate} of {n} ({:.1} %), {compared} planar without a support (compared with the exact planar solution); {tag_counts:?}",
        100.0 * degenerate as f64 / n.max(1) as f64
    );
    println!(
        "{} of {n} failed ({errors} ended in an error, {wrong} ended with a wrong answer), {classified} classified only ({branch_errors} branches of two-solution starts ended in an error); ended {}, agreed {} ({:.1} s)",
        errors + wrong,
        n - errors - classified,
        n - errors - classified - wrong,
        start.elapsed().as_secs_f64()
    );
}
