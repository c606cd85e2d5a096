//! Checks of 002_b53e4779673eb6ed.txt: Proposition 1 and (1.9)-(1.13) over seeded random bodies,
//! the pendulum's B* (2.5) and its cut-off condition, and the Coriolis billiard problem
//! (3.9)-(3.14).

use super::{ClaimSpec, Outcome, PaperClaims, Verdict, VerifyError, holds, outcome};
use crate::integrate::{Method, OdeSystem, Options, solve};
use crate::models::rigid_impact::{Body, Law, b_matrix, impact_with_matrix};
use crate::report::svg::{Scale, Series};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use crate::rng::Rng;

const SAMPLES: usize = 400;

/// One random impact configuration.
#[derive(Clone, Debug)]
struct Config {
    b1: Body,
    b2: Body,
    v: Vector3<f64>,
    e: f64,
    /// Friction at C, in [0, 1.5).
    mu: f64,
}

fn random_body(r: &mut Rng) -> Body {
    let inertia = r.spd((0.05, 1.0), 0.5) * 0.1;
    Body {
        mass: Some(r.range(0.1, 10.0)),
        inertia,
        offset: Vector3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5)),
    }
}

fn configs(seed: u64) -> Vec<Config> {
    let mut r = Rng(seed);
    (0..SAMPLES)
        .map(|_| {
            let b1 = random_body(&mut r);
            let b2 = random_body(&mut r);
            let v = Vector3::new(r.range(-2.0, 2.0), r.range(-2.0, 2.0), -r.range(0.05, 3.0));
            // a friction coefficient is drawn (and unused by the checks left here) so that the
            // seeded cases stay those of earlier reports
            let mu = r.range(0.0, 1.5);
            let e = r.range(0.0, 1.0);
            Config { b1, b2, v, e, mu }
        })
        .collect()
}

fn fmt_m(m: &Matrix3<f64>) -> String {
    format!(
        "[[{:.4}, {:.4}, {:.4}], [{:.4}, {:.4}, {:.4}], [{:.4}, {:.4}, {:.4}]]",
        m[(0, 0)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 0)],
        m[(1, 1)],
        m[(1, 2)],
        m[(2, 0)],
        m[(2, 1)],
        m[(2, 2)]
    )
}

/// The two billiard balls of section 3 with m = 1, R = 1, rho^2 = 0.4 R^2: (B, B_A, B~, B*)
/// computed from the definitions (1.7), (3.4), (3.8).
fn billiard() -> (Matrix3<f64>, Matrix3<f64>, Matrix3<f64>, Matrix3<f64>, f64) {
    let (m, r) = (1.0, 1.0);
    let rho2 = 0.4 * r * r;
    let j2inv = Matrix3::identity() / (m * rho2);
    let g1c = Vector3::new(r, 0.0, 0.0);
    let g2c = -g1c;
    let g2a = Vector3::new(0.0, 0.0, -r);
    let nn = Vector3::z();
    let ball = |off: Vector3<f64>| Body {
        mass: Some(m),
        inertia: Matrix3::identity() * (m * rho2),
        offset: off,
    };
    let b = b_matrix(&ball(g1c), &ball(g2c)).expect("invertible");
    let col = |f: &dyn Fn(Vector3<f64>) -> Vector3<f64>| {
        Matrix3::from_columns(&[f(Vector3::x()), f(Vector3::y()), f(Vector3::z())])
    };
    let bt = col(&|f| f / m + (j2inv * g2c.cross(&f)).cross(&g2a));
    let ba = col(&|f| f / m + (j2inv * g2a.cross(&f)).cross(&g2a));
    let beta = (ba * nn).dot(&nn);
    let bstar = col(&|f| b * f - (bt.transpose() * nn) * ((bt * f).dot(&nn) / beta));
    (b, ba, bt, bstar, r * r / rho2)
}

/// The values of the billiard configuration: m = 1, R = 1, rho^2 = 0.4 R^2.
fn billiard_values(name: &str) -> Option<f64> {
    match name {
        "m" | "R" => Some(1.0),
        "rho" => Some(0.4f64.sqrt()),
        _ => None,
    }
}

/// The claim's `printed_matrix`, each formula evaluated with `values`.
fn printed_matrix(
    c: &ClaimSpec,
    values: &dyn Fn(&str) -> Option<f64>,
) -> Result<Matrix3<f64>, VerifyError> {
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    if c.printed_matrix.len() != 3 || c.printed_matrix.iter().any(|r| r.len() != 3) {
        return Err(bad("printed_matrix must be 3 rows of 3 formulas".into()));
    }
    let mut m = Matrix3::zeros();
    for (i, row) in c.printed_matrix.iter().enumerate() {
        for (j, text) in row.iter().enumerate() {
            let e = crate::algebra::expr::parse(text)
                .map_err(|e| bad(format!("printed_matrix[{i}][{j}]: {e}")))?;
            m[(i, j)] = e.eval(values).map_err(bad)?;
        }
    }
    Ok(m)
}

/// (3.13): $V_1' = 2/m$, $r' = -(\mu/m)(6 + \sin^2\varphi)$, $r\varphi' = -(\mu/2m)\sin 2\varphi$.
struct Coriolis {
    mu: f64,
}

impl OdeSystem for Coriolis {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&self, _chi: f64, y: &[f64], dy: &mut [f64]) {
        let (r, phi) = (y[0], y[1]);
        dy[0] = -self.mu * (6.0 + phi.sin().powi(2));
        dy[1] = -0.5 * self.mu * (2.0 * phi).sin() / r;
    }
}

