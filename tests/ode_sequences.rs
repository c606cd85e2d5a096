//! Text models that carry whole impact sequences (issue 44): definitions in any order, numeric
//! initial values in their state's unit, several events on one `when`, `stop_after`, the
//! accumulation of impacts (a bouncing ball comes to rest in finite time), the state just after
//! a jump (`@+`), outcomes that are formulas of firings and of other outcomes, and a right side
//! that switches with the sign of a state. Every reference is a closed form derived by hand in
//! the comments, or the same model written another way.

use impactcheck::scene;
use serde_json::Value;

/// Runs a scene given as text; the JSON outcome, or the error's message.
fn run(text: &str) -> Result<Value, String> {
    let t: toml::Table = toml::from_str(text).map_err(|e| e.to_string())?;
    let s = scene::parse_table(&t, "s.toml").map_err(|e| e.to_string())?;
    s.run().map(|r| r.0).map_err(|e| e.to_string())
}

fn num(v: &Value, path: &str) -> f64 {
    path.split('.')
        .fold(v, |v, p| &v[p])
        .as_f64()
        .unwrap_or_else(|| panic!("{path} in {v}"))
}

/// A ball dropped from `h` under gravity `g`, bouncing with restitution `e`, as text; `extra`
/// is added to the file (events, outcomes), `defs` is its `[definitions]` table.
fn ball(defs: &str, event_extra: &str, extra: &str, t_end: f64) -> String {
    format!(
        r#"model = "ode"
[parameters]
g = 9.81
e = 0.8
h = 1.0
[units]
t = "s"
g = "m/s^2"
e = "1"
h = "m"
z = "m"
v = "m/s"
[definitions]
{defs}
[state]
z = 1.0
v = 0.0
[equations]
z = "v"
v = "-g"
[[event]]
name = "impact"
when = "z"
direction = "down"
jump = {{ v = "-e*v" }}
{event_extra}
{extra}
[solve]
rtol = 1e-12
atol = 1e-14
t_end = {t_end}
"#
    )
}

#[test]
fn definitions_are_read_in_the_order_they_use_each_other() {
    // written in reverse: the kinetic energy per mass through the speed squared, then the speed
    // squared; reference: at the first impact v^2 = 2 g h (energy conservation), KE/m = g h
    let text = ball(
        "ke = \"v2/2\"\nv2 = \"w*w\"\nw = \"v\"",
        "",
        "[outcome]\nke1 = \"ke@impact[1]\"",
        1.0,
    );
    let v = run(&text).expect("runs");
    assert!((num(&v, "outcome.ke1") - 9.81).abs() < 1e-9, "{v}");
    // a cycle is an error naming its members, not the definition that happens to come first
    let text = ball("a = \"b + v\"\nb = \"a\"\nc = \"v\"", "", "", 1.0);
    let err = run(&text).unwrap_err();
    assert!(
        err.contains("definitions.a") && err.contains("a, b"),
        "{err}"
    );
    assert!(!err.contains("c,"), "{err}");
    let err = run(&ball("a = \"a*2\"", "", "", 1.0)).unwrap_err();
    assert!(
        err.contains("cycle") && err.contains("definitions.a"),
        "{err}"
    );
}

#[test]
fn a_number_in_state_is_a_value_in_the_states_unit() {
    // z = 1.0 in m (the ball above), v = 0.0; the first impact at sqrt(2 h/g) (free fall)
    let text = ball("", "", "[outcome]\nt1 = \"t@impact[1]\"", 1.0);
    let v = run(&text).expect("a number in metres is metres");
    let t1 = (2.0f64 / 9.81).sqrt();
    assert!((num(&v, "outcome.t1") - t1).abs() < 1e-10, "{v}");
    // an integer too; a formula still has its unit checked
    assert!(run(&text.replace("z = 1.0", "z = 1")).is_ok());
    let err = run(&text.replace("z = 1.0", "z = \"e\"")).unwrap_err();
    assert!(err.contains("state.z") && err.contains("is in 1"), "{err}");
}

