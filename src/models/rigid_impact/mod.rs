//! Impact of two rigid bodies with one contact point and Coulomb friction, integrated in the
//! normal impulse (Darboux-Keller), 002_b53e4779673eb6ed.txt section 1.
//!
//! $$\Delta\mathbf V_C = \mathbf B\mathbf I,\quad \mathbf B = (m_1^{-1} + m_2^{-1})\mathbf E_3 + \|b_{ij}\|,\quad
//!   b_{ij} = \sum_k (\mathbf J_k^{-1}(\mathbf G_k\mathbf C\times\mathbf e_i), \mathbf G_k\mathbf C\times\mathbf e_j) \quad (1.7)$$
//! With $\chi = I_n$ the independent variable, $d\mathbf V/d\chi = \mathbf B\,d\mathbf I/d\chi$ and
//! $d\mathbf I/d\chi = \mathbf n - \mu\,\mathbf V_t/|\mathbf V_t|$ while sliding (1.5); when the
//! slip speed reaches zero the body sticks if the tangential impulse rate $\boldsymbol\tau$ that
//! keeps $\mathbf V_t = 0$ satisfies $|\boldsymbol\tau| \le \mu$, and otherwise slides again in the
//! direction $\mathbf u$ the dynamics give ($\mathbf P_t\mathbf B(\mathbf n - \mu\mathbf u) =
//! \kappa\mathbf u$, $\kappa > 0$): no chattering and no division by zero at zero slip.
//! Compression ends at $V_n = 0$; restitution follows Newton ($V_n^+ = -eV_n^-$), Poisson
//! ($I_n = (1+e)I_{n,c}$) or Stronge (normal work in restitution $= -e^2\times$ that in
//! compression). The normal $\mathbf n$ points into the first body, and $\mathbf I$ is the impulse
//! on the first body (1.2)-(1.4).
//!
//! Every solve also returns the checks of Proposition 1: Kelvin's formula (1.10)/(1.11) against
//! the kinetic energy change computed directly from body velocities, (1.12), and the bounds (1.9)
//! and (1.13) with the eigenvalues of $\mathbf B$.

mod driver;
mod events;
mod friction;
mod keller;
mod support;

use crate::integrate::IntegrateError;
use driver::*;
use friction::*;
use keller::*;
use nalgebra::{Matrix3, Vector3};
use support::*;

pub use support::SupportMode;

/// A rigid body at the contact.
#[derive(Clone, Debug)]
pub struct Body {
    /// Mass (kg); `None` for a fixed massive obstacle.
    pub mass: Option<f64>,
    /// Central inertia tensor (kg m^2), symmetric positive-definite.
    pub inertia: Matrix3<f64>,
    /// Vector from the centre of mass G to the contact point C (m).
    pub offset: Vector3<f64>,
}

/// Restitution law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// Newton: $V_n^+ = -e V_n^-$.
    Newton,
    /// Poisson: $I_n = (1 + e) I_{n,c}$.
    Poisson,
    /// Stronge: restitution work $= -e^2 \times$ compression work.
    Energetic,
}

impl Law {
    /// Scene name.
    pub fn name(self) -> &'static str {
        match self {
            Law::Newton => "newton",
            Law::Poisson => "poisson",
            Law::Energetic => "energetic",
        }
    }
}

/// The matrix B of (1.7) for two bodies (a body with no mass contributes nothing).
pub fn b_matrix(b1: &Body, b2: &Body) -> Option<Matrix3<f64>> {
    let mut b = Matrix3::zeros();
    for body in [b1, b2] {
        let Some(m) = body.mass else { continue };
        let jinv = body.inertia.try_inverse()?;
        b += Matrix3::identity() / m;
        let r = body.offset;
        for i in 0..3 {
            for j in 0..3 {
                let ei = Vector3::ith(i, 1.0);
                let ej = Vector3::ith(j, 1.0);
                b[(i, j)] += (jinv * r.cross(&ei)).dot(&r.cross(&ej));
            }
        }
    }
    Some(b)
}

/// A phase of the impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Phase {
    /// "slip", "stick" or "reversal" (slip resumed in a new direction).
    pub kind: String,
    /// Normal impulse at which the phase starts (N s).
    pub normal_impulse: f64,
}