/// Checks one claim of paper 002.
pub fn check(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    let bad = |m: &str| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m.into(),
    };
    let cfgs = configs(0x5EED_0002);
    Ok(match c.check.as_str() {
        "pendulum-bstar" => {
            // (2.4): dV_C = (e*, I) e* /(m rho^2), e* = e x OC; compare with (2.5)
            let (m, rho) = (2.0, 0.3);
            let e_axis = Vector3::new(0.2, 1.0, -0.1).normalize();
            let oc = Vector3::new(0.4, -0.1, -0.5);
            let es = e_axis.cross(&oc);
            let derived =
                Matrix3::from_columns(&[Vector3::x(), Vector3::y(), Vector3::z()].map(|i| {
                    let dw = e_axis * (oc.cross(&i).dot(&e_axis) / (m * rho * rho));
                    dw.cross(&oc)
                }));
            let printed = es * es.transpose() / (m * rho * rho);
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
        }
        "pendulum-cutoff" => {
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
                    let Ok(r) =
                        impact_with_matrix(&b, Vector3::z(), -es, mu, Law::Poisson, 0.5, 1e-10)
                    else {
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
        }
        "billiard-matrix" => {
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
            let same = (derived - printed).abs().max() <= 1e-12 * printed.abs().max();
            let ratio = printed.abs().max() / derived.abs().max();
            outcome(
                paper,
                c,
                holds(same),
                format!(
                    "m = 1, R = 1, rho^2 = 0.4 R^2 (R^2/rho^2 = {k}): derived from the definitions {}; printed {}{}",
                    fmt_m(&derived),
                    fmt_m(&printed),
                    if same {
                        String::new()
                    } else {
                        format!("; printed/derived (largest entries) = {ratio:.4}")
                    }
                ),
            )
        }
        "billiard-312" => {
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
        }
        "billiard-313" => {
            // r' and r phi' from V' = B* F (derived B*) against the printed (3.13), at sample angles
            let (_, _, _, bs, _) = billiard();
            let mu = 0.3;
            let mut worst: f64 = 0.0;
            for k in 0..36 {
                let phi = -std::f64::consts::PI + (k as f64 + 0.5) * std::f64::consts::PI / 18.0;
                let f = Vector3::new(1.0, -mu * phi.sin(), -mu * phi.cos());
                let dv = bs * f;
                let r_dot = phi.sin() * dv.y + phi.cos() * dv.z;
                let r_phi_dot = phi.cos() * dv.y - phi.sin() * dv.z;
                let pr = -mu * (6.0 + phi.sin().powi(2));
                let pp = -0.5 * mu * (2.0 * phi).sin();
                worst = worst
                    .max((r_dot - pr).abs())
                    .max((r_phi_dot - pp).abs())
                    .max((dv.x - 2.0).abs());
            }
            outcome(
                paper,
                c,
                holds(worst <= 1e-12),
                format!(
                    "V1', r', r phi' from V' = B* F (derived B*, m = 1) against (3.13) at 36 angles: max difference {worst:.2e}"
                ),
            )
        }
        "billiard-314" => {
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
                let sol =
                    solve(&sys, 0.0, &[r0, phi0], 10.0, &o).map_err(|e| bad(&e.to_string()))?;
                let mut pts = Vec::new();
                let mut prev = phi0;
                for (_, y) in &sol.trajectory {
                    let closed =
                        r0 * (y[1].sin() / phi0.sin()).powi(6) * (y[1].cos() / phi0.cos()).powi(-7);
                    worst = worst.max((y[0] - closed).abs() / y[0].abs().max(1e-3));
                    monotone &= y[1].abs() >= prev.abs() - 1e-12;
                    prev = y[1];
                    pts.push((y[1].to_degrees(), y[0]));
                }
                series.push((format!("phi0 = {phi0_deg} deg"), pts));
            }
            let svg_name = "002_coriolis_curves.svg".to_string();
            let svg = crate::report::svg::plot_curves(
                "Coriolis problem: integral curves of (3.13), r against phi",
                "phi (degrees)",
                "r / r0",
                Scale::Linear,
                Scale::Linear,
                &series,
            );
            outcome(
                paper,
                c,
                holds(worst <= 1e-8),
                format!(
                    "(3.13) integrated by DOP853 (rtol 1e-12) from r0 = 1, phi0 = 100..170 deg, mu = 0.3, until r = 1e-3: max relative difference from (3.14) {worst:.2e}; |phi| increases along every curve: {monotone}"
                ),
            )
            .with_plot(
                "integral curves of (3.13)",
                svg_name,
                svg,
                crate::report::svg::csv_curves("phi (degrees)", "r / r0", &series),
            )
        }
        "billiard-fixed-angles" => {
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
            let printed = [-180.0, -90.0, 90.0, 180.0];
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
                    "phi' = 0 in (3.13) where sin 2 phi = 0: at {:?} degrees; the printed list (+-180, +-90) misses {:?} (V_t pointing along N; excluded only by the paper's assumption (V-, N) < 0)",
                    zeros, extra
                ),
            )
        }
        "plane-support" => plane_support(paper, c)?,
        "deformable-elements" => deformable_elements(paper, c)?,
        "rest-types" => rest_types(paper, c)?,
        "rolling-ball" => rolling_ball(paper, c)?,
        "pendulum-wall" => pendulum_wall(paper, c)?,
        "balls-wall" => {
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
            let mut table: Vec<Vec<String>> =
                kappas.iter().map(|k| vec![format!("{k:.4e}")]).collect();
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
        }
        "rough-support" => {
            // the impact with friction at C and at the support integrated (rolling, sliding,
            // letting go; 002 section 4) over the seeded bodies: (a) as mu* -> 0 it tends to the
            // smooth support (3.7)-(3.8); (b) the kinetic energy from the bodies' velocities
            // never grows (Poisson's and the energetic law); (c) the billiard example: the
            // vertical impulses balance, F*_3 = F_3, in every case (rolling or sliding)
            use crate::models::rigid_impact::{
                RoughSupport, SmoothSupport, impact_general, impact_rough, kinetic_change_moving,
            };
            use crate::models::support::{Support, matrices};
            let mut rng = Rng(0x5EED_0044);
            let (mut limit_worst, mut limit_n, mut shrink_bad) = (0.0f64, 0usize, 0usize);
            let (mut energy_n, mut grew, mut refused, mut painleve) =
                (0usize, 0usize, 0usize, 0usize);
            let mut modes = std::collections::BTreeMap::<String, usize>::new();
            for (k, cf) in cfgs.iter().enumerate().take(200) {
                let sup = Support {
                    offset: Vector3::new(
                        cf.b2.offset.y * 0.5,
                        cf.b2.offset.x * 0.5,
                        -0.3 - 0.2 * (k % 3) as f64,
                    ),
                    normal: Vector3::z(),
                    mu: 0.0,
                };
                let (Some(b), Some(sm)) = (b_matrix(&cf.b1, &cf.b2), matrices(&cf.b2, &sup)) else {
                    continue;
                };
                let rough = |mu_star: f64| RoughSupport {
                    b_tilde: sm.b_tilde,
                    b_a: sm.b_a,
                    normal: Vector3::z(),
                    mu: mu_star,
                    v_a: Vector3::zeros(),
                };
                let law = if k % 2 == 0 {
                    Law::Poisson
                } else {
                    Law::Energetic
                };
                // (a)
                let smooth = SmoothSupport {
                    b_tilde: sm.b_tilde,
                    normal: Vector3::z(),
                    beta: (sm.b_a * Vector3::z()).z,
                };
                if let Ok(s0) = impact_general(
                    &b,
                    Some(smooth),
                    Vector3::z(),
                    cf.v,
                    cf.mu,
                    law,
                    cf.e,
                    1e-11,
                ) {
                    let si = Vector3::from(s0.impulse);
                    let d: Vec<f64> = [1e-3, 1e-6]
                        .iter()
                        .filter_map(|&m| {
                            impact_rough(
                                &b,
                                rough(m),
                                None,
                                Vector3::z(),
                                cf.v,
                                cf.mu,
                                law,
                                cf.e,
                                1e-11,
                            )
                            .ok()
                            .map(|r| (Vector3::from(r.impulse) - si).norm() / si.norm())
                        })
                        .collect();
                    if d.len() == 2 {
                        limit_n += 1;
                        limit_worst = limit_worst.max(d[1]);
                        shrink_bad += usize::from(!(d[1] < d[0] || d[0] < 1e-8));
                    }
                }
                // (b)
                let mu_star = rng.range(0.05, 1.5);
                match impact_rough(
                    &b,
                    rough(mu_star),
                    None,
                    Vector3::z(),
                    cf.v,
                    cf.mu,
                    law,
                    cf.e,
                    1e-10,
                ) {
                    Ok(r) => {
                        energy_n += 1;
                        for p in &r.support_phases {
                            *modes.entry(p.kind.clone()).or_default() += 1;
                        }
                        let de = kinetic_change_moving(
                            &cf.b1,
                            &cf.b2,
                            &cf.v,
                            &Vector3::zeros(),
                            &Vector3::from(r.impulse),
                            Some((sup.offset, Vector3::from(r.support_impulse))),
                        );
                        grew += usize::from(de > 1e-7 * 0.5 * cf.v.norm_squared() / r.lambda_max);
                    }
                    Err(crate::models::rigid_impact::ImpactError::Painleve { .. }) => painleve += 1,
                    Err(_) => refused += 1,
                }
            }
            // (c)
            let (bb, ba, bt, _, _) = billiard();
            let mut balance: f64 = 0.0;
            let mut billiard_modes = std::collections::BTreeSet::new();
            for mu_star in [0.01, 0.1, 0.2, 1.0, 3.0] {
                let r = impact_rough(
                    &bb,
                    RoughSupport {
                        b_tilde: bt,
                        b_a: ba,
                        normal: Vector3::z(),
                        mu: mu_star,
                        v_a: Vector3::zeros(),
                    },
                    None,
                    Vector3::x(),
                    Vector3::new(-1.0, 0.3, -0.4),
                    0.2,
                    Law::Poisson,
                    0.9,
                    1e-11,
                );
                if let Ok(r) = r {
                    balance = balance
                        .max((r.impulse[2] - r.support_impulse[2]).abs() / r.impulse[0].abs());
                    for p in &r.support_phases {
                        billiard_modes.insert(p.kind.clone());
                    }
                } else {
                    balance = f64::INFINITY;
                }
            }
            let ok = limit_n >= 100
                && limit_worst < 1e-4
                && shrink_bad == 0
                && grew == 0
                && energy_n >= 150
                && balance < 1e-10;
            outcome(
                paper,
                c,
                holds(ok),
                format!(
                    "200 seeded bodies, the second on a rough support, friction at C (mu in [0, 1.5)), Poisson's and the energetic law alternating. (a) mu* -> 0: |I(mu* = 1e-6) - I(smooth)|/|I| at most {limit_worst:.2e} over {limit_n} cases, smaller than at mu* = 1e-3 in all but {shrink_bad}; (b) mu* in [0.05, 1.5): {energy_n} integrated (support phases {modes:?}), {painleve} Painleve-type (no consistent motion at A, or at C under the support, reported), {refused} refused by the solver (it says so); the kinetic energy from the bodies' velocities grew in {grew}; (c) the billiard example (mu* = 0.01 .. 3, phases {billiard_modes:?}): |I_3 - I*_3| / I_1 at most {balance:.1e} (F*_3 = F_3)"
                ),
            )
        }
        "proposition-3" => {
            use crate::models::rigid_impact::{
                RoughSupport, SmoothSupport, impact_general, impact_rough,
            };
            use crate::models::support::{Support, b_star, matrices};
            // three sets over the same seeded bodies: the proposition's (a smooth support with
            // a smooth contact at C, and with Coulomb friction at C), and, outside it, a rough
            // support (mu* in (0, 1.5)) with friction at C
            let mut violations = [0usize; 3];
            let mut worst = [0.0f64; 3];
            let mut solved = [0usize; 3];
            let mut refused = [0usize; 3];
            let mut rng = Rng(0x5EED_0003);
            let mut grew = 0usize;
            for (k, cf) in cfgs.iter().enumerate().take(200) {
                let sup = Support {
                    offset: Vector3::new(
                        cf.b2.offset.y * 0.5,
                        cf.b2.offset.x * 0.5,
                        -0.3 - 0.2 * (k % 3) as f64,
                    ),
                    normal: Vector3::new(0.1 * cf.v.x, 0.1 * cf.v.y, 1.0).normalize(),
                    mu: 0.0,
                };
                let mu_star = rng.range(0.05, 1.5);
                let (Some(b), Some(sm)) = (b_matrix(&cf.b1, &cf.b2), matrices(&cf.b2, &sup)) else {
                    continue;
                };
                let beta = (sm.b_a * sup.normal).dot(&sup.normal);
                let bs = b_star(&b, &sm, &sup.normal);
                let lam = SymmetricEigen::new(b)
                    .eigenvalues
                    .min()
                    .min(SymmetricEigen::new(bs).eigenvalues.min());
                let smooth = SmoothSupport {
                    b_tilde: sm.b_tilde,
                    normal: sup.normal,
                    beta,
                };
                let law = if k % 2 == 0 {
                    Law::Poisson
                } else {
                    Law::Energetic
                };
                let runs = [
                    impact_general(
                        &b,
                        Some(smooth.clone()),
                        Vector3::z(),
                        cf.v,
                        0.0,
                        law,
                        cf.e,
                        1e-10,
                    ),
                    impact_general(
                        &b,
                        Some(smooth),
                        Vector3::z(),
                        cf.v,
                        cf.mu,
                        law,
                        cf.e,
                        1e-10,
                    ),
                    impact_rough(
                        &b,
                        RoughSupport {
                            b_tilde: sm.b_tilde,
                            b_a: sm.b_a,
                            normal: sup.normal,
                            mu: mu_star,
                            v_a: Vector3::zeros(),
                        },
                        None,
                        Vector3::z(),
                        cf.v,
                        cf.mu,
                        law,
                        cf.e,
                        1e-10,
                    ),
                ];
                for (i, run) in runs.into_iter().enumerate() {
                    let Ok(r) = run else {
                        refused[i] += 1;
                        continue;
                    };
                    solved[i] += 1;
                    if i == 2 {
                        // the kinetic energy from the bodies' velocities under both impulses
                        let de = crate::models::rigid_impact::kinetic_change_moving(
                            &cf.b1,
                            &cf.b2,
                            &cf.v,
                            &Vector3::zeros(),
                            &Vector3::from(r.impulse),
                            Some((sup.offset, Vector3::from(r.support_impulse))),
                        );
                        let scale = 0.5 * cf.v.norm_squared() / r.lambda_max;
                        grew += usize::from(de > 1e-7 * scale);
                    }
                    let ratio = Vector3::from(r.impulse).norm() / (2.0 * cf.v.norm() / lam);
                    worst[i] = worst[i].max(ratio);
                    if ratio > 1.0 + 1e-9 {
                        violations[i] += 1;
                    }
                }
            }
            outcome(
                paper,
                c,
                holds(violations[0] + violations[1] == 0 && solved[0] > 0 && solved[1] > 0),
                format!(
                    "seeded impacts with a smooth support under the second body (B or B* of (3.8)), Poisson's and the energetic law alternating; max |I| / (2|V-|/lambda), lambda = min eigenvalue of B and B*: smooth contact at C {:.3e} ({} solved, {} violations), Coulomb friction at C (mu in [0, 1.5)) {:.3e} ({} solved, {} refused by the solver, {} violations). Outside the proposition, a rough support (mu* in [0.05, 1.5)) with friction at C: {:.3e} ({} solved, {} refused as Painleve-type or by the solver, {} above the bound; the kinetic energy from the bodies' velocities grew in {grew})",
                    worst[0],
                    solved[0],
                    violations[0],
                    worst[1],
                    solved[1],
                    refused[1],
                    violations[1],
                    worst[2],
                    solved[2],
                    refused[2],
                    violations[2]
                ),
            )
        }
        "proposition-2" => {
            use crate::models::fixed_points::{Hold, b_star, line_meets_both, singular};
            let mut rng = Rng(0x5EED_0022);
            let mut agree = 0;
            let mut total = 0;
            let mut singular_count = 0;
            let mut min_eig: f64 = f64::INFINITY;
            let mut first_bad = String::new();
            let spd = |rng: &mut Rng| rng.spd((0.2, 1.0), 0.3);
            let rv = |rng: &mut Rng| {
                Vector3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                )
            };
            for k in 0..600 {
                // half of the cases are built to meet Proposition 2's condition on purpose
                let kinds = [k % 4, (k / 4) % 4];
                let shared = rv(&mut rng);
                let special = k % 2 == 0;
                let mut holds_ = Vec::new();
                for (idx, kind) in kinds.iter().enumerate() {
                    let h = match kind {
                        0 => Hold::Free {
                            mass: rng.range(0.5, 5.0),
                            inertia: spd(&mut rng),
                            gc: rv(&mut rng),
                        },
                        1 => Hold::Point {
                            inertia_o: spd(&mut rng),
                            oc: if special {
                                shared * rng.range(0.3, 2.0) * if idx == 0 { 1.0 } else { -1.0 }
                            } else {
                                rv(&mut rng)
                            },
                        },
                        2 => {
                            let oc = rv(&mut rng);
                            // an axis whose line meets the line C + t*shared when special
                            // O = C - OC; the axis through O towards C + t*shared meets that line
                            let e = if special {
                                (oc + shared * rng.range(0.5, 2.0)).normalize()
                            } else {
                                rv(&mut rng).normalize()
                            };
                            Hold::Axis {
                                j_axis: rng.range(0.2, 2.0),
                                e,
                                oc,
                            }
                        }
                        _ => Hold::Fixed,
                    };
                    holds_.push(h);
                }
                let b = b_star(&holds_[0], &holds_[1]);
                let ev = SymmetricEigen::new(b).eigenvalues;
                min_eig = min_eig.min(ev.min() / ev.max().abs().max(1e-300));
                let s_num = singular(&b);
                let s_geo = line_meets_both(&holds_[0], &holds_[1]);
                total += 1;
                singular_count += usize::from(s_num);
                if s_num == s_geo {
                    agree += 1;
                } else if first_bad.is_empty() {
                    first_bad = format!("; first disagreement: case {k}, kinds {kinds:?}");
                }
            }
            outcome(
                paper,
                c,
                holds(agree == total && min_eig >= -1e-12),
                format!(
                    "{total} seeded pairs of bodies (free, fixed point, fixed axis, immovable; half built to meet the condition): B* singular by its eigenvalues in {singular_count}; the geometric condition (a line through C meets both fixed sets) agrees in {agree}; smallest eigenvalue/largest {min_eig:.2e} (B* non-negative, (2.2)){first_bad}"
                ),
            )
        }
        "billiard-general" => {
            // the two balls with the second on a smooth table, integrated by the general model
            use crate::models::rigid_impact::{SmoothSupport, impact_general};
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
                    Vector3::x(),
                    v,
                    mu,
                    Law::Poisson,
                    0.8,
                    1e-12,
                )
                .map_err(|e| bad(&e.to_string()))?;
                for (chi, vv) in &res.path {
                    let rr = (vv[1] * vv[1] + vv[2] * vv[2]).sqrt();
                    if rr < 1e-3 * r0 {
                        continue;
                    }
                    let phi = vv[1].atan2(vv[2]);
                    let closed =
                        r0 * (phi.sin() / phi0.sin()).powi(6) * (phi.cos() / phi0.cos()).powi(-7);
                    worst = worst.max((rr - closed).abs() / rr);
                    worst_v1 = worst_v1.max((vv[0] - (v1 + 2.0 * chi / m)).abs());
                    points += 1;
                }
            }
            outcome(
                paper,
                c,
                holds(worst <= 1e-7 && worst_v1 <= 1e-9),
                format!(
                    "two homogeneous balls (m = R = 1), the second on a smooth table, integrated by the general model (B of (1.7), the support reaction (3.7) switched on while alpha < 0) in the normal impulse, 4 impacts, {points} steps: max relative difference of r(phi) from (3.14) {worst:.2e}; V1 against V1- + 2 I_n/m: {worst_v1:.2e}"
                ),
            )
        }
        other => return Err(bad(&format!("unknown check `{other}`"))),
    })
}

