//! Constrained impact from a scene: a fixed point or axis (section 2 of 002_b53e4779673eb6ed.txt)
//! or a support under the second body (sections 3-4), on top of [`super::rigid_impact`].
//!
//! A smooth support switches between $\mathbf B$ and $\mathbf B^*$ along the impact (3.8). A
//! rough support is classified at the start (section 4) and integrated with its switches between
//! rolling (4.2), sliding (4.3)-(4.4) and letting go ([`impact_rough`]); a Painleve-type start
//! with no consistent motion is reported as such, one with two is integrated along both.
use crate::models::doc as d;

use super::fixed_points::{Hold, b_star};
use super::planar_impact::{PlanarError, impact_planar};
use super::rigid_impact::{
    Body, ImpactError, ImpactResult, Law, RoughSupport, SmoothSupport, SupportMode, b_matrix,
    impact, impact_general, impact_rough, kinetic_change,
};
use super::support::{Classification, classify_at_rest, classify_sliding, matrices};
use nalgebra::{Matrix3, Vector3};

fn hold(body: &Body, go: &Vector3<f64>, axis: Option<Vector3<f64>>) -> Hold {
    let m = body.mass.unwrap_or(f64::INFINITY);
    // inertia about O by the parallel-axis theorem; O->C = G->C - G->O
    let j_o = body.inertia + (Matrix3::identity() * go.norm_squared() - go * go.transpose()) * m;
    let oc = body.offset - go;
    match axis {
        Some(e) => Hold::Axis {
            j_axis: e.dot(&(j_o * e)),
            e,
            oc,
        },
        None => Hold::Point { inertia_o: j_o, oc },
    }
}

fn free(body: &Body) -> Hold {
    match body.mass {
        Some(mass) => Hold::Free {
            mass,
            inertia: body.inertia,
            gc: body.offset,
        },
        None => Hold::Fixed,
    }
}

/// $\mathbf B^*$ of (2.1) with body `k` held at the point `go` (from its G) or about the axis
/// through it.
fn held_matrix(
    s: &RigidImpactScene,
    k: usize,
    go: &Vector3<f64>,
    axis: Option<Vector3<f64>>,
) -> Matrix3<f64> {
    let h = [0, 1].map(|j| {
        if j == k {
            hold(&s.bodies[j], go, axis)
        } else {
            free(&s.bodies[j])
        }
    });
    b_star(&h[0], &h[1])
}

/// The matrix of the scene's impact where it is fixed along it: $\mathbf B$ of (1.7) for free
/// bodies, $\mathbf B^*$ of (2.1) with a fixed point or axis; `None` with a support (its matrix
/// switches along the impact) or an inertia that cannot be inverted.
pub fn scene_matrix(s: &RigidImpactScene) -> Option<Matrix3<f64>> {
    match (&s.fixed, &s.support) {
        (Some((k, go, axis)), _) => Some(held_matrix(s, *k, go, *axis)),
        (None, None) => b_matrix(&s.bodies[0], &s.bodies[1]),
        (None, Some(_)) => None,
    }
}

/// `(result, support classification, warnings)`; no result when the case is only classified.
pub type SceneOutcome = (Option<ImpactResult>, Option<Classification>, Vec<String>);

/// The two bodies as if no support or fixed point held them: exactly where the impact is
/// planar (and the method allows), else integrated.
fn free_impact(s: &RigidImpactScene) -> Result<ImpactResult, ImpactError> {
    if let Some(b) = b_matrix(&s.bodies[0], &s.bodies[1])
        && let Some(mut r) = planar_or_none(s, &b)?
    {
        r.energy_change = kinetic_change(
            &s.bodies[0],
            &s.bodies[1],
            &s.v_rel,
            &Vector3::from(r.impulse),
        );
        return Ok(r);
    }
    impact(
        &s.bodies[0],
        &s.bodies[1],
        crate::models::rigid_impact::Contact::new(s.normal, s.v_rel, s.mu, s.law, s.e),
        s.rtol,
    )
}