/// The ball's closed forms (free fall between impacts, v -> -e v at each): the first impact at
/// t1 = sqrt(2 h/g) with speed v1 = sqrt(2 g h); the k-th flight lasts 2 e^k v1/g, so the
/// impacts accumulate at t1 + 2 v1 e/(g (1 - e)).
const G: f64 = 9.81;
const E: f64 = 0.8;
fn v1() -> f64 {
    (2.0 * G).sqrt()
}
fn t1() -> f64 {
    (2.0 / G).sqrt()
}

#[test]
fn stop_after_ends_the_run_at_that_firing_after_its_jump() {
    let text = ball("", "stop_after = 3", "", 10.0);
    let v = run(&text).expect("runs");
    let t3 = t1() + 2.0 * v1() * (E + E * E) / G;
    assert!((num(&v, "t_end") - t3).abs() < 1e-9, "{v}");
    assert_eq!(v["stopped_by"], "impact");
    assert_eq!(num(&v, "event_counts.impact"), 3.0);
    // the state is the one after the third jump: moving up at e^3 v1
    assert!((num(&v, "state.v") - E.powi(3) * v1()).abs() < 1e-9, "{v}");
    for bad in ["stop_after = 0", "stop_after = 1.5", "stop_after = \"3\""] {
        let err = run(&ball("", bad, "", 10.0)).unwrap_err();
        assert!(err.contains("event.impact.stop_after"), "{bad}: {err}");
    }
}

#[test]
fn the_state_after_a_jump_and_outcomes_of_firings_and_outcomes() {
    // before the first jump v = -v1, after it e v1; at the second, -e v1 and e^2 v1. The ratio
    // of kinetic energies across one impact is e^2, the same as the ratio of two outcomes.
    let outcomes = r#"[outcome]
before1 = "v@impact[1]"
after1 = "v@+impact[1]"
after2 = "v@+impact[2]"
ratio = "(v^2)@+impact[1]/(v^2)@impact[1]"
ke1 = "(v^2/2)@impact[1]"
ke1p = "(v^2/2)@+impact[1]"
loss = "ke1p/ke1"
lossd = "1 - loss"
flight = "t@impact[2] - t@impact[1]"
count = "2*hits@impact - hits@impact"
late = "v@+impact[40]"
"#;
    // (a definition with `_` in its name read at two firings)
    let outcomes = format!("{outcomes}loss_d = \"ke_m@+impact[1]/ke_m@impact[1]\"\n");
    let v = run(&ball("ke_m = \"v^2/2\"", "stop_after = 3", &outcomes, 10.0)).expect("runs");
    let o = |k: &str| num(&v, &format!("outcome.{k}"));
    assert!((o("loss_d") - E * E).abs() < 1e-12, "{v}");
    assert!((o("before1") + v1()).abs() < 1e-9, "{v}");
    assert!((o("after1") - E * v1()).abs() < 1e-9, "{v}");
    assert!((o("after2") - E * E * v1()).abs() < 1e-9, "{v}");
    for k in ["ratio", "loss"] {
        assert!((o(k) - E * E).abs() < 1e-12, "{k}: {v}");
    }
    assert!((o("lossd") - (1.0 - E * E)).abs() < 1e-12, "{v}");
    assert!((o("flight") - 2.0 * E * v1() / G).abs() < 1e-9, "{v}");
    assert_eq!(o("count"), 3.0);
    // units derived: m^2 s^-2 for the energies per mass, 1 for their ratio, s for the flight
    assert_eq!(v["outcome_units"]["ke1"], "m^2 s^-2");
    assert_eq!(v["outcome_units"]["loss"], "1");
    assert_eq!(v["outcome_units"]["flight"], "s");
    // a firing that did not happen: null, and a warning naming it
    assert!(v["outcome"]["late"].is_null());
    assert!(v["warnings"].to_string().contains("outcome.late"), "{v}");
    // an outcome formula that mixes units, a cycle of outcomes, a name that is nothing
    for (bad, says) in [
        ("x = \"t@impact[1] + v@impact[1]\"", "outcome.x"),
        ("x = \"y\"\ny = \"x\"", "cycle"),
        ("x = \"w@impact[1] + t@impact[2]\"", "`w`"),
        (
            "x = \"t@impct[1] + t@impact[2]\"",
            "`impct` is not an event",
        ),
    ] {
        let err = run(&ball("", "", &format!("[outcome]\n{bad}"), 1.0)).unwrap_err();
        assert!(err.contains(says), "{bad}: {err}");
    }
}