/// The outcome of one impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ImpactResult {
    /// Impulse on the first body (N s).
    pub impulse: [f64; 3],
    /// Relative velocity at C after impact (m/s).
    pub v_rel_after: [f64; 3],
    /// Normal impulse at the end of compression (N s).
    pub compression_impulse: f64,
    /// Kinetic energy change computed from the bodies' velocities (J).
    pub energy_change: f64,
    /// Kelvin's formula (1.10), $\tfrac12(\mathbf V^- + \mathbf V^+, \mathbf I)$ (J).
    pub kelvin_energy_change: f64,
    /// Smallest eigenvalue of B (1/kg).
    pub lambda_min: f64,
    /// Largest eigenvalue of B (1/kg).
    pub lambda_max: f64,
    /// (1.9): $2|\mathbf V^-|/\lambda$ (N s).
    pub bound_upper: f64,
    /// (1.13): $|(\mathbf V^-, \mathbf n)|/\Lambda$ (N s).
    pub bound_lower: f64,
    /// Phases with the normal impulse at each switch.
    pub phases: Vec<Phase>,
    /// The bodies wedged: relative velocity zero, contact stresses persist (only with a singular
    /// $\mathbf B^*$); the impulse is the one at the moment of wedging.
    pub cut_off: bool,
    /// Work done.
    pub stats: crate::integrate::Stats,
    /// How the impact was solved: "integrate" (the Darboux-Keller equations (1.5) integrated in
    /// the normal impulse) or "planar-exact" ([`super::planar_impact`]).
    pub method: &'static str,
    /// Impulse of the support on the second body (N s), zero without a support.
    pub support_impulse: [f64; 3],
    /// A rough support's motion: "roll", "slide" or "detached" with the normal impulse at C at
    /// which each phase starts (empty without a rough support).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub support_phases: Vec<Phase>,
    /// Tangential velocity of A after the impact (m/s), with a rough support.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_support_after: Option<[f64; 3]>,
    /// The relative velocity along the impact: `(normal impulse, V)` at every accepted step.
    #[serde(skip)]
    pub path: Vec<(f64, [f64; 3])>,
}

/// Why an impact could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum ImpactError {
    /// Bad input.
    #[error("{field} = {value} is not allowed; allowed: {allowed}")]
    OutOfRange {
        /// Field.
        field: String,
        /// Value.
        value: String,
        /// Allowed range.
        allowed: String,
    },
    /// The solver failed.
    #[error("solver: {0}")]
    Integrate(#[from] IntegrateError),
    /// A Painleve-type case at the support: (3.6) with (3.2)/(3.3) admits no motion.
    #[error(
        "Painleve-type case at the support at normal impulse {chi:e} N s: {what}; classical impact theory has no solution here (deformations at A must be modelled)"
    )]
    Painleve {
        /// Normal impulse at C where it happens.
        chi: f64,
        /// What fails.
        what: String,
    },
    /// The integration broke a law it must keep: friction did positive work over a stage (a
    /// slip speeding up under its own friction), or the energy grew under the energetic law.
    /// Never a property of the restitution law: an error of the solver, said with where.
    #[error("solver inconsistency at normal impulse {chi:e} N s: {what}")]
    Inconsistent {
        /// Normal impulse at C where the stage ended (N s).
        chi: f64,
        /// What was broken, with its size.
        what: String,
    },
    /// The restitution condition was not reached.
    #[error("the {law} restitution condition was not reached by normal impulse {chi_max:e} N s")]
    NoEnd {
        /// Law.
        law: String,
        /// Largest normal impulse tried.
        chi_max: f64,
    },
}

/// A smooth support under the second body: $\tilde{\mathbf B}$, N and $\beta$ of (3.6).
#[derive(Clone, Debug)]
pub struct SmoothSupport {
    /// $\tilde{\mathbf B}$ of (3.4).
    pub b_tilde: Matrix3<f64>,
    /// Unit normal N at A.
    pub normal: Vector3<f64>,
    /// $\beta = (\mathbf B_A\mathbf N, \mathbf N)$.
    pub beta: f64,
}

