//! Models as text (`model = "ode"`): the Hertz impact written in a scene agrees with the built-in
//! model, and the text scenes of `scenes/` (an oscillator on a wall with an impact map, a ball
//! on a vibrating table, a two-mass chain) agree with their closed forms, derived by hand in the
//! comments. Bad formulas stop with exit 2 naming the equation and the term.

use impactcheck::scene;
use serde_json::Value;
use std::f64::consts::PI;
use std::path::Path;
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Runs a scene table with some fields set; the JSON outcome.
fn run_with(file: &str, set: &[(&str, f64)]) -> Value {
    let mut t = scene::read_table(&root().join(file)).expect("reads");
    for (f, v) in set {
        scene::set_field(&mut t, f, *v, file).expect("sets");
    }
    let s = scene::parse_table(&t, file).unwrap_or_else(|e| panic!("{file}: {e}"));
    s.run().unwrap_or_else(|e| panic!("{file}: {e}")).0
}

fn num(v: &Value, path: &str) -> f64 {
    path.split('.')
        .fold(v, |v, p| &v[p])
        .as_f64()
        .unwrap_or_else(|| panic!("{path} in {v}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

#[test]
fn hertz_as_text_agrees_with_the_built_in_model() {
    // both at rtol 1e-12; the reference is the built-in model (its own tests check it against
    // the closed form t_c = tau (m/k)^(2/5) v0^(-1/5)); damped and undamped, both methods
    for (c, method) in [
        (0.0, "dop853"),
        (0.4, "dop853"),
        (0.4, "radau5"),
        (0.0, "radau5"),
    ] {
        for (m, k, v0) in [(1.0, 1.0, 1.0), (2.5, 3.0e6, 0.7), (0.1, 1.0e9, 20.0)] {
            let mut t = scene::read_table(&root().join("scenes/hertz_ode.toml")).expect("reads");
            for (f, v) in [
                ("parameters.m", m),
                ("parameters.k", k),
                ("parameters.v0", v0),
                ("parameters.c", c),
            ] {
                scene::set_field(&mut t, f, v, "s").expect("sets");
            }
            scene::set_value(
                &mut t,
                "solve.method",
                toml::Value::String(method.into()),
                "s",
            )
            .expect("sets");
            let text = scene::parse_table(&t, "hertz_ode")
                .expect("valid")
                .run()
                .expect("runs")
                .0;
            let built = format!(
                "model = \"hertz\"\n[impactor]\nmass = {m:e}\nv0 = {v0:e}\n[contact]\nk = {k:e}\ndamping = {c:e}\n[solve]\nrtol = 1e-12\natol = 1e-15\nmethod = \"dop853\"\n"
            );
            let b = scene::parse(&built, "hertz")
                .expect("valid")
                .run()
                .expect("runs")
                .0;
            let case = format!("m {m} k {k} v0 {v0} c {c} {method}");
            assert_eq!(text["stopped_by"], "contact-end", "{case}");
            for (a, bb) in [
                ("outcome.duration", "contact.duration"),
                ("outcome.max_indentation", "contact.max_indentation"),
                ("outcome.v_out", "v_out"),
                ("outcome.restitution", "restitution"),
            ] {
                let (x, y) = (num(&text, a), num(&b, bb));
                assert!(rel(x, y) < 1e-9, "{case}: {a} {x} vs {bb} {y}");
            }
            if c == 0.0 {
                // undamped: the closed form t_c = tau (m/k)^(2/5) v0^(-1/5), rebound -v0
                let tc =
                    impactcheck::models::hertz::TAU_UNDAMPED * (m / k).powf(0.4) * v0.powf(-0.2);
                assert!(rel(num(&text, "outcome.duration"), tc) < 1e-9, "{case}");
                assert!(rel(num(&text, "outcome.restitution"), 1.0) < 1e-9, "{case}");
            }
        }
    }
}

#[test]
fn an_oscillator_on_a_wall_bounces_as_its_closed_form_says() {
    // x'' = -w^2 x - 2 zeta w x', the wall at x = 0 (the spring's rest point), released from
    // rest at x = X; impact map x' -> -e x'. From rest: x = X e^(-zeta w t)(cos wd t + (zeta
    // w/wd) sin wd t) first reaches 0 at t1 = (pi - atan(wd/(zeta w)))/wd with speed
    // X w^2/wd e^(-zeta w t1) sin(wd t1). Between impacts the motion starts and ends at x = 0: a
    // half period pi/wd, the speed decaying by exp(-zeta w pi/wd). So impact k (from 1) is at
    // t1 + (k-1) pi/wd with speed u1 (e exp(-zeta w pi/wd))^(k-1).
    let v = run_with("scenes/oscillator_wall.toml", &[]);
    let (w, zeta, e, x0) = (
        num(&v, "outcome.w"),
        num(&v, "outcome.zeta"),
        num(&v, "outcome.e"),
        num(&v, "outcome.x0"),
    );
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let t1 = (PI - (wd / (zeta * w)).atan()) / wd;
    let u1 = x0 * w * w / wd * (-zeta * w * t1).exp() * (wd * t1).sin();
    let decay = e * (-zeta * w * PI / wd).exp();
    for k in 1..=5 {
        let t = num(&v, &format!("outcome.t{k}"));
        let u = num(&v, &format!("outcome.u{k}"));
        let (tk, uk) = (t1 + (k - 1) as f64 * PI / wd, u1 * decay.powi(k - 1));
        assert!(rel(t, tk) < 1e-9, "impact {k}: t {t} vs {tk}");
        assert!(rel(u, uk) < 1e-8, "impact {k}: speed {u} vs {uk}");
    }
}

#[test]
fn a_ball_on_a_vibrating_table_keeps_its_period_one_orbit() {
    // the table at A sin(w t + phi); the ball leaves it at t = 0 with speed V = g T/2, T = 2 pi/w,
    // and lands after T with speed -V; the impact law v+ = (1 + e) u - e v- returns V when the
    // table's speed is u = V (1 - e)/(1 + e), i.e. A w cos(phi) = V (1 - e)/(1 + e): the scene's
    // phi. The bounces are then at T, 2T, ... exactly (the orbit of Holmes 1982).
    let v = run_with("scenes/vibrating_table.toml", &[]);
    let t_period = num(&v, "outcome.period");
    for k in 1..=3 {
        let t = num(&v, &format!("outcome.t{k}"));
        assert!(
            rel(t, k as f64 * t_period) < 1e-8,
            "bounce {k}: {t} vs {}",
            k as f64 * t_period
        );
    }
    assert!(rel(num(&v, "outcome.rebound1"), num(&v, "outcome.v_orbit")) < 1e-8);
}

#[test]
fn a_two_mass_chain_ends_with_the_elastic_velocities() {
    // m1 at v0 meets m2 at rest through a linear spring k: in the relative coordinate a half
    // period of sqrt(mu/k), mu = m1 m2/(m1 + m2), so contact lasts pi sqrt(mu/k) and the
    // velocities are those of an elastic central impact: (m1 - m2)/(m1 + m2) v0, 2 m1/(m1 + m2) v0
    for (m1, m2) in [(1.0, 1.0), (1.0, 3.0), (2.0, 0.5)] {
        let v = run_with(
            "scenes/two_mass_chain.toml",
            &[("parameters.m1", m1), ("parameters.m2", m2)],
        );
        let (k, v0) = (num(&v, "outcome.k"), num(&v, "outcome.v0"));
        let mu = m1 * m2 / (m1 + m2);
        let case = format!("m1 {m1} m2 {m2}");
        assert!(
            rel(num(&v, "outcome.duration"), PI * (mu / k).sqrt()) < 1e-9,
            "{case}"
        );
        let v1 = (m1 - m2) / (m1 + m2) * v0;
        let v2 = 2.0 * m1 / (m1 + m2) * v0;
        assert!((num(&v, "outcome.v1_out") - v1).abs() < 1e-9 * v0, "{case}");
        assert!(rel(num(&v, "outcome.v2_out"), v2) < 1e-9, "{case}");
    }
}

fn impact_run(text: &str, name: &str) -> (Option<i32>, String) {
    let d = std::env::temp_dir().join(format!("impactcheck-ode-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("dir");
    let p = d.join("s.toml");
    std::fs::write(&p, text).expect("write");
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["run", p.to_str().expect("utf-8"), "--format", "json"])
        .output()
        .expect("runs");
    let _ = std::fs::remove_dir_all(&d);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn units_are_checked_equation_by_equation_before_anything_runs() {
    let good = std::fs::read_to_string(root().join("scenes/hertz_ode.toml")).expect("reads");
    assert_eq!(impact_run(&good, "good").0, Some(0));
    for (name, from, to, says) in [
        // a term in m/s^2 added to one in m/s
        (
            "term",
            "v = \"-F/m\"",
            "v = \"-F/m + v\"",
            &["equations.v", "`v` is m s^-1"][..],
        ),
        // the right side of dz/dt in m/s^2
        (
            "rate",
            "z = \"v\"\nv =",
            "z = \"-F/m\"\nv =",
            &["equations.z", "m s^-1"][..],
        ),
        // an initial value in the wrong unit
        ("init", "v = \"v0\"", "v = \"m\"", &["state.v", "kg"][..]),
        // a name that is nothing
        (
            "name",
            "z = \"v\"\nv =",
            "z = \"w\"\nv =",
            &["equations.z", "`w`"][..],
        ),
        // a jump in the wrong unit
        (
            "jump",
            "action = \"stop\"",
            "action = \"stop\"\njump = { v = \"-z\" }",
            &["jump.v", "m s^-1"][..],
        ),
        // an outcome at an event that does not exist
        (
            "event",
            "t@contact-end",
            "t@contact-ends",
            &["outcome.duration", "contact-end"][..],
        ),
        // a missing unit
        ("unit", "c = \"s/m\"\n", "", &["units.c"][..]),
    ] {
        assert!(good.contains(from), "{name}: {from}");
        let bad = good.replacen(from, to, 1);
        let (code, err) = impact_run(&bad, name);
        assert_eq!(code, Some(2), "{name}: {err}");
        for s in says {
            assert!(err.contains(s), "{name}: `{s}` not in: {err}");
        }
    }
}

/// A text scene read from the repository with fields set, as the library's text model.
fn ode_scene(file: &str, set: &[(&str, f64)]) -> impactcheck::models::ode::OdeScene {
    use impactcheck::models::Model;
    let mut t = scene::read_table(&root().join(file)).expect("reads");
    for (f, v) in set {
        scene::set_field(&mut t, f, *v, file).expect("sets");
    }
    impactcheck::models::ode::OdeScene::from_table(&t, file).expect("a text model")
}

#[test]
fn taylor_series_of_a_text_model_are_exact_and_agree_with_its_numerics() {
    use impactcheck::algebra::expr::parse;
    // the undamped oscillator from rest at x0 is x0 cos(w t): its Taylor polynomial of degree 8
    // is x0 sum_k (-1)^k (w t)^(2k)/(2k)! (the cosine series, independent of the code)
    let ode = ode_scene("scenes/oscillator_wall.toml", &[]);
    let got = ode.taylor("x", 8).expect("polynomial right sides");
    let want = parse("x0*(1 - (w*t)^2/2 + (w*t)^4/24 - (w*t)^6/720 + (w*t)^8/40320)")
        .expect("parses")
        .to_ratfunc()
        .expect("rational");
    let zeta0 = got
        .subst(
            impactcheck::algebra::poly::Sym::new("zeta"),
            &impactcheck::algebra::ratfunc::RatFunc::zero(),
        )
        .expect("substitutes");
    assert!((&zeta0 - &want).is_zero(), "{zeta0} against {want}");
    // a misprinted coefficient (1/700 for 1/720) is not the series
    let wrong = parse("x0*(1 - (w*t)^2/2 + (w*t)^4/24 - (w*t)^6/700 + (w*t)^8/40320)")
        .expect("parses")
        .to_ratfunc()
        .expect("rational");
    assert!(!(&zeta0 - &wrong).is_zero());
    // series against numerics (the general form of 000's check): damped, at t = 2e-3 s
    // (w t = 0.04) the degree-8 polynomial is within (w t)^9/9! ~ 7e-19 of the solution, so the
    // solver (rtol 1e-12) and the series agree to ~1e-12
    let tt = 2e-3;
    let run = run_with(
        "scenes/oscillator_wall.toml",
        &[("solve.t_end", tt), ("parameters.zeta", 0.3)],
    );
    let vals = |s: &str| match s {
        "t" => Some(tt),
        "w" => Some(20.0),
        "zeta" => Some(0.3),
        "x0" => Some(0.01),
        _ => None,
    };
    for (state, order) in [("x", 8), ("v", 7)] {
        let series = ode.taylor(state, order).expect("series");
        let value = parse(&series.to_text())
            .expect("prints as a formula")
            .eval(&vals)
            .expect("evaluates");
        let numeric = num(&run, &format!("state.{state}"));
        assert!(
            rel(value, numeric) < 1e-10,
            "{state}: series {value}, solver {numeric}"
        );
    }
    // a right side that is not polynomial in the states has no such series: an error says so
    let hertz = ode_scene("scenes/hertz_ode.toml", &[]);
    let err = hertz.taylor("z", 4).expect_err("z^(3/2)");
    assert!(err.contains("not rational"), "{err}");
    let err = ode.taylor("q", 4).expect_err("no such state");
    assert!(
        err.contains("its states: x, v") || err.contains("its states: v, x"),
        "{err}"
    );
}
