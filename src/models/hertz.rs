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
use crate::models::doc as d;

use super::params::{Fields, SceneError, SolveSpec};
use super::trace::{Trace, Traced, or_why};
use super::{Curves, Model, RunError};
use crate::integrate::{
    Direction, Event, IntegrateError, Method, OdeSystem, Options, Stats, Stop, solve,
};
use toml::Value;

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
            ContactLaw::Hertz => {
                let elastic = self.k * z * z.sqrt();
                if self.damping == 0.0 {
                    // the factor 1 + c v is then exactly 1 (for a finite v): the product is
                    // the same without its multiplication, which sits on the step's longest
                    // chain of dependent operations
                    return elastic.max(0.0);
                }
                (elastic * (1.0 + self.damping * v)).max(0.0)
            }
            ContactLaw::Linear => self.k * z + self.damping * v,
        }
    }

    /// $dF/dt$ along the motion (N/s); zero at the peak force.
    pub fn force_rate(&self, z: f64, v: f64) -> f64 {
        if z <= 0.0 {
            return 0.0;
        }
        if self.law == ContactLaw::Hertz && self.damping == 0.0 {
            // undamped: F = k z^1.5 is positive for z > 0 (unless it underflows, for z below
            // about 1e-200 m, where this rate is as small), the factor 1 + c v is exactly 1 and
            // the viscous term z^1.5 c z'' a zero, which leave the sum as it is; the force
            // itself is then not needed (the event runs on every sample)
            return self.k * (1.5 * z.sqrt() * v);
        }
        let f = self.force(z, v);
        match self.law {
            ContactLaw::Hertz if f <= 0.0 => 0.0,
            ContactLaw::Hertz => {
                let elastic = 1.5 * z.sqrt() * v * (1.0 + self.damping * v);
                self.k * (elastic + z * z.sqrt() * self.damping * (-f / self.mass))
            }
            ContactLaw::Linear => self.k * v + self.damping * (-f / self.mass),
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
    run_recorded(model, v0, (rtol, atol, method), t_window, false).map(|(r, _)| r)
}

/// [`run`], with its path ([`Trace`]: `z`, `dz/dt` at every accepted step, the three events)
/// when `record` is set; the result is the same to the bit either way.
pub fn run_recorded(
    model: &Hertz,
    v0: f64,
    (rtol, atol, method): (f64, f64, Method),
    t_window: Option<f64>,
    record: bool,
) -> Result<(HertzResult, Option<Trace>), IntegrateError> {
    let ends = t_window.is_none();
    let t_end = t_window.unwrap_or(100.0 * model.undamped_duration(v0));
    let gap = |_t: f64, y: &[f64]| y[0];
    let vel = |_t: f64, y: &[f64]| y[1];
    let rate = |_t: f64, y: &[f64]| model.force_rate(y[0], y[1]);
    let events = vec![
        Event::new("contact end", &gap, Direction::Falling, ends).reading(0),
        Event::new("max indentation", &vel, Direction::Falling, false).reading(1),
        Event::new("peak force", &rate, Direction::Falling, false),
    ];
    let opts = Options {
        rtol,
        atol,
        method,
        events,
        trajectory: record,
        ..Options::default()
    };
    let sol = solve(model, 0.0, &[0.0, v0], t_end, &opts)?;
    let trace = record.then(|| {
        let mut tr = Trace::new(("t", "s"), &[("z", "m"), ("dz/dt", "m/s")]);
        tr.extend(&sol.trajectory);
        for e in &sol.events {
            tr.event(&opts.events[e.index].name, e.t, &e.y);
        }
        tr
    });
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
    let result = HertzResult {
        ended,
        duration: sol.t,
        peak_force: peak,
        max_indentation: max_z,
        v_out,
        energy_lost: 0.5 * model.mass * (v0 * v0 - v_out * v_out),
        stats: sol.stats,
    };
    Ok((result, trace))
}

/// The `hertz` scene: an impactor on a rigid-backed half-space.
#[derive(Clone, Debug)]
pub struct HertzScene {
    /// Impactor mass (kg).
    pub mass: f64,
    /// Impact speed (m/s).
    pub v0: f64,
    /// Contact stiffness (N/m^1.5, or N/m for the linear law).
    pub k: f64,
    /// Hunt-Crossley coefficient (s/m), or the dashpot (N s/m) of the linear law.
    pub damping: f64,
    /// Force law: Hertz (default) or a linear spring-dashpot.
    pub law: ContactLaw,
    /// Solver settings.
    pub solve: SolveSpec,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    model: Option<Value>,
    impactor: Option<Value>,
    contact: Option<Value>,
    solve: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImpactor {
    mass: Option<Value>,
    v0: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    k: Option<Value>,
    damping: Option<Value>,
    law: Option<Value>,
}

/// What `impact run` prints for a `hertz` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct HertzOutcome {
    /// `"hertz"`.
    pub model: &'static str,
    /// The absolute tolerance used (tightened to the indentation scale when needed).
    pub atol_used: f64,
    /// What the user should know.
    pub warnings: Vec<String>,
    /// The method.
    pub method: &'static str,
    /// States integrated.
    pub state_size: usize,
    /// The contact.
    pub contact: super::ContactOutcome,
    /// Velocity at the end (m/s), negative when rebounding.
    pub v_out: f64,
    /// -v_out/v0.
    pub restitution: f64,
    /// `"hertz"` or `"linear"`.
    pub contact_law: &'static str,
    /// Kinetic energy lost (J).
    pub energy_lost: f64,
    /// Work done.
    pub stats: Stats,
}

/// The numeric fields of a Hertz scene: name, check, and the allowed range as messages state it
/// (read from a table and set by a sweep alike).
/// A numeric field: its dotted name, its check and the allowed range as messages state it.
type NumberField = (&'static str, fn(f64) -> bool, &'static str);

const HERTZ_NUMBERS: [NumberField; 4] = [
    ("impactor.mass", |v| v > 0.0, "mass > 0 (kg)"),
    (
        "impactor.v0",
        |v| v > 0.0,
        "v0 > 0 (m/s), toward the surface",
    ),
    (
        "contact.k",
        |v| v > 0.0,
        "k > 0 (N/m^1.5 for hertz, N/m for linear)",
    ),
    (
        "contact.damping",
        |v| v >= 0.0,
        "damping >= 0 (s/m for hertz, N s/m for linear)",
    ),
];

impl Model for HertzScene {
    const NAME: &'static str = "hertz";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = HertzOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError> {
        let f = Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let _ = raw.model;
        let imp: RawImpactor = f.raw(f.table(raw.impactor.as_ref(), "impactor")?, "impactor")?;
        let con: RawContact = f.raw(f.table(raw.contact.as_ref(), "contact")?, "contact")?;
        let law = match f.choice(
            con.law.as_ref(),
            "contact.law",
            &["hertz", "linear"],
            "hertz",
        ) {
            Ok(l) if l == "linear" => ContactLaw::Linear,
            Ok(_) => ContactLaw::Hertz,
            Err(SceneError::OutOfRange { value, .. }) => {
                return Err(f.out_of_range(
                    "contact.law",
                    value,
                    "\"hertz\" (F = k z^1.5 (1 + c z')) or \"linear\" (F = k z + c z')",
                ));
            }
            Err(e) => return Err(e),
        };
        let num = |v: Option<&Value>, i: usize, default: Option<f64>| {
            let (name, ok, allowed) = HERTZ_NUMBERS[i];
            f.num(v, name, default, ok, allowed)
        };
        Ok(HertzScene {
            law,
            mass: num(imp.mass.as_ref(), 0, None)?,
            v0: num(imp.v0.as_ref(), 1, None)?,
            k: num(con.k.as_ref(), 2, None)?,
            damping: num(con.damping.as_ref(), 3, Some(0.0))?,
            solve: f.solve(raw.solve.as_ref(), "contact-end", false)?,
        })
    }

    fn set_number(&mut self, field: &str, v: f64, path: &str) -> Option<Result<(), SceneError>> {
        let i = HERTZ_NUMBERS.iter().position(|(n, ..)| *n == field)?;
        let (name, ok, allowed) = HERTZ_NUMBERS[i];
        if !(v.is_finite() && ok(v)) {
            return Some(Err(SceneError::OutOfRange {
                path: path.into(),
                field: name.into(),
                value: v.to_string(),
                allowed: allowed.into(),
            }));
        }
        *[&mut self.mass, &mut self.v0, &mut self.k, &mut self.damping][i] = v;
        Some(Ok(()))
    }

    fn run(&self) -> Result<(HertzOutcome, Curves), RunError> {
        Ok((self.go(false)?.0, vec![]))
    }

    fn run_traced(&self) -> Result<(HertzOutcome, Traced), RunError> {
        let (out, trace) = self.go(true)?;
        Ok((out, or_why(trace, "nothing was recorded")))
    }
}