/// A rough support under the second body (002 section 4): Coulomb friction $\mu^*$ at A.
#[derive(Clone, Debug)]
pub struct RoughSupport {
    /// $\tilde{\mathbf B}$ of (3.4).
    pub b_tilde: Matrix3<f64>,
    /// $\mathbf B_A$ of (3.4).
    pub b_a: Matrix3<f64>,
    /// Unit normal N at A, from the support into the body.
    pub normal: Vector3<f64>,
    /// Friction coefficient $\mu^*$ at A (> 0).
    pub mu: f64,
    /// Velocity of A before the impact (m/s; its tangential part is the slip at A).
    pub v_a: Vector3<f64>,
}

fn out_of_range(field: &str, value: String, allowed: &str) -> ImpactError {
    ImpactError::OutOfRange {
        field: field.into(),
        value,
        allowed: allowed.into(),
    }
}

/// The conditions of an impact at the contact point C: what every solver takes besides the
/// bodies (or their matrix B) and the tolerance.
#[derive(Clone, Copy, Debug)]
pub struct Contact {
    /// The contact normal, into the first body.
    pub normal: Vector3<f64>,
    /// The relative velocity at C before the impact (m/s), approaching: (V-, n) < 0.
    pub v_minus: Vector3<f64>,
    /// Coulomb's friction coefficient at C.
    pub mu: f64,
    /// The restitution law.
    pub law: Law,
    /// The restitution coefficient, 0 <= e <= 1.
    pub e: f64,
}

impl Contact {
    /// The conditions `normal`, `v_minus`, `mu`, `law`, `e`.
    pub fn new(normal: Vector3<f64>, v_minus: Vector3<f64>, mu: f64, law: Law, e: f64) -> Self {
        Contact {
            normal,
            v_minus,
            mu,
            law,
            e,
        }
    }
}

/// Solves one impact. `v_minus` is the relative velocity at C before impact (m/s), with
/// $(\mathbf V^-, \mathbf n) < 0$ (approaching).
pub fn impact(
    b1: &Body,
    b2: &Body,
    contact: Contact,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let Contact {
        normal,
        v_minus,
        mu,
        law,
        e,
    } = contact;
    let bad = out_of_range;
    let b = b_matrix(b1, b2).ok_or_else(|| {
        bad(
            "body.inertia",
            "singular".into(),
            "symmetric positive-definite",
        )
    })?;
    let mut r = impact_with_matrix(&b, Contact::new(normal, v_minus, mu, law, e), rtol)?;
    r.energy_change = kinetic_change(b1, b2, &v_minus, &Vector3::from(r.impulse));
    Ok(r)
}

/// Solves one impact for a given matrix $\mathbf B$ (or $\mathbf B^*$ of (2.1), possibly
/// singular); `energy_change` is then Kelvin's (1.11) from B. A cut-off impact (the relative
/// velocity vanishes while sticking is possible and $\mathbf B(\mathbf n + \boldsymbol\tau) = 0$:
/// the bodies wedge) is reported with `cut_off = true`.
pub fn impact_with_matrix(
    b: &Matrix3<f64>,
    contact: Contact,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let Contact {
        normal,
        v_minus,
        mu,
        law,
        e,
    } = contact;
    impact_general(b, None, Contact::new(normal, v_minus, mu, law, e), rtol)
}

/// As [`impact_with_matrix`], with an optional smooth support under the second body (section
/// 3): the support reacts only while $\alpha < 0$, so $\mathbf B$ switches to $\mathbf B^*$ (3.8).
pub fn impact_general(
    b: &Matrix3<f64>,
    support: Option<SmoothSupport>,
    contact: Contact,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let Contact {
        normal,
        v_minus,
        mu,
        law,
        e,
    } = contact;
    let at_a = support.map(|s| {
        (
            AtA {
                b_tilde: s.b_tilde,
                b_a: Matrix3::zeros(),
                b_a_inv: Matrix3::zeros(),
                normal: s.normal.normalize(),
                beta_n: s.beta,
                mu: 0.0,
                mode: SupportMode::Slide,
                hint: Vector3::zeros(),
                held: false,
                regular: 0.0,
                floor: 0.0,
            },
            Vector3::zeros(),
            false,
        )
    });
    impact_core(b, at_a, Contact::new(normal, v_minus, mu, law, e), rtol)
}

