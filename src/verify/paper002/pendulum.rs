//! The pendulum of 002_b53e4779673eb6ed.txt section 2: B* of (2.5), its cut-off condition, and
//! Fig. 2 with deformable elements at the contact and at the suspension ((2.6)-(2.15)).

use super::*;

/// The check `pendulum-bstar`: the claim's `printed_matrix` is B* of (2.5) as printed, a matrix
/// of m, rho and the coordinates alpha1..3 of e* = e x OC.
pub(super) fn pendulum_bstar(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    Ok({
        // (2.4): dV_C = (e*, I) e* /(m rho^2), e* = e x OC; compare with (2.5)
        let (m, rho) = (2.0, 0.3);
        let e_axis = Vector3::new(0.2, 1.0, -0.1).normalize();
        let oc = Vector3::new(0.4, -0.1, -0.5);
        let es = e_axis.cross(&oc);
        let derived = Matrix3::from_columns(&[Vector3::x(), Vector3::y(), Vector3::z()].map(|i| {
            let dw = e_axis * (oc.cross(&i).dot(&e_axis) / (m * rho * rho));
            dw.cross(&oc)
        }));
        let values = |s: &str| match s {
            "m" => Some(m),
            "rho" => Some(rho),
            "alpha1" => Some(es.x),
            "alpha2" => Some(es.y),
            "alpha3" => Some(es.z),
            _ => None,
        };
        let printed = printed_matrix(c, &values)?;
        let eig = SymmetricEigen::new(derived).eigenvalues;
        let mut ev: Vec<f64> = eig.iter().copied().collect();
        ev.sort_by(f64::total_cmp);
        let zeros = ev.iter().filter(|x| x.abs() <= 1e-12 * ev[2]).count();
        let same = (derived - printed).abs().max() <= 1e-12 * printed.abs().max();
        outcome(
            paper,
            c,
            holds(same && zeros == 2),
            format!(
                "B* from (2.3)-(2.4) for axis {:?}, OC {:?}: {}; printed (2.5): {}; equal: {same}; eigenvalues {:.4e}, {:.4e}, {:.4e} (two zero: {})",
                e_axis
                    .as_slice()
                    .iter()
                    .map(|x: &f64| (x * 1e4).round() / 1e4)
                    .collect::<Vec<_>>(),
                oc.as_slice(),
                fmt_m(&derived),
                fmt_m(&printed),
                ev[0],
                ev[1],
                ev[2],
                zeros == 2
            ),
        )
    })
}

/// The check `pendulum-cutoff`.
pub(super) fn pendulum_cutoff(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    Ok({
        // the printed condition from the claims file: `printed` >= 0 means cut-off
        let cond = c
            .printed
            .as_deref()
            .map(crate::algebra::expr::parse)
            .transpose()
            .map_err(|e| bad(&format!("printed: {e}")))?
            .ok_or_else(|| bad("needs `printed`, the cut-off condition as `lhs - rhs`"))?;
        // integrate the pendulum impact in the normal impulse over a grid of (angle, mu)
        let mut agree_printed = 0;
        let mut agree_derived = 0;
        let mut total = 0;
        let mut counter = String::new();
        for k in 1..=17 {
            let th = (5.0 * k as f64).to_radians();
            let es = Vector3::new(th.cos(), 0.0, th.sin());
            let b = es * es.transpose();
            for mu in [
                0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 5.0, 8.0,
            ] {
                let Ok(r) = impact_with_matrix(
                    &b,
                    crate::models::rigid_impact::Contact::new(
                        Vector3::z(),
                        -es,
                        mu,
                        Law::Poisson,
                        0.5,
                    ),
                    1e-10,
                ) else {
                    continue;
                };
                total += 1;
                let (a3, at) = (th.sin(), th.cos());
                let value = |n: &str| match n {
                    "mu" => Some(mu),
                    "alpha1" => Some(at),
                    "alpha2" => Some(0.0),
                    "alpha3" => Some(a3),
                    _ => None,
                };
                let printed = cond.eval(&value).map_err(|e| bad(&e))? >= 0.0;
                // independent of the model's stick rule: a cut-off needs an impulse that does
                // not move the body (the kernel of B*, from an SVD) inside the friction cone
                // at C (normal z: I_z > 0, |I_t| <= mu I_z), searched on 3600 directions of
                // the kernel plane
                let derived = kernel_meets_cone(&b, &Vector3::z(), mu);
                agree_printed += usize::from(printed == r.cut_off);
                agree_derived += usize::from(derived == r.cut_off);
                if printed != r.cut_off && counter.is_empty() {
                    counter = format!(
                        "; e.g. alpha = ({:.4}, 0, {:.4}), mu = {mu}: the integration {} a cut-off, the printed condition says {}",
                        at,
                        a3,
                        if r.cut_off { "ends in" } else { "has no" },
                        if printed { "cut-off" } else { "no cut-off" }
                    );
                }
            }
        }
        outcome(
            paper,
            c,
            holds(agree_printed == total),
            format!(
                "pendulum impacts integrated in the normal impulse (B* of (2.5), Poisson's law, e = 0.5) over {total} (angle, mu) pairs: the printed condition mu alpha3 >= (alpha1^2 + alpha2^2)^(1/2) predicts the cut-off in {agree_printed}; an impulse in the kernel of B* (found by SVD) inside the friction cone, which is mu (alpha1^2 + alpha2^2)^(1/2) >= |alpha3| here, predicts it in {agree_derived}{counter}"
            ),
        )
    })
}

