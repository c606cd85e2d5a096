//! The `rigid-impact` scene: its raw tables, their validation into a [`RigidImpactScene`], its
//! outcome and its documentation.

use super::{Alternative, ImpactMethod, RigidImpactScene, solve_scene_all};
use crate::models::doc as d;
use crate::models::rigid_impact::{Body, Law};
use crate::models::support::Classification;
use crate::models::trace::{Trace, Traced, or_why};
use nalgebra::{Matrix3, Vector3};

type Value = toml::Value;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct RawScene {
    model: Option<Value>,
    body: Option<Value>,
    contact: Option<Value>,
    initial: Option<Value>,
    solve: Option<Value>,
    support: Option<Value>,
    fixed: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    mass: Option<Value>,
    inertia: Option<Value>,
    contact_offset: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawContact {
    normal: Option<Value>,
    mu: Option<Value>,
    law: Option<Value>,
    e: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInitial {
    v_rel: Option<Value>,
    v_support: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSupport {
    offset: Option<Value>,
    normal: Option<Value>,
    mu: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFixed {
    offset: Option<Value>,
    axis: Option<Value>,
    body: Option<Value>,
}

/// What `impact run` prints for a `rigid-impact` scene. When the case is only classified (a
/// rough support that slides, a Painleve-type case) the impulse is `null` and the fields of an
/// integrated impact are absent.
#[derive(Clone, Debug, serde::Serialize)]
pub struct RigidImpactOutcome {
    /// `"rigid-impact"`.
    pub model: &'static str,
    /// The restitution law.
    pub law: &'static str,
    /// The impulse on the first body (N s), `null` when not integrated.
    pub impulse: Option<[f64; 3]>,
    /// Relative velocity at C after (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_rel_after: Option<[f64; 3]>,
    /// Normal impulse at the end of compression (N s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub compression_impulse: Option<f64>,
    /// Kinetic energy change (J).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_change: Option<f64>,
    /// The same by Kelvin's theorem (J).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kelvin_energy_change: Option<f64>,
    /// Smallest eigenvalue of B.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_min: Option<f64>,
    /// Largest eigenvalue of B.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda_max: Option<f64>,
    /// Upper bound (1.9) on |I|.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound_upper: Option<f64>,
    /// Lower bound (1.13) on |I|.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound_lower: Option<f64>,
    /// Stick/slip phases.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phases: Option<Vec<crate::models::rigid_impact::Phase>>,
    /// Whether the impact was cut off (a fixed point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cut_off: Option<bool>,
    /// The support's classification, if any.
    pub classification: Option<String>,
    /// The support analysis, if any.
    pub support_analysis: Option<Classification>,
    /// The support's impulse on the second body (N s), with a support.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub support_impulse: Option<[f64; 3]>,
    /// A rough support's phases: "roll", "slide" or "detached", each with the normal impulse at
    /// C where it starts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub support_phases: Option<Vec<crate::models::rigid_impact::Phase>>,
    /// Tangential velocity of A after the impact (m/s), with a rough support.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_support_after: Option<[f64; 3]>,
    /// The branches of a Painleve-type case with two solutions at the support.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub alternatives: Vec<Alternative>,
    /// Work done.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stats: Option<crate::integrate::Stats>,
    /// How the impact was solved: "planar-exact" (the exact planar solution by events in closed
    /// form) or "integrate" (the Darboux-Keller equations integrated in the normal impulse).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method: Option<&'static str>,
    /// What the user should know.
    pub warnings: Vec<String>,
}

/// The two `[[body]]` tables: mass (or "inf"), inertia, contact offset.
fn read_bodies(
    f: &crate::models::params::Fields,
    raw: &RawScene,
) -> Result<Vec<Body>, crate::models::SceneError> {
    let bodies = match &raw.body {
        Some(Value::Array(a)) if a.len() == 2 => a,
        other => {
            return Err(f.out_of_range(
                "[[body]]",
                other.as_ref().map_or("missing".into(), |v| {
                    format!("{} tables", v.as_array().map_or(0, |a| a.len()))
                }),
                "exactly two [[body]] tables",
            ));
        }
    };
    let mut out = Vec::new();
    for (k, b) in bodies.iter().enumerate() {
        let name = format!("body[{k}]");
        let t = b
            .as_table()
            .ok_or_else(|| f.out_of_range(&name, b.to_string(), "a table"))?;
        let rb: RawBody = f.raw(t, &name)?;
        let mass = match &rb.mass {
            Some(Value::String(s)) if s == "inf" => None,
            _ => Some(f.num(
                rb.mass.as_ref(),
                &format!("{name}.mass"),
                None,
                |v| v > 0.0,
                "mass > 0 (kg), or \"inf\" for a fixed massive obstacle",
            )?),
        };
        let inertia = match (mass, &rb.inertia) {
            (None, None) => Matrix3::identity(),
            (_, v) => {
                let err = |val: String| {
                    f.out_of_range(
                        &format!("{name}.inertia"),
                        val,
                        "a symmetric positive-definite 3x3 array (kg m^2)",
                    )
                };
                let v = v.as_ref().ok_or_else(|| err("missing".into()))?;
                let rows = v.as_array().ok_or_else(|| err(v.to_string()))?;
                let mut m = Matrix3::zeros();
                if rows.len() != 3 {
                    return Err(err(v.to_string()));
                }
                for (i, row) in rows.iter().enumerate() {
                    let cols = row.as_array().ok_or_else(|| err(v.to_string()))?;
                    if cols.len() != 3 {
                        return Err(err(v.to_string()));
                    }
                    for (j, c) in cols.iter().enumerate() {
                        m[(i, j)] = c
                            .as_float()
                            .or_else(|| c.as_integer().map(|x| x as f64))
                            .filter(|x| x.is_finite())
                            .ok_or_else(|| err(v.to_string()))?;
                    }
                }
                let asym = (m - m.transpose()).abs().max();
                if asym > 1e-12 * m.abs().max() || m.cholesky().is_none() {
                    return Err(err(format!("{v} (not symmetric positive-definite)")));
                }
                m
            }
        };
        let offset = match (mass, &rb.contact_offset) {
            (None, None) => Vector3::zeros(),
            _ => f.vec3(
                rb.contact_offset.as_ref(),
                &format!("{name}.contact_offset"),
            )?,
        };
        out.push(Body {
            mass,
            inertia,
            offset,
        });
    }
    if out.iter().all(|b| b.mass.is_none()) {
        return Err(f.out_of_range(
            "[[body]].mass",
            "\"inf\" twice".into(),
            "at least one body with finite mass",
        ));
    }
    Ok(out)
}

/// The `[support]` and `[fixed]` tables (at most one of them), given the bodies.
#[allow(clippy::type_complexity)]
fn read_holds(
    f: &crate::models::params::Fields,
    raw: &RawScene,
    out: &[Body],
) -> Result<
    (
        Option<crate::models::support::Support>,
        Option<(usize, Vector3<f64>, Option<Vector3<f64>>)>,
    ),
    crate::models::SceneError,
> {
    let support = match &raw.support {
        None => None,
        Some(_) => {
            let t: RawSupport = f.raw(f.table(raw.support.as_ref(), "support")?, "support")?;
            let normal = f.vec3(t.normal.as_ref(), "support.normal")?;
            if normal.norm() <= 0.0 {
                return Err(f.out_of_range(
                    "support.normal",
                    format!("{normal:?}"),
                    "a non-zero vector from the support into the second body",
                ));
            }
            if out[1].mass.is_none() {
                return Err(f.out_of_range(
                    "[support]",
                    "second body with mass \"inf\"".into(),
                    "a support under a second body of finite mass",
                ));
            }
            Some(crate::models::support::Support {
                offset: f.vec3(t.offset.as_ref(), "support.offset")?,
                normal: normal.normalize(),
                mu: f.num(
                    t.mu.as_ref(),
                    "support.mu",
                    Some(0.0),
                    |v| v >= 0.0,
                    "mu >= 0",
                )?,
            })
        }
    };
    let fixed = match &raw.fixed {
        None => None,
        Some(_) => {
            let t: RawFixed = f.raw(f.table(raw.fixed.as_ref(), "fixed")?, "fixed")?;
            let body = match &t.body {
                None => 0,
                Some(Value::Integer(1)) => 0,
                Some(Value::Integer(2)) => 1,
                Some(other) => {
                    return Err(f.out_of_range("fixed.body", other.to_string(), "1 or 2"));
                }
            };
            if out[body].mass.is_none() {
                return Err(f.out_of_range(
                    "fixed.body",
                    (body + 1).to_string(),
                    "a body of finite mass (an immovable body needs no fixed point)",
                ));
            }
            let axis = if t.axis.is_some() {
                let a = f.vec3(t.axis.as_ref(), "fixed.axis")?;
                if a.norm() <= 0.0 {
                    return Err(f.out_of_range(
                        "fixed.axis",
                        format!("{a:?}"),
                        "a non-zero direction",
                    ));
                }
                Some(a.normalize())
            } else {
                None
            };
            Some((body, f.vec3(t.offset.as_ref(), "fixed.offset")?, axis))
        }
    };
    Ok((support, fixed))
}

impl crate::models::Model for RigidImpactScene {
    const NAME: &'static str = "rigid-impact";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = RigidImpactOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, crate::models::SceneError> {
        use crate::models::SceneError;
        let f = crate::models::params::Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let out = read_bodies(&f, &raw)?;
        let c: RawContact = f.raw(f.table(raw.contact.as_ref(), "contact")?, "contact")?;
        let normal = f.vec3(c.normal.as_ref(), "contact.normal")?;
        if normal.norm() <= 0.0 || normal.norm().is_nan() {
            return Err(f.out_of_range(
                "contact.normal",
                format!("{normal:?}"),
                "a non-zero vector pointing into the first body",
            ));
        }
        let law = match f
            .choice(
                c.law.as_ref(),
                "law",
                &["newton", "poisson", "energetic"],
                "poisson",
            )?
            .as_str()
        {
            "newton" => Law::Newton,
            "energetic" => Law::Energetic,
            _ => Law::Poisson,
        };
        let mu = f.num(
            c.mu.as_ref(),
            "contact.mu",
            Some(0.0),
            |v| v >= 0.0,
            "mu >= 0",
        )?;
        let e = f.num(
            c.e.as_ref(),
            "contact.e",
            None,
            |v| (0.0..=1.0).contains(&v),
            "0 <= e <= 1",
        )?;
        let init: RawInitial = f.raw(f.table(raw.initial.as_ref(), "initial")?, "initial")?;
        let v_rel = f.vec3(init.v_rel.as_ref(), "initial.v_rel")?;
        let v_support = if init.v_support.is_some() {
            f.vec3(init.v_support.as_ref(), "initial.v_support")?
        } else {
            Vector3::zeros()
        };
        let (support, fixed) = read_holds(&f, &raw, &out)?;
        if support.is_some() && fixed.is_some() {
            return Err(f.out_of_range(
                "[support] and [fixed]",
                "both present".into(),
                "one of them",
            ));
        }
        let n = normal.normalize();
        if v_rel.dot(&n) >= 0.0 || v_rel.dot(&n).is_nan() {
            return Err(SceneError::OutOfRange {
                path: path.into(),
                field: "initial.v_rel".into(),
                value: format!("[{}, {}, {}]", v_rel.x, v_rel.y, v_rel.z),
                allowed: "(v_rel, normal) < 0: the bodies approach at C".into(),
            });
        }
        // `[solve] method` names how the impact is solved, not an ODE method (the integrator
        // picks its own: DOP853, Radau5 where the slip turns stiff)
        let mut solve_table = raw.solve.clone();
        let method = match solve_table
            .as_mut()
            .and_then(|t| t.as_table_mut())
            .and_then(|t| t.remove("method"))
        {
            None => ImpactMethod::Auto,
            Some(Value::String(name)) => ImpactMethod::parse(&name).ok_or_else(|| {
                f.out_of_range("solve.method", format!("\"{name}\""), ImpactMethod::ALLOWED)
            })?,
            Some(other) => {
                return Err(f.out_of_range(
                    "solve.method",
                    other.to_string(),
                    ImpactMethod::ALLOWED,
                ));
            }
        };
        if method == ImpactMethod::PlanarExact && support.is_some() {
            return Err(f.out_of_range(
                "solve.method",
                "\"planar-exact\" with a [support]".into(),
                "\"auto\" or \"integrate\" with a support (the exact planar solution covers free bodies and bodies held by a fixed point or axis)",
            ));
        }
        let solve = f.solve(solve_table.as_ref(), "impact-end", false)?;
        Ok(RigidImpactScene {
            bodies: [out[0].clone(), out[1].clone()],
            normal,
            mu,
            law,
            e,
            v_rel,
            rtol: solve.rtol,
            support,
            v_support,
            fixed,
            method,
        })
    }

    fn run(&self) -> Result<(RigidImpactOutcome, crate::models::Curves), crate::models::RunError> {
        Ok((self.go(false)?.0, vec![]))
    }

    fn run_traced(&self) -> Result<(RigidImpactOutcome, Traced), crate::models::RunError> {
        let (out, trace) = self.go(true)?;
        Ok((
            out,
            or_why(trace, "this run took no steps (no impact to follow)"),
        ))
    }
}

/// The path of an impact in the normal impulse: the relative velocity at C (the first body's
/// less the second's, in the scene's axes) at every accepted step (a planar impact solved
/// exactly: at each event of its closed form, between which the velocity is linear in the
/// impulse), each phase's start and the end of compression as events; `None` without steps.
fn trace_of(r: &crate::models::rigid_impact::ImpactResult) -> Option<Trace> {
    if r.path.is_empty() {
        return None;
    }
    let mut tr = Trace::new(
        ("I_n", "N s"),
        &[("V_x", "m/s"), ("V_y", "m/s"), ("V_z", "m/s")],
    );
    for (chi, v) in &r.path {
        tr.push(*chi, v);
    }
    // the velocity where an event fired: stages end on their events, so a step sits there
    let at = |chi: f64| {
        r.path
            .iter()
            .rev()
            .find(|(c, _)| *c <= chi)
            .map_or([f64::NAN; 3], |(_, v)| *v)
    };
    let mut events: Vec<(String, f64)> = r
        .phases
        .iter()
        .map(|p| (format!("{} starts", p.kind), p.normal_impulse))
        .collect();
    events.push(("compression ends".into(), r.compression_impulse));
    events.sort_by(|a, b| a.1.total_cmp(&b.1));
    for (name, chi) in events {
        tr.event(&name, chi, &at(chi));
    }
    Some(tr)
}

impl RigidImpactScene {
    /// The run, with its path ([`trace_of`]) when `record` is set.
    fn go(
        &self,
        record: bool,
    ) -> Result<(RigidImpactOutcome, Option<Trace>), crate::models::RunError> {
        let s = self;
        let mut alternatives = Vec::new();
        let (r, classification, mut warnings) =
            solve_scene_all(s, &mut alternatives).map_err(|e| {
                crate::models::RunError::BadArgument {
                    arg: "impact".into(),
                    message: e.to_string(),
                }
            })?;
        let mut out = RigidImpactOutcome {
            model: <Self as crate::models::Model>::NAME,
            law: s.law.name(),
            impulse: None,
            v_rel_after: None,
            compression_impulse: None,
            energy_change: None,
            kelvin_energy_change: None,
            lambda_min: None,
            lambda_max: None,
            bound_upper: None,
            bound_lower: None,
            phases: None,
            cut_off: None,
            classification: classification.as_ref().map(|c| c.kind.clone()),
            support_analysis: classification,
            support_impulse: None,
            support_phases: None,
            v_support_after: None,
            alternatives,
            stats: None,
            method: None,
            warnings: vec![],
        };
        let mut trace = None;
        if let Some(r) = r {
            if record {
                trace = trace_of(&r);
            }
            let scale = 0.5 * s.v_rel.norm_squared() / r.lambda_min.max(1e-300);
            // only Newton's law is to blame for a gain: the energetic law dissipates always (a
            // gain is the solver's inconsistency, an error), Poisson's in planar motion (where
            // the exact solution is used); elsewhere the theory does not bound Poisson's
            if r.energy_change > 1e-9 * scale {
                match s.law {
                    Law::Newton => warnings.push(format!(
                        "kinetic energy grows by {:.6e} J: Newton's restitution with friction is not energetically consistent here",
                        r.energy_change
                    )),
                    Law::Energetic => {
                        return Err(crate::models::RunError::BadArgument {
                            arg: "impact".into(),
                            message: format!(
                                "solver inconsistency: the kinetic energy grew by {:.6e} J under the energetic law, which dissipates",
                                r.energy_change
                            ),
                        });
                    }
                    Law::Poisson => warnings.push(format!(
                        "kinetic energy grows by {:.6e} J under Poisson's law: outside planar motion the theory does not bound it",
                        r.energy_change
                    )),
                }
            }
            out.impulse = Some(r.impulse);
            out.v_rel_after = Some(r.v_rel_after);
            out.compression_impulse = Some(r.compression_impulse);
            out.energy_change = Some(r.energy_change);
            out.kelvin_energy_change = Some(r.kelvin_energy_change);
            out.lambda_min = Some(r.lambda_min);
            out.lambda_max = Some(r.lambda_max);
            out.bound_upper = Some(r.bound_upper);
            out.bound_lower = Some(r.bound_lower);
            out.phases = Some(r.phases);
            out.cut_off = Some(r.cut_off);
            if s.support.is_some() {
                out.support_impulse = Some(r.support_impulse);
            }
            out.support_phases = (!r.support_phases.is_empty()).then_some(r.support_phases);
            out.v_support_after = r.v_support_after;
            out.stats = Some(r.stats);
            out.method = Some(r.method);
        }
        out.warnings = warnings;
        Ok((out, trace))
    }
}

/// The `rigid-impact` model's reference (`impact describe rigid-impact`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "rigid-impact",
    summary: "Two rigid bodies colliding at a point C with Coulomb friction (002, (1.1)-(1.13), sec. 3-4): Darboux-Keller's equations in the normal impulse with stick and slip, Newton's, Poisson's or Stronge's energetic restitution; a fixed point or axis on one body (cut-off impacts, 002 sec. 2) or a support under the second body (sec. 3-4: smooth, rough, the Painleve-type cases classified). A planar impact is solved exactly by events in closed form.",
    conventions: &[
        "the impulse I is the one on the first body (002 (1.2)-(1.3)); N s",
        "the contact normal points into the first body",
        "v_rel is the velocity at C of the first body minus that of the second; the bodies approach: (v_rel, normal) < 0",
        "contact_offset is the vector from the body's centre of mass G to C (m)",
        "mass = \"inf\" makes a body an immovable obstacle",
    ],
    example: "scenes/rigid_impact.toml",
    keys: &[&[
        d::Key {
            key: "model",
            unit: "-",
            range: "\"rigid-impact\"",
            default: "required",
            meaning: "the model",
        },
        d::Key {
            key: "body[].mass",
            unit: "kg",
            range: "mass > 0, or \"inf\"",
            default: "required",
            meaning: "mass of each of the two [[body]] tables",
        },
        d::Key {
            key: "body[].inertia[]",
            unit: "kg m^2",
            range: "a symmetric positive definite 3x3 matrix (rows), or 3 principal values",
            default: "identity for \"inf\"",
            meaning: "central inertia tensor in the contact frame",
        },
        d::Key {
            key: "body[].contact_offset",
            unit: "m",
            range: "a 3-vector",
            default: "required",
            meaning: "from G to C",
        },
        d::Key {
            key: "contact.normal",
            unit: "1",
            range: "a non-zero 3-vector",
            default: "required",
            meaning: "contact normal, into the first body (normalised)",
        },
        d::Key {
            key: "contact.mu",
            unit: "1",
            range: "mu >= 0",
            default: "0",
            meaning: "Coulomb friction at C",
        },
        d::Key {
            key: "contact.e",
            unit: "1",
            range: "0 <= e <= 1",
            default: "required",
            meaning: "coefficient of restitution (of the law)",
        },
        d::Key {
            key: "contact.law",
            unit: "-",
            range: "\"newton\", \"poisson\", \"energetic\"",
            default: "\"poisson\"",
            meaning: "restitution law",
        },
        d::Key {
            key: "initial.v_rel",
            unit: "m/s",
            range: "a 3-vector with (v_rel, normal) < 0",
            default: "required",
            meaning: "relative velocity at C before impact",
        },
        d::Key {
            key: "initial.v_support",
            unit: "m/s",
            range: "a 3-vector",
            default: "zero",
            meaning: "velocity of the second body at the support point A before impact",
        },
        d::Key {
            key: "support.offset",
            unit: "m",
            range: "a 3-vector",
            default: "no support",
            meaning: "from the second body's G to the support point A",
        },
        d::Key {
            key: "support.normal",
            unit: "1",
            range: "a non-zero vector from the support into the second body",
            default: "required with [support]",
            meaning: "the support's normal",
        },
        d::Key {
            key: "support.mu",
            unit: "1",
            range: "mu >= 0",
            default: "0",
            meaning: "friction at A (0: a smooth support)",
        },
        d::Key {
            key: "fixed.body",
            unit: "-",
            range: "1 or 2, a body of finite mass",
            default: "required with [fixed]",
            meaning: "the body with a fixed point or axis",
        },
        d::Key {
            key: "fixed.offset",
            unit: "m",
            range: "a 3-vector",
            default: "required with [fixed]",
            meaning: "from that body's G to the fixed point",
        },
        d::Key {
            key: "fixed.axis",
            unit: "1",
            range: "a non-zero direction",
            default: "none (a fixed point)",
            meaning: "a fixed axis through the point",
        },
        d::Key {
            key: "solve.method",
            unit: "-",
            range: "\"auto\", \"planar-exact\", \"integrate\"",
            default: "\"auto\"",
            meaning: "the exact planar solution where the impact is planar, else integrated",
        },
        d::Key {
            key: "solve.rtol",
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
                path: "impulse",
                unit: "N s",
                meaning: "the impulse on the first body; null when only classified",
            },
            d::Out {
                path: "v_rel_after",
                unit: "m/s",
                meaning: "relative velocity at C after",
            },
            d::Out {
                path: "compression_impulse",
                unit: "N s",
                meaning: "normal impulse at the end of compression",
            },
            d::Out {
                path: "energy_change",
                unit: "J",
                meaning: "kinetic energy change (never > 0 under a dissipative law)",
            },
            d::Out {
                path: "kelvin_energy_change",
                unit: "J",
                meaning: "the same by Kelvin's theorem (1.10)",
            },
            d::Out {
                path: "lambda_min",
                unit: "1/kg",
                meaning: "smallest eigenvalue of B (or B*)",
            },
            d::Out {
                path: "lambda_max",
                unit: "1/kg",
                meaning: "largest eigenvalue of B",
            },
            d::Out {
                path: "bound_upper",
                unit: "N s",
                meaning: "the upper bound (1.9) on |I|",
            },
            d::Out {
                path: "bound_lower",
                unit: "N s",
                meaning: "the lower bound (1.13) on |I|",
            },
            d::Out {
                path: "phases[].kind",
                unit: "-",
                meaning: "\"stick\" or \"slip\" (and a support's \"roll\", \"slide\", \"detached\")",
            },
            d::Out {
                path: "phases[].normal_impulse",
                unit: "N s",
                meaning: "normal impulse where the phase starts",
            },
            d::Out {
                path: "cut_off",
                unit: "-",
                meaning: "whether the impact was cut off (002 sec. 2)",
            },
            d::Out {
                path: "classification",
                unit: "-",
                meaning: "the support's classification, if any",
            },
            d::Out {
                path: "support_analysis.kind",
                unit: "-",
                meaning: "\"unique\", \"none\" or \"two\" admissible motions at the support",
            },
            d::Out {
                path: "support_analysis.admissible",
                unit: "-",
                meaning: "the admissible motions: \"detach\", \"roll\", \"slide\"",
            },
            d::Out {
                path: "support_analysis.alpha",
                unit: "1/kg",
                meaning: "alpha of (3.6), -(B~ f, N) for the unit direction f of C's impulse",
            },
            d::Out {
                path: "support_analysis.beta",
                unit: "1/kg",
                meaning: "beta: (4.4) when sliding, else (B_A N, N) (an inverse mass, as B_A)",
            },
            d::Out {
                path: "support_analysis",
                unit: "-",
                meaning: "null without a support",
            },
            d::Out {
                path: "support_impulse",
                unit: "N s",
                meaning: "the support's impulse on the second body",
            },
            d::Out {
                path: "support_phases[].kind",
                unit: "-",
                meaning: "a rough support's phases: \"roll\", \"slide\", \"detached\"",
            },
            d::Out {
                path: "support_phases[].normal_impulse",
                unit: "N s",
                meaning: "normal impulse at C where it starts",
            },
            d::Out {
                path: "v_support_after",
                unit: "m/s",
                meaning: "tangential velocity of A after, with a rough support",
            },
            d::Out {
                path: "alternatives[].start",
                unit: "-",
                meaning: "a Painleve-type case's branch: the support's motion at the start",
            },
            d::Out {
                path: "alternatives[].impulse",
                unit: "N s",
                meaning: "that branch's impulse on the first body",
            },
            d::Out {
                path: "alternatives[].support_impulse",
                unit: "N s",
                meaning: "that branch's support impulse",
            },
            d::Out {
                path: "alternatives[].energy_change",
                unit: "J",
                meaning: "that branch's energy change",
            },
            d::Out {
                path: "alternatives[].error",
                unit: "-",
                meaning: "why that branch could not be integrated",
            },
            d::Out {
                path: "method",
                unit: "-",
                meaning: "\"planar-exact\" or \"integrate\"",
            },
            d::Out {
                path: "law",
                unit: "-",
                meaning: "the restitution law",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the user should know (an energy gain under Newton's law, a Painleve-type case)",
            },
        ],
        d::STATS,
    ],
};
