//! The Coriolis billiard problem of 002_b53e4779673eb6ed.txt section 3: the matrices of (3.9)-(3.11),
//! (3.12)-(3.14), the fixed angles, the general model against (3.14), and the balls against a wall.

use super::*;

/// The check `billiard-matrix`.
pub(super) fn billiard_matrix(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    Ok({
        let (b, ba, bt, bs, k) = billiard();
        let which = c.part.clone().ok_or_else(|| bad("needs `part`"))?;
        let derived = match which.as_str() {
            "B" => b,
            "BA" => ba,
            "Btilde" => bt,
            "Bstar" => bs,
            _ => return Err(bad("part must be B, BA, Btilde or Bstar")),
        };
        let printed = printed_matrix(c, &billiard_values)?;
        let agree =
            |d: &Matrix3<f64>, p: &Matrix3<f64>| (d - p).abs().max() <= 1e-12 * p.abs().max();
        let same = agree(&derived, &printed);
        let ratio = printed.abs().max() / derived.abs().max();
        // m = R = 1 cannot tell a power of m or R: the same at m = 1.7, R = 1.3
        let (m2, r2) = (1.7, 1.3);
        let (b2, ba2, bt2, bs2, _) = billiard_at(m2, r2);
        let derived2 = match which.as_str() {
            "B" => b2,
            "BA" => ba2,
            "Btilde" => bt2,
            _ => bs2,
        };
        let printed2 = printed_matrix(c, &billiard_values_at(m2, r2))?;
        let same2 = agree(&derived2, &printed2);
        outcome(
            paper,
            c,
            holds(same && same2),
            format!(
                "m = 1, R = 1, rho^2 = 0.4 R^2 (R^2/rho^2 = {k}): derived from the definitions {}; printed {}{}; at m = {m2}, R = {r2}: {}",
                fmt_m(&derived),
                fmt_m(&printed),
                if same {
                    String::new()
                } else {
                    format!("; printed/derived (largest entries) = {ratio:.4}")
                },
                if same2 {
                    "derived = printed".to_string()
                } else {
                    format!("derived {}, printed {}", fmt_m(&derived2), fmt_m(&printed2))
                }
            ),
        )
    })
}

/// The check `billiard-312`.
pub(super) fn billiard_312(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    Ok({
        // m V' = m B* F with F = (1, -mu sin phi, -mu cos phi): the coefficients of (3.12) are
        // the diagonal of m B*; the printed ones are read from the claim
        let (_, _, _, bs, _) = billiard();
        let derived = [bs[(0, 0)], bs[(1, 1)], bs[(2, 2)]];
        let pm = printed_matrix(c, &billiard_values)?;
        let printed = [pm[(0, 0)], pm[(1, 1)], pm[(2, 2)]];
        let diffs: Vec<String> = (0..3)
            .filter(|i| (derived[*i] - printed[*i]).abs() > 1e-12)
            .map(|i| {
                format!(
                    "V{}: derived {:.4}, printed {}",
                    i + 1,
                    derived[i],
                    printed[i]
                )
            })
            .collect();
        outcome(
            paper,
            c,
            holds(diffs.is_empty()),
            format!(
                "m V' = m B* F with B* from (3.8): coefficients ({:.4}, {:.4}, {:.4}) against the printed ({}, {}, {}){}; the polar form that follows (3.12) in the paper uses 6",
                derived[0],
                derived[1],
                derived[2],
                printed[0],
                printed[1],
                printed[2],
                if diffs.is_empty() {
                    String::new()
                } else {
                    format!("; differ: {}", diffs.join(", "))
                }
            ),
        )
    })
}

