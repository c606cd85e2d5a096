//! A sphere striking a rigid-backed half-space: Hertz contact with optional Hunt-Crossley
//! damping, the smallest real impact model; or, with [`ContactLaw::Linear`], the linear
//! spring-dashpot (Kelvin-Voigt) contact of the classic restitution formula.
//!
//! $$m\ddot z = -F,\qquad F = \max\!\big(0,\ k\,z_+^{3/2}\,(1 + c\,\dot z)\big),\qquad
//!   z(0) = 0,\ \dot z(0) = v_0,$$
//! with $z$ the indentation (m), $k$ the contact stiffness (N/m^{3/2}) and $c$ the Hunt-Crossley
//! coefficient (s/m); the force is clamped at zero (no adhesion). Contact ends when $z$ returns
//! to zero (a falling event). The linear law is $F = k z + c\dot z$ for $z > 0$ ($k$ in N/m,
//! $c$ in N s/m), not clamped: the dashpot may pull at the end of contact, as in the closed form
//! $e = \exp(-\zeta\pi/\sqrt{1-\zeta^2})$, $\zeta = c/(2\sqrt{km})$, that it is checked against. For $c = 0$ the contact duration is
//! $t_c = \tau\,(m/k)^{2/5} v_0^{-1/5}$ with $\tau = 3.2180654597\ldots$ and the rebound
//! velocity is $-v_0$ (energy is conserved), which the tests use as closed forms.

use crate::integrate::{
    Direction, Event, IntegrateError, Method, OdeSystem, Options, Stats, Stop, solve,
};

/// $\tau$ in $t_c = \tau (m/k)^{2/5} v_0^{-1/5}$ for the undamped Hertz impact, i.e. the time for
/// $z'' = -z_+^{3/2}$, $z(0)=0$, $z'(0)=1$ to return to zero ($2\int_0^{z_m} dz/\sqrt{1 -
/// \tfrac45 z^{5/2}}$, $z_m = (5/4)^{2/5}$).
pub const TAU_UNDAMPED: f64 = 3.218_065_459_719_043;

/// The force law of the contact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ContactLaw {
    /// $F = k z^{3/2}(1 + c\dot z)$, clamped at zero: Hertz with Hunt-Crossley damping.
    #[default]
    Hertz,
    /// $F = k z + c\dot z$: a linear spring and dashpot in parallel.
    Linear,
}

impl ContactLaw {
    /// The name used in scenes and output.
    pub fn name(self) -> &'static str {
        match self {
            ContactLaw::Hertz => "hertz",
            ContactLaw::Linear => "linear",
        }
    }
}

/// Parameters of the impact (SI).
#[derive(Clone, Debug)]
pub struct Hertz {
    /// Impactor mass (kg).
    pub mass: f64,
    /// Contact stiffness (N/m^1.5 for Hertz, N/m for linear).
    pub k: f64,
    /// Damping: the Hunt-Crossley coefficient (s/m) for Hertz, the dashpot (N s/m) for linear.
    pub damping: f64,
    /// The force law.
    pub law: ContactLaw,
}

impl Hertz {
    /// Contact force (N) at indentation `z` (m) and rate `v` (m/s).
    pub fn force(&self, z: f64, v: f64) -> f64 {
        if z <= 0.0 {
            return 0.0;
        }
        match self.law {
            ContactLaw::Hertz => (self.k * z * z.sqrt() * (1.0 + self.damping * v)).max(0.0),
            ContactLaw::Linear => self.k * z + self.damping * v,
        }
    }

    /// $dF/dt$ along the motion (N/s); zero at the peak force.
    pub fn force_rate(&self, z: f64, v: f64) -> f64 {
        if z <= 0.0 {
            return 0.0;
        }
        let acc = -self.force(z, v) / self.mass;
        match self.law {
            ContactLaw::Hertz if self.force(z, v) <= 0.0 => 0.0,
            ContactLaw::Hertz => {
                self.k
                    * (1.5 * z.sqrt() * v * (1.0 + self.damping * v)
                        + z * z.sqrt() * self.damping * acc)
            }
            ContactLaw::Linear => self.k * v + self.damping * acc,
        }
    }

    /// Undamped contact duration (s) for impact speed `v0`: $\tau (m/k)^{2/5} v_0^{-1/5}$ for
    /// Hertz, $\pi\sqrt{m/k}$ for the linear spring.
    pub fn undamped_duration(&self, v0: f64) -> f64 {
        match self.law {
            ContactLaw::Hertz => TAU_UNDAMPED * (self.mass / self.k).powf(0.4) * v0.powf(-0.2),
            ContactLaw::Linear => std::f64::consts::PI * (self.mass / self.k).sqrt(),
        }
    }

    /// The undamped maximum indentation (m): $(5 m v_0^2/(4k))^{2/5}$ for Hertz,
    /// $v_0\sqrt{m/k}$ for the linear spring.
    pub fn indentation_scale(&self, v0: f64) -> f64 {
        match self.law {
            ContactLaw::Hertz => (5.0 * self.mass * v0 * v0 / (4.0 * self.k)).powf(0.4),
            ContactLaw::Linear => v0 * (self.mass / self.k).sqrt(),
        }
    }
}

