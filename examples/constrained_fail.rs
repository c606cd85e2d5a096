//! Seeded random constrained impacts (002 sections 2-4, [`impactcheck::perf::constrained_scene`]):
//! two free bodies, one with a fixed point or a fixed axis, or a support (smooth or rough) under
//! the second, the three restitution laws in turn; lists those that fail (all of them) and counts
//! those only classified (Painleve-type cases, said so; `CLASSIFIED=1` lists them). Usage: `constrained_fail [COUNT]`
//! (default 20000), or `constrained_fail --case I` to print case I's scene and result.
use impactcheck::models::constrained::{solve_scene, solve_scene_all};
use impactcheck::perf::constrained_scene;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let case: Option<u64> = (args.get(1).map(String::as_str) == Some("--case"))
        .then(|| args.get(2).and_then(|s| s.parse().ok()))
        .flatten();
    if let Some(i) = case {
        let s = constrained_scene(i);
        println!("{s:#?}");
        println!("{:#?}", solve_scene(&s).map(|r| (r.0, r.2)));
        return;
    }
    let n: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20000);
    // CLASSIFIED=1 lists the classified cases with their reasons too
    let verbose = std::env::var_os("CLASSIFIED").is_some();
    let start = std::time::Instant::now();
    let mut bad = 0;
    let mut classified = 0;
    // branches of two-solution starts that end in an error other than a Painleve-type instant
    // (the case is then classified by its other branches; the branch says why in `alternatives`)
    let mut branch_errors = 0;
    for i in 0..n {
        let s = constrained_scene(i);
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
            Ok((Some(_), _, _)) => {}
            Ok((None, _, warnings)) => {
                classified += 1;
                if verbose {
                    println!("{i} classified: {}", warnings.join("; "));
                }
            }
            Err(err) => {
                bad += 1;
                println!("{i} kind {} {:?}: {err}", i % 4, s.law);
            }
        }
    }
    println!(
        "{bad} of {n} failed, {classified} classified only ({branch_errors} branches of \
         two-solution starts ended in an error), {:.1} s",
        start.elapsed().as_secs_f64()
    );
}