/// The plane example of section 4, embedded in 3D: x along the support, y = N, z out of plane.
struct Plane {
    m2: f64,
    rho2: f64,
    a2: f64,
    b2: f64,
    a3: f64,
    b3: f64,
    mu_star: f64,
}

impl Plane {
    fn parts(&self) -> (Body, crate::models::support::Support) {
        let body = Body {
            mass: Some(self.m2),
            inertia: Matrix3::identity() * (self.m2 * self.rho2 * self.rho2),
            offset: Vector3::new(self.a2, self.b2, 0.0),
        };
        let s = crate::models::support::Support {
            offset: Vector3::new(self.a3, self.b3, 0.0),
            normal: Vector3::y(),
            mu: self.mu_star,
        };
        (body, s)
    }
}

/// Whether the kernel of a singular `b` (the impulses that leave the body at rest) meets the
/// friction cone at the contact of normal `n`: `I.n > 0`, `|I - (I.n) n| <= mu I.n`.
fn kernel_meets_cone(b: &Matrix3<f64>, n: &Vector3<f64>, mu: f64) -> bool {
    let svd = b.svd(true, true);
    let Some(v_t) = svd.v_t else {
        return false;
    };
    let scale = svd.singular_values.max().max(f64::MIN_POSITIVE);
    let kernel: Vec<Vector3<f64>> = (0..3)
        .filter(|&i| svd.singular_values[i] <= 1e-12 * scale)
        .map(|i| v_t.row(i).transpose())
        .collect();
    let dirs: Vec<Vector3<f64>> = match kernel.as_slice() {
        [] => vec![],
        [k] => vec![*k, -*k],
        [k1, k2, ..] => (0..3600)
            .map(|j| {
                let a = std::f64::consts::TAU * j as f64 / 3600.0;
                k1 * a.cos() + k2 * a.sin()
            })
            .collect(),
    };
    dirs.iter().any(|i| {
        let i_n = i.dot(n);
        i_n > 0.0 && (i - n * i_n).norm() <= mu * i_n * (1.0 + 1e-9)
    })
}

