//! The pendulum striking a smooth wall with deformable elements at the contact and at the
//! suspension, 002_b53e4779673eb6ed.txt (2.6)-(2.15), in the paper's special case m = 1,
//! |GO| = 1, |G'C| = 1, |GG'| = |OO'| with linear elements (2.14):
//! $$\varepsilon_{On}'' = -\varepsilon_{On}(1+\rho^{-2}) - \sigma\varepsilon_{Cn}(1-\rho^{-2}),\quad
//!   \varepsilon_{Cn}'' = -\varepsilon_{On}(1-\rho^{-2}) - \sigma\varepsilon_{Cn}(1+\rho^{-2}),$$
//! $\varepsilon(0) = 0$, $\varepsilon_{On}'(0) = 0$, $\varepsilon_{Cn}'(0) = 1$, until the contact
//! element unloads ($\varepsilon_{Cn} = 0$, an event). The energy lost as O is braked is (2.13)
//! with $V_{Ot} = 0$, $(\mathbf{GO}, \mathbf n) = 0$, $|(\mathbf{GO}, \mathbf t)| = 1$,
//! $\rho_O^2 = \rho^2 + 1$, relative to the pendulum's energy before impact $T_0 = (1+\rho^2)/8$
//! ($|V_{Cn}^-| = 1$ with $|\mathbf{OC}\cdot\mathbf t| = 2$).

use crate::integrate::{Direction, Event, IntegrateError, Method, OdeSystem, Options, Stop, solve};

/// (2.15) for given rho and sigma.
pub struct PendulumWall {
    /// Central radius of inertia (|GO| = 1).
    pub rho: f64,
    /// Stiffness ratio c1/c2.
    pub sigma: f64,
}

impl OdeSystem for PendulumWall {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let r2 = 1.0 / (self.rho * self.rho);
        let (eo, ec) = (y[0], y[1]);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -eo * (1.0 + r2) - self.sigma * ec * (1.0 - r2);
        dy[3] = -eo * (1.0 - r2) - self.sigma * ec * (1.0 + r2);
    }
}

/// The outcome of one impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PendulumImpact {
    /// Duration of the contact (in the time unit of (2.15)).
    pub duration: f64,
    /// $V_{On}$ at the end, $-\varepsilon_{On}'$.
    pub v_on: f64,
    /// $V_{Cn}$ at the end, $-\varepsilon_{Cn}'$.
    pub v_cn: f64,
    /// $\Omega$ after impact from (2.12) (with $(\mathbf{GC},\mathbf t) - (\mathbf{GO},\mathbf t) = -2$).
    pub omega: f64,
    /// Relative energy loss $-\Delta T/T_0$ of (2.13).
    pub loss: f64,
    /// Accepted integration steps.
    pub steps: usize,
}

/// Integrates (2.15) to the unloading of the contact element.
pub fn impact(rho: f64, sigma: f64, rtol: f64) -> Result<PendulumImpact, IntegrateError> {
    let sys = PendulumWall { rho, sigma };
    let g = |_t: f64, y: &[f64]| y[1];
    let o = Options {
        rtol,
        atol: rtol * 1e-3,
        method: Method::Auto,
        events: vec![Event::new("contact unloads", &g, Direction::Falling, true)],
        ..Options::default()
    };
    // the contact lasts at most a few periods of the slower mode
    let t_max = 200.0 * (1.0 + 1.0 / sigma.sqrt());
    let sol = solve(&sys, 0.0, &[0.0, 0.0, 0.0, 1.0], t_max, &o)?;
    if !matches!(sol.stop, Stop::Event { .. }) {
        return Err(IntegrateError::TooManySteps {
            t: sol.t,
            h: 0.0,
            max_steps: 0,
        });
    }
    let (v_on, v_cn) = (-sol.y[2], -sol.y[3]);
    let rho_o2 = rho * rho + 1.0;
    let d_t = -0.5 * v_on * v_on + 0.5 * v_on * v_on / rho_o2;
    let t0 = (1.0 + rho * rho) / 8.0;
    Ok(PendulumImpact {
        duration: sol.t,
        v_on,
        v_cn,
        omega: (sol.y[2] - sol.y[3]) / -2.0,
        loss: -d_t / t0,
        steps: sol.stats.steps,
    })
}
