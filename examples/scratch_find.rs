fn main() {
    let a: Vec<u64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    for i in a[0]..a[1] {
        let s = impactcheck::perf::rigid_sample(i);
        let t = std::time::Instant::now();
        let r = impactcheck::models::rigid_impact::impact_with_matrix(
            &s.b,
            nalgebra::Vector3::z(),
            s.v,
            s.mu,
            s.law,
            s.e,
            1e-10,
        );
        let el = t.elapsed().as_secs_f64();
        if el > 0.05 {
            println!(
                "{i} {el:.3}s {:?} {:?} {}",
                s.degenerate,
                r.as_ref().map(|r| r.stats.steps).map_err(|e| e.to_string()),
                s.law.name()
            );
        }
    }
}
