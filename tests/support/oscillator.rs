//! The harmonic oscillator y'' = -y (y = cos t from y(0) = 1, y'(0) = 0), shared by the tests.
use impactcheck::integrate::OdeSystem;

/// y'' = -y.
pub struct Oscillator;
impl OdeSystem for Oscillator {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }
}
