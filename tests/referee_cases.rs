//! The cases a referee met writing claims for a paper the tool had never seen (issue 53), each
//! failing on the code before it: a text model's outcome used without a unit declared, a
//! declared unit that contradicts the model's, a parameter named `gamma`, a NaN at a grid point
//! that must be named, `verify init` on a relation with an application `z(t)`; and the
//! `threshold` kind (where a behaviour changes along one parameter).
//!
//! The references are independent of the code under test: the period-one orbit of the ball on
//! the vibrating table lands every T = 2 pi/w (by construction of its initial state, see
//! scenes/vibrating_table.toml); x' = -gamma x gives x(1) = exp(-gamma); sqrt(a - 1) is NaN
//! for a < 1; the stick threshold of the rod is derived by hand in verify/classics.toml.

use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

#[path = "support/scratch.rs"]
mod scratch;
use scratch::Scratch;

fn verify(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("verify runs")
}

/// `verify --claims claims.toml --format json` in `dir`: the claims' JSON, or the stderr of a
/// run that did not exit 0 or 1.
fn run_claims(dir: &Path) -> Result<Vec<Value>, String> {
    let out = verify(dir, &["--claims", "claims.toml", "--format", "json"]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    if !matches!(out.status.code(), Some(0 | 1)) {
        return Err(err);
    }
    let v: Value = serde_json::from_slice(&out.stdout).map_err(|e| format!("{e}: {err}"))?;
    Ok(v["claims"].as_array().cloned().unwrap_or_default())
}

const TABLE: &str = "scenes/vibrating_table.toml";

/// A folder with the project's scene `scene` copied as `name_as` and the claims file `text`.
fn scene_claims(name: &str, scene: &str, name_as: &str, text: &str) -> Scratch {
    let dir = Scratch::new(&format!("referee-{name}"));
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(root.join(scene), dir.join(name_as)).unwrap();
    std::fs::write(dir.join("claims.toml"), text).unwrap();
    dir
}

/// A folder with the vibrating table's scene and a claims file of `symbols` and `claims`.
fn table_claims(name: &str, symbols: &str, claims: &str) -> Scratch {
    scene_claims(
        name,
        TABLE,
        "table.toml",
        &format!("paper = \"t\"\ntitle = \"t\"\nreport = \"t.md\"\n[symbols]\n{symbols}\n{claims}"),
    )
}

const SECOND_BOUNCE: &str = r#"
[[claim]]
id = "t.second-bounce"
equation = "(1)"
reading = "the second bounce one period after the first"
kind = "model"
scene = "table.toml"
quantity = "outcome.t2"
printed = "outcome.t1 + 2*pi/w"
bind = { w = "parameters.w" }
vary = ["parameters.w=50:80:3"]
rtol = 1e-8
"#;

#[test]
fn a_text_models_outcome_has_the_models_unit_without_a_declaration() {
    // outcome.t1 and outcome.t2 are declared nowhere: the model derives them (times, s)
    let dir = table_claims("undeclared", "w = \"Hz\"", SECOND_BOUNCE);
    let claims = run_claims(&dir).expect("the claim runs");
    assert_eq!(claims[0]["verdict"], "holds", "{}", claims[0]);
    assert!(
        !claims[0]["detail"].as_str().unwrap().contains("units:"),
        "no unit note: the formula and the quantity are both times: {}",
        claims[0]
    );
}

#[test]
fn a_declared_unit_that_contradicts_the_model_is_an_error_naming_both() {
    for symbols in [
        "w = \"Hz\"\n\"outcome.t1\" = \"m/s\"",
        "w = \"Hz\"\n\"outcome.t2\" = \"m\"",
    ] {
        let dir = table_claims("contradicts", symbols, SECOND_BOUNCE);
        let err = run_claims(&dir).expect_err("a wrong unit is refused");
        let (name, wrong) = if symbols.contains("t1") {
            ("outcome.t1", "m s^-1")
        } else {
            ("outcome.t2", "m")
        };
        assert!(
            err.contains(&format!(
                "`{name}`: [symbols] gives it in {wrong}, but the model computes it in s"
            )),
            "{err}"
        );
    }
    // the model's own unit declared again is no contradiction
    let dir = table_claims(
        "agrees",
        "w = \"Hz\"\n\"outcome.t1\" = \"s\"",
        SECOND_BOUNCE,
    );
    assert_eq!(run_claims(&dir).expect("runs")[0]["verdict"], "holds");
}

/// A folder with a text model of `x' = -gamma x` (x(0) = x0) and a claims file of `claims`.
fn decay(name: &str, outcome: &str, claims: &str) -> Scratch {
    let dir = Scratch::new(&format!("referee-{name}"));
    std::fs::write(
        dir.join("decay.toml"),
        format!(
            "model = \"ode\"\n[parameters]\ngamma = 2.0\na = 2.0\n[units]\nt = \"s\"\ngamma = \"Hz\"\na = \"1\"\nx = \"1\"\n[state]\nx = \"1\"\n[equations]\nx = \"-gamma*x\"\n[outcome]\n{outcome}\n[solve]\nrtol = 1e-10\natol = 1e-12\nt_end = 1.0\n"
        ),
    )
    .unwrap();
    std::fs::write(
        dir.join("claims.toml"),
        format!("paper = \"d\"\ntitle = \"d\"\nreport = \"d.md\"\n[symbols]\ngamma = \"Hz\"\nt = \"s\"\na = \"1\"\n{claims}"),
    )
    .unwrap();
    dir
}

#[test]
fn a_parameter_may_be_named_gamma_in_the_scene_and_the_claims() {
    let claim = r#"
[[claim]]
id = "d.decay"
equation = "(1)"
reading = "x(1) = exp(-gamma)"
kind = "model"
scene = "decay.toml"
quantity = "outcome.xe"
printed = "exp(-gamma*t)"
where = { t = "1" }
bind = { gamma = "parameters.gamma" }
vary = ["parameters.gamma=0.5:2:4"]
rtol = 1e-6
"#;
    let dir = decay("gamma", "xe = \"x\"", claim);
    let claims = run_claims(&dir).expect("gamma is a parameter");
    assert_eq!(claims[0]["verdict"], "holds", "{}", claims[0]);
    // and the function gamma is still there, called with `(`: Gamma(5) = 24
    let claim = claim.replace("exp(-gamma*t)", "exp(-gamma*t)*gamma(5)/24");
    let dir = decay("gamma-call", "xe = \"x\"", &claim);
    assert_eq!(run_claims(&dir).expect("runs")[0]["verdict"], "holds");
    // `impact run` takes it too
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["run", "decay.toml", "--format", "json"])
        .current_dir(&*dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let xe = v["outcome"]["xe"].as_f64().unwrap();
    assert!((xe - (-2.0f64).exp()).abs() < 1e-8, "{xe}");
}

#[test]
fn a_nan_at_a_grid_point_names_the_point_the_values_and_the_outcome() {
    let claim = r#"
[[claim]]
id = "d.root"
equation = "(2)"
reading = "r = sqrt(a - 1)"
kind = "model"
scene = "decay.toml"
quantity = "outcome.r"
printed = "sqrt(a - 1)"
bind = { a = "parameters.a" }
vary = ["parameters.a=2:0.5:4"]
rtol = 1e-9
"#;
    let dir = decay("nan", "r = \"sqrt(a - 1)\"", claim);
    let claims = run_claims(&dir).expect("runs");
    let detail = claims[0]["detail"].as_str().unwrap();
    assert_eq!(claims[0]["verdict"], "fails", "{detail}");
    for says in [
        "1 of 4 grid point(s) did not run",
        "point 4 (parameters.a = 0.5)",
        "outcome.r is NaN (not finite; written null) with the parameters a = 0.5, gamma = 2",
    ] {
        assert!(detail.contains(says), "`{says}` not in: {detail}");
    }
    // a state's initial value: the first point of the grid is the one that fails
    let scene = std::fs::read_to_string(dir.join("decay.toml"))
        .unwrap()
        .replace("[state]\nx = \"1\"", "[state]\nx = \"sqrt(a - 1)\"");
    std::fs::write(dir.join("decay.toml"), scene).unwrap();
    let claims_text = std::fs::read_to_string(dir.join("claims.toml"))
        .unwrap()
        .replace("parameters.a=2:0.5:4", "parameters.a=0.5:2:4");
    std::fs::write(dir.join("claims.toml"), claims_text).unwrap();
    let err = run_claims(&dir).expect_err("the probe point fails");
    for says in [
        "the initial value is NaN (not finite) with the parameters a = 0.5, gamma = 2",
        "(the claim's first point: parameters.a = 0.5)",
    ] {
        assert!(err.contains(says), "`{says}` not in: {err}");
    }
}

#[test]
fn init_writes_a_claim_for_every_relation_the_audit_reads() {
    let dir = Scratch::new("referee-init");
    // (1) an application z(t), (2) a chain, an unnumbered relation, a row of two relations
    std::fs::write(
        dir.join("paper.tex"),
        r"\documentclass{article}
\begin{document}
A ball of mass $m$ falls from rest; $g$ is the acceleration of gravity. Here $t$ is the time.
\begin{equation} z(t) = \frac{1}{2} g t^2 \label{eq:z} \end{equation}
\begin{equation} E = m g z(t) = \frac{1}{2} m g^2 t^2 \end{equation}
\[ v = g t , \qquad p = m v \]
\end{document}
",
    )
    .unwrap();
    let out = verify(&dir, &["init", "paper.tex", "--paper", "b"]);
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for claim in [
        "id = \"b.eq1.units\"",
        // the chain E = m g z(t) = m g^2 t^2/2: a claim per link
        "id = \"b.eq2-link1.units\"",
        "id = \"b.eq2-link2.units\"",
        "printed_from = { display = 3, relation = 1, form = \"difference\" }",
        "printed_from = { display = 3, relation = 2, form = \"difference\" }",
    ] {
        assert!(text.contains(claim), "`{claim}` not in:\n{text}");
    }
    assert!(!text.contains("no claim"), "{text}");
    std::fs::write(dir.join("claims.toml"), &text).unwrap();
    let claims = run_claims(&dir).expect("the scaffold runs");
    assert_eq!(claims.len(), 5, "{claims:?}");
    for c in &claims {
        assert_eq!(c["verdict"], "holds", "{c}");
    }
    // a unit error in the middle of the chain is seen by its claim
    let bad = std::fs::read_to_string(dir.join("paper.tex"))
        .unwrap()
        .replace("E = m g z(t) =", "E = m z(t) =");
    std::fs::write(dir.join("paper.tex"), bad).unwrap();
    let claims = run_claims(&dir).expect("runs");
    // both links hold the misprinted m z(t), an energy over g: both see it
    for link in ["b.eq2-link1.units", "b.eq2-link2.units"] {
        let chain = claims.iter().find(|c| c["id"] == link).unwrap();
        assert_eq!(chain["verdict"], "fails", "{chain}");
    }
}

fn rod_threshold(printed: &str) -> Vec<Value> {
    let dir = scene_claims(
        "threshold",
        "scenes/rod_floor.toml",
        "rod.toml",
        &format!(
            r#"paper = "r"
title = "r"
report = "r.md"
[symbols]
e = "1"
mu = "1"
vz0 = "m/s"
[[claim]]
id = "r.stick"
equation = "(1)"
reading = "the stick threshold of the rod"
kind = "threshold"
scene = "rod.toml"
along = "initial.v_rel.0=0.01:20"
changes = "phases.1.kind"
printed = "{printed}"
where = {{ vn = "-vz0" }}
bind = {{ e = "contact.e", mu = "contact.mu", vz0 = "initial.v_rel.2" }}
vary = ["contact.mu=0.1:1.5:3", "contact.e=0:1:3"]
rtol = 1e-6
"#
        ),
    );
    run_claims(&dir).expect("the threshold claim runs")
}

#[test]
fn a_threshold_holds_for_the_right_formula_and_fails_for_its_misprints() {
    let right = rod_threshold("(1 + e)*vn*(3 + 5*mu)/(5 + 3*mu)");
    assert_eq!(right[0]["verdict"], "holds", "{}", right[0]);
    let detail = right[0]["detail"].as_str().unwrap();
    assert!(detail.contains("9 grid points"), "{detail}");
    for misprint in [
        "(1 - e)*vn*(3 + 5*mu)/(5 + 3*mu)",
        "2*(1 + e)*vn*(3 + 5*mu)/(5 + 3*mu)",
        "(1 + e)*vn*(5 + 3*mu)/(3 + 5*mu)",
        "(1 + e)*vn*(3 - 5*mu)/(5 + 3*mu)",
    ] {
        let v = rod_threshold(misprint);
        assert_eq!(v[0]["verdict"], "fails", "{misprint}: {}", v[0]);
    }
}

fn hunt_crossley(printed: &str, order: u32) -> Value {
    let dir = scene_claims(
        "order",
        "scenes/hertz.toml",
        "hertz.toml",
        &format!(
            r#"paper = "h"
title = "h"
report = "h.md"
[symbols]
alpha_hc = "s/m"
v0 = "m/s"
restitution = "1"
[[claim]]
id = "h.restitution"
equation = "HC"
reading = "e = 1 - 2 alpha v0/3 for small damping"
kind = "model"
scene = "hertz.toml"
quantity = "restitution"
printed = "{printed}"
bind = {{ alpha_hc = "contact.damping", v0 = "impactor.v0" }}
vary = ["contact.damping=0.001:1:7:log"]
rtol = 1e-3
order = {order}
small = "alpha_hc*v0"
small_max = 0.03
"#
        ),
    );
    run_claims(&dir).expect("runs")[0].clone()
}

#[test]
fn an_approximation_is_judged_by_the_order_of_its_error_within_its_range() {
    // Hunt and Crossley's e = 1 - 2 alpha v0/3 is right to first order in alpha v0: the
    // error of the integrated impact falls as (alpha v0)^2 (as an identity over damping up to
    // 1 it is off by 44 %)
    let right = hunt_crossley("1 - 2*alpha_hc*v0/3", 1);
    assert_eq!(right["verdict"], "holds", "{right}");
    // a wrong first-order coefficient: the error falls only as alpha v0
    let wrong = hunt_crossley("1 - alpha_hc*v0/3", 1);
    assert_eq!(wrong["verdict"], "fails", "{wrong}");
    // the right formula claimed to second order: its error does not fall as (alpha v0)^3
    let over = hunt_crossley("1 - 2*alpha_hc*v0/3", 2);
    assert_eq!(over["verdict"], "fails", "{over}");
    assert!(
        over["detail"]
            .as_str()
            .unwrap()
            .contains("must fall at least as (alpha_hc*v0)^3"),
        "{over}"
    );
}
