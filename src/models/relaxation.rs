//! Relaxation in a dissipative Hamiltonian system, the last fragment of 001_989b2e860c39ca83.txt,
//! eq. (1.1): $\dot p = -\partial H/\partial q + Q$, $\dot q = \partial H/\partial p$,
//! $H = \tfrac12(p^2 + q^2) + \Pi_1(q)$ with $\Pi_1$ cubic. Here n = 2,
//! $\Pi_1 = \kappa(q_1^3 + q_1 q_2^2)$ and $Q = -\mathrm{diag}(d_1, d_2)\,p$, so
//! $\dot H = (Q, p) \le 0$; the linearised modes decay at the rates $d_i/2$ ($d_i < 2$).

use crate::integrate::{IntegrateError, Method, OdeSystem, Options, solve};

/// The system.
pub struct Relaxation {
    /// Cubic coefficient of $\Pi_1$.
    pub kappa: f64,
    /// Damping of each coordinate.
    pub d: [f64; 2],
}

impl Relaxation {
    /// $H(p, q)$.
    pub fn energy(&self, y: &[f64]) -> f64 {
        let (p1, p2, q1, q2) = (y[0], y[1], y[2], y[3]);
        0.5 * (p1 * p1 + p2 * p2 + q1 * q1 + q2 * q2) + self.kappa * (q1 * q1 * q1 + q1 * q2 * q2)
    }

    /// Slowest decay rate of the linearised system (1/s).
    pub fn linear_rate(&self) -> f64 {
        0.5 * self.d[0].min(self.d[1])
    }
}

impl OdeSystem for Relaxation {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let (p1, p2, q1, q2) = (y[0], y[1], y[2], y[3]);
        dy[0] = -(q1 + self.kappa * (3.0 * q1 * q1 + q2 * q2)) - self.d[0] * p1;
        dy[1] = -(q2 + self.kappa * 2.0 * q1 * q2) - self.d[1] * p2;
        dy[2] = p1;
        dy[3] = p2;
    }
}

/// Integrates from `y0` to `t_end`, returning the energy at `n` equally spaced times.
pub fn energy_history(
    sys: &Relaxation,
    y0: &[f64; 4],
    t_end: f64,
    n: usize,
) -> Result<Vec<(f64, f64)>, IntegrateError> {
    let times: Vec<f64> = (1..=n).map(|i| t_end * i as f64 / n as f64).collect();
    let o = Options {
        rtol: 1e-11,
        atol: 1e-16,
        method: Method::Dop853,
        dense_times: times,
        ..Options::default()
    };
    let sol = solve(sys, 0.0, y0, t_end, &o)?;
    let mut out = vec![(0.0, sys.energy(y0))];
    out.extend(sol.dense.iter().map(|(t, y)| (*t, sys.energy(y))));
    Ok(out)
}