/// The complementarity problem of (3.2), (3.3) at A for the plane example, body 2 sliding to the
/// right and F = n horizontal, enumerated from the matrices of (3.4): the normal acceleration at
/// A is affine in F*_N, acc(F*) = (B_A l F* - B~ F, N), l = N - mu* e_T. A solution either leaves
/// (F* = 0, acc >= 0) or stays (acc = 0, F* >= 0). Returns the count ("none", "unique", "two"),
/// the slope beta and the staying reaction -alpha/beta.
fn complementarity_at_a(
    sm: &crate::models::support::SupportMatrices,
    s: &crate::models::support::Support,
) -> (&'static str, f64, f64) {
    let n_a = s.normal;
    let l = n_a - Vector3::x() * s.mu;
    let f = Vector3::x();
    let acc = |fs: f64| (sm.b_a * (l * fs) - sm.b_tilde * f).dot(&n_a);
    let (a0, slope) = (acc(0.0), acc(1.0) - acc(0.0));
    let leaves = a0 >= 0.0;
    let stays = slope != 0.0 && -a0 / slope >= 0.0;
    let count = usize::from(leaves) + usize::from(stays);
    (["none", "unique", "two"][count], slope, -a0 / slope)
}

/// Which types of motion of A the rigid model admits when A is at rest at the start (section 4,
/// the plane example, F = n horizontal): (detach, roll, slide to +x, slide to -x). Type 1: F* = 0
/// and the normal acceleration of A non-negative; type 2: F* = B_A^-1 B~ F inside the friction
/// cone; type 4: (4.5), kappa e_T = F*_N B_A (N - mu* e_T) - B~ F with kappa > 0, F*_N >= 0.
fn types_at_rest(p: &Plane) -> Option<[bool; 4]> {
    use crate::models::support::matrices;
    let (body, sup) = p.parts();
    let sm = matrices(&body, &sup)?;
    let (f, n) = (Vector3::x(), sup.normal);
    let btf = sm.b_tilde * f;
    let detach = (-btf).dot(&n) >= 0.0;
    let roll = sm.b_a.try_inverse().is_some_and(|inv| {
        let fs = inv * btf;
        let f_n = fs.dot(&n);
        f_n >= 0.0 && (fs - n * f_n).norm() <= p.mu_star * f_n
    });
    let slide = |dir: f64| {
        let e_t = Vector3::x() * dir;
        let l = sm.b_a * (n - e_t * p.mu_star);
        if l.dot(&n) == 0.0 {
            return false;
        }
        let f_n = btf.dot(&n) / l.dot(&n);
        let kappa = (f_n * l.x - btf.x) * dir;
        f_n >= 0.0 && kappa > 0.0
    };
    Some([detach, roll, slide(1.0), slide(-1.0)])
}