impl HertzScene {
    /// The run, its path recorded when `record` is set.
    fn go(&self, record: bool) -> Result<(HertzOutcome, Option<Trace>), RunError> {
        let s = self;
        let model = Hertz {
            mass: s.mass,
            k: s.k,
            damping: s.damping,
            law: s.law,
        };
        // an absolute tolerance above rtol times the indentation scale would make a grazing
        // impact silently inaccurate: tighten it to that scale and say so
        let z_scale = model
            .indentation_scale(s.v0)
            .min(s.v0.abs().max(f64::MIN_POSITIVE));
        let atol = s.solve.atol.min(s.solve.rtol * z_scale);
        let mut warnings = Vec::new();
        if atol < s.solve.atol {
            warnings.push(format!(
                "atol tightened from {:e} to {atol:e} = rtol x the indentation scale {z_scale:e} m, so that the tolerance is relative to the motion",
                s.solve.atol
            ));
        }
        let (r, trace) = run_recorded(
            &model,
            s.v0,
            (s.solve.rtol, atol, s.solve.method),
            s.solve.t_end,
            record,
        )?;
        let out = HertzOutcome {
            model: Self::NAME,
            atol_used: atol,
            warnings,
            method: s.solve.method.name(),
            state_size: 2,
            contact: super::ContactOutcome {
                ended: r.ended,
                duration: r.duration,
                peak_force: r.peak_force,
                max_indentation: r.max_indentation,
            },
            v_out: r.v_out,
            restitution: -r.v_out / s.v0,
            contact_law: s.law.name(),
            energy_lost: r.energy_lost,
            stats: r.stats,
        };
        Ok((out, trace))
    }
}

