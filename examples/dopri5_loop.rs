//! Profiling aid: DOPRI5 on the cone peer problem at rtol 1e-12, repeated (run under `perf`).
use impactcheck::integrate::{Method, Options, solve};
fn main() {
    let sys = impactcheck::perf::ConeKv {
        tau: impactcheck::perf::CONE_TAU,
    };
    let method = match std::env::args().nth(1).as_deref() {
        Some("dop853") => Method::Dop853,
        _ => Method::Dopri5,
    };
    let o = Options {
        rtol: 1e-12,
        atol: 1e-12,
        method,
        ..Options::default()
    };
    let s = std::time::Instant::now();
    let mut acc = 0.0;
    for _ in 0..20000 {
        let r = solve(&sys, 0.0, &[0.0, 1.0], impactcheck::perf::CONE_T_END, &o).expect("solves");
        acc += r.y[0];
    }
    println!(
        "{:.2} us per solve ({acc})",
        s.elapsed().as_secs_f64() / 20000.0 * 1e6
    );
}
