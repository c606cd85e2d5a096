//! Fixed cost of one solve (a single short step) per method, median of 20001.
use impactcheck::integrate::{Method, Options, solve};
fn main() {
    let sys = impactcheck::perf::HertzUnit;
    for m in [Method::Dop853, Method::Dopri5] {
        let o = Options {
            rtol: 1e-6,
            atol: 1e-6,
            method: m,
            ..Options::default()
        };
        let mut ts: Vec<f64> = (0..20001)
            .map(|_| {
                let s = std::time::Instant::now();
                let r = solve(&sys, 0.0, &[0.0, 1.0], 1e-3, &o).expect("solves");
                std::hint::black_box(r);
                s.elapsed().as_secs_f64()
            })
            .collect();
        ts.sort_by(f64::total_cmp);
        println!("{:?}: {:.0} ns", m.name(), ts[10000] * 1e9);
    }
}