#[test]
fn events_on_one_when_all_fire_in_the_order_written() {
    // a second event on the ball's `when`: one that only counts, one that adds u = e sqrt(g h)
    // to v after the impact's jump. By hand: after the first impact v = e v1, then e v1 + u.
    let second = r#"
[[event]]
name = "count"
when = "z"
direction = "down"

[[event]]
name = "kick"
when = "z"
direction = "down"
jump = { v = "v + e*sqrt(g*h)" }
"#;
    let outcomes = "[outcome]\nafter_impact = \"v@+impact[1]\"\nafter_kick = \"v@+kick[1]\"\nkicked = \"v@kick[1]\"";
    let v = run(&ball(
        "",
        "stop_after = 2",
        &format!("{second}\n{outcomes}"),
        10.0,
    ))
    .expect("runs");
    let o = |k: &str| num(&v, &format!("outcome.{k}"));
    assert!((o("after_impact") - E * v1()).abs() < 1e-9, "{v}");
    // the kick sees the state after the impact's jump, and adds e sqrt(g h) to it
    assert!((o("kicked") - E * v1()).abs() < 1e-9, "{v}");
    assert!(
        (o("after_kick") - (E * v1() + E * G.sqrt())).abs() < 1e-9,
        "{v}"
    );
    assert_eq!(num(&v, "event_counts.count"), 2.0, "{v}");
    assert_eq!(num(&v, "event_counts.kick"), 2.0, "{v}");
}

#[test]
fn impacts_that_accumulate_end_the_run_at_their_accumulation_time() {
    // without stop_after the impacts of the ball accumulate at t* (closed form above), long
    // before t_end = 10 s: the run ends there with the warning, not with a step-size error
    let t_star = t1() + 2.0 * v1() * E / (G * (1.0 - E));
    let v = run(&ball("", "", "", 10.0)).expect("ends at the accumulation");
    let t_end = num(&v, "t_end");
    assert!(
        (t_end - t_star).abs() < 1e-9 * t_star,
        "{t_end} vs {t_star}"
    );
    assert!((num(&v, "accumulation.t") - t_star).abs() < 1e-9 * t_star);
    assert_eq!(v["accumulation"]["event"], "impact");
    // (the ratio of the last two intervals, each about 1e-9 s, known to about 1e-6)
    assert!((num(&v, "accumulation.ratio") - E).abs() < 1e-4, "{v}");
    let w = v["warnings"].to_string();
    assert!(
        w.contains("event impact") && w.contains("accumulate"),
        "{w}"
    );
    // at rest on the floor: the last flight's speed is below 1e-8 of the first
    assert!(num(&v, "state.v").abs() < 1e-8 * v1(), "{v}");
    // with t_end before t*, the run ends at t_end as before, with no warning
    let v = run(&ball("", "", "", 0.5 * t_star)).expect("runs");
    assert_eq!(num(&v, "t_end"), 0.5 * t_star);
    assert!(v["accumulation"].is_null() && v["warnings"].as_array().unwrap().is_empty());
}

/// The rocking block of scenes/rocking_block.toml, read with its fields set.
fn rocking(set: &[(&str, f64)]) -> String {
    let mut t: toml::Table = toml::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/rocking_block.toml"),
        )
        .expect("reads"),
    )
    .expect("TOML");
    for (f, v) in set {
        scene::set_field(&mut t, f, *v, "rocking").expect("sets");
    }
    toml::to_string(&t).expect("writes")
}

