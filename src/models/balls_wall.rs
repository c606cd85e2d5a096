//! Two identical balls in a line, the second touching a much stiffer wall, the first striking it
//! head-on (the closing experiment of section 3 of 002_b53e4779673eb6ed.txt), with deformable
//! elements at both contacts: $F = k\,\delta_+^p$ between the balls and $F = \kappa k\,\delta_+^p$ at
//! the wall, $p = 3/2$ (Hertz) or $p = 1$ (linear), m = 1, V = 1, k = 1. The run continues until the
//! balls have separated for good (both contacts open, ball 1 no faster towards the wall than
//! ball 2, both moving away).
use crate::models::doc as d;

use super::params::{Fields, SceneError};
use super::trace::{Steps, Trace, Traced, or_why};
use super::{Curves, Model, RunError};
use crate::integrate::{IntegrateError, Method, OdeSystem, Options, solve};
use toml::Value;

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
    rebound_recorded(kappa, p, rtol, false).map(|(v, _)| v)
}

/// [`rebound`] with, when `record` is set, every accepted step `(t, [x1, v1, x2, v2])` in the
/// scaled variables (displacements from the start in units of v0 times the time unit,
/// velocities in units of v0, positive toward the wall); the result is the same to the bit.
pub fn rebound_recorded(
    kappa: f64,
    p: f64,
    rtol: f64,
    record: bool,
) -> Result<((f64, f64), Steps), IntegrateError> {
    let sys = BallsWall { kappa, p };
    let mut steps = Vec::new();
    let mut y = vec![0.0, 1.0, 0.0, 0.0];
    let mut t = 0.0;
    for _ in 0..200 {
        let o = Options {
            rtol,
            atol: rtol * 1e-3,
            method: Method::Auto,
            trajectory: record,
            ..Options::default()
        };
        let mut sol = solve(&sys, t, &y, t + 20.0, &o)?;
        steps.append(&mut sol.trajectory);
        t = sol.t;
        y = sol.y;
        let open = y[0] < y[2] && y[2] < 0.0;
        if open && y[1] <= y[3] && y[3] <= 0.0 {
            break;
        }
    }
    Ok(((y[1], y[3]), steps))
}

/// The `balls-wall` scene: section 3's closing experiment of 002_b53e4779673eb6ed.txt.
#[derive(Clone, Debug)]
pub struct BallsWallScene {
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Exponent: 1.5 (Hertz) or 1 (linear).
    pub exponent: f64,
    /// Speed of the striking ball (m/s).
    pub v0: f64,
    /// Wall contact stiffness over ball-ball contact stiffness.
    pub wall_stiffness_ratio: f64,
    /// Ball-ball stiffness (N/m^p), if known (gives the contact time in seconds).
    pub stiffness: Option<f64>,
    /// Relative tolerance.
    pub rtol: f64,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct RawScene {
    model: Option<Value>,
    radius: Option<Value>,
    mass: Option<Value>,
    contact_law: Option<Value>,
    v0: Option<Value>,
    wall_stiffness_ratio: Option<Value>,
    stiffness: Option<Value>,
    rtol: Option<Value>,
}

/// What `impact run` prints for a `balls-wall` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BallsWallOutcome {
    /// `"balls-wall"`.
    pub model: &'static str,
    /// `"hertz"` or `"linear"`.
    pub contact_law: &'static str,
    /// Wall over ball-ball stiffness.
    pub wall_stiffness_ratio: f64,
    /// Velocity of the striking ball after, in units of v0.
    pub v_striker_after: f64,
    /// Velocity of the ball at the wall after, in units of v0.
    pub v_wall_ball_after: f64,
    /// The units.
    pub units: &'static str,
    /// Ball radius (m).
    pub radius: f64,
    /// The time unit (s), when the stiffness is given.
    pub time_unit_s: Option<f64>,
}

impl Model for BallsWallScene {
    const NAME: &'static str = "balls-wall";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = BallsWallOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, SceneError> {
        let f = Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let law = f.choice(
            raw.contact_law.as_ref(),
            "contact_law",
            &["hertz", "linear"],
            "hertz",
        )?;
        let stiffness = match &raw.stiffness {
            None => None,
            Some(_) => Some(f.num(
                raw.stiffness.as_ref(),
                "stiffness",
                None,
                |v| v > 0.0,
                "stiffness > 0 (N/m^1.5 for hertz, N/m for linear), the ball-ball contact",
            )?),
        };
        Ok(BallsWallScene {
            radius: f.num(raw.radius.as_ref(), "radius", None, |v| v > 0.0, "radius > 0 (m)")?,
            mass: f.num(raw.mass.as_ref(), "mass", None, |v| v > 0.0, "mass > 0 (kg)")?,
            exponent: if law == "hertz" { 1.5 } else { 1.0 },
            v0: f.num(raw.v0.as_ref(), "v0", None, |v| v > 0.0, "v0 > 0 (m/s), toward the wall")?,
            wall_stiffness_ratio: f.num(
                raw.wall_stiffness_ratio.as_ref(),
                "wall_stiffness_ratio",
                Some(2.0 * 2f64.sqrt()),
                |v| (1e-6..=1e8).contains(&v),
                "1e-6 <= wall_stiffness_ratio <= 1e8 (2 sqrt(2): identical elastic balls, rigid wall, Hertz)",
            )?,
            stiffness,
            rtol: f.rtol(raw.rtol.as_ref())?,
        })
    }

    fn run(&self) -> Result<(BallsWallOutcome, Curves), RunError> {
        Ok((self.go(false)?.0, vec![]))
    }

    fn run_traced(&self) -> Result<(BallsWallOutcome, Traced), RunError> {
        let (out, trace) = self.go(true)?;
        Ok((
            out,
            or_why(
                trace,
                "a path in seconds and metres needs `stiffness` (the ball-ball contact stiffness): without it the model is scale-free",
            ),
        ))
    }
}

