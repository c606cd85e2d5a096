//! The catalogue of hard cases: for each, what makes it hard and what the tool must do, finish
//! within the tolerance (measured against an independent reference: a closed form, a second
//! method, or an exact evaluation) or stop with a clear diagnosis. Scenes live in
//! `tests/hard_cases/`; `tests/hard_cases/main.rs` runs the catalogue and `verify` reports it in
//! `reports/hard_cases.md`, with the bad-input table of [`bad_inputs`].

use crate::models::rigid_impact::Contact;
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use serde_json::Value;
use std::path::Path;

/// One hard case's outcome.
#[derive(Clone, Debug, Serialize)]
pub struct HardCase {
    /// Identifier.
    pub id: String,
    /// What is run.
    pub what: String,
    /// What makes it hard.
    pub hard: String,
    /// Method used.
    pub method: String,
    /// Steps taken (accepted steps of the integrator), where one runs.
    pub steps: Option<usize>,
    /// Error achieved against the reference.
    pub error: Option<f64>,
    /// The tolerance it must meet.
    pub tolerance: Option<f64>,
    /// The reference the error is measured against.
    pub reference: String,
    /// "finished within tolerance", "stopped with a diagnosis: ...", or "FAILED: ...".
    pub outcome: String,
    /// Whether the tool did what it must.
    pub ok: bool,
}

struct Case {
    id: &'static str,
    what: String,
    hard: &'static str,
    method: String,
    steps: Option<usize>,
    error: Option<f64>,
    tolerance: Option<f64>,
    reference: &'static str,
}

impl Case {
    fn finish(self) -> HardCase {
        let ok = match (self.error, self.tolerance) {
            (Some(e), Some(t)) => e <= t,
            _ => false,
        };
        let outcome = if ok {
            "finished within tolerance".to_string()
        } else {
            format!(
                "FAILED: error {:?} against tolerance {:?}",
                self.error, self.tolerance
            )
        };
        self.with(outcome, ok)
    }
    fn finish_noting(self, note: Option<&str>) -> HardCase {
        let mut h = self.finish();
        if let Some(n) = note {
            h.outcome = format!("{}; {n}", h.outcome);
        }
        h
    }
    fn with(self, outcome: String, ok: bool) -> HardCase {
        HardCase {
            id: self.id.into(),
            what: self.what,
            hard: self.hard.into(),
            method: self.method,
            steps: self.steps,
            error: self.error,
            tolerance: self.tolerance,
            reference: self.reference.into(),
            outcome,
            ok,
        }
    }
}

fn scene_json(root: &Path, file: &str) -> Result<Value, String> {
    let scene =
        crate::scene::load(&root.join("tests/hard_cases").join(file)).map_err(|e| e.to_string())?;
    scene.run().map(|(v, _)| v).map_err(|e| e.to_string())
}

fn with_method(root: &Path, file: &str, method: &str, rtol: f64) -> Result<Value, String> {
    let mut t = crate::scene::read_table(&root.join("tests/hard_cases").join(file))
        .map_err(|e| e.to_string())?;
    if let Some(toml::Value::Table(s)) = t.get_mut("solve") {
        s.insert("method".into(), toml::Value::String(method.into()));
        s.insert("rtol".into(), toml::Value::Float(rtol));
    }
    let scene = crate::scene::parse_table(&t, file).map_err(|e| e.to_string())?;
    scene.run().map(|(v, _)| v).map_err(|e| e.to_string())
}

fn num(v: &Value, path: &[&str]) -> Option<f64> {
    path.iter().try_fold(v, |v, k| v.get(k))?.as_f64()
}

fn failed(id: &'static str, what: String, hard: &'static str, e: String) -> HardCase {
    Case {
        id,
        what,
        hard,
        method: "-".into(),
        steps: None,
        error: None,
        tolerance: None,
        reference: "-",
    }
    .with(format!("FAILED: {e}"), false)
}

