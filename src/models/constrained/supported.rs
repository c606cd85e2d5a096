//! The second body on a support (sections 3-4 of 002_b53e4779673eb6ed.txt): classified at the
//! start, then smooth (B and B* switching along the impact, (3.8)) or rough (rolling (4.2),
//! sliding (4.3)-(4.4), letting go), with Painleve-type starts said so or integrated along each
//! branch.

use super::{Alternative, RigidImpactScene, SceneOutcome};
use crate::models::rigid_impact::{
    ImpactError, ImpactResult, RoughSupport, SmoothSupport, SupportMode, b_matrix, impact_general,
    impact_rough,
};
use crate::models::support::{
    Classification, Support, classify_at_rest, classify_sliding, matrices,
};
use nalgebra::Vector3;

/// The impact of scene `s` with the second body on the support `sup`; the branches of a
/// Painleve-type case with two solutions pushed to `alternatives`.
pub(super) fn impact_supported(
    s: &RigidImpactScene,
    sup: &Support,
    alternatives: &mut Vec<Alternative>,
    mut warnings: Vec<String>,
) -> Result<SceneOutcome, ImpactError> {
    let bad = |m: String| ImpactError::OutOfRange {
        field: "body".into(),
        value: m,
        allowed: "symmetric positive-definite inertia".into(),
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
        crate::models::rigid_impact::kinetic_change_moving(
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