impl BallsWallScene {
    /// The run, with its path in SI units when `record` is set and the stiffness gives the time
    /// unit: t in s, each ball's displacement from the start x1, x2 in m (toward the wall) and
    /// its velocity in m/s.
    fn go(&self, record: bool) -> Result<(BallsWallOutcome, Option<Trace>), RunError> {
        let s = self;
        let ((v1, v2), steps) =
            rebound_recorded(s.wall_stiffness_ratio, s.exponent, s.rtol, record)?;
        // m x'' = -k d^p is scale-free: velocities in units of v0 depend on p and the
        // stiffness ratio only; the time unit is (m v0^(1-p)/k)^(1/(p+1))
        let time_unit = s
            .stiffness
            .map(|k| (s.mass * s.v0.powf(1.0 - s.exponent) / k).powf(1.0 / (s.exponent + 1.0)));
        let out = BallsWallOutcome {
            model: Self::NAME,
            contact_law: if s.exponent > 1.0 { "hertz" } else { "linear" },
            wall_stiffness_ratio: s.wall_stiffness_ratio,
            v_striker_after: v1,
            v_wall_ball_after: v2,
            units: "velocities in units of v0, positive toward the wall",
            radius: s.radius,
            time_unit_s: time_unit,
        };
        let trace = time_unit.filter(|_| record).map(|unit| {
            let mut tr = Trace::new(
                ("t", "s"),
                &[("x1", "m"), ("v1", "m/s"), ("x2", "m"), ("v2", "m/s")],
            );
            let length = s.v0 * unit;
            let si: Steps = steps
                .iter()
                .map(|(t, y)| {
                    let v = vec![y[0] * length, y[1] * s.v0, y[2] * length, y[3] * s.v0];
                    (t * unit, v)
                })
                .collect();
            // a window restarts where the last one stopped: `extend` keeps that step once
            tr.extend(&si);
            tr
        });
        Ok((out, trace))
    }
}

/// The `balls-wall` model's reference (`impact describe balls-wall`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "balls-wall",
    summary: "Two identical balls in a line against a wall (002, sec. 3, the closing numerical result): the striking ball meets a ball at rest touching the wall; contacts are Hertz (or linear) springs, the wall's stiffer by wall_stiffness_ratio. The velocities after are scale-free: in units of v0 they depend only on the law and the ratio.",
    conventions: &[
        "velocities in units of v0, positive toward the wall",
        "v_striker_after < 0 is the striking ball rebounding; v_wall_ball_after < 0 the ball at the wall recoiling from it",
    ],
    example: "scenes/balls_wall.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"balls-wall\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "radius",
            unit: "m",
            range: "radius > 0",
            default: "required",
            meaning: "ball radius",
        },
        d::Key {
            key: "mass",
            unit: "kg",
            range: "mass > 0",
            default: "required",
            meaning: "ball mass",
        },
        d::Key {
            key: "v0",
            unit: "m/s",
            range: "v0 > 0",
            default: "required",
            meaning: "speed of the striking ball, toward the wall",
        },
        d::Key {
            key: "wall_stiffness_ratio",
            unit: "1",
            range: "1e-6 <= ratio <= 1e8",
            default: "2 sqrt(2)",
            meaning: "wall stiffness over ball-ball stiffness (2 sqrt(2): identical elastic balls, a rigid wall, Hertz)",
        },
        d::Key {
            key: "contact_law",
            unit: "-",
            range: "\"hertz\", \"linear\"",
            default: "\"hertz\"",
            meaning: "force exponent 3/2 or 1",
        },
        d::Key {
            key: "stiffness",
            unit: "N/m^1.5 (hertz), N/m (linear)",
            range: "stiffness > 0",
            default: "none",
            meaning: "the ball-ball stiffness, only for the time unit",
        },
        d::Key {
            key: "rtol",
            unit: "1",
            range: "1e-14 <= rtol <= 1e-2",
            default: "1e-10",
            meaning: "relative tolerance",
        },
    ]],
    outcomes: &[
        d::COMMON,
        &[
            d::Out {
                path: "v_striker_after",
                unit: "1 (v0)",
                meaning: "velocity of the striking ball after, in units of v0, positive toward the wall",
            },
            d::Out {
                path: "v_wall_ball_after",
                unit: "1 (v0)",
                meaning: "velocity of the ball at the wall after, in units of v0",
            },
            d::Out {
                path: "wall_stiffness_ratio",
                unit: "1",
                meaning: "as given",
            },
            d::Out {
                path: "contact_law",
                unit: "-",
                meaning: "\"hertz\" or \"linear\"",
            },
            d::Out {
                path: "radius",
                unit: "m",
                meaning: "as given",
            },
            d::Out {
                path: "time_unit_s",
                unit: "s",
                meaning: "(m v0^(1-p)/k)^(1/(p+1)), with the stiffness given; else null",
            },
            d::Out {
                path: "units",
                unit: "-",
                meaning: "what the velocities are in",
            },
        ],
    ],
};