/// The cone at extreme viscosity: the tested run (Auto, rtol 1e-8) against Radau5 at rtol 1e-12.
fn cone(root: &Path, id: &'static str, file: &'static str, what: &str) -> HardCase {
    let hard = "the memory rate lambda = E/eta spans 10 decades: stiff at one end, nearly elastic at the other";
    let run = (|| {
        let v = scene_json(root, file)?;
        let r = with_method(root, file, "radau5", 1e-12)?;
        Ok::<_, String>((v, r))
    })();
    match run {
        Err(e) => failed(id, what.into(), hard, e),
        Ok((v, r)) => {
            // the maximum indentation (located by an event) and the final energy over the
            // initial one; the duration is ill-conditioned when the force returns to zero
            // tangentially, and the run warns when it does
            let rel = |k: &[&str]| {
                let (a, b) = (
                    num(&v, k).unwrap_or(f64::NAN),
                    num(&r, k).unwrap_or(f64::NAN),
                );
                (a - b).abs() / b.abs()
            };
            let e0 = num(&r, &["energy", "initial"]).unwrap_or(f64::NAN);
            let err = worse(
                rel(&["contact", "max_indentation"]),
                (num(&v, &["energy", "final"]).unwrap_or(f64::NAN)
                    - num(&r, &["energy", "final"]).unwrap_or(f64::NAN))
                .abs()
                    / e0,
            );
            let tangential = v["warnings"].as_array().is_some_and(|w| {
                w.iter()
                    .any(|x| x.as_str().is_some_and(|s| s.contains("tangentially")))
            });
            Case {
                id,
                what: what.into(),
                hard,
                method: v["method"].as_str().unwrap_or("?").into(),
                steps: num(&v, &["stats", "steps"]).map(|s| s as usize),
                error: Some(err),
                tolerance: Some(1e-6),
                reference: "Radau5 at rtol 1e-12 (max indentation, relative; final energy over the initial)",
            }
            .finish_noting(tangential.then_some("the run warned that the contact force returns to zero tangentially (duration ill-conditioned)"))
        }
    }
}

/// The pendulum (2.15) by closed form: release time and energy loss.
fn pendulum_reference(rho: f64, sigma: f64) -> (f64, f64) {
    let cf = crate::models::pendulum_wall::ClosedForm::new(rho, sigma);
    let t_rel = cf.release();
    let v_on = -cf.state(t_rel)[2];
    let loss = 0.5 * v_on * v_on * (1.0 - 1.0 / (rho * rho + 1.0)) / ((1.0 + rho * rho) / 8.0);
    (t_rel, loss)
}

fn pendulum(id: &'static str, sigma: f64) -> HardCase {
    let rho = 0.5;
    let hard = "stiffness ratio far from 1: the two elements' time scales differ by 6 decades (stiff), the slow one spanning many fast periods";
    let what = format!("pendulum-wall, rho = {rho}, sigma = {sigma:e}, rtol 1e-9");
    match crate::models::pendulum_wall::impact(rho, sigma, 1e-9) {
        Err(e) => failed(id, what, hard, e.to_string()),
        Ok(r) => {
            let (t_ref, loss_ref) = pendulum_reference(rho, sigma);
            Case {
                id,
                what,
                hard,
                method: "auto".into(),
                steps: Some(r.steps),
                error: Some(worse(
                    (r.duration - t_ref).abs() / t_ref,
                    (r.loss - loss_ref).abs(),
                )),
                tolerance: Some(1e-6),
                reference: "closed form: normal modes of (2.15), release time by bisection (relative time error, absolute loss error)",
            }
            .finish()
        }
    }
}

fn hertz(
    root: &Path,
    id: &'static str,
    file: &'static str,
    what: &str,
    hard: &'static str,
) -> HardCase {
    let run = scene_json(root, file).and_then(|v| {
        let scene = crate::scene::load(&root.join("tests/hard_cases").join(file))
            .map_err(|e| e.to_string())?;
        Ok((v, scene))
    });
    match run {
        Err(e) => failed(id, what.into(), hard, e),
        Ok((v, scene)) => {
            let Some(s) = scene.get::<crate::models::hertz::HertzScene>() else {
                return failed(id, what.into(), hard, "not a hertz scene".into());
            };
            let model = crate::models::hertz::Hertz {
                mass: s.mass,
                k: s.k,
                damping: 0.0,
                law: s.law,
            };
            let exact = model.undamped_duration(s.v0);
            let d = num(&v, &["contact", "duration"]).unwrap_or(f64::NAN);
            let v_out = num(&v, &["v_out"]).unwrap_or(f64::NAN);
            Case {
                id,
                what: what.into(),
                hard,
                method: v["method"].as_str().unwrap_or("?").into(),
                steps: num(&v, &["stats", "steps"]).map(|s| s as usize),
                error: Some(worse(
                    (d - exact).abs() / exact,
                    (v_out + s.v0).abs() / s.v0,
                )),
                tolerance: Some(1e-6),
                reference: "closed form: contact time 3.2180654597 (m/k)^(2/5) v0^(-1/5), exit speed v0 (relative)",
            }
            .finish()
        }
    }
}

