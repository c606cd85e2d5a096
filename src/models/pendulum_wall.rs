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
use crate::models::doc as d;

use super::params::{Fields, SceneError};
use super::trace::{Steps, Trace, Traced, or_why};
use super::{Curves, Model, RunError};
use crate::integrate::{Direction, Event, IntegrateError, Method, OdeSystem, Options, Stop, solve};
use toml::Value;

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
    /// (2.15) is linear: its Jacobian is the constant matrix of the right side (Radau5 then
    /// needs no finite differences).
    fn jacobian(&self, _t: f64, _y: &[f64], jac: &mut nalgebra::DMatrix<f64>) -> bool {
        let r2 = 1.0 / (self.rho * self.rho);
        jac.fill(0.0);
        jac[(0, 2)] = 1.0;
        jac[(1, 3)] = 1.0;
        jac[(2, 0)] = -(1.0 + r2);
        jac[(2, 1)] = -self.sigma * (1.0 - r2);
        jac[(3, 0)] = -(1.0 - r2);
        jac[(3, 1)] = -self.sigma * (1.0 + r2);
        true
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
    impact_recorded(rho, sigma, rtol, false).map(|(r, _)| r)
}

/// [`impact`] with, when `record` is set, every accepted step `(t, [eps_On, eps_Cn, eps_On',
/// eps_Cn'])` in the paper's scaled variables, the last at the unloading; the result is the
/// same to the bit either way.
pub fn impact_recorded(
    rho: f64,
    sigma: f64,
    rtol: f64,
    record: bool,
) -> Result<(PendulumImpact, Steps), IntegrateError> {
    let sys = PendulumWall { rho, sigma };
    let g = |_t: f64, y: &[f64]| y[1];
    let o = Options {
        rtol,
        atol: rtol * 1e-3,
        method: Method::Auto,
        events: vec![Event::new("contact unloads", &g, Direction::Falling, true)],
        trajectory: record,
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
    let result = PendulumImpact {
        duration: sol.t,
        v_on,
        v_cn,
        omega: (sol.y[2] - sol.y[3]) / -2.0,
        loss: -d_t / t0,
        steps: sol.stats.steps,
    };
    Ok((result, sol.trajectory))
}

/// (2.15) solved in closed form: it is linear, $\varepsilon'' = -K\varepsilon$ with
/// $K = A\,\mathrm{diag}(1, \sigma)$, A symmetric positive-definite, so K has real positive
/// eigenvalues $\omega_i^2$ and $\varepsilon(t) = \sum_i c_i v_i \sin(\omega_i t)/\omega_i$.
/// An independent reference for the integrator (nalgebra's eigen-solver, no ODE method).
pub struct ClosedForm {
    w: [f64; 2],
    v: [nalgebra::Vector2<f64>; 2],
    c: nalgebra::Vector2<f64>,
}

impl ClosedForm {
    /// The modes for `rho` and `sigma`.
    pub fn new(rho: f64, sigma: f64) -> Self {
        let r2 = 1.0 / (rho * rho);
        let k = nalgebra::Matrix2::new(1.0 + r2, sigma * (1.0 - r2), 1.0 - r2, sigma * (1.0 + r2));
        // eigenvalues of a 2x2 matrix with real positive spectrum
        let (tr, det) = (k.trace(), k.determinant());
        let disc = (0.25 * tr * tr - det).max(0.0).sqrt();
        let l = [0.5 * tr - disc, 0.5 * tr + disc];
        // the small one from the product (the difference cancels when sigma is far from 1)
        let l = [det / l[1], l[1]];
        let vec_for = |lam: f64| {
            // a null vector of K - lam I from whichever row is larger
            let r0 = nalgebra::Vector2::new(-k[(0, 1)], k[(0, 0)] - lam);
            let r1 = nalgebra::Vector2::new(k[(1, 1)] - lam, -k[(1, 0)]);
            if r0.norm() >= r1.norm() {
                r0.normalize()
            } else {
                r1.normalize()
            }
        };
        let v = [vec_for(l[0]), vec_for(l[1])];
        let m = nalgebra::Matrix2::from_columns(&v);
        let c = m
            .try_inverse()
            .map(|inv| inv * nalgebra::Vector2::new(0.0, 1.0))
            .unwrap_or_else(|| nalgebra::Vector2::new(f64::NAN, f64::NAN));
        ClosedForm {
            w: [l[0].sqrt(), l[1].sqrt()],
            v,
            c,
        }
    }

    /// $(\varepsilon_{On}, \varepsilon_{Cn}, \varepsilon_{On}', \varepsilon_{Cn}')$ at `t`.
    pub fn state(&self, t: f64) -> [f64; 4] {
        let mut s = [0.0; 4];
        for i in 0..2 {
            let (sn, cs) = (self.w[i] * t).sin_cos();
            let a = self.c[i] * sn / self.w[i];
            let b = self.c[i] * cs;
            s[0] += self.v[i][0] * a;
            s[1] += self.v[i][1] * a;
            s[2] += self.v[i][0] * b;
            s[3] += self.v[i][1] * b;
        }
        s
    }

    /// The first time the contact element unloads ($\varepsilon_{Cn}$ falls to zero): scanned at
    /// 1/400 of the fastest half-period, then bisected to the last bit.
    pub fn release(&self) -> f64 {
        let h = std::f64::consts::PI / self.w[0].max(self.w[1]) / 400.0;
        let mut t = h;
        while self.state(t)[1] > 0.0 && t < 1e9 {
            t += h;
        }
        let (mut lo, mut hi) = (t - h, t);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.state(mid)[1] > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// The `pendulum-wall` scene: 002_b53e4779673eb6ed.txt (2.14)-(2.15), the paper's geometry
/// (|GO| = |G'C| = `length`, |GG'| = |OO'|) with linear elements.
#[derive(Clone, Debug)]
pub struct PendulumWallScene {
    /// Central radius of inertia (m).
    pub rho: f64,
    /// Stiffness ratio c1/c2 (contact over suspension).
    pub sigma: f64,
    /// |GO| (m).
    pub length: f64,
    /// Approach speed of the contact point (m/s).
    pub v0: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Suspension stiffness c2 (N/m).
    pub stiffness_o: f64,
    /// Relative tolerance.
    pub rtol: f64,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct RawScene {
    model: Option<Value>,
    rho: Option<Value>,
    sigma: Option<Value>,
    length: Option<Value>,
    v0: Option<Value>,
    mass: Option<Value>,
    stiffness_o: Option<Value>,
    rtol: Option<Value>,
}

/// Velocities after impact, (2.12).
#[derive(Clone, Debug, serde::Serialize)]
pub struct VelocitiesAfter {
    /// Angular velocity (rad/s).
    pub omega: f64,
    /// Normal velocity of G (m/s).
    pub v_gn: f64,
    /// Tangential velocity of G (m/s).
    pub v_gt: f64,
}

/// What `impact run` prints for a `pendulum-wall` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PendulumWallOutcome {
    /// What the user should know.
    pub warnings: Vec<String>,
    /// `"pendulum-wall"`.
    pub model: &'static str,
    /// Energy lost while O is braked, over the energy before impact.
    pub energy_loss_ratio: f64,
    /// How the loss is counted.
    pub energy_counted: &'static str,
    /// Velocities when the contact element unloads.
    pub v_after: VelocitiesAfter,
    /// What `v_after` means.
    pub v_after_note: &'static str,
    /// Normal velocity of O after (m/s).
    pub v_on_after: f64,
    /// Normal velocity of C after (m/s).
    pub v_cn_after: f64,
    /// Contact duration (s).
    pub contact_time: f64,
    /// Whether (2.10) holds: rho = |GO|.
    pub suspension_reaction_free: bool,
}

impl Model for PendulumWallScene {
    const NAME: &'static str = "pendulum-wall";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = PendulumWallOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError> {
        let f = Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let length = f.num(
            raw.length.as_ref(),
            "length",
            Some(1.0),
            |v| v > 0.0,
            "length = |GO| > 0 (m)",
        )?;
        Ok(PendulumWallScene {
            rho: f.num(
                raw.rho.as_ref(),
                "rho",
                None,
                |v| v > 0.0 && v / length >= 1e-3 && v / length <= 1e3,
                "rho > 0 (m), central radius of inertia, 1e-3 <= rho/length <= 1e3",
            )?,
            sigma: f.num(
                raw.sigma.as_ref(),
                "sigma",
                None,
                |v| (1e-8..=1e8).contains(&v),
                "1e-8 <= sigma <= 1e8, stiffness ratio c1/c2 (contact over suspension)",
            )?,
            length,
            v0: f.num(
                raw.v0.as_ref(),
                "v0",
                Some(1.0),
                |v| v > 0.0,
                "v0 > 0 (m/s), approach speed of C",
            )?,
            mass: f.num(
                raw.mass.as_ref(),
                "mass",
                Some(1.0),
                |v| v > 0.0,
                "mass > 0 (kg)",
            )?,
            stiffness_o: f.num(
                raw.stiffness_o.as_ref(),
                "stiffness_o",
                Some(1.0),
                |v| v > 0.0,
                "stiffness_o > 0 (N/m), the suspension element c2",
            )?,
            rtol: f.rtol(raw.rtol.as_ref())?,
        })
    }

    fn run(&self) -> Result<(PendulumWallOutcome, Curves), RunError> {
        Ok((self.go(false)?.0, vec![]))
    }

    fn run_traced(&self) -> Result<(PendulumWallOutcome, Traced), RunError> {
        let (out, trace) = self.go(true)?;
        Ok((out, or_why(trace, "nothing was recorded")))
    }
}

impl PendulumWallScene {
    /// The run, with its path in SI units when `record` is set: time in s, the elements'
    /// deformations eps_On, eps_Cn in m and their rates in m/s (the equations are linear, so the
    /// scaled deformations scale with v0 sqrt(m/c2)), the unloading as the event.
    fn go(&self, record: bool) -> Result<(PendulumWallOutcome, Option<Trace>), RunError> {
        let s = self;
        // (2.15) is written with m = 1, |GO| = 1, c2 = 1, approach speed 1: lengths scale with
        // |GO|, velocities with v0, times with sqrt(m/c2)
        let (r, steps) = impact_recorded(s.rho / s.length, s.sigma, s.rtol, record)?;
        let time = (s.mass / s.stiffness_o).sqrt();
        let trace = record.then(|| {
            let mut tr = Trace::new(
                ("t", "s"),
                &[
                    ("eps_On", "m"),
                    ("eps_Cn", "m"),
                    ("deps_On/dt", "m/s"),
                    ("deps_Cn/dt", "m/s"),
                ],
            );
            let si = |y: &[f64]| {
                let d = s.v0 * time;
                [y[0] * d, y[1] * d, y[2] * s.v0, y[3] * s.v0]
            };
            for (t, y) in &steps {
                tr.push(t * time, &si(y));
            }
            if let Some((t, y)) = steps.last() {
                tr.event("contact unloads", t * time, &si(y));
            }
            tr
        });
        let mut warnings = Vec::new();
        if r.v_cn.abs() < s.rtol.sqrt() {
            // eps_Cn reaches zero with (nearly) zero slope: a multiple root, located in time
            // only to about (tolerance)^(1/order); the after-velocities inherit that error
            warnings.push(format!(
                "the contact element unloads tangentially (V_Cn = {:.2e} v0 at release): the release instant is ill-conditioned, and the velocities after impact carry an error of about that size",
                r.v_cn
            ));
        }
        let out = PendulumWallOutcome {
            warnings,
            model: Self::NAME,
            energy_loss_ratio: r.loss,
            energy_counted: "kinetic energy lost while the suspension point O is braked after the contact unloads, (2.13), over the pendulum's kinetic energy before impact T0 = (1/2) m (rho^2 + |GO|^2) Omega0^2, Omega0 = v0/|OC.t| = v0/(2 |GO|)",
            v_after: VelocitiesAfter {
                omega: r.omega * s.v0 / s.length,
                v_gn: (r.v_on - r.omega) * s.v0,
                v_gt: 0.0,
            },
            v_after_note: "(2.12) at the instant the contact element unloads (before O is braked); n is the wall normal into the pendulum, t along the wall; v_gt = (GO, n) Omega - eps'_Ot = 0 in this geometry",
            v_on_after: r.v_on * s.v0,
            v_cn_after: r.v_cn * s.v0,
            contact_time: r.duration * (s.mass / s.stiffness_o).sqrt(),
            suspension_reaction_free: ((s.rho / s.length) - 1.0).abs() < 1e-12,
        };
        Ok((out, trace))
    }
}

/// The `pendulum-wall` model's reference (`impact describe pendulum-wall`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "pendulum-wall",
    summary: "A pendulum suspended at O striking a wall at C with deformable elements at both (002, (2.8)-(2.15), Fig. 2): |GO| = length, |G'C| = length, the central radius of inertia rho, the contact over suspension stiffness sigma = c1/c2. Gives the energy lost while O is braked, the velocities when the contact unloads, and whether (2.10) holds (no reaction at O).",
    conventions: &[
        "normal velocities along the wall's normal, positive away from the wall",
        "energy_loss_ratio is the energy lost while O is braked over the kinetic energy before impact",
    ],
    example: "scenes/pendulum_on_wall.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"pendulum-wall\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "length",
            unit: "m",
            range: "length > 0",
            default: "1",
            meaning: "|GO| (= |G'C|, 002's special case)",
        },
        d::Key {
            key: "rho",
            unit: "m",
            range: "rho > 0, 1e-3 <= rho/length <= 1e3",
            default: "required",
            meaning: "central radius of inertia",
        },
        d::Key {
            key: "sigma",
            unit: "1",
            range: "1e-8 <= sigma <= 1e8",
            default: "required",
            meaning: "stiffness ratio c1/c2, contact over suspension",
        },
        d::Key {
            key: "v0",
            unit: "m/s",
            range: "v0 > 0",
            default: "1",
            meaning: "approach speed of C",
        },
        d::Key {
            key: "mass",
            unit: "kg",
            range: "mass > 0",
            default: "1",
            meaning: "pendulum mass",
        },
        d::Key {
            key: "stiffness_o",
            unit: "N/m",
            range: "stiffness_o > 0",
            default: "1",
            meaning: "the suspension element c2",
        },
    ]],
    outcomes: &[
        d::COMMON,
        &[
            d::Out {
                path: "energy_loss_ratio",
                unit: "1",
                meaning: "energy lost while O is braked, over the energy before impact",
            },
            d::Out {
                path: "energy_counted",
                unit: "-",
                meaning: "how the loss is counted",
            },
            d::Out {
                path: "v_after.omega",
                unit: "rad/s",
                meaning: "angular velocity when the contact element unloads",
            },
            d::Out {
                path: "v_after.v_gn",
                unit: "m/s",
                meaning: "normal velocity of G then",
            },
            d::Out {
                path: "v_after.v_gt",
                unit: "m/s",
                meaning: "tangential velocity of G then",
            },
            d::Out {
                path: "v_after_note",
                unit: "-",
                meaning: "what v_after means",
            },
            d::Out {
                path: "v_on_after",
                unit: "m/s",
                meaning: "normal velocity of O after",
            },
            d::Out {
                path: "v_cn_after",
                unit: "m/s",
                meaning: "normal velocity of C after",
            },
            d::Out {
                path: "contact_time",
                unit: "s",
                meaning: "contact duration",
            },
            d::Out {
                path: "suspension_reaction_free",
                unit: "-",
                meaning: "whether (2.10) holds: rho = |GO|",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the user should know",
            },
        ],
    ],
};

