//! Lists the seeded random rigid impacts of the sweep benchmark that fail, with the error: impact
//! `i` has the random B, V-, mu in [0, 1.5] and e of `perf::rigid_inputs(i)`, and the restitution
//! law `i % 3` (Poisson, Newton, energetic). Usage: `rigid_fail [COUNT]` (default 20000).
use impactcheck::models::rigid_impact::{Law, impact_with_matrix};

fn main() {
    let n: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20000);
    let t = std::time::Instant::now();
    let mut bad = 0;
    for i in 0..n {
        let law = [Law::Poisson, Law::Newton, Law::Energetic][(i % 3) as usize];
        let (b, v, mu, e) = impactcheck::perf::rigid_inputs(i);
        if let Err(err) = impact_with_matrix(&b, nalgebra::Vector3::z(), v, mu, law, e, 1e-10) {
            bad += 1;
            println!("{i} ({}): {err}", law.name());
        }
    }
    println!("{bad} of {n} failed in {:.2} s", t.elapsed().as_secs_f64());
}
