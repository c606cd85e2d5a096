//! Lists the seeded random rigid impacts of the sweep benchmark that fail, with the error.
fn main() {
    let n: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(20000);
    let t = std::time::Instant::now();
    let mut bad = 0;
    for i in 0..n {
        if let Err(e) = impactcheck::perf::rigid_case(i) {
            bad += 1;
            println!("{i}: {e}");
        }
    }
    println!("{bad} of {n} failed in {:.2} s", t.elapsed().as_secs_f64());
}
