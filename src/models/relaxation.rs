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

#[cfg(test)]
mod tests {
    use super::*;

    /// Without the cubic term, with equal damping d, each coordinate is a damped oscillator
    /// q'' + d q' + q = 0: from q = A, p = 0, q = A e^(-d t/2) (cos wt + d/(2w) sin wt) and
    /// p = -A e^(-d t/2) sin(wt)/w, w = sqrt(1 - d^2/4) (by hand), so H is known in closed form.
    /// A small amplitude (H ~ 1e-11) asks the solver for an absolute accuracy far below 1e-6.
    #[test]
    fn the_linear_damped_energy_follows_its_closed_form() {
        let d = 0.3;
        let sys = Relaxation {
            kappa: 0.0,
            d: [d, d],
        };
        let a = 4e-6;
        let w = (1.0 - d * d / 4.0_f64).sqrt();
        let hist = energy_history(&sys, &[0.0, 0.0, a, 0.0], 10.0, 20).expect("integrates");
        assert_eq!(hist.len(), 21);
        for (t, h) in hist {
            let decay = a * (-d * t / 2.0).exp();
            let q = decay * ((w * t).cos() + d / (2.0 * w) * (w * t).sin());
            let p = -decay * (w * t).sin() / w;
            let want = 0.5 * (p * p + q * q);
            assert!((h - want).abs() < 1e-8 * want, "t = {t}: H {h} vs {want}");
        }
        assert!((sys.linear_rate() - d / 2.0).abs() < 1e-15);
    }
}
