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
