//! Two identical balls in a line, the second touching a much stiffer wall, the first striking it
//! head-on (the closing experiment of section 3 of 002_b53e4779673eb6ed.txt), with deformable
//! elements at both contacts: $F = k\,\delta_+^p$ between the balls and $F = \kappa k\,\delta_+^p$ at
//! the wall, $p = 3/2$ (Hertz) or $p = 1$ (linear), m = 1, V = 1, k = 1. The run continues until the
//! balls have separated for good (both contacts open, ball 1 no faster towards the wall than
//! ball 2, both moving away).

use crate::integrate::{IntegrateError, Method, OdeSystem, Options, solve};

/// The chain: states x1, v1, x2, v2 (x towards the wall; the wall at x2 = 0).
pub struct BallsWall {
    /// Wall stiffness / ball-ball stiffness.
    pub kappa: f64,
    /// Exponent of the force law.
    pub p: f64,
}

impl OdeSystem for BallsWall {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let d12 = (y[0] - y[2]).max(0.0);
        let d2w = y[2].max(0.0);
        let f12 = d12.powf(self.p);
        let f2w = self.kappa * d2w.powf(self.p);
        dy[0] = y[1];
        dy[1] = -f12;
        dy[2] = y[3];
        dy[3] = f12 - f2w;
    }
}

/// Final velocities `(v1, v2)` relative to the striking speed (negative: away from the wall).
pub fn rebound(kappa: f64, p: f64, rtol: f64) -> Result<(f64, f64), IntegrateError> {
    let sys = BallsWall { kappa, p };
    let mut y = vec![0.0, 1.0, 0.0, 0.0];
    let mut t = 0.0;
    for _ in 0..200 {
        let o = Options {
            rtol,
            atol: rtol * 1e-3,
            method: Method::Auto,
            ..Options::default()
        };
        let sol = solve(&sys, t, &y, t + 20.0, &o)?;
        t = sol.t;
        y = sol.y;
        let open = y[0] < y[2] && y[2] < 0.0;
        if open && y[1] <= y[3] && y[3] <= 0.0 {
            break;
        }
    }
    Ok((y[1], y[3]))
}