/// The largest componentwise difference of two impulses.
fn impulse_diff(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).abs()).fold(0.0, f64::max)
}

/// How the rigid-impact model integrates (the Keller equations in the normal impulse).
const RIGID_METHOD: &str = "auto (DOP853, Radau5 once stiffness is detected) in the normal impulse, events on slip and phase";

/// A particle (B = I/m) whose slip stops exactly when compression ends.
fn slip_stops_at_compression_end() -> HardCase {
    use crate::models::rigid_impact::{Contact, Law, impact_with_matrix};
    let (mu, e) = (0.5, 0.5);
    let b = Matrix3::identity();
    let v = Vector3::new(mu, 0.0, -1.0);
    let what = "rigid impact of a particle (B = I), mu = 0.5, e = 0.5 (Poisson), V- = (0.5, 0, -1)"
        .to_string();
    let hard = "the slip speed reaches zero exactly at the end of compression: the stick switch and the phase switch coincide";
    match impact_with_matrix(
        &b,
        Contact::new(Vector3::z(), v, mu, Law::Poisson, e),
        1e-10,
    ) {
        Err(err) => failed("slip-stops-at-compression-end", what, hard, err.to_string()),
        Ok(r) => {
            // slip for p in [0, 1] takes (-0.5, 0, 1), then sticking restitution adds (0, 0, 0.5)
            let exact = [-0.5, 0.0, 1.5];
            let err = impulse_diff(r.impulse, exact);
            Case {
                id: "slip-stops-at-compression-end",
                what,
                hard,
                method: RIGID_METHOD.into(),
                steps: Some(r.stats.steps),
                error: Some(err),
                tolerance: Some(1e-8),
                reference: "closed form: I = (-0.5, 0, 1.5) by hand (sliding then sticking)",
            }
            .finish()
        }
    }
}

/// mu within 1e-12 of the stick threshold mu* = |B_tt^-1 B_tn|: both sides finish and agree.
fn stick_slip_threshold() -> HardCase {
    use crate::models::rigid_impact::{Law, impact_with_matrix};
    let b = Matrix3::new(2.0, 0.0, 0.6, 0.0, 2.0, 0.0, 0.6, 0.0, 1.0);
    let mu_star = 0.3;
    let v = Vector3::new(0.05, 0.0, -1.0);
    let what = "rigid impact with B coupling slip and normal (mu* = 0.3), mu = mu* (1 -+ 1e-12), V- = (0.05, 0, -1)".to_string();
    let hard = "mu at the stick/slip threshold: after the slip stops, sticking is only just possible (or only just not)";
    let run = |mu: f64| {
        impact_with_matrix(
            &b,
            Contact::new(Vector3::z(), v, mu, Law::Poisson, 0.5),
            1e-10,
        )
    };
    match (run(mu_star * (1.0 - 1e-12)), run(mu_star * (1.0 + 1e-12))) {
        (Ok(a), Ok(c)) => {
            let err = impulse_diff(a.impulse, c.impulse);
            Case {
                id: "stick-slip-threshold",
                what,
                hard,
                method: RIGID_METHOD.into(),
                steps: Some(a.stats.steps.max(c.stats.steps)),
                error: Some(err),
                tolerance: Some(1e-8),
                reference: "continuity: the impulse on either side of the threshold (it must not jump)",
            }
            .finish()
        }
        (Err(e), _) | (_, Err(e)) => failed("stick-slip-threshold", what, hard, e.to_string()),
    }
}

/// Slip dying out just above the stick threshold (mu = 1.382, mu* = 1.371): near |V_t| = 0 the
/// slip direction relaxes at a rate that grows like 1/|V_t|, so the Keller equations turn stiff.
fn stiff_slip_stop() -> HardCase {
    use crate::models::rigid_impact::{Law, impact_with_matrix};
    let (b, v, mu, e) = crate::models::samples::rigid_inputs_generic(448);
    let what = format!(
        "rigid impact #448 of the sweep benchmark: random SPD B, mu = {mu:.4} just above the stick threshold mu* = 1.3710, e = {e:.3} (Poisson), rtol 1e-10"
    );
    let hard = "the slip stops slowly just above the stick threshold: the slip direction's relaxation rate grows like 1/|V_t|, the equations turn stiff and an explicit method stalls (DOP853 needed more than 1e5 steps)";
    let run = |rtol: f64| {
        impact_with_matrix(
            &b,
            Contact::new(nalgebra::Vector3::z(), v, mu, Law::Poisson, e),
            rtol,
        )
    };
    match (run(1e-10), run(1e-13)) {
        (Ok(a), Ok(r)) => {
            let scale = Vector3::from(r.impulse).norm();
            let err = impulse_diff(a.impulse, r.impulse) / scale;
            Case {
                id: "stiff-slip-stop",
                what,
                hard,
                method: RIGID_METHOD.into(),
                steps: Some(a.stats.steps),
                error: Some(err),
                tolerance: Some(1e-8),
                reference: "the same impact at rtol 1e-13 (relative impulse)",
            }
            .finish()
        }
        (Err(e), _) | (_, Err(e)) => failed("stiff-slip-stop", what, hard, e.to_string()),
    }
}