/// As [`impact_general`], with Coulomb friction $\mu^*$ at the support (002 section 4): the
/// support rolls (4.2), slides (4.3)-(4.4) or lets go, switching as its slip stops, its reaction
/// leaves the friction cone or would have to pull; the slide direction at a start from rest
/// solves (4.5). `start` forces the support's mode at the start (the branches of a Painleve
/// case with two solutions); `None` takes the one (3.6) admits.
pub fn impact_rough(
    b: &Matrix3<f64>,
    rough: RoughSupport,
    start: Option<SupportMode>,
    contact: Contact,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let Contact {
        normal,
        v_minus,
        mu,
        law,
        e,
    } = contact;
    if !(rough.mu > 0.0 && rough.mu.is_finite()) {
        return Err(out_of_range(
            "support.mu",
            rough.mu.to_string(),
            "mu* > 0 (0 is the smooth support)",
        ));
    }
    let b_a_inv = rough.b_a.try_inverse().ok_or_else(|| {
        out_of_range(
            "support",
            "singular B_A".into(),
            "a second body with mass and an invertible inertia",
        )
    })?;
    let nn = rough.normal.normalize();
    let a = AtA {
        b_tilde: rough.b_tilde,
        b_a: rough.b_a,
        b_a_inv,
        normal: nn,
        beta_n: (rough.b_a * nn).dot(&nn),
        mu: rough.mu,
        mode: start.unwrap_or(SupportMode::Roll),
        hint: Vector3::zeros(),
        held: false,
        regular: 0.0,
        floor: 0.0,
    };
    impact_core(
        b,
        Some((a, rough.v_a, start.is_some())),
        Contact::new(normal, v_minus, mu, law, e),
        rtol,
    )
}

/// Kinetic energy change of the bodies computed from their velocities (1.2)-(1.3): body 1
/// translating with the relative velocity, body 2 at rest (any split gives the same change).
pub fn kinetic_change(b1: &Body, b2: &Body, v_minus: &Vector3<f64>, imp: &Vector3<f64>) -> f64 {
    kinetic_change_supported(b1, b2, v_minus, imp, None)
}

/// As [`kinetic_change`], with the support impulse `(G2->A, I*)` on the second body (3.1).
pub fn kinetic_change_supported(
    b1: &Body,
    b2: &Body,
    v_minus: &Vector3<f64>,
    imp: &Vector3<f64>,
    support: Option<(Vector3<f64>, Vector3<f64>)>,
) -> f64 {
    kinetic_change_moving(b1, b2, v_minus, &Vector3::zeros(), imp, support)
}

/// As [`kinetic_change_supported`], with the second body translating at `v2` before the impact
/// (a support point that slides at `v2`) and the first at `v2 + v_minus`.
pub fn kinetic_change_moving(
    b1: &Body,
    b2: &Body,
    v_minus: &Vector3<f64>,
    v2: &Vector3<f64>,
    imp: &Vector3<f64>,
    support: Option<(Vector3<f64>, Vector3<f64>)>,
) -> f64 {
    let ke = |body: &Body, v: &Vector3<f64>, w: &Vector3<f64>| -> f64 {
        body.mass.map_or(0.0, |m| {
            0.5 * m * v.norm_squared() + 0.5 * w.dot(&(body.inertia * w))
        })
    };
    let mut before = 0.0;
    let mut after = 0.0;
    for (k, body) in [b1, b2].into_iter().enumerate() {
        let Some(m) = body.mass else { continue };
        let sign = if k == 0 { 1.0 } else { -1.0 };
        // the relative velocity is carried by body 1, or by body 2 when body 1 is fixed
        let v0 = match (k, b1.mass) {
            (0, _) => *v_minus + v2,
            (_, None) => -v_minus,
            _ => *v2,
        };
        let w0 = Vector3::zeros();
        let (extra_f, extra_m) = match (k, support) {
            (1, Some((g2a, istar))) => (istar, g2a.cross(&istar)),
            _ => (Vector3::zeros(), Vector3::zeros()),
        };
        let dv = (imp * sign + extra_f) / m;
        let dw = body.inertia.try_inverse().unwrap_or_else(Matrix3::zeros)
            * (body.offset.cross(&(imp * sign)) + extra_m);
        before += ke(body, &v0, &w0);
        after += ke(body, &(v0 + dv), &(w0 + dw));
    }
    after - before
}