/// The `hertz` model's reference (`impact describe hertz`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "hertz",
    summary: "A sphere striking a rigid-backed half-space: m z'' = -F, F = k z^(3/2) (1 + c z') clamped at zero (Hertz with Hunt-Crossley damping), or F = k z + c z' for contact.law = \"linear\" (a spring and dashpot). The textbook case of every contact model; checked against t_c = 3.2181 (m/k)^(2/5) v0^(-1/5) and the spring-dashpot restitution exp(-zeta pi/sqrt(1 - zeta^2)).",
    conventions: &[
        "z is the indentation (m), positive into the half-space; z(0) = 0, z'(0) = v0 > 0",
        "v_out is the velocity at the end of contact in the same axis: negative when the sphere rebounds",
        "the Hertz force is clamped at zero (no adhesion); the linear law is not (its dashpot may pull at the end of contact, as in the closed form)",
        "atol is tightened to rtol times the indentation scale when larger (a warning says so)",
    ],
    example: "scenes/hertz.toml",
    keys: &[
        &[
            d::Key {
                key: "model",
                unit: "-",
                range: "\"hertz\"",
                default: "required",
                meaning: "the model",
            },
            d::Key {
                key: "impactor.mass",
                unit: "kg",
                range: "mass > 0",
                default: "required",
                meaning: "impactor mass m",
            },
            d::Key {
                key: "impactor.v0",
                unit: "m/s",
                range: "v0 > 0",
                default: "required",
                meaning: "impact speed, toward the surface",
            },
            d::Key {
                key: "contact.k",
                unit: "N/m^1.5 (hertz), N/m (linear)",
                range: "k > 0",
                default: "required",
                meaning: "contact stiffness",
            },
            d::Key {
                key: "contact.damping",
                unit: "s/m (hertz), N s/m (linear)",
                range: "damping >= 0",
                default: "0",
                meaning: "Hunt-Crossley coefficient c, or the dashpot of the linear law",
            },
            d::Key {
                key: "contact.law",
                unit: "-",
                range: "\"hertz\", \"linear\"",
                default: "\"hertz\"",
                meaning: "the force law",
            },
        ],
        d::SOLVE,
    ],
    outcomes: &[
        d::COMMON,
        d::CONTACT,
        &[
            d::Out {
                path: "v_out",
                unit: "m/s",
                meaning: "velocity at the end, along z: negative when rebounding",
            },
            d::Out {
                path: "restitution",
                unit: "1",
                meaning: "-v_out/v0",
            },
            d::Out {
                path: "energy_lost",
                unit: "J",
                meaning: "kinetic energy lost, m (v0^2 - v_out^2)/2",
            },
            d::Out {
                path: "contact_law",
                unit: "-",
                meaning: "\"hertz\" or \"linear\"",
            },
            d::Out {
                path: "atol_used",
                unit: "m",
                meaning: "the absolute tolerance used (tightened to the indentation scale when needed)",
            },
            d::Out {
                path: "method",
                unit: "-",
                meaning: "the integrator",
            },
            d::Out {
                path: "state_size",
                unit: "-",
                meaning: "states integrated (2)",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the user should know",
            },
        ],
        d::STATS,
    ],
};

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

    /// dF/dt along the motion against a central difference of F along (z', z'') = (v, -F/m)
    /// (an independent second way), for each law, damped and undamped.
    #[test]
    fn force_rate_is_the_derivative_of_the_force_along_the_motion() {
        for (law, k, c) in [
            (ContactLaw::Hertz, 3e8, 0.0),
            (ContactLaw::Hertz, 3e8, 0.4),
            (ContactLaw::Linear, 1e6, 0.0),
            (ContactLaw::Linear, 1e6, 30.0),
        ] {
            let h = Hertz {
                mass: 0.05,
                k,
                damping: c,
                law,
            };
            for (z, v) in [(1e-4, 0.7), (5e-5, -0.3), (2e-6, 1.5)] {
                let acc = -h.force(z, v) / h.mass;
                let dt = 1e-9;
                let fd = (h.force(z + v * dt, v + acc * dt) - h.force(z - v * dt, v - acc * dt))
                    / (2.0 * dt);
                let rate = h.force_rate(z, v);
                assert!(
                    (rate - fd).abs() <= 1e-5 * rate.abs().max(1.0),
                    "{law:?} c = {c}, z = {z}, v = {v}: {rate} against {fd}"
                );
            }
            assert!(h.force_rate(-1e-6, 1.0).abs() < f64::MIN_POSITIVE);
        }
    }

    /// The undamped shortcuts of `force` and `force_rate` give the bits of the general
    /// formulas with c = 0 (written out here as the damped law computes them), so that a sweep
    /// of undamped impacts gives the numbers it gave before the shortcuts; and `force_rate`
    /// stays zero for z <= 0.
    #[test]
    fn undamped_shortcuts_give_the_general_formulas_bits() {
        let h = Hertz {
            mass: 0.05,
            k: 3e8,
            damping: 0.0,
            law: ContactLaw::Hertz,
        };
        let c = 0.0;
        for z in [1e-12, 3.7e-9, 2e-6, 1.3e-4, 0.02] {
            for v in [-2.5, -1e-7, 0.0, 3e-9, 0.7, 11.0] {
                let general = (h.k * z * z.sqrt() * (1.0 + c * v)).max(0.0);
                assert_eq!(
                    h.force(z, v).to_bits(),
                    general.to_bits(),
                    "F at z = {z}, v = {v}"
                );
                let elastic = 1.5 * z.sqrt() * v * (1.0 + c * v);
                let viscous = z * z.sqrt() * c * (-general / h.mass);
                let rate = h.k * (elastic + viscous);
                // the viscous term is a (signed) zero: the sum's bits are the elastic term's
                // unless the elastic term is itself a zero
                let shortcut = h.force_rate(z, v);
                assert!(
                    shortcut.to_bits() == rate.to_bits()
                        || (shortcut.abs() < f64::MIN_POSITIVE && rate.abs() < f64::MIN_POSITIVE),
                    "dF/dt at z = {z}, v = {v}: {shortcut} against {rate}"
                );
            }
        }
        assert_eq!(h.force_rate(0.0, 1.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(h.force_rate(-1e-9, -1.0).to_bits(), 0.0f64.to_bits());
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