/// B nearly singular along a direction mixing n and t: the frictionless impulse in closed form.
fn near_singular_b() -> HardCase {
    use crate::models::rigid_impact::{Law, impact_with_matrix};
    let q = nalgebra::Rotation3::from_euler_angles(0.3, 0.7, 0.2).into_inner();
    let b = q * Matrix3::from_diagonal(&Vector3::new(1.0, 0.5, 1e-12)) * q.transpose();
    let v = Vector3::new(0.3, 0.1, -1.0);
    let what = "rigid impact with B of condition number 1e12 (a line through C nearly meets both fixed sets), mu = 0, e = 0.5".to_string();
    let hard = "B* nearly singular: the impulse needed to stop the approach is huge along the near-null direction";
    match impact_with_matrix(
        &b,
        Contact::new(Vector3::z(), v, 0.0, Law::Poisson, 0.5),
        1e-10,
    ) {
        Err(e) => failed("near-singular-b", what, hard, e.to_string()),
        Ok(r) => {
            let p = 1.5 / b[(2, 2)];
            let err = (r.impulse[2] - p).abs() / p + r.impulse[0].abs().max(r.impulse[1].abs()) / p;
            Case {
                id: "near-singular-b",
                what,
                hard,
                method: RIGID_METHOD.into(),
                steps: Some(r.stats.steps),
                error: Some(err),
                tolerance: Some(1e-9),
                reference: "closed form: I = (1 + e) |V_n-|/(B n, n) n (frictionless)",
            }
            .finish()
        }
    }
}

/// beta of (3.6)/(4.4) crossing zero as the support friction mu* passes its critical value.
fn beta_crossing_zero() -> HardCase {
    use crate::models::rigid_impact::Body;
    use crate::models::support::{Support, classify_sliding, matrices};
    let body = Body {
        mass: Some(1.0),
        inertia: Matrix3::from_diagonal(&Vector3::new(0.02, 0.02, 0.02)),
        offset: Vector3::new(0.0, 0.0, 0.2),
    };
    let g2a = Vector3::new(0.15, 0.0, -0.2);
    let e_t = Vector3::x();
    let n = Vector3::z();
    let what = "rough support under the second body, sliding along x, mu* at its critical value (beta = 0) and 1e-12 either side; contact force along -x - z and -x + z".to_string();
    let hard = "beta of (3.6) crosses zero: F_N* = -alpha/beta passes through infinity and the solution count changes (Painleve)";
    let sm0 = |mu: f64| {
        let s = Support {
            offset: g2a,
            normal: n,
            mu,
        };
        matrices(&body, &s).map(|m| (m, s))
    };
    let Some((m0, _)) = sm0(0.0) else {
        return failed("beta-crossing-zero", what, hard, "singular inertia".into());
    };
    // beta(mu*) = (B_A (N - mu* e_t), N) = b0 - mu* b1
    let (b0, b1) = ((m0.b_a * n).dot(&n), (m0.b_a * e_t).dot(&n));
    let mu_c = b0 / b1;
    let mut bad = Vec::new();
    let mut checked = 0;
    for f in [Vector3::new(-1.0, 0.0, -1.0), Vector3::new(-1.0, 0.0, 1.0)] {
        for mu in [mu_c * (1.0 - 1e-12), mu_c, mu_c * (1.0 + 1e-12)] {
            let Some((m, s)) = sm0(mu) else { continue };
            let c = classify_sliding(&f, &m, &s, &e_t);
            checked += 1;
            // the rule of section 4: beta > 0 -> one solution; beta < 0 -> none (alpha < 0) or
            // two (alpha > 0); beta = 0 -> detach only if alpha >= 0
            let expect = if c.beta > 0.0 {
                "unique"
            } else if c.beta < 0.0 {
                if c.alpha < 0.0 { "none" } else { "two" }
            } else if c.alpha >= 0.0 {
                "unique"
            } else {
                "none"
            };
            if !c.alpha.is_finite() || !c.beta.is_finite() || c.kind != expect {
                bad.push(format!("mu* = {mu:e}: {} (beta {:e})", c.kind, c.beta));
            }
        }
    }
    let case = Case {
        id: "beta-crossing-zero",
        what,
        hard,
        method: "classification (3.6)-(3.7), (4.4)".into(),
        steps: None,
        error: Some(bad.len() as f64),
        tolerance: Some(0.0),
        reference: "the sign rule of section 4 (beta > 0: one motion; beta < 0: none or two)",
    };
    if bad.is_empty() {
        case.with(
            format!("finished: {checked} classifications follow the sign rule, none NaN (mu*_c = {mu_c:.12})"),
            true,
        )
    } else {
        let msg = bad.join("; ");
        case.with(format!("FAILED: {msg}"), false)
    }
}