#[cfg(test)]
mod tests {
    use super::PendulumWall;
    use crate::integrate::OdeSystem;

    #[test]
    fn the_jacobian_is_the_right_sides_derivative() {
        // against central differences of the right side (a second method: (2.15) is linear, so
        // the differences are exact up to rounding), for both rho < 1 and rho > 1
        for (rho, sigma) in [(0.5, 1e-6), (1.7, 3.0)] {
            let sys = PendulumWall { rho, sigma };
            let y = [0.3, -0.2, 0.7, 1.1];
            let mut jac = nalgebra::DMatrix::zeros(4, 4);
            assert!(sys.jacobian(0.0, &y, &mut jac));
            for j in 0..4 {
                let (mut yp, mut ym) = (y, y);
                yp[j] += 1e-3;
                ym[j] -= 1e-3;
                let (mut fp, mut fm) = ([0.0; 4], [0.0; 4]);
                sys.rhs(0.0, &yp, &mut fp);
                sys.rhs(0.0, &ym, &mut fm);
                for i in 0..4 {
                    let fd = (fp[i] - fm[i]) / 2e-3;
                    assert!(
                        (jac[(i, j)] - fd).abs() <= 1e-9 * (1.0 + fd.abs()),
                        "rho {rho}: J[{i}][{j}] = {} vs {fd}",
                        jac[(i, j)]
                    );
                }
            }
        }
    }
}