/// Body `k` held at the point `go` (from its G) or about the axis through it (002 sec. 2): the
/// relative velocity at C must be one the held body can have (when the other cannot move); then
/// B* of (2.1), solved exactly where planar.
fn held_impact(
    s: &RigidImpactScene,
    k: usize,
    go: &Vector3<f64>,
    axis: Option<Vector3<f64>>,
) -> Result<ImpactResult, ImpactError> {
    let oc = s.bodies[k].offset - go;
    let sign = if k == 0 { 1.0 } else { -1.0 };
    let v_body = s.v_rel * sign;
    let off = match axis {
        Some(e) => {
            let es = e.cross(&oc);
            (v_body - es * (v_body.dot(&es) / es.norm_squared().max(f64::MIN_POSITIVE))).norm()
        }
        None => v_body.dot(&oc).abs() / oc.norm().max(f64::MIN_POSITIVE),
    };
    let other_free = s.bodies[1 - k].mass.is_some();
    if !other_free && off > 1e-9 * s.v_rel.norm() {
        return Err(ImpactError::OutOfRange {
            field: "initial.v_rel".into(),
            value: format!("[{}, {}, {}]", s.v_rel.x, s.v_rel.y, s.v_rel.z),
            allowed: match axis {
                Some(e) => format!(
                    "a velocity of C turning about the axis: parallel to e x OC = {:?}",
                    e.cross(&oc).as_slice()
                ),
                None => format!(
                    "a velocity of C turning about O: orthogonal to OC = {:?}",
                    oc.as_slice()
                ),
            },
        });
    }
    let b = held_matrix(s, k, go, axis);
    match planar_or_none(s, &b)? {
        Some(r) => Ok(r),
        None => impact_general(
            &b,
            None,
            crate::models::rigid_impact::Contact::new(s.normal, s.v_rel, s.mu, s.law, s.e),
            s.rtol,
        ),
    }
}

/// Solves the scene.
pub fn solve_scene(s: &RigidImpactScene) -> Result<SceneOutcome, ImpactError> {
    solve_scene_all(s, &mut Vec::new())
}