/// The elliptic forms at k = 1 -+ 1e-15 against the quadrature about the instantaneous centre.
fn elliptic_near_one() -> HardCase {
    use crate::models::disk_friction::{force_moment_elliptic, friction};
    let mut err: f64 = 0.0;
    for k in [1.0 - 1e-15, 1.0 - 1e-12, 1.0 + 1e-15] {
        let r = friction([k, 0.0], 1.0, [0.0, 0.0], 1.0, 1e-14);
        let (fe, me) = force_moment_elliptic(k);
        err = worse(
            worse(err, (r.force[0].hypot(r.force[1]) - fe).abs()),
            (-r.moment - me).abs(),
        );
    }
    Case {
        id: "elliptic-k-near-1",
        what: "disk friction F, M at k = 1 - 1e-15, 1 - 1e-12, 1 + 1e-15".into(),
        hard: "K(k) diverges logarithmically at k = 1 and m = k^2 rounds away the distance to 1",
        method: "Carlson R_F, R_D with m_c = (1-k)(1+k)".into(),
        steps: None,
        error: Some(err),
        tolerance: Some(1e-12),
        reference: "quadrature about the instantaneous centre (exact in r, adaptive in angle)",
    }
    .finish()
}

/// a2 of the series with alpha within 1e-12 of gamma: the evaluator against its 448-bit path.
fn series_alpha_near_gamma() -> HardCase {
    use crate::algebra::eval::Evaluator;
    use crate::algebra::poly::parse_q;
    use crate::algebra::series::{self, SeriesParams, Viscous};
    let what =
        "a2 of the series (19)-(22) with alpha = 1000, gamma = 1000 (1 + 1e-12), t = 1e-9 .. 2e-2"
            .to_string();
    let hard =
        "every part of a2 carries 1/(alpha - gamma)^j: the closed forms cancel to the last digit";
    let run = || -> Result<(f64, usize, usize), String> {
        let mut p = SeriesParams::symbolic();
        for (k, v) in [
            ("alpha", "1000"),
            ("gamma", "1000000000001/1000000000"),
            ("v0", "5"),
            ("a8", "14000000"),
            ("a9", "140000"),
        ] {
            p.set(k, parse_q(v).ok_or("bad rational")?)
                .map_err(|e| e.to_string())?;
        }
        let a2 = series::adomian_terms(&p, 2, Viscous::TwoZZ).remove(2);
        let ev = Evaluator::new(&a2).map_err(|e| e.to_string())?;
        let mut worst: f64 = 0.0;
        let (mut n, mut by_taylor) = (0, 0);
        for i in 0..=14 {
            let t = 1e-9 * (2e7f64).powf(i as f64 / 14.0);
            let v = ev.eval(t).map_err(|e| e.to_string())?;
            // the 448-bit path refuses where more than 300 bits cancel (tiny t): there the
            // exact Taylor series, summed in rationals at the binary value of t, is the reference
            let hp = match ev.high_precision(t) {
                Ok(x) => x,
                Err(_) => {
                    by_taylor += 1;
                    exact_taylor(&a2, t)?
                }
            };
            let rel = (v - hp).abs() / hp.abs();
            // a reference that is not a finite number is a failed reference, never skipped
            // (f64::max would drop a NaN)
            if !rel.is_finite() {
                return Err(format!(
                    "at t = {t:e} the reference is {hp:e} and the evaluator gives {v:e}"
                ));
            }
            worst = worse(worst, rel);
            n += 1;
        }
        Ok((worst, n, by_taylor))
    };
    match run() {
        Err(e) => failed("series-alpha-near-gamma", what, hard, e),
        Ok((err, n, by_taylor)) => Case {
            id: "series-alpha-near-gamma",
            what: format!(
                "{what} ({n} points, {by_taylor} of them against the exact Taylor series)"
            ),
            hard,
            method: "evaluator: direct, exact Taylor or fixed point by measured condition number".into(),
            steps: None,
            error: Some(err),
            tolerance: Some(1e-12),
            reference: "the 448-bit fixed-point evaluation of the exact expression, or below t = 1e-5 where it cancels more than 300 bits the exact Taylor series summed in rationals (relative)",
        }
        .finish(),
    }
}