pub(super) fn pendulum_wall(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    match c.part.as_deref().unwrap_or_default() {
        "condition" => pendulum_wall_condition(paper, c),
        "derivation" => pendulum_wall_derivation(paper, c),
        "figure" => pendulum_wall_figure(paper, c),
        "fifteen" => pendulum_wall_fifteen(paper, c),
        _ => Err(VerifyError::BadClaim {
            id: c.id.clone(),
            message: "part must be derivation, figure or fifteen".into(),
        }),
    }
}

/// The claim's error with a message.
fn claim_error(c: &NamedCheck, message: String) -> VerifyError {
    VerifyError::BadClaim {
        id: c.id.clone(),
        message,
    }
}

/// The energy loss of (2.15) for rho and sigma (the model of Fig. 2 at rtol 1e-10).
fn fig2_loss(c: &NamedCheck, rho: f64, sigma: f64) -> Result<f64, VerifyError> {
    crate::models::pendulum_wall::impact(rho, sigma, 1e-10)
        .map(|r| r.loss)
        .map_err(|e| claim_error(c, e.to_string()))
}

/// The largest |eps_On| of (2.15) (sigma = 1) while the contact at C is loaded.
fn peak_deformation_at_o(c: &NamedCheck, rho: f64) -> Result<f64, VerifyError> {
    use crate::integrate::{Direction, Event};
    use crate::models::pendulum_wall::PendulumWall;
    let sys = PendulumWall { rho, sigma: 1.0 };
    let unloads = |_t: f64, y: &[f64]| y[1];
    let o = crate::integrate::Options {
        rtol: 1e-12,
        atol: 1e-15,
        trajectory: true,
        events: vec![Event::new(
            "contact unloads",
            &unloads,
            Direction::Falling,
            true,
        )],
        ..Default::default()
    };
    let sol = crate::integrate::solve(&sys, 0.0, &[0.0, 0.0, 0.0, 1.0], 100.0, &o)
        .map_err(|e| claim_error(c, e.to_string()))?;
    Ok(sol
        .trajectory
        .iter()
        .map(|(_, y)| y[0].abs())
        .fold(0.0, f64::max))
}

