//! The command-line contracts of `impact series`, `impact galerkin` and `verify`.

use std::process::Command;

fn impact(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn series_json_with_every_symbol_is_exact_rationals() {
    let (code, out, err) = impact(&[
        "series",
        "--order",
        "2",
        "--at",
        "alpha=-3,gamma=5/2,v0=1,a8=0.25,a9=1e-3",
        "--format",
        "json",
        "--eval-t",
        "0.05,0.1",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let terms = v["terms"].as_array().expect("terms");
    assert_eq!(terms.len(), 3);
    assert_eq!(terms[0]["k"], 0);
    // a0 = v0 t = 1 * t^1 * exp(0)
    assert_eq!(
        terms[0]["parts"][0],
        serde_json::json!({"t_power": 1, "rate": "0", "coeff": "1"})
    );
    for t in terms {
        for p in t["parts"].as_array().expect("parts") {
            for key in ["coeff", "rate"] {
                let s = p[key].as_str().expect("string");
                assert!(
                    impactcheck::algebra::poly::parse_q(s).is_some(),
                    "{key} = {s} is not an exact rational"
                );
            }
            assert_ne!(p["coeff"], "0", "zero coefficient not dropped");
        }
    }
    let values = v["values"].as_array().expect("values");
    assert_eq!(values.len(), 2);
    // a0 + a1 + a2 at t = 0.05 is close to v0 t = 0.05 (the correction is O(t^5))
    let z = values[0]["z"].as_f64().expect("number");
    assert!((z - 0.05).abs() < 1e-3, "{z}");
}

#[test]
fn series_parts_with_equal_key_are_merged() {
    let (_, out, _) = impact(&[
        "series",
        "--order",
        "3",
        "--at",
        "alpha=1,gamma=2,v0=1,a8=1,a9=1",
        "--format",
        "json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    for t in v["terms"].as_array().expect("terms") {
        let mut keys: Vec<(i64, String)> = t["parts"]
            .as_array()
            .expect("parts")
            .iter()
            .map(|p| {
                (
                    p["t_power"].as_i64().expect("int"),
                    p["rate"].as_str().expect("s").to_string(),
                )
            })
            .collect();
        let n = keys.len();
        keys.sort();
        keys.dedup();
        assert_eq!(
            keys.len(),
            n,
            "duplicate (t_power, rate) in term {}",
            t["k"]
        );
    }
}

#[test]
fn bad_rational_is_a_clear_error() {
    let (code, _, err) = impact(&["series", "--at", "alpha=abc"]);
    assert_eq!(code, 2);
    assert!(err.contains("abc") && err.contains("rational"), "{err}");
    let (code, _, err) = impact(&["series", "--at", "beta=1"]);
    assert_eq!(code, 2);
    assert!(
        err.contains("beta") && err.contains("alpha, gamma"),
        "{err}"
    );
    let (code, _, err) = impact(&["series", "--eval-t", "0.1"]);
    assert_eq!(code, 2);
    assert!(err.contains("no value"), "{err}");
}

#[test]
fn galerkin_json_contract() {
    let (code, out, err) = impact(&["galerkin", "--m", "1", "--n", "3", "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    assert_eq!(v["m"], 1);
    assert_eq!(v["n"], 3);
    let names: Vec<&str> = v["coefficients"]
        .as_array()
        .expect("array")
        .iter()
        .map(|c| c["name"].as_str().expect("name"))
        .collect();
    assert_eq!(names, ["A1", "A2", "A3", "A4", "A5", "A6", "A7"]);
    // (1,3): the load enters with sin(pi/2) sin(3 pi/2) = -1 (by hand), the paper prints +1
    assert_eq!(v["load_sign"]["derived"], -1);
    assert_eq!(v["load_sign"]["printed"], 1);
    assert_eq!(v["load_sign"]["verdict"], "differs");
}

#[test]
fn galerkin_values() {
    let (code, out, err) = impact(&[
        "galerkin",
        "--m",
        "1",
        "--n",
        "1",
        "--format",
        "json",
        "--at",
        "E=2e9,eta=1e6,nu=0.3,a=0.2,b=0.3,h=0.01,rho=1200,Kw=1e6,KG=1e3,CT=10,p1=0,p2=0,tan_theta=1",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let a4 = &v["coefficients"][3];
    // A4 = rho h a b / 4 = 1200 * 0.01 * 0.2 * 0.3 / 4 = 0.18 (by hand)
    assert!((a4["derived_value"].as_f64().expect("num") - 0.18).abs() < 1e-12);
    assert!((a4["printed_value"].as_f64().expect("num") - 0.18).abs() < 1e-12);
}

#[test]
fn even_mode_is_rejected_with_range() {
    let (code, _, err) = impact(&["galerkin", "--m", "2"]);
    assert_eq!(code, 2);
    assert!(err.contains("m = 2") && err.contains("odd"), "{err}");
}

#[test]
fn verify_writes_then_checks_clean_and_detects_a_change() {
    let dir = std::env::temp_dir().join(format!("impactcheck-verify-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let claims = concat!(env!("CARGO_MANIFEST_DIR"), "/verify");
    let run = |extra: &[&str]| {
        let mut args = vec!["--claims", claims, "--out", dir.to_str().expect("utf8")];
        args.extend_from_slice(extra);
        Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(&args)
            .output()
            .expect("runs")
    };
    assert!(run(&[]).status.success());
    for f in ["README.md", "summary.json", "000_cone_plate.md"] {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    assert!(run(&["--check"]).status.success());
    // flip one verdict in the baseline: --check must fail and name the claim
    let path = dir.join("summary.json");
    let text = std::fs::read_to_string(&path).expect("read");
    let changed = text.replacen("\"verdict\": \"holds\"", "\"verdict\": \"fails\"", 1);
    assert_ne!(text, changed);
    std::fs::write(&path, changed).expect("write");
    let out = run(&["--check"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("verdict fails -> holds"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn verify_only_runs_a_subset_and_writes_nothing() {
    let dir = std::env::temp_dir().join(format!("impactcheck-only-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let claims = concat!(env!("CARGO_MANIFEST_DIR"), "/verify");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args([
            "--claims",
            claims,
            "--out",
            dir.to_str().expect("utf8"),
            "--only",
            "000.eq21",
            "--format",
            "json",
        ])
        .output()
        .expect("runs");
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let ids: Vec<&str> = v["claims"]
        .as_array()
        .expect("claims")
        .iter()
        .map(|c| c["id"].as_str().expect("id"))
        .collect();
    assert_eq!(ids, ["000.eq21"]);
    assert_eq!(v["claims"][0]["verdict"], "holds");
    assert!(!dir.exists(), "--only must not write reports");
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["--claims", claims, "--only", "999"])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
}

fn run_json(scene: &str) -> serde_json::Value {
    let (code, out, err) = impact(&["run", scene, "--format", "json"]);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).expect("json")
}

#[test]
fn rigid_impact_json_contract_and_constrained_scenes() {
    let root = env!("CARGO_MANIFEST_DIR");
    let v = run_json(&format!("{root}/scenes/rigid_impact.toml"));
    for key in [
        "impulse",
        "v_rel_after",
        "energy_change",
        "kelvin_energy_change",
        "lambda_min",
        "lambda_max",
        "bound_upper",
        "bound_lower",
        "phases",
        "classification",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert!(v["classification"].is_null());
    // Kelvin (1.10) against the bodies' kinetic energy (computed from their velocities)
    let (a, b) = (
        v["energy_change"].as_f64().expect("num"),
        v["kelvin_energy_change"].as_f64().expect("num"),
    );
    assert!((a - b).abs() <= 1e-9 * a.abs());
    // the pendulum with mu >= |alpha3|/|alpha_t| = 1.25 wedges (cut-off impact)
    let p = run_json(&format!("{root}/scenes/pendulum_wall.toml"));
    assert_eq!(p["cut_off"], true);
    let vr: Vec<f64> = p["v_rel_after"]
        .as_array()
        .expect("arr")
        .iter()
        .map(|x| x.as_f64().expect("num"))
        .collect();
    assert!(vr.iter().all(|x| x.abs() < 1e-9));
    // the billiard balls on a smooth table: unique, energy from the bodies equals Kelvin
    let bt = run_json(&format!("{root}/scenes/billiard_table.toml"));
    assert_eq!(bt["classification"], "unique");
    let (a, b) = (
        bt["energy_change"].as_f64().expect("num"),
        bt["kelvin_energy_change"].as_f64().expect("num"),
    );
    assert!((a - b).abs() <= 1e-9 * a.abs(), "{a} vs {b}");
}

#[test]
fn rigid_impact_bad_input_names_the_field() {
    let dir = std::env::temp_dir().join(format!("impactcheck-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/rigid_impact.toml"
    ))
    .expect("read");
    for (from, to, field) in [
        ("e = 0.6", "e = 1.5", "contact.e"),
        ("mu = 0.3", "mu = -1", "contact.mu"),
        (
            "v_rel = [0.8, 0.2, -1.0]",
            "v_rel = [0.8, 0.2, 1.0]",
            "initial.v_rel",
        ),
        (
            "[[0.002, 0.0, 0.0], [0.0, 0.003, 0.0001], [0.0, 0.0001, 0.0025]]",
            "[[0.002, 0.1, 0.0], [0.0, 0.003, 0.0], [0.0, 0.0, 0.0025]]",
            "body[0].inertia",
        ),
        ("mass = 0.5", "mass = 0", "body[0].mass"),
        ("law = \"poisson\"", "law = \"hooke\"", "law"),
    ] {
        let path = dir.join("s.toml");
        let text = base.replace(from, to);
        assert_ne!(text, base, "{from}");
        std::fs::write(&path, text).expect("write");
        let (code, _, err) = impact(&["run", path.to_str().expect("utf8")]);
        assert_eq!(code, 2, "{field}");
        assert!(err.contains(field), "{field}: {err}");
        assert!(!err.contains("panicked"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn grazing_hertz_impact_is_not_silently_inaccurate() {
    // v0 = 1e-9 m/s, k = 1e12: indentations of 1e-12 m, below the default atol. Closed form:
    // t_c = 3.218065459719043 (m/k)^(2/5) v0^(-1/5).
    let dir = std::env::temp_dir().join(format!("impactcheck-graze-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("g.toml");
    std::fs::write(
        &path,
        "model = \"hertz\"\n[impactor]\nmass = 1.0\nv0 = 1e-9\n[contact]\nk = 1e12\n",
    )
    .expect("write");
    let v = run_json(path.to_str().expect("utf8"));
    let tc = 3.218_065_459_719_043 * 1e-12f64.powf(0.4) * 1e-9f64.powf(-0.2);
    let d = v["contact"]["duration"].as_f64().expect("num");
    assert!((d - tc).abs() < 1e-7 * tc, "{d} vs {tc}");
    assert!(!v["warnings"].as_array().expect("warnings").is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

fn write_scene(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("impactcheck-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write scene");
    p
}

/// The pendulum-wall contract; reference: with rho = |GO| (condition (2.10)) the two elements
/// decouple, eps_Cn = sin(sqrt(2 sigma) t)/sqrt(2 sigma) by hand, so the contact lasts
/// pi/sqrt(2 sigma), the spin reverses (Omega = -v0/(2 L)), V_Gn = v0/2 and nothing is lost;
/// with rho = 0.5, sigma = 1 the modes are sin x and sin 2x (x = sqrt(2) t), eps_Cn ~ sin x (1 +
/// cos x) releases at x = pi with eps'_On = -1: loss 0.64 exactly, with a triple root (warned).
#[test]
fn pendulum_wall_contract_against_closed_forms() {
    let p = write_scene(
        "pw.toml",
        "model = \"pendulum-wall\"\nrho = 2.0\nsigma = 0.5\nlength = 2.0\nv0 = 3.0\nmass = 4.0\nstiffness_o = 9.0\n",
    );
    let v = run_json(p.to_str().expect("utf8"));
    assert!(
        v["energy_loss_ratio"].as_f64().expect("loss").abs() < 1e-9,
        "{v}"
    );
    assert!((v["v_after"]["omega"].as_f64().expect("omega") + 3.0 / 4.0).abs() < 1e-8);
    assert!((v["v_after"]["v_gn"].as_f64().expect("v_gn") - 1.5).abs() < 1e-8);
    assert_eq!(v["v_after"]["v_gt"].as_f64(), Some(0.0));
    // time unit sqrt(m/c2) = 2/3 s, contact pi/sqrt(2 sigma) = pi units
    let t = v["contact_time"].as_f64().expect("time");
    assert!((t - std::f64::consts::PI * 2.0 / 3.0).abs() < 1e-8, "{t}");
    assert_eq!(v["suspension_reaction_free"], true);

    let p = write_scene(
        "pw2.toml",
        "model = \"pendulum-wall\"\nrho = 0.5\nsigma = 1.0\n",
    );
    let v = run_json(p.to_str().expect("utf8"));
    let loss = v["energy_loss_ratio"].as_f64().expect("loss");
    assert!((loss - 0.64).abs() < 1e-6, "{loss}");
    assert!(
        v["warnings"][0]
            .as_str()
            .expect("a warning")
            .contains("tangentially")
    );
}

/// Balls against a wall: the contract keys, checked against an invariant the code does not
/// impose: the elements are elastic, so once both contacts are open the kinetic energy equals the
/// striker's initial energy; both balls leave the wall, the striker no slower than its neighbour.
#[test]
fn balls_wall_contract() {
    let v = run_json("scenes/balls_wall.toml");
    let (v1, v2) = (
        v["v_striker_after"].as_f64().expect("striker"),
        v["v_wall_ball_after"].as_f64().expect("wall ball"),
    );
    // elastic: the kinetic energy is conserved once both contacts are open
    assert!((v1 * v1 + v2 * v2 - 1.0).abs() < 1e-8, "{v1} {v2}");
    assert!(v1 < 0.0 && v2 < 0.0 && v1 <= v2);
}

/// Disk friction: the contract keys; pure spin gives M = 2 f N a/3 and F = 0 (by hand).
#[test]
fn disk_friction_contract() {
    let p = write_scene(
        "disk.toml",
        "model = \"disk-friction\"\na = 0.1\nv = 0.0\nomega = 5.0\n",
    );
    let v = run_json(p.to_str().expect("utf8"));
    assert!(v["force"].as_f64().expect("force").abs() < 1e-14);
    assert!((v["moment"].as_f64().expect("moment") - 2.0 / 3.0).abs() < 1e-14);
    assert!((v["moment_elliptic"].as_f64().expect("elliptic") - 2.0 / 3.0).abs() < 1e-14);
    assert!(v["force_elliptic"].as_f64().expect("elliptic").abs() < 1e-14);
    let p = write_scene(
        "disk2.toml",
        "model = \"disk-friction\"\nk = 0.5\nv = 1.0\n",
    );
    let (code, _, err) = impact(&["run", p.to_str().expect("utf8")]);
    assert_ne!(code, 0);
    assert!(err.contains("either k, or v and omega"), "{err}");
}

/// `impact sweep --vary` in csv and json: values evenly spaced (both ends included), one row per
/// value, a bad value rejected before anything runs, and a malformed spec named.
#[test]
fn sweep_vary_csv_and_json() {
    let (code, out, err) = impact(&[
        "sweep",
        "scenes/pendulum_on_wall.toml",
        "--vary",
        "sigma=0.5:2:4",
        "--format",
        "csv",
    ]);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 5);
    assert!(lines[0].starts_with("sigma,") && lines[0].contains("energy_loss_ratio"));
    let firsts: Vec<f64> = lines[1..]
        .iter()
        .map(|l| l.split(',').next().expect("cell").parse().expect("number"))
        .collect();
    assert_eq!(firsts, vec![0.5, 1.0, 1.5, 2.0]);
    let (code, out, _) = impact(&[
        "sweep",
        "scenes/disk_friction.toml",
        "--vary",
        "omega=0.1:10:3",
        "--log",
        "--format",
        "json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).expect("json");
    let runs = v["runs"].as_array().expect("runs");
    assert_eq!(runs.len(), 3);
    assert!((runs[1]["value"].as_f64().expect("v") - 1.0).abs() < 1e-12);
    let (code, _, err) = impact(&[
        "sweep",
        "scenes/pendulum_on_wall.toml",
        "--vary",
        "sigma=-1:2:3",
    ]);
    assert_ne!(code, 0);
    assert!(
        err.contains("sigma") && err.contains("1e-8 <= sigma"),
        "{err}"
    );
    let (code, _, err) = impact(&["sweep", "scenes/hertz.toml", "--vary", "impactor.v0=1:2"]);
    assert_ne!(code, 0);
    assert!(err.contains("START:STOP:COUNT"), "{err}");
}

/// Sharding: three shards of one sweep, merged, equal the unsharded sweep point for point; a
/// missing shard is an error naming the missing indices.
#[test]
fn sharded_sweep_merges_to_the_whole() {
    let dir = std::env::temp_dir().join(format!("impactcheck-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let vary = ["--vary", "sigma=0.2:4:7", "--format", "json", "--quiet"];
    let mut files = Vec::new();
    for k in 0..3 {
        let shard = format!("{k}/3");
        let mut args = vec![
            "sweep",
            "scenes/pendulum_on_wall.toml",
            "--shard",
            shard.as_str(),
        ];
        args.extend(vary);
        let (code, out, err) = impact(&args);
        assert_eq!(code, 0, "{err}");
        let f = dir.join(format!("s{k}.json"));
        std::fs::write(&f, out).expect("write");
        files.push(f.to_str().expect("utf8").to_string());
    }
    let mut args = vec!["merge"];
    args.extend(files.iter().map(String::as_str));
    let (code, merged, err) = impact(&args);
    assert_eq!(code, 0, "{err}");
    let mut whole_args = vec!["sweep", "scenes/pendulum_on_wall.toml"];
    whole_args.extend(vary);
    let (_, whole, _) = impact(&whole_args);
    let (m, w): (serde_json::Value, serde_json::Value) = (
        serde_json::from_str(&merged).expect("json"),
        serde_json::from_str(&whole).expect("json"),
    );
    assert_eq!(m["runs"], w["runs"]);
    let (code, _, err) = impact(&["merge", &files[0], &files[2]]);
    assert_ne!(code, 0);
    assert!(err.contains("first missing indices [2, 3]"), "{err}");
}

/// `impact --help` describes every subcommand under its own name (a doc comment once slid onto
/// the next command: `describe` read "Merge the JSON outputs..." and `merge` had no text).
#[test]
fn every_impact_subcommand_has_its_own_description() {
    let out = Command::new(env!("CARGO_BIN_EXE_impact"))
        .arg("--help")
        .output()
        .expect("runs");
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    let line = |name: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(&format!("{name} ")))
            .unwrap_or_else(|| panic!("{name} not listed:\n{text}"))
            .trim_start()[name.len()..]
            .trim()
            .to_string()
    };
    for (name, says) in [
        ("run", "Run one scene"),
        ("sweep", "over a range"),
        ("describe", "scene key"),
        ("merge", "Merge the JSON outputs"),
        ("bench", "Measure"),
        ("series", "Adomian"),
        ("galerkin", "A1..A7"),
    ] {
        let l = line(name);
        assert!(l.contains(says), "{name}: `{l}`");
    }
}