/// The larger of two errors, NaN if either is (`f64::max` drops a NaN: a missing or undefined
/// reference must fail a case, never vanish from it).
fn worse(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

fn exact_taylor(e: &crate::algebra::expo::Expo, t: f64) -> Result<f64, String> {
    use num_traits::{ToPrimitive, Zero};
    let tq = crate::algebra::poly::Q::from_float(t).ok_or("t not finite")?;
    let mut acc = crate::algebra::poly::Q::zero();
    for n in 0..40u32 {
        let c = e.taylor_coeff(n).as_constant().ok_or("not numeric")?;
        acc += c * tq.pow(n as i32);
    }
    acc.to_f64()
        .filter(|x| x.is_finite())
        .ok_or_else(|| "the exact Taylor sum is not a finite f64".to_string())
}

/// The paper's constant-bulk law over a long window: must stop with the growing-mode diagnosis.
fn growing_mode(root: &Path) -> HardCase {
    let what =
        "cone-plate, constant-bulk law (000 (11)-(12)), all effects, t_end = 2e-3 s".to_string();
    let hard = "the law's operator has a growing mode: the solution blows up, and a bare 'step too small' would hide why";
    let case = |outcome: String, ok: bool| {
        Case {
            id: "cone-growing-mode",
            what: what.clone(),
            hard,
            method: "auto".into(),
            steps: None,
            error: None,
            tolerance: None,
            reference: "must stop with the growing mode's rate named",
        }
        .with(outcome, ok)
    };
    match scene_json(root, "cone_growing_mode.toml") {
        Ok(_) => case("FAILED: finished without a diagnosis".into(), false),
        Err(e) if e.contains("not passive") && e.contains("growing mode") => {
            case(format!("stopped with a diagnosis: {e}"), true)
        }
        Err(e) => case(format!("FAILED: stopped without the diagnosis: {e}"), false),
    }
}

/// Runs the whole catalogue (`root`: the repository, for `tests/hard_cases/`).
pub fn catalogue(root: &Path) -> Vec<HardCase> {
    vec![
        cone(
            root,
            "cone-lambda-1e-2",
            "cone_lambda_1e-2.toml",
            "cone on a Kelvin-Voigt half-space, lambda = E/eta = 1e-2 1/s (very viscous), rtol 1e-8",
        ),
        cone(
            root,
            "cone-lambda-1e8",
            "cone_lambda_1e8.toml",
            "cone on a Kelvin-Voigt half-space, lambda = E/eta = 1e8 1/s (nearly elastic), rtol 1e-8",
        ),
        growing_mode(root),
        pendulum("pendulum-sigma-1e-6", 1e-6),
        pendulum("pendulum-sigma-1e6", 1e6),
        hertz(
            root,
            "hertz-grazing",
            "hertz_grazing.toml",
            "Hertz impact at v0 = 1e-9 m/s (m = 1 kg, k = 1e9 N/m^1.5), rtol 1e-8",
            "a grazing impact: indentations of 1e-12 m, far below a default absolute tolerance",
        ),
        hertz(
            root,
            "si-20-orders",
            "hertz_20_orders.toml",
            "Hertz impact with m = 1e-12 kg, k = 1e8 N/m^1.5, v0 = 1e-3 m/s (20 decades in one scene), rtol 1e-8",
            "SI parameters spanning 20 orders of magnitude: scales must not leak into tolerances",
        ),
        slip_stops_at_compression_end(),
        stick_slip_threshold(),
        stiff_slip_stop(),
        near_singular_b(),
        beta_crossing_zero(),
        elliptic_near_one(),
        series_alpha_near_gamma(),
    ]
}

/// One bad scene and the message it gets.
#[derive(Clone, Debug, Serialize)]
pub struct BadInput {
    /// What is wrong.
    pub case: String,
    /// The error message (empty if, wrongly, it was accepted).
    pub message: String,
    /// Whether the message names the field and the allowed range (or the parse position).
    pub ok: bool,
}

/// The bad-input table: each scene text, parsed, must give one clear error naming the file, the
/// field and what is allowed. `(case, scene text, words the message must contain)`.
pub fn bad_input_cases(root: &Path) -> Vec<(&'static str, String, Vec<&'static str>)> {
    let hertz = "model = \"hertz\"\n[impactor]\nmass = 1.0\nv0 = 1.0\n[contact]\nk = 1.0\n";
    let cone = std::fs::read_to_string(root.join("scenes/cone_plate.toml")).unwrap_or_default();
    let rigid = std::fs::read_to_string(root.join("scenes/rigid_impact.toml")).unwrap_or_default();
    vec![
        (
            "unknown model",
            hertz.replace("hertz", "hetrz"),
            vec!["model", "did you mean \"hertz\""],
        ),
        (
            "unknown effect",
            cone.replace("\"membrane\"", "\"membrain\""),
            vec!["effects", "membrane"],
        ),
        (
            "an effect without its parameters",
            cone.replace("kw = 1.0e6\n", ""),
            vec!["foundation.kw", "kw"],
        ),
        (
            "negative mass",
            hertz.replace("mass = 1.0", "mass = -1.0"),
            vec!["impactor.mass", "mass > 0"],
        ),
        (
            "zero mass",
            hertz.replace("mass = 1.0", "mass = 0.0"),
            vec!["impactor.mass", "mass > 0"],
        ),
        (
            "nu outside (-1, 0.5)",
            cone.replace("nu = 0.3", "nu = 0.5"),
            vec!["material.nu", "0.5"],
        ),
        (
            "theta not in (0, 90) degrees",
            cone.replace("theta_deg = 60.0", "theta_deg = 90.0"),
            vec!["impactor.theta_deg", "90"],
        ),
        (
            "non-finite number (nan)",
            hertz.replace("v0 = 1.0", "v0 = nan"),
            vec!["impactor.v0", "NaN"],
        ),
        (
            "non-finite number (inf)",
            hertz.replace("k = 1.0", "k = inf"),
            vec!["contact.k", "inf"],
        ),
        (
            "inertia not symmetric",
            rigid.replace("[0.0, 0.003, 0.0001]", "[0.0, 0.003, 0.0002]"),
            vec!["inertia", "symmetric"],
        ),
        (
            "inertia not positive-definite",
            rigid.replace("0.0025]]", "-0.0025]]"),
            vec!["inertia", "positive-definite"],
        ),
        (
            "mu < 0",
            rigid.replace("mu = 0.3", "mu = -0.1"),
            vec!["contact.mu", "mu >= 0"],
        ),
        (
            "e outside [0, 1]",
            rigid.replace("e = 0.6", "e = 1.2"),
            vec!["contact.e", "1"],
        ),
        (
            "malformed TOML",
            "model = \"hertz\"\n[impactor\nmass = 1\n".into(),
            vec!["not valid TOML"],
        ),
        (
            "truncated TOML",
            hertz[..hertz.len() - 7].to_string(),
            vec!["not valid TOML", "line 6"],
        ),
        (
            "unknown key, near miss",
            hertz.replace("v0 = 1.0", "vo = 1.0"),
            vec!["impactor.vo", "did you mean impactor.v0"],
        ),
        (
            "wrong type",
            hertz.replace("mass = 1.0", "mass = \"heavy\""),
            vec!["impactor.mass", "a number"],
        ),
        (
            "disk pressure centre beyond a/4",
            "model = \"disk-friction\"\na = 1.0\nk = 0.5\nc = 0.3\n".into(),
            vec!["c =", "a/4"],
        ),
    ]
}

/// Parses every bad-input case (`root`: the repository, for the base scenes).
pub fn bad_inputs(root: &Path) -> Vec<BadInput> {
    bad_input_cases(root)
        .into_iter()
        .map(
            |(case, text, words)| match crate::scene::parse(&text, "bad.toml") {
                Ok(_) => BadInput {
                    case: case.into(),
                    message: String::new(),
                    ok: false,
                },
                Err(e) => {
                    let message = e.to_string();
                    let ok = message.starts_with("bad.toml")
                        && words.iter().all(|w| message.contains(w));
                    BadInput {
                        case: case.into(),
                        message,
                        ok,
                    }
                }
            },
        )
        .collect()
}

fn esc(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// The catalogue as a Markdown table.
pub fn table(cases: &[HardCase]) -> String {
    let mut out = String::from(
        "| case | what | method | steps | error | tolerance | reference | outcome |\n|---|---|---|---|---|---|---|---|\n",
    );
    for c in cases {
        out.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} |\n",
            c.id,
            esc(&c.what),
            esc(&c.method),
            c.steps.map_or("-".into(), |s| s.to_string()),
            c.error.map_or("-".into(), |e| format!("{e:.1e}")),
            c.tolerance.map_or("-".into(), |e| format!("{e:.0e}")),
            esc(&c.reference),
            esc(&c.outcome)
        ));
    }
    out
}