/// Fig. 2 and (2.15), part `condition`: the claim's `printed` is the second condition of (2.10)
/// (its left side, = 0), in `rho` and `GO_GC`; the special geometry has F_C perpendicular to GO
/// and (GO, GC) = -1 (|GO| = 1 m). The condition must hold exactly where O is not deformed: at
/// its root in rho (bisection) and at fixed radii on both sides of it.
fn pendulum_wall_condition(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let cond = |rho: f64| {
        c.printed_value("the second condition of (2.10), = 0", &|name| match name {
            "rho" => Some(rho),
            "GO_GC" => Some(-1.0),
            _ => None,
        })
    };
    // the root of the printed condition in rho over (0, 10], by a scan and bisection
    let grid: Vec<f64> = (1..=400).map(|k| 0.025 * f64::from(k)).collect();
    let mut root = None;
    for w in grid.windows(2) {
        let (fa, fb) = (cond(w[0])?, cond(w[1])?);
        if fa == 0.0 || fa.signum() != fb.signum() {
            let (mut lo, mut hi, mut flo) = (w[0], w[1], fa);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                let fm = cond(mid)?;
                if fm == 0.0 || fm.signum() == flo.signum() {
                    (lo, flo) = (mid, fm);
                } else {
                    hi = mid;
                }
            }
            root = Some(0.5 * (lo + hi));
            break;
        }
    }
    let mut radii = vec![0.5, 0.9, 0.99, 1.0, 1.01, 1.1, 2.0];
    if let Some(r) = root.filter(|r| radii.iter().all(|x| (x - r).abs() > 1e-9 * r)) {
        radii.push(r);
    }
    let mut rows = Vec::new();
    let mut agree = root.is_some();
    for &rho in &radii {
        let holds_here = root.is_some_and(|r| (rho - r).abs() <= 1e-9 * r);
        let peak = peak_deformation_at_o(c, rho)?;
        let undeformed = peak <= 1e-10;
        agree &= holds_here == undeformed;
        rows.push(format!(
            "rho = {rho:.6}: condition {}, max |eps_On| = {peak:.1e}",
            if holds_here { "holds" } else { "fails" }
        ));
    }
    let loss_root = match root {
        // + 0.0 prints a loss of -0 as 0
        Some(r) => format!("{:.1e}", fig2_loss(c, r, 1.0)? + 0.0),
        None => "-".into(),
    };
    Ok(outcome(
        paper,
        c,
        holds(agree),
        format!(
            "In the special case of (2.14)-(2.15) F_C is perpendicular to GO and (GO, GC) = -1 (|GO| = 1 m). The printed condition {} = 0 {}; (2.15) integrated (rtol 1e-12, sigma = 1) while the contact is loaded, O counted undeformed below 1e-10: {}; the energy loss (2.13) at the root: {loss_root}",
            c.printed.as_deref().unwrap_or_default(),
            match root {
                Some(r) => format!("has its root at rho = {r:.9} m"),
                None => "has no root in rho over (0, 10] m".into(),
            },
            rows.join("; ")
        ),
    ))
}