/// "Computations show that if a3 < 0, b2 < 0, beta < 0 and (rho2^2 + b2 b3) - b3 a2 (mu*(rho2^2 +
/// b3^2) + a3 b3)/(rho2^2 + a3^2 + mu* a3 b3) < 0, motion of each of the three types 1, 2 and 4
/// is possible" (V_A = 0 at the start): seeded random plane configurations, the printed
/// conditions with beta of (4.8), and the types admitted, computed from the matrices of (3.4).
fn rest_types(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    // the printed forms, from the claims file: m2 rho2^2 beta of (4.8), and the fourth condition
    if c.printed_equations.len() != 2 {
        return Err(bad(
            "printed_equations must give m2 rho2^2 beta of (4.8) and the fourth condition's left side".into(),
        ));
    }
    let printed: Vec<crate::algebra::expr::Expr> = c
        .printed_equations
        .iter()
        .enumerate()
        .map(|(k, t)| {
            crate::algebra::expr::parse(t).map_err(|e| bad(format!("printed_equations[{k}]: {e}")))
        })
        .collect::<Result<_, _>>()?;
    let at = |e: &crate::algebra::expr::Expr, p: &Plane, mu: f64| -> Result<f64, VerifyError> {
        e.eval(&|s| {
            Some(match s {
                "m2" => p.m2,
                "rho2" => p.rho2,
                "a2" => p.a2,
                "b2" => p.b2,
                "a3" => p.a3,
                "b3" => p.b3,
                "mu_star" => mu,
                _ => return None,
            })
        })
        .map_err(bad)
    };
    let mut rng = Rng(0x7E57_0471);
    let (mut n, mut meet, mut all_three, mut beta_neg) = (0, 0, 0, 0);
    let mut example = String::new();
    let mut mirrored = (0, 0);
    for _ in 0..200_000 {
        let p = Plane {
            m2: rng.range(0.2, 5.0),
            rho2: rng.range(0.1, 1.0),
            a2: rng.range(-1.0, 1.0),
            b2: -rng.range(0.01, 1.0),
            a3: -rng.range(0.01, 1.0),
            b3: -rng.range(0.05, 1.0),
            mu_star: rng.range(0.0, 5.0),
        };
        n += 1;
        // as printed: beta of (4.8) (sliding to +x) and the fourth condition
        let beta = at(&printed[0], &p, p.mu_star)?;
        let fourth = |mu: f64| at(&printed[1], &p, mu);
        beta_neg += usize::from(beta < 0.0);
        let Some(t) = types_at_rest(&p) else {
            continue;
        };
        let three = t[0] && t[1] && (t[2] || t[3]);
        if beta < 0.0 && fourth(p.mu_star)? < 0.0 {
            meet += 1;
            all_three += usize::from(three);
        }
        // read with mu* -> -mu* (sliding to -x, the direction in which beta can be negative)
        let beta_m = at(&printed[0], &p, -p.mu_star)?;
        if beta_m < 0.0 && fourth(-p.mu_star)? < 0.0 {
            mirrored.0 += 1;
            mirrored.1 += usize::from(three);
            if !three && example.is_empty() {
                example = format!(
                    "; e.g. m2 = {:.3}, rho2 = {:.3}, G2C = ({:.3}, {:.3}), G2A = ({:.3}, {:.3}), mu* = {:.3}: detach {}, roll {}, slide right {}, slide left {}",
                    p.m2, p.rho2, p.a2, p.b2, p.a3, p.b3, p.mu_star, t[0], t[1], t[2], t[3]
                );
            }
        }
    }
    let verdict = if meet > 0 {
        holds(all_three == meet)
    } else {
        Verdict::Fails
    };
    Ok(outcome(
        paper,
        c,
        verdict,
        format!(
            "{n} seeded plane configurations with a3 < 0, b2 < 0, b3 < 0, mu* in [0, 5]: with beta of (4.8) as printed, beta < 0 in {beta_neg} (m2 rho2^2 beta = {} is positive when a3, b3 < 0), and all four printed conditions in {meet}{}; read with -mu* (sliding to the left, where beta can be negative) the conditions hold in {} configurations, and the rigid model admits all of the types 1, 2 and 4 in {} of them{example}",
            c.printed_equations[0],
            if meet > 0 {
                format!(", of which {all_three} admit all of the types 1, 2 and 4")
            } else {
                ": the printed conditions are never met together".into()
            },
            mirrored.0,
            mirrored.1
        ),
    ))
}