/// The bad-input cases as a Markdown table.
pub fn bad_table(bad: &[BadInput]) -> String {
    let mut out = String::from(
        "Each scene is parsed as `bad.toml`; `impact run` exits with code 2 on each.\n\n| bad input | message | names field and range |\n|---|---|---|\n",
    );
    for b in bad {
        out.push_str(&format!(
            "| {} | {} | {} |\n",
            b.case,
            esc(&b.message),
            if b.ok { "yes" } else { "NO" }
        ));
    }
    out
}

/// The named checks of the hard cases, by the name a claim's `check` gives.
pub const CHECKS: &[(&str, super::NamedFn)] = &[
    ("hard-case", |n, p, c| hard_case(p, c, n.root)),
    ("bad-input", |n, p, c| bad_input(p, c, n.root)),
];

/// One case of the catalogue (the claim's `part` names it); the first carries the table.
fn hard_case(
    paper: &super::PaperClaims,
    c: &super::kinds::NamedCheck,
    root: &Path,
) -> Result<super::Outcome, super::VerifyError> {
    static CASES: std::sync::OnceLock<Vec<HardCase>> = std::sync::OnceLock::new();
    let bad = |m: String| super::VerifyError::BadClaim {
        id: c.id.clone(),
        message: m,
    };
    let cases = CASES.get_or_init(|| catalogue(root));
    let id = c.part.as_deref().unwrap_or_default();
    let h = cases
        .iter()
        .find(|h| h.id == id)
        .ok_or_else(|| bad(format!("no hard case `{id}` in the catalogue")))?;
    let mut o = super::outcome(
        paper,
        c,
        super::holds(h.ok),
        format!(
            "{}. Hard because {}. Method {}; steps {}; error {} (tolerance {}) against {}. Outcome: {}",
            h.what,
            h.hard,
            h.method,
            h.steps.map_or("-".into(), |s| s.to_string()),
            h.error.map_or("-".into(), |e| format!("{e:.2e}")),
            h.tolerance.map_or("-".into(), |e| format!("{e:.0e}")),
            h.reference,
            h.outcome
        ),
    );
    if id == cases.first().map_or("", |h| h.id.as_str()) {
        o.extra_md = Some(table(cases));
    }
    Ok(o)
}

