//! Constrained impact from a scene: a fixed point or axis (section 2 of 002_b53e4779673eb6ed.txt)
//! or a support under the second body (sections 3-4), on top of [`super::rigid_impact`].
//!
//! A smooth support switches between $\mathbf B$ and $\mathbf B^*$ along the impact (3.8). A
//! rough support is classified at the start (section 4) and integrated with its switches between
//! rolling (4.2), sliding (4.3)-(4.4) and letting go ([`impact_rough`]); a Painleve-type start
//! with no consistent motion is reported as such, one with two is integrated along both.
//!
//! Here the scene's types and the dispatch; apart: `held` (a fixed point or axis, section 2),
//! `supported` (a support under the second body, sections 3-4) and `scene` (reading the scene,
//! its outcome and documentation).

mod held;
mod scene;
mod supported;

pub use scene::{DOC, RigidImpactOutcome};

use super::planar_impact::{PlanarError, impact_planar};
use super::rigid_impact::{Body, ImpactError, ImpactResult, Law, b_matrix, impact, kinetic_change};
use super::support::Classification;
use held::{held_impact, held_matrix};
use nalgebra::{Matrix3, Vector3};

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
    match &s.support {
        None => Ok((Some(free_impact(s)?), None, warnings)),
        Some(sup) => supported::impact_supported(s, sup, alternatives, warnings),
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