/// As [`solve_scene`], with the branches of a Painleve-type case with two solutions at the
/// support pushed to `alternatives`.
pub fn solve_scene_all(
    s: &RigidImpactScene,
    alternatives: &mut Vec<Alternative>,
) -> Result<SceneOutcome, ImpactError> {
    let mut warnings = Vec::new();
    if let Some((k, go, axis)) = &s.fixed {
        let r = held_impact(s, *k, go, *axis)?;
        if r.cut_off {
            warnings.push("cut-off impact: the relative velocity vanished while the contact stresses persist (the bodies are wedged)".into());
        }
        return Ok((Some(r), None, warnings));
    }
    let bad = |m: String| ImpactError::OutOfRange {
        field: "body".into(),
        value: m,
        allowed: "symmetric positive-definite inertia".into(),
    };
    let Some(sup) = &s.support else {
        return Ok((Some(free_impact(s)?), None, warnings));
    };
    let b = b_matrix(&s.bodies[0], &s.bodies[1]).ok_or_else(|| bad("singular".into()))?;
    let sm = matrices(&s.bodies[1], sup).ok_or_else(|| bad("singular".into()))?;
    let n = s.normal.normalize();
    // the contact force direction at the start: n - mu u (sliding at C) or n
    let vt = s.v_rel - n * s.v_rel.dot(&n);
    let f = if vt.norm() > 0.0 {
        n - vt.normalize() * s.mu
    } else {
        n
    };
    let nn = sup.normal;
    let va_t = s.v_support - nn * s.v_support.dot(&nn);
    let cl = if sup.mu > 0.0 && va_t.norm() > 0.0 {
        classify_sliding(&f, &sm, sup, &va_t.normalize())
    } else if sup.mu > 0.0 {
        classify_at_rest(&f, &sm, sup)
    } else {
        // smooth support: beta > 0, the solution (3.7) is unique
        let alpha = -(sm.b_tilde * f).dot(&nn);
        let beta = (sm.b_a * nn).dot(&nn);
        Classification {
            kind: "unique".into(),
            admissible: vec![if alpha >= 0.0 {
                "detach".into()
            } else {
                "slide".into()
            }],
            alpha,
            beta,
        }
    };
    // the kinetic energy change from the bodies' velocities (the second moving with A's velocity
    // before the impact), support impulse included
    let energy_of = |r: &ImpactResult| {
        super::rigid_impact::kinetic_change_moving(
            &s.bodies[0],
            &s.bodies[1],
            &s.v_rel,
            &s.v_support,
            &Vector3::from(r.impulse),
            Some((sup.offset, Vector3::from(r.support_impulse))),
        )
    };
    if sup.mu == 0.0 {
        let beta = (sm.b_a * nn).dot(&nn);
        let support = SmoothSupport {
            b_tilde: sm.b_tilde,
            normal: nn,
            beta,
        };
        let mut r = impact_general(
            &b,
            Some(support),
            crate::models::rigid_impact::Contact::new(s.normal, s.v_rel, s.mu, s.law, s.e),
            s.rtol,
        )?;
        r.energy_change = energy_of(&r);
        let gap = r.energy_change - r.kelvin_energy_change;
        if gap.abs() > 1e-9 * r.energy_change.abs().max(1e-300) {
            warnings.push(format!(
                "with the support, Kelvin's (1.10) over the contact at C misses the support's term (V_A- + V_A+, I*)/2 = {gap:.6e} J (the second body leaves the table with a normal velocity at A)"
            ));
        }
        return Ok((Some(r), Some(cl), warnings));
    }
    // a rough support: integrated with its roll/slide/let-go switches (section 4); a Painleve
    // case with no consistent start is said so, one with two is integrated along each branch
    let rough = RoughSupport {
        b_tilde: sm.b_tilde,
        b_a: sm.b_a,
        normal: nn,
        mu: sup.mu,
        v_a: s.v_support,
    };
    let run = |start: Option<SupportMode>| -> Result<ImpactResult, ImpactError> {
        let mut r = impact_rough(
            &b,
            rough.clone(),
            start,
            crate::models::rigid_impact::Contact::new(s.normal, s.v_rel, s.mu, s.law, s.e),
            s.rtol,
        )?;
        r.energy_change = energy_of(&r);
        Ok(r)
    };
    match cl.kind.as_str() {
        "none" => {
            warnings.push(format!(
                "Painleve-type case at the support: (3.6) with (3.2)/(3.3) has no solution at the start (alpha = {:.6e}, beta = {:.6e}); classical impact theory cannot resolve it, deformations at A must be modelled",
                cl.alpha, cl.beta
            ));
            Ok((None, Some(cl), warnings))
        }
        "two" => {
            let mode_of = |name: &str| match name {
                "detach" => SupportMode::Free,
                "roll" => SupportMode::Roll,
                _ => SupportMode::Slide,
            };
            let mut main = None;
            let mut main_name = "";
            for name in &cl.admissible {
                match run(Some(mode_of(name))) {
                    Ok(r) => {
                        if name == "detach" || main.is_none() {
                            main = Some(r.clone());
                            main_name = name;
                        }
                        alternatives.push(Alternative {
                            start: name.clone(),
                            impulse: Some(r.impulse),
                            support_impulse: Some(r.support_impulse),
                            energy_change: Some(r.energy_change),
                            error: None,
                        });
                    }
                    Err(e) => alternatives.push(Alternative {
                        start: name.clone(),
                        impulse: None,
                        support_impulse: None,
                        energy_change: None,
                        error: Some(e.to_string()),
                    }),
                }
            }
            // the result: the detaching branch where it is admissible and ends (section 4: with
            // deformable elements the body leaves the support), else the first that ends
            let result = match main_name {
                "detach" => "the result is the detaching one (section 4: with deformable elements the body leaves the support)".to_string(),
                "" => "no branch ends as a classical impact (each says why in `alternatives`)".to_string(),
                name => format!("the result is the {name} one (the first that ends; no detaching branch ends)"),
            };
            warnings.push(format!(
                "Painleve-type case at the support: (3.6) admits {:?} at the start; each branch is integrated (`alternatives`), {result}",
                cl.admissible
            ));
            Ok((main, Some(cl), warnings))
        }
        _ => match run(None) {
            Ok(r) => Ok((Some(r), Some(cl), warnings)),
            // a Painleve-type instant later in the impact: said, with the classification
            Err(e @ ImpactError::Painleve { .. }) => {
                warnings.push(e.to_string());
                Ok((None, Some(cl), warnings))
            }
            Err(e) => Err(e),
        },
    }
}

/// The exact planar solution of the scene's impact with matrix `b` ($\mathbf B$ of (1.7) or
/// $\mathbf B^*$ of (2.1)) where the scene's method takes it; `Ok(None)` to integrate (a scene
/// that is not planar under "auto", or "integrate").
fn planar_or_none(
    s: &RigidImpactScene,
    b: &Matrix3<f64>,
) -> Result<Option<ImpactResult>, ImpactError> {
    if s.method == ImpactMethod::Integrate {
        return Ok(None);
    }
    let r = impact_planar(b, s.normal, s.v_rel, s.mu, s.law, s.e).map_err(|e| match e {
        PlanarError::OutOfRange {
            field,
            value,
            allowed,
        } => ImpactError::OutOfRange {
            field: field.into(),
            value,
            allowed: allowed.into(),
        },
        PlanarError::NoEnd { law, p } => ImpactError::NoEnd {
            law: law.into(),
            chi_max: p,
        },
    })?;
    if r.is_none() && s.method == ImpactMethod::PlanarExact {
        return Err(ImpactError::OutOfRange {
            field: "solve.method".into(),
            value: "\"planar-exact\" for an impact that is not planar".into(),
            allowed: "a planar impact (the plane of the contact normal and the slip invariant under B, to 1e-12 of |B|, and no relative velocity across it), or \"auto\" / \"integrate\"".into(),
        });
    }
    Ok(r)
}