#[test]
fn a_sign_in_the_right_side_is_held_between_its_zeros() {
    // the rocking block as written (theta'' = -p^2 sin(alpha sign(theta) - theta)) against the
    // same block mirrored (phi = |theta| >= 0 always, phi'' = -p^2 sin(alpha - phi), and the
    // impact map w -> -r w at phi = 0): the same impact times, and the sign costs no more
    // rejected steps than the mirrored form, which has no discontinuity at all
    let signed = rocking(&[("solve.t_end", 6.0)]);
    let mirrored = signed
        .replace("alpha*sign(th) - th", "alpha - th")
        .replace("direction = \"any\"", "direction = \"down\"")
        .replace("w = \"w*(R2/3", "w = \"-w*(R2/3");
    assert_ne!(signed, mirrored);
    let outcomes = "t6 = \"t@impact[6]\"\n";
    let with = |text: &str| text.replace("[outcome]\n", &format!("[outcome]\n{outcomes}"));
    let a = run(&with(&signed)).expect("signed");
    let b = run(&with(&mirrored)).expect("mirrored");
    let (ta, tb) = (num(&a, "outcome.t6"), num(&b, "outcome.t6"));
    assert!((ta - tb).abs() < 1e-9 * tb, "{ta} vs {tb}");
    let rejected = |v: &Value| num(v, "stats.rejected");
    assert!(
        rejected(&a) <= rejected(&b) + 2.0,
        "signed {} rejected, mirrored {}",
        rejected(&a),
        rejected(&b)
    );
    // each impact is also the sign's zero: one switch per impact
    assert_eq!(num(&a, "switches"), num(&a, "event_counts.impact"));
    assert_eq!(num(&b, "switches"), 0.0);
    // the sign held wherever it sits in the formula: under a minus, a product, a function
    let negated = signed.replace(
        "\"-p2*sin(alpha*sign(th) - th)\"",
        "\"-(p2*sin(alpha*sign(th) - th))\"",
    );
    assert_ne!(negated, signed);
    let c = run(&with(&negated)).expect("negated");
    assert_eq!(num(&c, "switches"), num(&a, "switches"));
    assert_eq!(rejected(&c), rejected(&a));
}

#[test]
fn a_rocking_block_comes_to_rest_where_its_impacts_accumulate() {
    // a squat block (b = h/2: r = 1 - 1.5 sin^2(atan(1/2)) = 0.7) loses half its energy at each
    // impact; its impacts accumulate long before 30 s, where the run ends with the warning
    let v = run(&rocking(&[("parameters.b", 0.5)])).expect("runs");
    let acc = &v["accumulation"];
    assert_eq!(acc["event"], "impact", "{v}");
    assert!(num(&v, "t_end") < 30.0);
    assert!((num(&v, "outcome.r1") - 0.7).abs() < 1e-12, "{v}");
    // the intervals shrink by r near rest (theta'' -> -p^2 alpha sign(theta), a bouncing ball)
    assert!((num(&v, "accumulation.ratio") - 0.7).abs() < 1e-3, "{v}");
}

