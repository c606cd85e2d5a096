//! The rolling ball of 002_b53e4779673eb6ed.txt section 4: (4.6) and its special case (4.7).

use super::*;

/// Rates of the rolling-ball problem of section 4 from the general matrices (m = R = 1,
/// rho^2 = 0.4): the second ball slides on the rough table in direction xi, the balls slide at
/// C in direction phi. Returns (m r', m r phi', m r*', m r* xi').
pub(super) fn rolling_rates(phi: f64, xi: f64, mu: f64, mu_star: f64) -> [f64; 4] {
    let (_, _, bt, _, _) = billiard();
    let (b, _, _, _, _) = billiard();
    let ba = {
        use crate::models::support::{Support, matrices};
        let ball = Body {
            mass: Some(1.0),
            inertia: Matrix3::identity() * 0.4,
            offset: Vector3::new(-1.0, 0.0, 0.0),
        };
        matrices(
            &ball,
            &Support {
                offset: Vector3::new(0.0, 0.0, -1.0),
                normal: Vector3::z(),
                mu: mu_star,
            },
        )
        .map(|m| m.b_a)
        .unwrap_or_else(Matrix3::zeros)
    };
    let f = Vector3::new(1.0, -mu * phi.sin(), -mu * phi.cos());
    let n = Vector3::z();
    let e_t = Vector3::new(xi.cos(), xi.sin(), 0.0);
    let i_dir = n - e_t * mu_star;
    let beta = (ba * i_dir).dot(&n);
    let fn_star = (bt * f).dot(&n) / beta;
    let fs = i_dir * fn_star;
    let vc = b * f - bt.transpose() * fs;
    let va = ba * fs - bt * f;
    let (sp, cp, sx, cx) = (phi.sin(), phi.cos(), xi.sin(), xi.cos());
    [
        sp * vc.y + cp * vc.z,
        cp * vc.y - sp * vc.z,
        cx * va.x + sx * va.y,
        cx * va.y - sx * va.x,
    ]
}

/// The angle phi of (4.7)'s conserved direction for `mu`: the claim's `printed` is cos phi as
/// printed, a formula of mu; a value outside [-1, 1] is an error naming it.
fn special_angle(c: &NamedCheck, mu: f64) -> Result<f64, VerifyError> {
    let cos = c.printed_value("cos phi of (4.7), a formula of mu", &|s| {
        (s == "mu").then_some(mu)
    })?;
    if !(-1.0..=1.0).contains(&cos) {
        return Err(VerifyError::BadClaim {
            id: c.id.clone(),
            message: format!("printed: cos phi = {cos} at mu = {mu}, outside [-1, 1]"),
        });
    }
    Ok(cos.acos())
}

/// The claim's `printed_equations`: the right-hand sides of (4.6), in m = 1 units, parsed once.
pub(super) fn rolling_equations(
    c: &NamedCheck,
) -> Result<Vec<crate::algebra::expr::Expr>, VerifyError> {
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    if c.printed_equations.len() != 4 {
        return Err(bad(
            "printed_equations must give the four right-hand sides of (4.6)".into(),
        ));
    }
    c.printed_equations
        .iter()
        .enumerate()
        .map(|(k, t)| {
            crate::algebra::expr::parse(t).map_err(|e| bad(format!("printed_equations[{k}]: {e}")))
        })
        .collect()
}

/// Four right-hand sides of the (4.6) kind at a state (phi, xi, mu, mu*).
pub(super) fn rolling_eval(
    eqs: &[crate::algebra::expr::Expr],
    phi: f64,
    xi: f64,
    mu: f64,
    mu_star: f64,
) -> Result<[f64; 4], String> {
    let values = |s: &str| match s {
        "phi" => Some(phi),
        "xi" => Some(xi),
        "mu" => Some(mu),
        "mu_star" => Some(mu_star),
        _ => None,
    };
    let mut out = [0.0; 4];
    for (o, e) in out.iter_mut().zip(eqs) {
        *o = e.eval(&values)?;
    }
    Ok(out)
}

