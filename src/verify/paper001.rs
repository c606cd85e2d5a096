//! Checks of 001_989b2e860c39ca83.txt (Sinitsyn's disk, middle part): the friction force and
//! moment of a sliding and spinning disk by direct quadrature against (2.3).

use super::{ClaimSpec, Outcome, PaperClaims, Verdict, VerifyError, outcome};
use crate::models::disk_friction::{f123, quadrature};

/// Checks one claim of paper 001.
pub fn check(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    let (verdict, detail) = match c.check.as_str() {
        "disk-friction" => {
            // F/M from the quadrature (two resolutions give its error) against (3/a) k f1/f3 and
            // (3/a) f1(k1)/f2(k1), a = 1
            let mut worst: f64 = 0.0;
            let mut quad_err: f64 = 0.0;
            let ks: Vec<f64> = (1..=19)
                .map(|i| 0.05 * i as f64)
                .chain([0.99, 0.999_999])
                .collect();
            for &k in &ks {
                for spin_dominant in [true, false] {
                    let (v, w) = if spin_dominant { (k, 1.0) } else { (1.0, k) };
                    let (f, m) = quadrature(v, w, 160, 1600);
                    let (f2_, m2_) = quadrature(v, w, 80, 800);
                    let (a1, a2, a3) = f123(k);
                    let closed = if spin_dominant {
                        3.0 * k * a1 / a3
                    } else {
                        3.0 * a1 / a2
                    };
                    quad_err = quad_err.max(((f / m) - (f2_ / m2_)).abs() / (f / m).abs());
                    worst = worst.max(((f / m) - closed).abs() / closed.abs());
                }
            }
            (
                // agreement counts within the quadrature's own error (estimated by halving the grid)
                if worst <= (10.0 * quad_err).max(1e-9) {
                    Verdict::Holds
                } else {
                    Verdict::Fails
                },
                format!(
                    "F/M of a disk under uniform pressure (a = 1, f = 1) by Gauss-Legendre x midpoint quadrature against (3/a) k f1(k)/f3(k) (V <= Omega) and (3/a) f1(k1)/f2(k1) (Omega <= V), K and E from Carlson's R_F, R_D with m_c = (1-k)(1+k), k = 0.05..0.95, 0.99, 1 - 1e-6: max relative difference {worst:.2e}, within the quadrature's error estimate (change on halving the grid: {quad_err:.2e})"
                ),
            )
        }
        "disk-closed-forms" => {
            // case a): omega+ = omega- - 2 a f u0/(3 rho^2), V+ = V-(1 - (2f/mu) u0/(a omega-))^(mu/2)
            let (m, rho, a, f, u0) = (1.0, 0.7, 1.0, 0.3, 0.5);
            let mu = 3.0 * rho * rho / (a * a);
            let mut worst: f64 = 0.0;
            let mut rows = Vec::new();
            for k in [0.003, 0.01, 0.03] {
                let (v0, w0) = (k, 1.0);
                let (vp, wp) =
                    crate::models::disk_friction::impulsive_motion(m, rho, a, f, v0, w0, u0, 0.0)
                        .map_err(|e| VerifyError::BadClaim {
                        id: c.id.clone(),
                        message: e.to_string(),
                    })?;
                let w_closed = w0 - 2.0 * a * f * u0 / (3.0 * rho * rho);
                let v_closed = v0 * (1.0 - 2.0 * f / mu * u0 / (a * w0)).powf(mu / 2.0);
                let (ew, ev) = (
                    (wp - w_closed).abs() / w_closed,
                    (vp - v_closed).abs() / v_closed,
                );
                worst = worst.max((ew.max(ev)) / (k * k));
                rows.push(format!(
                    "V-/(a omega-) = {k}: omega+ off by {ew:.1e}, V+ by {ev:.1e}"
                ));
            }
            (
                if worst <= 10.0 {
                    Verdict::Holds
                } else {
                    Verdict::Fails
                },
                format!(
                    "(2.2) with c = 0 integrated in the normal impulse (friction force and moment by quadrature, inelastic, m = a = 1, rho = 0.7, f = 0.3, u0 = 0.5) against the closed forms of case a): {}; relative errors / k^2 at most {worst:.2} (a linearisation in k = V/(a omega) must be O(k^2))",
                    rows.join("; ")
                ),
            )
        }
        "relaxation" => {
            use crate::models::relaxation::{Relaxation, energy_history};
            let sys = Relaxation {
                kappa: 0.3,
                d: [0.1, 0.25],
            };
            let hist = energy_history(&sys, &[0.2, -0.1, 0.1, 0.15], 300.0, 3000).map_err(|e| {
                VerifyError::BadClaim {
                    id: c.id.clone(),
                    message: e.to_string(),
                }
            })?;
            // H never grows (up to the integration error)
            let grows = hist
                .windows(2)
                .filter(|w| w[1].1 > w[0].1 * (1.0 + 1e-9) + 1e-18)
                .count();
            // late-time rate: least-squares slope of ln H over the last third; H ~ exp(-2 sigma t)
            let late: Vec<(f64, f64)> = hist.iter().skip(2000).map(|(t, h)| (*t, h.ln())).collect();
            let n = late.len() as f64;
            let (mt, mh) = (
                late.iter().map(|x| x.0).sum::<f64>() / n,
                late.iter().map(|x| x.1).sum::<f64>() / n,
            );
            let slope = late.iter().map(|(t, h)| (t - mt) * (h - mh)).sum::<f64>()
                / late.iter().map(|(t, _)| (t - mt).powi(2)).sum::<f64>();
            let rate = -slope / 2.0;
            let predicted = sys.linear_rate();
            let rel = (rate - predicted).abs() / predicted;
            (
                if grows == 0 && rel < 2e-2 {
                    Verdict::Holds
                } else {
                    Verdict::Fails
                },
                format!(
                    "n = 2, Pi1 = 0.3 (q1^3 + q1 q2^2), Q = -diag(0.1, 0.25) p, from H(0) = {:.4e}: H grew at {grows} of 3000 samples; late-time decay rate of H^(1/2) {rate:.5} 1/s against the linearised system's slowest rate {predicted:.5} 1/s (relative difference {rel:.1e})",
                    hist[0].1
                ),
            )
        }
        "disk-linear" => {
            // the small-k limits of force and moment (f = 1, a = 1, unit normal load) by quadrature
            let eps = 1e-3;
            match c.part.as_deref() {
                Some("a") => {
                    // (2.4): V << a omega: m V' = -f V/Omega, J omega' = -2 a f/3
                    let (f, m) = quadrature(eps, 1.0, 160, 1600);
                    let (rf, rm) = (f.abs() / eps, m.abs() / (2.0 / 3.0));
                    let ok = (rf - 1.0).abs() < 1e-4 && (rm - 1.0).abs() < 1e-4;
                    (
                        if ok { Verdict::Holds } else { Verdict::Fails },
                        format!(
                            "at V/Omega = {eps:e}: |F|/(f V/Omega) = {rf:.6}, |M|/(2 f a/3) = {rm:.6}; so dV/dOmega = (mu/2) V/Omega and V = V-(omega/omega-)^(mu/2) as printed"
                        ),
                    )
                }
                _ => {
                    // (2.5): V >> a omega: m V' = -f, J omega' = -(5/6) f a Omega/V (printed)
                    let (f, m) = quadrature(1.0, eps, 160, 1600);
                    let (rf, coef) = (f.abs(), m.abs() / eps);
                    let ok = (rf - 1.0).abs() < 1e-4 && (coef - 5.0 / 6.0).abs() < 1e-4;
                    (
                        if ok { Verdict::Holds } else { Verdict::Fails },
                        format!(
                            "at Omega/V = {eps:e}: |F|/f = {rf:.6}; |M|/(f a Omega/V) = {coef:.6} against the printed 5/6 = 0.833333 (the first-order expansion of the direction field gives 1/4: M = -f a (Omega/V) int x^2 dA/(pi a^4) = -f a Omega/(4V)); with 1/4, dV/dOmega = (4 mu/3) V/Omega and V = V-(omega/omega-)^(4 mu/3), where the printed (2.5) has exponent 'mu/s'"
                        ),
                    )
                }
            }
        }
        other => {
            return Err(VerifyError::BadClaim {
                id: c.id.clone(),
                message: format!("unknown check `{other}`"),
            });
        }
    };
    Ok(outcome(paper, c, verdict, detail))
}
