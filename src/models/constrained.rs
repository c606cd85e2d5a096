//! Constrained impact from a scene: a fixed point or axis (section 2 of 002_b53e4779673eb6ed.txt)
//! or a support under the second body (sections 3-4), on top of [`super::rigid_impact`].
//!
//! A smooth support switches between $\mathbf B$ and $\mathbf B^*$ along the impact (3.8). With a
//! rough support the problem is classified first (section 4): when the admissible motion is unique
//! and is detachment or rolling, the impact is integrated with that motion held for the whole
//! impact ($\mathbf B$, or $\mathbf B - \tilde{\mathbf B}'\mathbf B_A^{-1}\tilde{\mathbf B}$ while
//! rolling; the tool says so in a warning); sliding supports and the Painleve-type cases are
//! classified but not integrated (no solution, or two, in classical impact theory).

use super::fixed_points::{Hold, b_star};
use super::rigid_impact::{
    Body, ImpactError, ImpactResult, SmoothSupport, b_matrix, impact, impact_general,
};
use super::support::{Classification, classify_at_rest, classify_sliding, matrices};
use crate::scene::RigidImpactScene;
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

/// `(result, support classification, warnings)`; no result when the case is only classified.
pub type SceneOutcome = (Option<ImpactResult>, Option<Classification>, Vec<String>);

/// Solves the scene.
pub fn solve_scene(s: &RigidImpactScene) -> Result<SceneOutcome, ImpactError> {
    let mut warnings = Vec::new();
    // the two bodies as if no support or fixed point held them
    let free_impact = || {
        impact(
            &s.bodies[0],
            &s.bodies[1],
            s.normal,
            s.v_rel,
            s.mu,
            s.law,
            s.e,
            s.rtol,
        )
    };
    let bad = |m: String| ImpactError::OutOfRange {
        field: "body".into(),
        value: m,
        allowed: "symmetric positive-definite inertia".into(),
    };
    if let Some((k, go, axis)) = &s.fixed {
        // the relative velocity at C must be one the constrained body can have
        let oc = s.bodies[*k].offset - go;
        let sign = if *k == 0 { 1.0 } else { -1.0 };
        let v_body = s.v_rel * sign;
        let off = match axis {
            Some(e) => {
                let es = e.cross(&oc);
                (v_body - es * (v_body.dot(&es) / es.norm_squared().max(f64::MIN_POSITIVE))).norm()
            }
            None => v_body.dot(&oc).abs() / oc.norm().max(f64::MIN_POSITIVE),
        };
        let other_free = s.bodies[1 - *k].mass.is_some();
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
        let h = [
            if *k == 0 {
                hold(&s.bodies[0], go, *axis)
            } else {
                free(&s.bodies[0])
            },
            if *k == 1 {
                hold(&s.bodies[1], go, *axis)
            } else {
                free(&s.bodies[1])
            },
        ];
        let b = b_star(&h[0], &h[1]);
        let r = impact_general(&b, None, s.normal, s.v_rel, s.mu, s.law, s.e, s.rtol)?;
        if r.cut_off {
            warnings.push("cut-off impact: the relative velocity vanished while the contact stresses persist (the bodies are wedged)".into());
        }
        return Ok((Some(r), None, warnings));
    }
    let Some(sup) = &s.support else {
        return Ok((Some(free_impact()?), None, warnings));
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
            s.normal,
            s.v_rel,
            s.mu,
            s.law,
            s.e,
            s.rtol,
        )?;
        // the kinetic energy change from the bodies' velocities, support impulse included
        r.energy_change = super::rigid_impact::kinetic_change_supported(
            &s.bodies[0],
            &s.bodies[1],
            &s.v_rel,
            &Vector3::from(r.impulse),
            Some((sup.offset, Vector3::from(r.support_impulse))),
        );
        let gap = r.energy_change - r.kelvin_energy_change;
        if gap.abs() > 1e-9 * r.energy_change.abs().max(1e-300) {
            warnings.push(format!(
                "with the support, Kelvin's (1.10) over the contact at C misses the support's term (V_A- + V_A+, I*)/2 = {gap:.6e} J (the second body leaves the table with a normal velocity at A)"
            ));
        }
        return Ok((Some(r), Some(cl), warnings));
    }
    if cl.kind != "unique" {
        warnings.push(format!(
            "Painleve-type case at the support: (3.6) with (3.2)/(3.3) has {} solution(s) (admissible: {:?}); classical impact theory cannot resolve it, deformations at A and C must be modelled",
            if cl.kind == "none" { "no" } else { "two or more" },
            cl.admissible
        ));
        return Ok((None, Some(cl), warnings));
    }
    match cl.admissible[0].as_str() {
        "detach" => {
            warnings.push("the second body detaches from the support at the start; integrated as free for the whole impact".into());
            Ok((Some(free_impact()?), Some(cl), warnings))
        }
        "roll" => {
            let inv = sm
                .b_a
                .try_inverse()
                .ok_or_else(|| bad("singular B_A".into()))?;
            let b_roll = b - sm.b_tilde.transpose() * inv * sm.b_tilde;
            warnings.push("the support point rolls at the start; integrated with rolling held for the whole impact".into());
            Ok((
                Some(impact_general(
                    &b_roll, None, s.normal, s.v_rel, s.mu, s.law, s.e, s.rtol,
                )?),
                Some(cl),
                warnings,
            ))
        }
        _ => {
            warnings.push("the support point slides: classified, not integrated (rough sliding support not implemented in the impulse integration)".into());
            Ok((None, Some(cl), warnings))
        }
    }
}