/// The check `billiard-313`: the claim's `printed_equations` are V1', r', r phi' of (3.13) as
/// printed (formulas of m, mu, phi).
pub(super) fn billiard_313(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    Ok({
        // r' and r phi' from V' = B* F (derived B*) against the printed (3.13), at sample angles;
        // at m = 1 (the derived B*'s) and, for the powers of m, the printed side also at m = 1.7
        // against the derived one scaled by 1/m (B* is proportional to 1/m)
        let (_, _, _, bs, _) = billiard();
        let mu = 0.3;
        let mut worst: f64 = 0.0;
        for k in 0..36 {
            let phi = -std::f64::consts::PI + (k as f64 + 0.5) * std::f64::consts::PI / 18.0;
            let f = Vector3::new(1.0, -mu * phi.sin(), -mu * phi.cos());
            let dv = bs * f;
            let r_dot = phi.sin() * dv.y + phi.cos() * dv.z;
            let r_phi_dot = phi.cos() * dv.y - phi.sin() * dv.z;
            for m in [1.0, 1.7] {
                let values = |s: &str| match s {
                    "m" => Some(m),
                    "mu" => Some(mu),
                    "phi" => Some(phi),
                    _ => None,
                };
                let p = c.printed_values(3, "V1', r', r phi' of (3.13)", &values)?;
                worst = worst
                    .max((r_dot / m - p[1]).abs())
                    .max((r_phi_dot / m - p[2]).abs())
                    .max((dv.x / m - p[0]).abs());
            }
        }
        outcome(
            paper,
            c,
            holds(worst <= 1e-12),
            format!(
                "V1', r', r phi' from V' = B* F (derived B*, m = 1 and 1.7) against (3.13) at 36 angles: max difference {worst:.2e}"
            ),
        )
    })
}

/// The check `billiard-314`: the claim's `printed` is r of (3.14) as printed (a formula of r0,
/// phi0, phi).
pub(super) fn billiard_314(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    Ok({
        // integrate (3.13) in chi and compare r(phi) with the closed form (3.14)
        let mu = 0.3;
        let mut worst: f64 = 0.0;
        let mut series = Vec::new();
        let mut monotone = true;
        for phi0_deg in [100.0f64, 120.0, 135.0, 150.0, 170.0] {
            let phi0 = phi0_deg.to_radians();
            let r0 = 1.0;
            let sys = Coriolis { mu };
            let stop = |_c: f64, y: &[f64]| y[0] - 1e-3;
            let o = Options {
                rtol: 1e-12,
                atol: 1e-14,
                method: Method::Dop853,
                trajectory: true,
                events: vec![crate::integrate::Event::new(
                    "slip ends",
                    &stop,
                    crate::integrate::Direction::Falling,
                    true,
                )],
                ..Options::default()
            };
            let sol = solve(&sys, 0.0, &[r0, phi0], 10.0, &o).map_err(|e| bad(&e.to_string()))?;
            let mut pts = Vec::new();
            let mut phis = vec![phi0];
            for (_, y) in &sol.trajectory {
                let values = |s: &str| match s {
                    "r0" => Some(r0),
                    "phi0" => Some(phi0),
                    "phi" => Some(y[1]),
                    _ => None,
                };
                let closed = c.printed_value("r of (3.14), a formula of r0, phi0, phi", &values)?;
                worst = worst.max((y[0] - closed).abs() / y[0].abs().max(1e-3));
                phis.push(y[1]);
                pts.push((y[1].to_degrees(), y[0]));
            }
            monotone &= abs_never_decreases(&phis);
            series.push((format!("phi0 = {phi0_deg} deg"), pts));
        }
        let svg_name = "002_coriolis_curves.svg".to_string();
        let svg = crate::report::svg::plot_curves(
            "Coriolis problem: integral curves of (3.13), r against phi",
            "phi (degrees)",
            "r / r0 (dimensionless)",
            Scale::Linear,
            Scale::Linear,
            &series,
        );
        outcome(
            paper,
            c,
            // the paper's statement (|phi| increases) and the closed form (3.14) both
            holds(worst <= 1e-8 && monotone),
            format!(
                "(3.13) integrated by DOP853 (rtol 1e-12) from r0 = 1, phi0 = 100..170 deg, mu = 0.3, until r = 1e-3: max relative difference from (3.14) {worst:.2e}; |phi| increases along every curve: {monotone}"
            ),
        )
        .with_plot(
            "integral curves of (3.13)",
            svg_name,
            svg,
            crate::report::svg::csv_curves("phi (degrees)", "r / r0 (dimensionless)", &series),
        )
    })
}