#[test]
fn a_varied_parameter_the_text_model_lacks_is_named_with_those_it_has() {
    // a typo in --vary: exit 2 naming the key and listing the parameters, not a missing unit
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_impact"))
        .args([
            "sweep",
            "scenes/rocking_block.toml",
            "--vary",
            "parameters.bb=0.1:0.2:2",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("impact runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("`parameters.bb`"), "{err}");
    assert!(
        err.contains("parameters.b, parameters.f0, parameters.g, parameters.h"),
        "{err}"
    );
    assert!(!err.contains("units."), "{err}");
    // a state likewise; a parameter it has sweeps
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_impact"))
        .args([
            "sweep",
            "scenes/rocking_block.toml",
            "--vary",
            "state.x=0:1:2",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("impact runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("state.th, state.w"), "{err}");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_impact"))
        .args([
            "sweep",
            "scenes/rocking_block.toml",
            "--vary",
            "parameters.b=0.1:0.2:2",
            "--format",
            "csv",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("impact runs");
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_sweep_sets_parameters_and_initial_states_on_the_compiled_model() {
    // the typed path of a sweep (no re-reading of the scene): g = 4 m/s^2 puts the first impact
    // of the ball dropped from z = 1 m at sqrt(2/4) s; z = 9 m with g = 4 at sqrt(18/4) s
    use impactcheck::models::Model;
    let text = ball(
        "",
        "stop_after = 1",
        "[outcome]\nt1 = \"t@impact[1]\"",
        10.0,
    );
    let t: toml::Table = toml::from_str(&text).expect("TOML");
    let mut m = impactcheck::models::ode::OdeScene::from_table(&t, "s").expect("a text model");
    assert!(matches!(
        m.set_number("parameters.g", 4.0, "s"),
        Some(Ok(()))
    ));
    let t1 = |m: &impactcheck::models::ode::OdeScene| m.run().expect("runs").0.outcome["t1"];
    assert!((t1(&m).expect("fired") - 0.5f64.sqrt()).abs() < 1e-10);
    assert!(matches!(m.set_number("state.z", 9.0, "s"), Some(Ok(()))));
    assert!((t1(&m).expect("fired") - 4.5f64.sqrt()).abs() < 1e-10);
    // not finite: an error naming the field; not a parameter or state of the model: not its own
    for field in ["parameters.g", "state.z"] {
        match m.set_number(field, f64::NAN, "s") {
            Some(Err(e)) => assert!(e.to_string().contains(field), "{e}"),
            other => panic!("{field}: {other:?}"),
        }
    }
    assert!(m.set_number("parameters.gg", 1.0, "s").is_none());
    assert!(m.set_number("state.zz", 1.0, "s").is_none());
    assert!(m.set_number("solve.rtol", 1e-6, "s").is_none());
}

#[test]
fn names_and_the_number_of_variables_are_checked() {
    // a parameter's name starts with a letter or `_`; 1k does not
    let good = ball("", "", "", 1.0);
    assert!(
        run(&good
            .replace("h = 1.0\n", "_h = 1.0\n")
            .replace("h = \"m\"", "_h = \"m\""))
        .is_ok()
    );
    let err = run(&good.replace("h = 1.0\n", "\"1k\" = 1.0\n")).unwrap_err();
    assert!(err.contains("parameters.1k"), "{err}");
    // at most 255 states and parameters: 300 parameters are refused by name, not a crash
    let many: String = (0..300).map(|i| format!("p{i} = 1.0\n")).collect();
    let units: String = (0..300).map(|i| format!("p{i} = \"1\"\n")).collect();
    let text = good
        .replace("[parameters]\n", &format!("[parameters]\n{many}"))
        .replace("[units]\n", &format!("[units]\n{units}"));
    let err = run(&text).unwrap_err();
    assert!(err.contains("at most 255 states and parameters"), "{err}");
}

/// A ball whose restitution alternates, 0.5 at odd impacts and 0.9 at even ones: its flights
/// shrink, but by 0.5 and 0.9 in turn, not geometrically. Two flights shrink by 0.45, so by the
/// closed form of the ball above the impacts still accumulate, at
/// t* = t1 + (2 v1/g) e1 (1 + e2)/(1 - e1 e2). An accumulation is only declared from intervals
/// whose ratios agree (to 2 %): this run says it cannot go on, at t*, and does not end with the
/// ball below the floor (as it did when a flight shorter than a step's first sample was missed:
/// tests/regression_flight_inside_a_step.rs).
#[test]
fn uneven_shrinking_is_not_taken_for_a_geometric_accumulation() {
    let (e1, e2) = (0.5, 0.9);
    let text = ball("", "", "", 10.0)
        .replace(
            "jump = { v = \"-e*v\" }",
            "jump = { v = \"-(0.5 + 0.4*c)*v\", c = \"1 - c\" }",
        )
        .replace("v = 0.0\n", "v = 0.0\nc = 0.0\n")
        .replace("v = \"-g\"\n", "v = \"-g\"\nc = \"0\"\n")
        .replace("v = \"m/s\"\n", "v = \"m/s\"\nc = \"1\"\n");
    assert!(text.contains("c = \"1 - c\""), "{text}");
    let t_star = t1() + 2.0 * v1() / G * e1 * (1.0 + e2) / (1.0 - e1 * e2);
    // the solver's own error at t*, with the step size: the firings are not geometric, so no
    // accumulation is declared (and no state below the floor returned)
    let e = run(&text).expect_err("no accumulation is declared");
    let at: f64 = e
        .split("at t = ")
        .nth(1)
        .and_then(|r| r.split_whitespace().next())
        .and_then(|x| x.parse().ok())
        .unwrap_or_else(|| panic!("{e}"));
    assert!(
        e.contains("step size") && (at - t_star).abs() < 1e-9 * t_star,
        "{e}"
    );
    // the first firings are where the closed form puts them (the alternation is modelled)
    let first = run(&text
        .replace("t_end = 10", "t_end = 1.5")
        .replace("[solve]", "[outcome]\nt3 = \"t@impact[3]\"\n[solve]"))
    .expect("runs");
    let t3 = t1() + 2.0 * v1() / G * (e1 + e1 * e2);
    assert!((num(&first, "outcome.t3") - t3).abs() < 1e-9, "{first}");
}