/// (4.6) integrated as printed (and with `corrected` for its third equation) in the normal
/// impulse, against the general impact model with the rough table ([`impact_rough`]: B of
/// (1.7), B~ and B_A of (3.4), F* = F_N* (N - mu* e_T)) from the same start: both balls slide at
/// C in direction phi, the second slides on the table in direction xi. Compared: r and phi of
/// V_C at the model's accepted steps while both slips exceed 5 % of their start; and, at the
/// special case (4.7) (mu = mu*, xi = phi, cos phi as the claim's `printed`), phi along the model's path.
pub(super) fn rolling_integrated(
    paper: &PaperClaims,
    c: &NamedCheck,
) -> Result<Outcome, VerifyError> {
    use crate::models::rigid_impact::{Contact, RoughSupport, SupportMode, impact_rough};
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let printed = rolling_equations(c)?;
    // `corrected`, when given, is the third equation as derived (a correction applied to the
    // whole system gives `printed_equations` mended instead, and none)
    let corrected = match &c.corrected {
        Some(t) => {
            Some(crate::algebra::expr::parse(t).map_err(|e| bad(format!("corrected: {e}")))?)
        }
        None => None,
    };
    struct Polar {
        eqs: Vec<crate::algebra::expr::Expr>,
        mu: f64,
        mu_star: f64,
    }
    impl OdeSystem for Polar {
        fn dim(&self) -> usize {
            4
        }
        fn rhs(&self, _c: f64, y: &[f64], dy: &mut [f64]) {
            // a formula that cannot be evaluated stops the solve as a non-finite value
            let v =
                rolling_eval(&self.eqs, y[1], y[3], self.mu, self.mu_star).unwrap_or([f64::NAN; 4]);
            dy[0] = v[0];
            dy[1] = v[1] / y[0];
            dy[2] = v[2];
            dy[3] = v[3] / y[2];
        }
    }
    let (b, ba, bt, _, _) = billiard();
    let model = |phi: f64, xi: f64, mu: f64, mu_star: f64| {
        let v = Vector3::new(-1.0, phi.sin(), phi.cos());
        impact_rough(
            &b,
            RoughSupport {
                b_tilde: bt,
                b_a: ba,
                normal: Vector3::z(),
                mu: mu_star,
                v_a: Vector3::new(xi.cos(), xi.sin(), 0.0),
            },
            Some(SupportMode::Slide),
            Contact::new(Vector3::x(), v, mu, Law::Poisson, 0.5),
            1e-11,
        )
    };
    // r and phi of V_C along the model's path against a polar integration of `eqs`
    let compare = |eqs: &[crate::algebra::expr::Expr],
                   phi: f64,
                   xi: f64,
                   mu: f64,
                   mu_star: f64|
     -> Result<(f64, usize), VerifyError> {
        let r = model(phi, xi, mu, mu_star).map_err(|e| bad(format!("the model: {e}")))?;
        let sys = Polar {
            eqs: eqs.to_vec(),
            mu,
            mu_star,
        };
        let stop = |_c: f64, y: &[f64]| y[0].min(y[2]) - 0.05;
        let times: Vec<f64> = r.path.iter().map(|p| p.0).filter(|t| *t > 0.0).collect();
        let o = Options {
            rtol: 1e-12,
            atol: 1e-14,
            dense_times: times,
            events: vec![crate::integrate::Event::new(
                "a slip ends",
                &stop,
                crate::integrate::Direction::Falling,
                true,
            )],
            ..Options::default()
        };
        let sol = solve(&sys, 0.0, &[1.0, phi, 1.0, xi], 50.0, &o)
            .map_err(|e| bad(format!("(4.6): {e}")))?;
        let mut worst: f64 = 0.0;
        let mut n = 0;
        // the dense samples are the path's times in order, up to where a slip ends
        let steps = r.path.iter().filter(|p| p.0 > 0.0);
        for ((_, y), p) in sol.dense.iter().zip(steps) {
            let (rm, pm) = (p.1[1].hypot(p.1[2]), p.1[1].atan2(p.1[2]));
            let dphi = (pm - y[1] + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
            worst = worst.max((rm - y[0]).abs()).max(dphi.abs());
            n += 1;
        }
        Ok((worst, n))
    };
    let mut corrected_eqs = printed.clone();
    if let Some(k) = corrected.clone() {
        corrected_eqs[2] = k;
    }
    let mut rng = Rng(0x5EED_0047);
    let (mut worst_p, mut worst_c, mut points) = (0.0f64, 0.0f64, 0usize);
    let mut example = String::new();
    for _ in 0..12 {
        let (phi, xi) = (rng.range(1.8, 3.0), rng.range(-3.0, 3.0));
        let (mu, ms) = (rng.range(0.05, 0.6), rng.range(0.05, 0.6));
        let (wp, n) = compare(&printed, phi, xi, mu, ms)?;
        let wc = match corrected {
            Some(_) => compare(&corrected_eqs, phi, xi, mu, ms)?.0,
            None => wp,
        };
        if wp > worst_p {
            worst_p = wp;
            example =
                format!(" (largest at phi = {phi:.3}, xi = {xi:.3}, mu = {mu:.3}, mu* = {ms:.3})");
        }
        worst_c = worst_c.max(wc);
        points += n;
    }
    // the special case of (4.7) in the model: phi stays put
    let mut special: f64 = 0.0;
    for mu in [0.3f64, 0.5, 1.0] {
        let phi = special_angle(c, mu)?;
        let r = model(phi, phi, mu, mu).map_err(|e| bad(format!("the model: {e}")))?;
        for p in r.path.iter().filter(|p| p.1[1].hypot(p.1[2]) > 1e-3) {
            special = special.max((p.1[1].atan2(p.1[2]) - phi).abs());
        }
    }
    let tol = 1e-7;
    let verdict = if worst_p <= tol && special <= tol {
        Verdict::Holds
    } else if worst_c <= tol && special <= tol {
        Verdict::HoldsWithCorrection
    } else {
        Verdict::Fails
    };
    Ok(outcome(
        paper,
        c,
        verdict,
        format!(
            "the general impact model with the rough table (B of (1.7), B~ and B_A of (3.4), F* = F_N* (N - mu* e_T) with (4.4); Poisson's law, rtol 1e-11) from 12 seeded starts (phi, xi, mu, mu*), both balls sliding: r and phi of V_C at {points} of its steps against (4.6) integrated in the normal impulse while both slips exceed 5 %: as printed, max difference {worst_p:.2e}{example}{}; the special case (4.7) (mu = mu* = 0.3, 0.5, 1, xi = phi, cos phi = {}) keeps phi within {special:.2e} along the model's path (tolerance {tol:.0e})",
            match corrected {
                Some(_) =>
                    format!("; with the third equation as derived (corrected), {worst_c:.2e}"),
                None => String::new(),
            },
            c.printed.as_deref().unwrap_or_default()
        ),
    ))
}

pub(super) fn rolling_ball(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let part = c.part.clone().unwrap_or_default();
    let mut rng = Rng(0x5EED_0046);
    Ok(match part.as_str() {
        "equations" => {
            let printed = rolling_equations(c)?;
            let mut worst = [0.0f64; 4];
            let mut example = String::new();
            for _ in 0..200 {
                let (phi, xi) = (rng.range(1.7, 3.1), rng.range(-3.1, 3.1));
                let (mu, ms) = (rng.range(0.01, 1.0), rng.range(0.01, 1.0));
                let d = rolling_rates(phi, xi, mu, ms);
                let p =
                    rolling_eval(&printed, phi, xi, mu, ms).map_err(|m| VerifyError::BadClaim {
                        id: c.id.clone(),
                        message: m,
                    })?;
                for k in 0..4 {
                    let e = (d[k] - p[k]).abs() / d[k].abs().max(1e-3);
                    if e > worst[k] {
                        worst[k] = e;
                        if k == 2 && example.is_empty() && e > 1e-9 {
                            example = format!(
                                "; e.g. phi = {phi:.3}, xi = {xi:.3}, mu = {mu:.3}, mu* = {ms:.3}: derived m r*' = {:.6}, printed {:.6}; the derived third equation is m r*' = (7/2) mu* mu cos phi - cos xi - mu (5/2 cos xi cos phi - sin xi sin phi)",
                                d[2], p[2]
                            );
                        }
                    }
                }
            }
            let ok: Vec<bool> = worst.iter().map(|w| *w <= 1e-9).collect();
            outcome(
                paper,
                c,
                holds(ok.iter().all(|x| *x)),
                format!(
                    "rates of two balls (m = R = 1, rho^2 = 0.4 R^2), the second sliding on a rough table, from the matrices of (1.7), (3.4) with F* = F_N* (N - mu* e_T), F_N* from (4.4), at 200 seeded states: max relative difference from the printed (4.6), equation by equation: {:.2e}, {:.2e}, {:.2e}, {:.2e}{example}",
                    worst[0], worst[1], worst[2], worst[3]
                ),
            )
        }
        "special-case" => {
            // mu = mu*, xi = phi, cos phi as printed: phi' and xi' vanish (derived rates)
            let mut worst: f64 = 0.0;
            let mut curves = Vec::new();
            for mu in [0.3f64, 0.5, 1.0, 2.0] {
                let phi = special_angle(c, mu)?;
                let d = rolling_rates(phi, phi, mu, mu);
                worst = worst.max(d[1].abs()).max(d[3].abs());
            }
            // integral curves of the derived system in (phi, xi) for mu = mu* = 0.5
            struct Rolling {
                mu: f64,
            }
            impl OdeSystem for Rolling {
                fn dim(&self) -> usize {
                    4
                }
                fn rhs(&self, _c: f64, y: &[f64], dy: &mut [f64]) {
                    let d = rolling_rates(y[1], y[3], self.mu, self.mu);
                    dy[0] = d[0];
                    dy[1] = d[1] / y[0];
                    dy[2] = d[2];
                    dy[3] = d[3] / y[2];
                }
            }
            let mu: f64 = 0.5;
            let phi_star = special_angle(c, mu)?;
            for dphi in [-0.4, -0.2, 0.0, 0.2, 0.4] {
                let y0 = [1.0, phi_star + dphi, 1.0, phi_star + dphi];
                let stop = |_c: f64, y: &[f64]| y[0].min(y[2]) - 1e-2;
                let o = Options {
                    rtol: 1e-11,
                    atol: 1e-13,
                    trajectory: true,
                    events: vec![crate::integrate::Event::new(
                        "a slip ends",
                        &stop,
                        crate::integrate::Direction::Falling,
                        true,
                    )],
                    ..Options::default()
                };
                if let Ok(sol) = solve(&Rolling { mu }, 0.0, &y0, 5.0, &o) {
                    if dphi == 0.0 {
                        for (_, y) in &sol.trajectory {
                            worst = worst.max((y[1] - phi_star).abs());
                        }
                    }
                    curves.push((
                        format!("phi0 = phi* {:+.1}", dphi),
                        sol.trajectory
                            .iter()
                            .map(|(c, y)| (*c, y[1].to_degrees()))
                            .collect::<Vec<_>>(),
                    ));
                }
            }
            let svg_name = "002_rolling_ball_curves.svg".to_string();
            let svg = crate::report::svg::plot_curves(
                "rolling ball on a rough table, mu = mu* = 0.5: slip angle phi at C against the normal impulse",
                "normal impulse I_n (kg m/s, with m = 1 kg)",
                "phi (degrees)",
                Scale::Linear,
                Scale::Linear,
                &curves,
            );
            outcome(
                paper,
                c,
                holds(worst <= 1e-9),
                format!(
                    "with mu = mu*, xi = phi and cos phi = {} as printed (mu = 0.3, 0.5, 1, 2) the derived phi' and xi' vanish (max {worst:.2e}, including phi along an integrated trajectory from phi* for mu = 0.5); this uses only the second and fourth equations of (4.6), which the derivation confirms",
                    c.printed.as_deref().unwrap_or_default()
                ),
            )
            .with_plot(
                "integral curves of (4.6)",
                svg_name,
                svg,
                crate::report::svg::csv_curves("normal impulse I_n (kg m/s, with m = 1 kg)", "phi (degrees)", &curves),
            )
        }
        "integrated" => rolling_integrated(paper, c)?,
        _ => {
            return Err(VerifyError::BadClaim {
                id: c.id.clone(),
                message: "part must be equations, special-case or integrated".into(),
            });
        }
    })
}