/// The check `billiard-fixed-angles`: the claim's `printed_equations` are the angles (radians)
/// where the paper says phi stays constant.
pub(super) fn billiard_fixed_angles(
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    Ok({
        // zeros of sin(2 phi) on (-pi, pi]: where (3.13) keeps phi constant
        let mut zeros = Vec::new();
        let n = 3600;
        let h = 2.0 * std::f64::consts::PI / n as f64;
        for k in 0..n {
            // intervals cover (-pi + h/2, pi + h/2]: every zero lies inside one
            let a = -std::f64::consts::PI + (k as f64 + 0.5) * h;
            let b = a + h;
            let (fa, fb) = ((2.0 * a).sin(), (2.0 * b).sin());
            if fa == 0.0 || fa.signum() != fb.signum() {
                let z = if fa == 0.0 {
                    a
                } else {
                    a - fa * (b - a) / (fb - fa)
                };
                let deg = (z.to_degrees() * 1e6).round() / 1e6;
                zeros.push(if deg > 180.0 { deg - 360.0 } else { deg });
            }
        }
        zeros.sort_by(f64::total_cmp);
        zeros.dedup();
        let printed: Vec<f64> = c
            .printed_values(c.printed_equations.len(), "the printed angles", &|_| None)?
            .into_iter()
            .map(f64::to_degrees)
            .collect();
        let extra: Vec<f64> = zeros
            .iter()
            .copied()
            .filter(|z| {
                !printed
                    .iter()
                    .any(|p| (p - z).abs() < 1e-3 || (p - z).abs() > 359.999)
            })
            .collect();
        outcome(
            paper,
            c,
            holds(extra.is_empty()),
            format!(
                "phi' = 0 in (3.13) where sin 2 phi = 0: at {:?} degrees; the printed list {:?} misses {:?} (V_t pointing along N; excluded only by the paper's assumption (V-, N) < 0)",
                zeros, printed, extra
            ),
        )
    })
}

/// The check `balls-wall`.
pub(super) fn balls_wall(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    Ok({
        use crate::models::balls_wall::rebound;
        // the setup is fixed before anything is compared: identical elastic balls, Hertz
        // contacts, the wall rigid ("substantially more rigid"). Hertz's contact stiffness
        // k = (4/3) E* sqrt(R*): ball-ball E* = E/(2(1 - nu^2)), R* = R/2; ball-rigid wall
        // E* = E/(1 - nu^2), R* = R; the ratio does not depend on E, nu, R
        let (e, nu, r) = (1.0, 0.3, 1.0);
        let k_bb = 4.0 / 3.0 * e / (2.0 * (1.0 - nu * nu)) * (r / 2.0f64).sqrt();
        let k_bw = 4.0 / 3.0 * e / (1.0 - nu * nu) * r.sqrt();
        let kappa = k_bw / k_bb;
        let (v1, v2) = rebound(kappa, 1.5, 1e-10).map_err(|e| bad(&e.to_string()))?;
        let (striker, recoil) = (-v1, -v2);
        // the printed speeds (0.96 V, 0.28 V) from the claims file, read as rounded: within
        // half a unit of their last digit
        let printed: Vec<(f64, f64)> = c
            .printed_equations
            .iter()
            .map(|t| {
                let v: f64 = t.trim().parse().ok()?;
                let digits = t.trim().split('.').nth(1).map_or(0, str::len) as i32;
                Some((v, 0.5 * 10f64.powi(-digits)))
            })
            .collect::<Option<Vec<_>>>()
            .filter(|v| v.len() == 2)
            .ok_or_else(|| {
                bad("printed_equations must give the two printed speeds, e.g. [\"0.96\", \"0.28\"]")
            })?;
        let [(p1, tol1), (p2, tol2)] = [printed[0], printed[1]];
        let ok = (striker - p1).abs() <= tol1 && (recoil - p2).abs() <= tol2;
        // context, not the verdict: other stiffness ratios and linear elements
        let kappas = [1.0, kappa, 10.0, 100.0, 1e3, 1e4, 1e6];
        let mut table: Vec<Vec<String>> = kappas.iter().map(|k| vec![format!("{k:.4e}")]).collect();
        for p in [1.5, 1.0] {
            for (i, &k) in kappas.iter().enumerate() {
                let (a, b) = rebound(k, p, 1e-10).map_err(|e| bad(&e.to_string()))?;
                table[i].push(format!("{:.4}", -a));
                table[i].push(format!("{:.4}", -b));
            }
        }
        let mut o = outcome(
            paper,
            c,
            holds(ok),
            format!(
                "Hertz elements, the wall rigid: the wall contact is {kappa:.4} times stiffer than the ball-ball contact (Hertz's k = (4/3) E* sqrt(R*): 2 sqrt(2)); integrated (rtol 1e-10): the striking ball rebounds at {striker:.4} V (printed {p1} V: {}), the ball at the wall at {recoil:.4} V (printed {p2} V: {}), each against half a unit of the printed last digit",
                if (striker - p1).abs() <= tol1 {
                    "agrees"
                } else {
                    "differs"
                },
                if (recoil - p2).abs() <= tol2 {
                    "agrees"
                } else {
                    "differs"
                },
            ),
        );
        o.extra_md = Some(format!(
            "Rebound speeds away from the wall in units of V (the paper: 0.96 V and 0.28 V) for other stiffness ratios and linear elements, for comparison only: the verdict uses the Hertz rigid-wall ratio alone.\n\n| wall / ball-ball stiffness | Hertz: striker | Hertz: wall ball | linear: striker | linear: wall ball |\n|---|---|---|---|---|\n{}",
            table
                .iter()
                .map(|r| format!("| {} |", r.join(" | ")))
                .collect::<Vec<_>>()
                .join("\n")
        ));
        o
    })
}

