//! A body held at a fixed point or about a fixed axis (section 2 of 002_b53e4779673eb6ed.txt):
//! the matrix $\mathbf B^*$ of (2.1), and the impact with it (exact where planar).

use super::{RigidImpactScene, planar_or_none};
use crate::models::fixed_points::{Hold, b_star};
use crate::models::rigid_impact::{Body, ImpactError, ImpactResult, impact_general};
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
pub(super) fn held_matrix(
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

/// Body `k` held at the point `go` (from its G) or about the axis through it (002 sec. 2): the
/// relative velocity at C must be one the held body can have (when the other cannot move); then
/// B* of (2.1), solved exactly where planar.
pub(super) fn held_impact(
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