/// The closing result of section 4 with deformable elements at C and A
/// ([`crate::models::deformable`]), as m1/m2 goes to 0 over four decades: in the two-solution
/// case the body leaves the support (no impulse at A); in the no-solution case the deformation at
/// A does not shrink with m1/m2 and the body rebounds; a unique-solution case for contrast, whose
/// support impulse tends to the rigid one.
fn deformable_elements(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    use crate::models::deformable::{Deformable, simulate};
    use crate::models::support::matrices;
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let ratios = [1e-1, 1e-2, 1e-3, 1e-4];
    // m2 = 1, rho2 = 0.5, G2C = (0.2, b2), G2A = (0.5, -0.6), unit springs and speeds
    let case = |b2: f64,
                mu_star: f64|
     -> Result<
        (
            &'static str,
            f64,
            Vec<crate::models::deformable::DeformableOutcome>,
        ),
        VerifyError,
    > {
        let plane = Plane {
            m2: 1.0,
            rho2: 0.5,
            a2: 0.2,
            b2,
            a3: 0.5,
            b3: -0.6,
            mu_star,
        };
        let (body, sup) = plane.parts();
        let sm = matrices(&body, &sup).ok_or_else(|| bad("singular body".into()))?;
        let (kind, _, stay) = complementarity_at_a(&sm, &sup);
        let runs = ratios
            .iter()
            .map(|&r| {
                let p = Deformable {
                    m1: r,
                    m2: 1.0,
                    rho2: 0.5,
                    c: [0.2, b2],
                    a: [0.5, -0.6],
                    mu_star,
                    k_c: 1.0,
                    k_a: 1.0,
                    v0: 1.0,
                    slide: 1.0,
                };
                simulate(&p, 1e-9).map_err(|e| bad(format!("m1/m2 = {r}: {e}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok((kind, stay, runs))
    };
    let part = c.part.clone().unwrap_or_default();
    Ok(match part.as_str() {
        "separation" => {
            let (kind, _, runs) = case(0.5, 2.5)?;
            let worst = runs
                .iter()
                .map(|o| o.impulse_a / o.impulse_c)
                .fold(0.0, f64::max);
            let rebound = runs.iter().all(|o| o.v_a_normal_end > 0.0);
            outcome(
                paper,
                c,
                holds(kind == "two" && worst <= 1e-9 && rebound),
                format!(
                    "b2 = 0.5, mu* = 2.5 (the complementarity problem at A has {kind} solution(s)); springs at C and A, m1/m2 = 1e-1 .. 1e-4: support impulse / impulse at C at most {worst:.2e}, A moving off the support at the end in every run ({})",
                    runs.iter()
                        .zip(ratios)
                        .map(|(o, r)| format!("{r:e}: v_A,N = {:.3e}", o.v_a_normal_end))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        }
        "no-solution" => {
            let (kind, _, runs) = case(-0.5, 2.5)?;
            let (kind_u, stay_u, unique) = case(-0.5, 0.5)?;
            // the deformation at A in units of slide speed * sqrt(m2/k_A) (= 1 here)
            let smallest = runs
                .iter()
                .map(|o| o.max_deformation_a)
                .fold(f64::INFINITY, f64::min);
            let rebound = runs.iter().all(|o| o.v_a_normal_end > 0.0);
            let shrink = unique[3].max_deformation_a / unique[0].max_deformation_a;
            // the same unique case with a support 1e4 times stiffer than C at m1/m2 = 0.1 (A
            // quasi-static): the impulse ratio is the rigid model's -alpha/beta, which ties the
            // deformable model to the matrices of (3.4)
            let stiff = simulate(
                &Deformable {
                    m1: 0.1,
                    m2: 1.0,
                    rho2: 0.5,
                    c: [0.2, -0.5],
                    a: [0.5, -0.6],
                    mu_star: 0.5,
                    k_c: 1.0,
                    k_a: 1e4,
                    v0: 1.0,
                    slide: 1.0,
                },
                1e-9,
            )
            .map_err(|e| bad(e.to_string()))?;
            let limit = stiff.impulse_a / stiff.impulse_c;
            let ok = kind == "none"
                && kind_u == "unique"
                && smallest >= 0.1
                && rebound
                && shrink <= 1e-2;
            outcome(
                paper,
                c,
                holds(ok),
                format!(
                    "b2 = -0.5, mu* = 2.5 (the complementarity problem at A has {kind} solution(s)): the largest compression at A, in units of v_slide sqrt(m2/k_A), is {} for m1/m2 = 1e-1, 1e-2, 1e-3, 1e-4 (never below {smallest:.3}), and the body leaves the support at the end (v_A,N = {}). For contrast, mu* = 0.5 ({kind_u} solution): {} (it shrinks by {shrink:.1e}); with a support 1e4 times stiffer than C (m1/m2 = 0.1) its support impulse / impulse at C is {limit:.4}, the rigid model's -alpha/beta = {stay_u:.4} within 1 %",
                    runs.iter()
                        .map(|o| format!("{:.3}", o.max_deformation_a))
                        .collect::<Vec<_>>()
                        .join(", "),
                    runs.iter()
                        .map(|o| format!("{:.3}", o.v_a_normal_end))
                        .collect::<Vec<_>>()
                        .join(", "),
                    unique
                        .iter()
                        .map(|o| format!("{:.2e}", o.max_deformation_a))
                        .collect::<Vec<_>>()
                        .join(", "),
                ),
            )
        }
        _ => return Err(bad("part must be separation or no-solution".into())),
    })
}

fn plane_support(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    use crate::models::support::{classify_sliding, matrices};
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let part = c.part.clone().unwrap_or_default();
    let mut rng = Rng(0x5EED_0048);
    Ok(match part.as_str() {
        "beta" => {
            // (4.8): m2 rho2^2 beta = a3^2 + rho2^2 + mu* a3 b3, and alpha = gamma a3 b2/(m2 rho2^2)
            let mut worst: f64 = 0.0;
            for _ in 0..200 {
                let p = Plane {
                    m2: rng.range(0.2, 5.0),
                    rho2: rng.range(0.1, 1.0),
                    a2: rng.range(-1.0, 1.0),
                    b2: rng.range(-1.0, 1.0),
                    a3: rng.range(-1.0, 1.0),
                    b3: -rng.range(0.05, 1.0),
                    mu_star: rng.range(0.0, 3.0),
                };
                let (body, s) = p.parts();
                let sm = matrices(&body, &s).ok_or_else(|| bad("singular body".into()))?;
                let cl = classify_sliding(&Vector3::x(), &sm, &s, &Vector3::x());
                let r2 = p.rho2 * p.rho2;
                let beta_printed = (p.a3 * p.a3 + r2 + p.mu_star * p.a3 * p.b3) / (p.m2 * r2);
                let alpha_printed = p.a3 * p.b2 / (p.m2 * r2);
                worst = worst
                    .max((cl.beta - beta_printed).abs() / beta_printed.abs().max(1e-12))
                    .max((cl.alpha - alpha_printed).abs() / alpha_printed.abs().max(1e-12));
            }
            outcome(
                paper,
                c,
                holds(worst <= 1e-10),
                format!(
                    "beta of (4.4) and alpha of (3.6) from the matrices of (3.4), body sliding to the right, F = n (horizontal), 200 seeded plane configurations: max relative difference from (4.8) and alpha = gamma a3 b2/(m2 rho2^2): {worst:.2e}"
                ),
            )
        }
        "btilde" => {
            let p = Plane {
                m2: 1.0,
                rho2: 1.0,
                a2: 0.3,
                b2: 0.7,
                a3: -0.4,
                b3: -0.9,
                mu_star: 0.5,
            };
            let (body, s) = p.parts();
            let sm = matrices(&body, &s).ok_or_else(|| bad("singular body".into()))?;
            let derived = [
                [sm.b_tilde[(0, 0)], sm.b_tilde[(0, 1)]],
                [sm.b_tilde[(1, 0)], sm.b_tilde[(1, 1)]],
            ];
            let printed = [
                [1.0 + p.b2 * p.b3, -p.a3 * p.b2],
                [-p.a2 * p.b3, 1.0 + p.a2 * p.a3],
            ];
            let same =
                (0..2).all(|i| (0..2).all(|j| (derived[i][j] - printed[i][j]).abs() < 1e-12));
            let transposed =
                (0..2).all(|i| (0..2).all(|j| (derived[i][j] - printed[j][i]).abs() < 1e-12));
            outcome(
                paper,
                c,
                holds(same),
                format!(
                    "m2 = rho2 = 1, G2C = (0.3, 0.7), G2A = (-0.4, -0.9): m2 B~ from (3.4) = [[{:.4}, {:.4}], [{:.4}, {:.4}]]; printed [[{:.4}, {:.4}], [{:.4}, {:.4}]]{}",
                    derived[0][0],
                    derived[0][1],
                    derived[1][0],
                    derived[1][1],
                    printed[0][0],
                    printed[0][1],
                    printed[1][0],
                    printed[1][1],
                    if transposed && !same {
                        "; the printed matrix is the transpose (its off-diagonal entries are swapped); alpha as printed follows from the derived one"
                    } else {
                        ""
                    }
                ),
            )
        }
        "classification" => {
            // map over (mu*, a3) for b2 > 0 and b2 < 0: the paper's two/none statement
            let mut disagreements = 0;
            let mut total = 0;
            let mut cls: std::collections::BTreeMap<String, Vec<(f64, f64)>> = Default::default();
            for b2 in [0.5, -0.5] {
                for i in 0..41 {
                    for j in 0..41 {
                        let mu_star = 3.0 * i as f64 / 40.0;
                        let a3 = -1.0 + 2.0 * j as f64 / 40.0;
                        let p = Plane {
                            m2: 1.0,
                            rho2: 0.5,
                            a2: 0.2,
                            b2,
                            a3,
                            b3: -0.6,
                            mu_star,
                        };
                        let (body, s) = p.parts();
                        let sm = matrices(&body, &s).ok_or_else(|| bad("singular body".into()))?;
                        // the complementarity problem of (3.2), (3.3) at A enumerated from the
                        // matrices of (3.4), not from a sign rule: the normal acceleration at A is
                        // affine in F*_N, acc(F*) = (B_A l F* - B~ F, N), l = N - mu* e_T (sliding
                        // to the right, F = n horizontal). A solution either leaves (F* = 0,
                        // acc >= 0) or stays (acc = 0, F* >= 0).
                        let (kind, slope, _) = complementarity_at_a(&sm, &s);
                        if b2 > 0.0 {
                            cls.entry(kind.to_string()).or_default().push((mu_star, a3));
                        }
                        if slope < 0.0 {
                            total += 1;
                            let expect = if b2 > 0.0 { "two" } else { "none" };
                            if kind != expect {
                                disagreements += 1;
                            }
                        }
                    }
                }
            }
            let svg_name = "002_painleve_map.svg".to_string();
            let series: Vec<Series> = cls
                .iter()
                .map(|(k, v)| Series {
                    name: k,
                    points: v.clone(),
                })
                .collect();
            let svg = crate::report::svg::scatter(
                "plane example of section 4 (b2 > 0): solutions of (3.6) with (3.2)/(3.3)",
                "mu* (friction at the support)",
                "a3 (G2A, horizontal)",
                &series,
            );
            outcome(
                paper,
                c,
                holds(disagreements == 0 && total > 0),
                format!(
                    "plane configurations on a 41 x 41 grid of (mu*, a3) with b3 = -0.6, rho2 = 0.5, b2 = +-0.5, the solutions of the complementarity problem at A counted from the matrices of (3.4): {total} have beta < 0; the count disagrees with 'two solutions if b2 > 0, none if b2 < 0' in {disagreements}"
                ),
            )
            .with_plot(
                "classification map",
                svg_name,
                svg,
                crate::report::svg::csv("mu* (friction at the support)", "a3 (G2A, horizontal)", &series),
            )
        }
        _ => return Err(bad("part must be beta, btilde or classification".into())),
    })
}

/// Rates of the rolling-ball problem of section 4 from the general matrices (m = R = 1,
/// rho^2 = 0.4): the second ball slides on the rough table in direction xi, the balls slide at
/// C in direction phi. Returns (m r', m r phi', m r*', m r* xi').
fn rolling_rates(phi: f64, xi: f64, mu: f64, mu_star: f64) -> [f64; 4] {
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

/// The claim's `printed_equations`: the right-hand sides of (4.6), in m = 1 units, parsed once.
fn rolling_equations(c: &ClaimSpec) -> Result<Vec<crate::algebra::expr::Expr>, VerifyError> {
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
fn rolling_eval(
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
/// special case (4.7) (mu = mu*, xi = phi, cos phi = -2/(7 mu)), phi along the model's path.
fn rolling_integrated(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    use crate::models::rigid_impact::{RoughSupport, SupportMode, impact_rough};
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let printed = rolling_equations(c)?;
    let corrected = match &c.corrected {
        Some(t) => crate::algebra::expr::parse(t).map_err(|e| bad(format!("corrected: {e}")))?,
        None => {
            return Err(bad(
                "corrected must give the third equation of (4.6) as derived".into(),
            ));
        }
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
            Vector3::x(),
            v,
            mu,
            Law::Poisson,
            0.5,
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
    corrected_eqs[2] = corrected;
    let mut rng = Rng(0x5EED_0047);
    let (mut worst_p, mut worst_c, mut points) = (0.0f64, 0.0f64, 0usize);
    let mut example = String::new();
    for _ in 0..12 {
        let (phi, xi) = (rng.range(1.8, 3.0), rng.range(-3.0, 3.0));
        let (mu, ms) = (rng.range(0.05, 0.6), rng.range(0.05, 0.6));
        let (wp, n) = compare(&printed, phi, xi, mu, ms)?;
        let (wc, _) = compare(&corrected_eqs, phi, xi, mu, ms)?;
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
        let phi = (-2.0 / (7.0 * mu)).acos();
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
            "the general impact model with the rough table (B of (1.7), B~ and B_A of (3.4), F* = F_N* (N - mu* e_T) with (4.4); Poisson's law, rtol 1e-11) from 12 seeded starts (phi, xi, mu, mu*), both balls sliding: r and phi of V_C at {points} of its steps against (4.6) integrated in the normal impulse while both slips exceed 5 %: as printed, max difference {worst_p:.2e}{example}; with the third equation as derived (corrected), {worst_c:.2e}; the special case (4.7) (mu = mu* = 0.3, 0.5, 1, xi = phi, cos phi = -2/(7 mu)) keeps phi within {special:.2e} along the model's path (tolerance {tol:.0e})"
        ),
    ))
}

fn rolling_ball(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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
            // mu = mu*, xi = phi, cos phi = -2/(7 mu): phi' and xi' vanish (derived rates)
            let mut worst: f64 = 0.0;
            let mut curves = Vec::new();
            for mu in [0.3f64, 0.5, 1.0, 2.0] {
                let phi = (-2.0 / (7.0 * mu)).acos();
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
            let phi_star = (-2.0 / (7.0 * mu)).acos();
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
                "normal impulse I_n (m = 1)",
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
                    "with mu = mu*, xi = phi and cos phi = -2/(7 mu) (mu = 0.3, 0.5, 1, 2) the derived phi' and xi' vanish (max {worst:.2e}, including phi along an integrated trajectory from phi* for mu = 0.5); this uses only the second and fourth equations of (4.6), which the derivation confirms"
                ),
            )
            .with_plot(
                "integral curves of (4.6)",
                svg_name,
                svg,
                crate::report::svg::csv_curves("normal impulse I_n (m = 1)", "phi (degrees)", &curves),
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

fn pendulum_wall(paper: &PaperClaims, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
    use crate::models::pendulum_wall::{PendulumWall, impact as pimpact};
    let bad = |m: String| VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let loss = |rho: f64, sigma: f64| {
        pimpact(rho, sigma, 1e-10)
            .map(|r| r.loss)
            .map_err(|e| bad(e.to_string()))
    };
    let part = c.part.clone().unwrap_or_default();
    Ok(match part.as_str() {
        "condition" => {
            // the special geometry has F_C perpendicular to GO and (GO, GC) = -1: (2.10) is rho = 1
            let peak = |rho: f64| -> Result<f64, VerifyError> {
                use crate::integrate::{Direction, Event};
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
                    .map_err(|e| bad(e.to_string()))?;
                Ok(sol
                    .trajectory
                    .iter()
                    .map(|(_, y)| y[0].abs())
                    .fold(0.0, f64::max))
            };
            let at_one = peak(1.0)?;
            let rows: Vec<(f64, f64)> = [0.5, 0.9, 0.99, 1.01, 1.1, 2.0]
                .iter()
                .map(|&r| peak(r).map(|p| (r, p)))
                .collect::<Result<_, _>>()?;
            let off = rows.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
            let loss_one = loss(1.0, 1.0)?;
            outcome(
                paper,
                c,
                holds(at_one <= 1e-12 && off > 1e-6 && loss_one.abs() <= 1e-12),
                format!(
                    "In the special case of (2.14)-(2.15) F_C is perpendicular to GO and (GO, GC) = -1, so (2.10) is rho = 1. (2.15) integrated (rtol 1e-12, sigma = 1) while the contact is loaded: max |eps_On| = {at_one:.1e} at rho = 1 (no deformation at O; the energy loss (2.13) is {loss_one:.1e}); away from it: {}",
                    rows.iter()
                        .map(|(r, p)| format!("rho = {r}: {p:.2e}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        }
        "derivation" => {
            // (2.8) with the special geometry: GO = t, GC = -t - d n, F_C = c1 eps_Cn n, F_O = c2 eps_O
            let mut rng = Rng(0x5EED_0215);
            let mut worst: f64 = 0.0;
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
                    + (gc * gc.dot(&fc) - fc * gc.dot(&gc) + go * gc.dot(&fo) - fo * go.dot(&gc))
                        * r2;
                let acc_o = -(fc + fo)
                    + (gc * go.dot(&fc) - fc * go.dot(&gc) + go * go.dot(&fo) - fo * go.dot(&go))
                        * r2;
                let sys = PendulumWall { rho, sigma };
                let mut dy = [0.0; 4];
                sys.rhs(0.0, &[eo, ec, 0.0, 0.0], &mut dy);
                worst = worst
                    .max((acc_o.y - dy[2]).abs())
                    .max((acc_c.y - dy[3]).abs())
                    .max(acc_o.x.abs());
            }
            outcome(
                paper,
                c,
                holds(worst <= 1e-12),
                format!(
                    "the normal components of (2.8) in the special geometry (m = 1, GO along the wall, (GO, GC) = -1, any distance d of G from the wall) against (2.15) at 200 seeded states: max difference {worst:.2e}; the tangential equation of O vanishes (eps_Ot = 0)"
                ),
            )
        }
        "figure" => {
            let sigmas: Vec<f64> = (1..=250).map(|k| 0.02 * k as f64).collect();
            let mut lines = Vec::new();
            let mut curves = Vec::new();
            let mut ok = true;
            for (rho, printed) in [(0.5, 0.36), (2.0, 0.53)] {
                let vals = sigmas
                    .iter()
                    .map(|s| loss(rho, *s))
                    .collect::<Result<Vec<_>, _>>()?;
                let (imax, vmax) =
                    vals.iter().enumerate().fold(
                        (0, f64::MIN),
                        |a, (i, v)| if *v > a.1 { (i, *v) } else { a },
                    );
                let at_one = (sigmas[imax] - 1.0).abs() <= 0.021;
                let close = (vmax - printed).abs() <= 0.02;
                ok &= at_one && close;
                lines.push(format!(
                    "rho = {rho}: maximum loss {:.1}% at sigma = {:.2} (printed: about {:.0}% at sigma = 1)",
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
                "sigma = c1/c2",
                "-dT/T0",
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
                "Relative energy loss -dT/T0 in % (T0: the pendulum's kinetic energy before impact; the loss is what is dissipated while the suspension point O is braked after the contact unloads, (2.13)):\n\n| sigma = c1/c2 | rho = 0.5 | rho = 2 |\n|---|---|---|\n{}",
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
                crate::report::svg::csv_curves("sigma = c1/c2", "-dT/T0", &curves),
            );
            o.extra_md = Some(format!("{table}\n\n{}", o.extra_md.unwrap_or_default()));
            o
        }
        "fifteen" => {
            let mut worst: Vec<String> = Vec::new();
            let mut ok = true;
            for (lo, hi) in [(0.02, 0.3), (0.7, 1.4), (3.0, 10.0)] {
                let mut m = (0.0f64, 0.0, 0.0);
                // interior points only: the intervals are open
                for i in 1..12 {
                    let rho = lo + (hi - lo) * i as f64 / 12.0;
                    for k in 1..=50 {
                        let sigma = 0.1 * k as f64 - 0.001;
                        let l = loss(rho, sigma)?;
                        if l > m.0 {
                            m = (l, rho, sigma);
                        }
                    }
                }
                ok &= m.0 <= 0.15;
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
                    "same computation and normalisation as Fig. 2, sigma in (0, 5): {}",
                    worst.join("; ")
                ),
            )
        }
        _ => return Err(bad("part must be derivation, figure or fifteen".into())),
    })
}