/// The check `billiard-general`.
pub(super) fn billiard_general(
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    Ok({
        // the two balls with the second on a smooth table, integrated by the general model
        use crate::models::rigid_impact::{Contact, SmoothSupport, impact_general};
        use crate::models::support::{Support, matrices};
        let (m, r) = (1.0, 1.0);
        let rho2 = 0.4 * r * r;
        let ball = |off: Vector3<f64>| Body {
            mass: Some(m),
            inertia: Matrix3::identity() * (m * rho2),
            offset: off,
        };
        let (b1, b2) = (
            ball(Vector3::new(r, 0.0, 0.0)),
            ball(Vector3::new(-r, 0.0, 0.0)),
        );
        let b = b_matrix(&b1, &b2).ok_or_else(|| bad("singular"))?;
        let sup = Support {
            offset: Vector3::new(0.0, 0.0, -r),
            normal: Vector3::z(),
            mu: 0.0,
        };
        let sm = matrices(&b2, &sup).ok_or_else(|| bad("singular"))?;
        let beta = (sm.b_a * Vector3::z()).dot(&Vector3::z());
        let mut worst: f64 = 0.0;
        let mut worst_v1: f64 = 0.0;
        let mut points = 0;
        for (phi0_deg, mu) in [(100.0f64, 0.3), (120.0, 0.1), (150.0, 0.03), (170.0, 0.2)] {
            let phi0 = phi0_deg.to_radians();
            let (r0, v1) = (0.5, -1.0);
            let v = Vector3::new(v1, r0 * phi0.sin(), r0 * phi0.cos());
            let support = SmoothSupport {
                b_tilde: sm.b_tilde,
                normal: Vector3::z(),
                beta,
            };
            let res = impact_general(
                &b,
                Some(support),
                Contact::new(Vector3::x(), v, mu, Law::Poisson, 0.8),
                1e-12,
            )
            .map_err(|e| bad(&e.to_string()))?;
            for (chi, vv) in &res.path {
                let rr = (vv[1] * vv[1] + vv[2] * vv[2]).sqrt();
                if rr < 1e-3 * r0 {
                    continue;
                }
                let phi = vv[1].atan2(vv[2]);
                let values = |name: &str| match name {
                    "r0" => Some(r0),
                    "phi" => Some(phi),
                    "phi0" => Some(phi0),
                    "m" => Some(m),
                    _ => None,
                };
                let closed = c.printed_value("r of (3.14) in r0, phi, phi0", &values)?;
                let dv1 = c.printed_values(1, "V1' of (3.13), in m", &values)?[0];
                worst = worst.max((rr - closed).abs() / rr);
                worst_v1 = worst_v1.max((vv[0] - (v1 + dv1 * chi)).abs());
                points += 1;
            }
        }
        outcome(
            paper,
            c,
            holds(worst <= 1e-7 && worst_v1 <= 1e-9),
            format!(
                "two homogeneous balls (m = R = 1), the second on a smooth table, integrated by the general model (B of (1.7), the support reaction (3.7) switched on while alpha < 0) in the normal impulse, 4 impacts, {points} steps: max relative difference of r(phi) from (3.14) as printed {worst:.2e}; V1 against V1- + V1' I_n with V1' of (3.13) as printed: {worst_v1:.2e}"
            ),
        )
    })
}

/// Whether |x| never decreases along `xs` (by more than rounding, 1e-12).
fn abs_never_decreases(xs: &[f64]) -> bool {
    xs.windows(2).all(|w| w[1].abs() >= w[0].abs() - 1e-12)
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_decrease_of_the_angle_is_seen() {
        assert!(super::abs_never_decreases(&[1.7, -1.8, 1.9, 1.9]));
        assert!(!super::abs_never_decreases(&[1.7, 1.9, -1.8]));
        assert!(super::abs_never_decreases(&[]));
    }
}