impl OdeSystem for Hertz {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -self.force(y[0], y[1]) / self.mass;
    }
}

/// What one impact gives.
#[derive(Clone, Debug, serde::Serialize)]
pub struct HertzResult {
    /// Whether contact ended inside the window.
    pub ended: bool,
    /// Contact duration (s) (or the window, if it did not end).
    pub duration: f64,
    /// Largest contact force (N).
    pub peak_force: f64,
    /// Largest indentation (m).
    pub max_indentation: f64,
    /// Velocity at the end (m/s), negative when rebounding.
    pub v_out: f64,
    /// Kinetic energy lost (J).
    pub energy_lost: f64,
    /// Work done.
    pub stats: Stats,
}

/// Integrates one impact with speed `v0` (m/s) until contact ends or `t_window` (s).
pub fn run(
    model: &Hertz,
    v0: f64,
    rtol: f64,
    atol: f64,
    method: Method,
    t_window: Option<f64>,
) -> Result<HertzResult, IntegrateError> {
    let ends = t_window.is_none();
    let t_end = t_window.unwrap_or(100.0 * model.undamped_duration(v0));
    let gap = |_t: f64, y: &[f64]| y[0];
    let vel = |_t: f64, y: &[f64]| y[1];
    let rate = |_t: f64, y: &[f64]| model.force_rate(y[0], y[1]);
    let events = vec![
        Event::new("contact end", &gap, Direction::Falling, ends),
        Event::new("max indentation", &vel, Direction::Falling, false),
        Event::new("peak force", &rate, Direction::Falling, false),
    ];
    let opts = Options {
        rtol,
        atol,
        method,
        events,
        ..Options::default()
    };
    let sol = solve(model, 0.0, &[0.0, v0], t_end, &opts)?;
    let mut max_z = sol.y[0].max(0.0);
    let mut peak = model.force(sol.y[0], sol.y[1]);
    for e in &sol.events {
        match e.index {
            1 => max_z = max_z.max(e.y[0]),
            2 => peak = peak.max(model.force(e.y[0], e.y[1])),
            _ => {}
        }
    }
    let ended = matches!(sol.stop, Stop::Event { index: 0, .. });
    let v_out = sol.y[1];
    Ok(HertzResult {
        ended,
        duration: sol.t,
        peak_force: peak,
        max_indentation: max_z,
        v_out,
        energy_lost: 0.5 * model.mass * (v0 * v0 - v_out * v_out),
        stats: sol.stats,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undamped_impact_matches_closed_forms() {
        // Closed forms: duration tau (m/k)^(2/5) v0^(-1/5), rebound -v0, max indentation
        // (5 m v0^2 / (4 k))^(2/5), peak force k z_max^(3/2).
        let h = Hertz {
            mass: 2.0,
            k: 3.0e6,
            damping: 0.0,
            law: ContactLaw::Hertz,
        };
        let v0 = 1.5;
        let r = run(&h, v0, 1e-12, 1e-14, Method::Dop853, None).expect("solves");
        assert!(r.ended);
        let tc = h.undamped_duration(v0);
        assert!(
            (r.duration - tc).abs() < 1e-10 * tc,
            "{} vs {tc}",
            r.duration
        );
        assert!((r.v_out + v0).abs() < 1e-9);
        let zmax = (5.0 * h.mass * v0 * v0 / (4.0 * h.k)).powf(0.4);
        assert!((r.max_indentation - zmax).abs() < 1e-10 * zmax);
        assert!((r.peak_force - h.k * zmax.powf(1.5)).abs() < 1e-8 * r.peak_force);
    }

    #[test]
    fn damping_dissipates_energy() {
        let h = Hertz {
            mass: 1.0,
            k: 1.0e5,
            damping: 0.2,
            law: ContactLaw::Hertz,
        };
        let r = run(&h, 1.0, 1e-10, 1e-12, Method::Dop853, None).expect("solves");
        assert!(r.ended);
        assert!(r.energy_lost > 0.0 && r.v_out < 0.0 && r.v_out > -1.0);
    }

    #[test]
    fn linear_spring_dashpot_matches_its_closed_form() {
        // closed form of the damped linear oscillator: contact ends at z = 0 after
        // pi/omega_d, omega_d = omega_n sqrt(1 - zeta^2), with v_out = -v0 exp(-zeta pi/sqrt(1-zeta^2))
        let (m, k, c) = (0.5_f64, 2.0e4_f64, 20.0_f64);
        let h = Hertz {
            mass: m,
            k,
            damping: c,
            law: ContactLaw::Linear,
        };
        let zeta = c / (2.0 * (k * m).sqrt());
        let r = run(&h, 2.0, 1e-12, 1e-15, Method::Dop853, None).expect("solves");
        let e = (-zeta * std::f64::consts::PI / (1.0 - zeta * zeta).sqrt()).exp();
        assert!(
            (-r.v_out / 2.0 - e).abs() < 1e-10,
            "{} vs {e}",
            -r.v_out / 2.0
        );
        let td = std::f64::consts::PI / ((k / m).sqrt() * (1.0 - zeta * zeta).sqrt());
        assert!((r.duration - td).abs() < 1e-10 * td);
    }
}
