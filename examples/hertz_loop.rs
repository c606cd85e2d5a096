//! Profiling aid: many DOP853 solves of the Hertz reference problem.
use impactcheck::integrate::{Method, Options, solve};
use impactcheck::models::hertz::{Hertz, TAU_UNDAMPED};
fn main() {
    let h = Hertz {
        mass: 1.0,
        k: 1.0,
        damping: 0.0,
        law: impactcheck::models::hertz::ContactLaw::Hertz,
    };
    let o = Options {
        rtol: 1e-6,
        atol: 1e-6,
        method: Method::Dop853,
        ..Options::default()
    };
    let n = 200_000;
    let t0 = std::time::Instant::now();
    let mut acc = 0.0;
    for _ in 0..n {
        acc += solve(&h, 0.0, &[0.0, 1.0], TAU_UNDAMPED, &o).unwrap().y[1];
    }
    println!(
        "{:.3} us per solve ({acc})",
        t0.elapsed().as_secs_f64() / n as f64 * 1e6
    );
}