/// Fig. 2 and (2.15), part `derivation`: the claim's `printed_equations` give (2.15)'s right sides
/// (eps_On'' and eps_Cn'', in `eOn`, `eCn`, `rho_s`, `sigma`, lengths in units of |GO|), compared
/// with (2.8) in the special geometry; the model [`PendulumWall`] must agree with (2.8) too.
fn pendulum_wall_derivation(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    use crate::models::pendulum_wall::PendulumWall;
    // (2.8) with the special geometry: GO = t, GC = -t - d n, F_C = c1 eps_Cn n, F_O = c2 eps_O
    let mut rng = Rng(0x5EED_0215);
    let (mut worst, mut worst_model, mut worst_t): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..200 {
        let (rho, sigma, d) = (
            rng.range(0.1, 5.0),
            rng.range(0.01, 5.0),
            rng.range(0.1, 2.0),
        );
        let (eo, ec) = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let (c1, c2) = (sigma, 1.0);
        let go = nalgebra::Vector2::new(1.0, 0.0);
        let gc = nalgebra::Vector2::new(-1.0, -d);
        let fc = nalgebra::Vector2::new(0.0, c1 * ec);
        let fo = nalgebra::Vector2::new(0.0, c2 * eo);
        let r2 = 1.0 / (rho * rho);
        let acc_c = -(fc + fo)
            + (gc * gc.dot(&fc) - fc * gc.dot(&gc) + go * gc.dot(&fo) - fo * go.dot(&gc)) * r2;
        let acc_o = -(fc + fo)
            + (gc * go.dot(&fc) - fc * go.dot(&gc) + go * go.dot(&fo) - fo * go.dot(&go)) * r2;
        let printed = c.printed_values(
            2,
            "the right sides of (2.15), eps_On'' and eps_Cn''",
            &|name| match name {
                "eOn" => Some(eo),
                "eCn" => Some(ec),
                "rho_s" => Some(rho),
                "sigma" => Some(sigma),
                _ => None,
            },
        )?;
        worst = worst
            .max((acc_o.y - printed[0]).abs())
            .max((acc_c.y - printed[1]).abs());
        worst_t = worst_t.max(acc_o.x.abs());
        let mut dy = [0.0; 4];
        PendulumWall { rho, sigma }.rhs(0.0, &[eo, ec, 0.0, 0.0], &mut dy);
        worst_model = worst_model
            .max((acc_o.y - dy[2]).abs())
            .max((acc_c.y - dy[3]).abs());
    }
    if worst_model > 1e-12 {
        return Err(claim_error(
            c,
            format!(
                "the pendulum-wall model differs from (2.8) in the special geometry by {worst_model:.2e}: a model error"
            ),
        ));
    }
    Ok(outcome(
        paper,
        c,
        holds(worst <= 1e-12 && worst_t <= 1e-12),
        format!(
            "the normal components of (2.8) in the special geometry (m = 1, GO along the wall, (GO, GC) = -1, any distance d of G from the wall) against (2.15) as printed at 200 seeded states: max difference {worst:.2e}; the tangential equation of O vanishes (eps_Ot = 0; largest {worst_t:.1e}); the model integrated for Fig. 2 agrees with (2.8) to {worst_model:.1e}"
        ),
    ))
}

/// Fig. 2 and (2.15), part `figure`: the claim's `printed_matrix` gives, per curve, rho, the
/// sigma of the largest loss and that loss as printed (rows `[rho, sigma, loss]`).
fn pendulum_wall_figure(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let loss = |rho: f64, sigma: f64| fig2_loss(c, rho, sigma);
    let printed_rows =
        c.printed_rows(3, "rho, the sigma of the largest loss, that loss", &|_| {
            None
        })?;
    if printed_rows.len() != 2 {
        return Err(claim_error(
            c,
            "printed_matrix must give Fig. 2's two curves, one row each".into(),
        ));
    }
    Ok({
        let sigmas: Vec<f64> = (1..=250).map(|k| 0.02 * k as f64).collect();
        let mut lines = Vec::new();
        let mut curves = Vec::new();
        let mut ok = true;
        for row in &printed_rows {
            let (rho, printed_sigma, printed) = (row[0], row[1], row[2]);
            let vals = sigmas
                .iter()
                .map(|s| loss(rho, *s))
                .collect::<Result<Vec<_>, _>>()?;
            let (imax, vmax) =
                vals.iter().enumerate().fold(
                    (0, f64::MIN),
                    |a, (i, v)| if *v > a.1 { (i, *v) } else { a },
                );
            let at_one = (sigmas[imax] - printed_sigma).abs() <= 0.021;
            let close = (vmax - printed).abs() <= 0.02;
            ok &= at_one && close;
            lines.push(format!(
                "rho = {rho}: maximum loss {:.1}% at sigma = {:.2} (printed: about {:.0}% at sigma = {printed_sigma})",
                100.0 * vmax,
                sigmas[imax],
                100.0 * printed
            ));
            curves.push((
                format!("rho = {rho}"),
                sigmas.iter().copied().zip(vals).collect::<Vec<_>>(),
            ));
        }
        let svg_name = "002_fig2_energy_loss.svg".to_string();
        let svg = crate::report::svg::plot_curves(
            "Fig. 2: relative energy loss of the pendulum against the stiffness ratio",
            "stiffness ratio sigma = c1/c2 (dimensionless)",
            "relative energy loss -dT/T0 (dimensionless)",
            Scale::Linear,
            Scale::Linear,
            &curves,
        );
        // the curves as a table at a few stiffness ratios (points of the same grid)
        let picks = [
            0.1, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0,
        ];
        let row = |sig: f64| {
            let at = |ci: usize| {
                curves[ci]
                    .1
                    .iter()
                    .find(|(x, _)| (x - sig).abs() < 1e-9)
                    .map_or("-".to_string(), |(_, v)| format!("{:.1}", 100.0 * v))
            };
            format!("| {sig} | {} | {} |", at(0), at(1))
        };
        let table = format!(
            "Relative energy loss -dT/T0 in % (T0: the pendulum's kinetic energy before impact; the loss is what is dissipated while the suspension point O is braked after the contact unloads, (2.13)):\n\n| sigma = c1/c2 | {} | {} |\n|---|---|---|\n{}",
            curves[0].0,
            curves[1].0,
            picks.iter().map(|s| row(*s)).collect::<Vec<_>>().join("\n")
        );
        let same = curves[0]
            .1
            .iter()
            .zip(&curves[1].1)
            .map(|(a, b)| (a.1 - b.1).abs())
            .fold(0.0, f64::max);
        let mut o = outcome(
            paper,
            c,
            holds(ok),
            format!(
                "(2.15) integrated to the unloading of the contact element, (2.13) with V_Ot = 0, (GO, n) = 0, rho_O^2 = rho^2 + 1, relative to the pendulum's kinetic energy before impact T0 = (1 + rho^2)/8 (|V_Cn-| = 1, |(OC, t)| = 2): {}. The two computed curves coincide (largest difference {same:.1e} over 250 values of sigma), where the paper's differ",
                lines.join("; ")
            ),
        )
        .with_plot(
            "Fig. 2 recomputed",
            svg_name,
            svg,
            crate::report::svg::csv_curves("stiffness ratio sigma = c1/c2 (dimensionless)", "relative energy loss -dT/T0 (dimensionless)", &curves),
        );
        o.extra_md = Some(format!("{table}\n\n{}", o.extra_md.unwrap_or_default()));
        o
    })
}