/// Bad scenes get one message naming the file, the field and what is allowed.
fn bad_input(
    paper: &super::PaperClaims,
    c: &super::kinds::NamedCheck,
    root: &Path,
) -> Result<super::Outcome, super::VerifyError> {
    let b = bad_inputs(root);
    let n_ok = b.iter().filter(|x| x.ok).count();
    let mut o = super::outcome(
        paper,
        c,
        super::holds(n_ok == b.len()),
        format!(
            "{} bad scenes parsed: {n_ok} got one message naming the file, the field and what is allowed",
            b.len()
        ),
    );
    o.extra_md = Some(bad_table(&b));
    Ok(o)
}

#[cfg(test)]
mod tests {
    use crate::algebra::expo::Expo;
    use crate::algebra::poly::{Poly, qi};
    use crate::algebra::ratfunc::RatFunc;

    #[test]
    fn the_exact_taylor_reference_sums_an_exponential_polynomial() {
        // 3 t exp(-2 t) + t^2 against its closed form in f64 (40 terms at t = 0.01: the tail is
        // far below rounding)
        let e = &Expo::part(RatFunc::from_q(qi(3)), 1, Poly::constant(qi(2)))
            + &Expo::monomial(RatFunc::from_q(qi(1)), 2);
        for t in [1e-9, 1e-4, 1e-2] {
            let x = super::exact_taylor(&e, t).expect("finite");
            let closed = 3.0 * t * (-2.0 * t).exp() + t * t;
            assert!(
                (x - closed).abs() <= 1e-15 * closed,
                "t = {t}: {x} vs {closed}"
            );
        }
    }

    #[test]
    fn an_undefined_error_is_never_dropped() {
        assert!(super::worse(1e-3, f64::NAN).is_nan());
        assert!(super::worse(f64::NAN, 1e-3).is_nan());
        assert!((super::worse(1e-3, 2e-3) - 2e-3).abs() < 1e-18);
    }
}
