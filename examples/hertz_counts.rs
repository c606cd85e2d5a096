//! Prints the evaluation counts on z'' = -max(z,0)^1.5 (the Hairer-count regression problem).
use impactcheck::integrate::{Method, OdeSystem, Options, solve};
struct H;
impl OdeSystem for H {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0].max(0.0).powf(1.5);
    }
}
fn main() {
    for m in [Method::Dop853, Method::Dopri5, Method::Radau5] {
        for tol in [1e-6, 1e-9, 1e-12] {
            let o = Options {
                rtol: tol,
                atol: tol,
                method: m,
                ..Options::default()
            };
            let s = solve(&H, 0.0, &[0.0, 1.0], 3.218065459719043, &o).unwrap();
            println!("{m:?} {tol:e}: {} y={:?}", s.stats, s.y);
        }
    }
}