/// Fig. 2 and (2.15), part `fifteen`: the claim's `printed_matrix` gives the intervals of rho
/// as printed (rows `[lo, hi]`), `printed_equations` the interval of sigma, `printed` the bound
/// on the loss.
fn pendulum_wall_fifteen(paper: &PaperClaims, c: &NamedCheck) -> Result<Outcome, VerifyError> {
    let loss = |rho: f64, sigma: f64| fig2_loss(c, rho, sigma);
    let none = |_: &str| None;
    let intervals = c.printed_rows(2, "an interval of rho, [lo, hi]", &none)?;
    let sig = c.printed_values(2, "the interval of sigma, lo and hi", &none)?;
    let bound = c.printed_value("the bound on the relative loss", &none)?;
    Ok({
        let mut worst: Vec<String> = Vec::new();
        let mut ok = true;
        for row in &intervals {
            let (lo, hi) = (row[0], row[1]);
            let mut m = (0.0f64, 0.0, 0.0);
            // interior points only: the intervals are open
            for i in 1..12 {
                let rho = lo + (hi - lo) * i as f64 / 12.0;
                for k in 1..=50 {
                    let sigma = sig[0] + (sig[1] - sig[0]) * k as f64 / 50.0 - 0.001;
                    let l = loss(rho, sigma)?;
                    if l > m.0 {
                        m = (l, rho, sigma);
                    }
                }
            }
            ok &= m.0 <= bound;
            worst.push(format!(
                "rho in ({lo}, {hi}): max {:.1}% at rho = {:.2}, sigma = {:.2}",
                100.0 * m.0,
                m.1,
                m.2
            ));
        }
        outcome(
            paper,
            c,
            holds(ok),
            format!(
                "same computation and normalisation as Fig. 2, sigma in ({}, {}), against the printed {:.0}%: {}",
                sig[0],
                sig[1],
                100.0 * bound,
                worst.join("; ")
            ),
        )
    })
}