/// One branch of a Painleve-type case with two solutions at the support.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Alternative {
    /// The support's motion at the start: "detach", "roll" or "slide".
    pub start: String,
    /// The impulse on the first body (N s).
    pub impulse: Option<[f64; 3]>,
    /// The support's impulse on the second body (N s).
    pub support_impulse: Option<[f64; 3]>,
    /// Kinetic energy change (J).
    pub energy_change: Option<f64>,
    /// Why the branch could not be integrated.
    pub error: Option<String>,
}

/// The `rigid-impact` scene of 002_b53e4779673eb6ed.txt: two bodies, one contact, Coulomb
/// friction; optionally a fixed point or axis of one body, or a support under the second.
#[derive(Clone, Debug)]
pub struct RigidImpactScene {
    /// The two bodies.
    pub bodies: [Body; 2],
    /// Contact normal, into the first body.
    pub normal: Vector3<f64>,
    /// Friction coefficient.
    pub mu: f64,
    /// Restitution law.
    pub law: Law,
    /// Coefficient of restitution.
    pub e: f64,
    /// Relative velocity at C before impact (m/s).
    pub v_rel: Vector3<f64>,
    /// Relative tolerance.
    pub rtol: f64,
    /// The second body's support, if any.
    pub support: Option<super::support::Support>,
    /// Velocity of the support point A before impact (m/s).
    pub v_support: Vector3<f64>,
    /// A fixed point or axis: (body index 0|1, G->O, optional axis).
    pub fixed: Option<(usize, Vector3<f64>, Option<Vector3<f64>>)>,
    /// How to solve it (`[solve] method`).
    pub method: ImpactMethod,
}

/// How a `rigid-impact` scene is solved (`[solve] method`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ImpactMethod {
    /// The exact planar solution where the impact is planar (free bodies, or one held by a
    /// fixed point or axis), else the integrator.
    #[default]
    Auto,
    /// The exact planar solution ([`super::planar_impact`]); a scene that is not planar, or
    /// has a support, is an error.
    PlanarExact,
    /// The Darboux-Keller equations integrated in the normal impulse, planar or not.
    Integrate,
}

impl ImpactMethod {
    /// The values `[solve] method` takes.
    pub const ALLOWED: &'static str = "\"auto\" (the exact planar solution where the impact is planar, else integrated), \"planar-exact\", \"integrate\"";

    /// The scene's name for it.
    pub fn name(self) -> &'static str {
        match self {
            ImpactMethod::Auto => "auto",
            ImpactMethod::PlanarExact => super::planar_impact::METHOD,
            ImpactMethod::Integrate => "integrate",
        }
    }

    /// The method a scene names.
    pub fn parse(name: &str) -> Option<Self> {
        [
            ImpactMethod::Auto,
            ImpactMethod::PlanarExact,
            ImpactMethod::Integrate,
        ]
        .into_iter()
        .find(|m| m.name() == name)
    }
}

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
    pub phases: Option<Vec<super::rigid_impact::Phase>>,
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
    pub support_phases: Option<Vec<super::rigid_impact::Phase>>,
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
fn read_bodies(f: &super::params::Fields, raw: &RawScene) -> Result<Vec<Body>, super::SceneError> {
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
    f: &super::params::Fields,
    raw: &RawScene,
    out: &[Body],
) -> Result<
    (
        Option<super::support::Support>,
        Option<(usize, Vector3<f64>, Option<Vector3<f64>>)>,
    ),
    super::SceneError,
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
            Some(super::support::Support {
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

impl super::Model for RigidImpactScene {
    const NAME: &'static str = "rigid-impact";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = RigidImpactOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, super::SceneError> {
        use super::SceneError;
        let f = super::params::Fields { path };
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

    fn run(&self) -> Result<(RigidImpactOutcome, super::Curves), super::RunError> {
        let s = self;
        let mut alternatives = Vec::new();
        let (r, classification, mut warnings) =
            solve_scene_all(s, &mut alternatives).map_err(|e| super::RunError::BadArgument {
                arg: "impact".into(),
                message: e.to_string(),
            })?;
        let mut out = RigidImpactOutcome {
            model: Self::NAME,
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
        if let Some(r) = r {
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
                        return Err(super::RunError::BadArgument {
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
        Ok((out, vec![]))
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
                unit: "1",
                meaning: "alpha of (3.6)",
            },
            d::Out {
                path: "support_analysis.beta",
                unit: "1",
                meaning: "beta: (4.4) when sliding, else (B_A N, N)",
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
