//! `impact run` keeps its contract: for every scene in `scenes/`, the JSON and text output (or, for
//! a scene whose run fails, the error and exit code 2) against the snapshot in `tests/golden/`.
//!
//! The snapshots were written by `impact run` at commit "000's printed formulas as text", before
//! the models owned their parameters and outcomes (the JSON trees were then assembled by hand in
//! `src/cli/`); they pin the keys, their nesting and the numbers of the contract across that and
//! later refactors. A scene added to `scenes/` needs its snapshot (the test says so). Numbers in
//! the JSON compare to 1e-12 relative, the rest exactly.

use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn same(a: &Value, b: &Value, path: &str) -> Result<(), String> {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            if x == y || (x - y).abs() <= 1e-12 * x.abs().max(y.abs()) {
                Ok(())
            } else {
                Err(format!("{path}: {x} != {y}"))
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            let kx: Vec<_> = x.keys().collect();
            let ky: Vec<_> = y.keys().collect();
            if kx != ky {
                return Err(format!("{path}: keys {kx:?} != {ky:?}"));
            }
            for (k, v) in x {
                same(v, &y[k], &format!("{path}.{k}"))?;
            }
            Ok(())
        }
        (Value::Array(x), Value::Array(y)) => {
            if x.len() != y.len() {
                return Err(format!("{path}: {} != {} items", x.len(), y.len()));
            }
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                same(u, v, &format!("{path}[{i}]"))?;
            }
            Ok(())
        }
        _ if a == b => Ok(()),
        _ => Err(format!("{path}: {a} != {b}")),
    }
}

#[test]
fn impact_run_output_is_unchanged_for_every_scene() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let golden = root.join("tests/golden");
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 10);
    for scene in scenes {
        let stem = scene
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or_default();
        let run = |format: &str| {
            Command::new(env!("CARGO_BIN_EXE_impact"))
                .args([
                    "run",
                    scene.to_str().unwrap_or_default(),
                    "--format",
                    format,
                ])
                .output()
                .expect("impact runs")
        };
        let err = golden.join(format!("{stem}.err"));
        if err.exists() {
            let out = run("json");
            assert_eq!(out.status.code(), Some(2), "{stem}: exit code");
            let want = std::fs::read_to_string(&err).expect("golden");
            assert_eq!(String::from_utf8_lossy(&out.stderr), want, "{stem}: error");
            continue;
        }
        let json = golden.join(format!("{stem}.json"));
        assert!(
            json.exists(),
            "{stem}: no snapshot; run `impact run scenes/{stem}.toml --format json > tests/golden/{stem}.json` (and --format text > .txt) once the output is right"
        );
        let out = run("json");
        assert!(
            out.status.success(),
            "{stem}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let got: Value = serde_json::from_slice(&out.stdout).expect("json");
        let want: Value =
            serde_json::from_str(&std::fs::read_to_string(&json).expect("golden")).expect("json");
        if let Err(e) = same(&got, &want, stem) {
            panic!("{stem}: --format json changed: {e}");
        }
        let text = run("text");
        let want = std::fs::read_to_string(golden.join(format!("{stem}.txt"))).expect("golden");
        assert_eq!(
            String::from_utf8_lossy(&text.stdout),
            want,
            "{stem}: --format text changed"
        );
    }
}

#[test]
fn a_sweep_sets_its_field_on_every_model() {
    // disk-friction sets no field on its typed parameters (the scene table is re-read per
    // point): k = v/(a omega) = 0.02/(0.05 omega) must follow omega = 1, 4 (0.4, 0.1 by hand)
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_impact"))
        .args([
            "sweep",
            "scenes/disk_friction.toml",
            "--vary",
            "omega=1:4:2",
        ])
        .args(["--format", "json", "--quiet"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("impact runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("json");
    let ks: Vec<f64> = v["runs"]
        .as_array()
        .expect("runs")
        .iter()
        .map(|r| r["result"]["k"].as_f64().expect("k"))
        .collect();
    assert_eq!(ks.len(), 2);
    assert!(
        (ks[0] - 0.4).abs() < 1e-12 && (ks[1] - 0.1).abs() < 1e-12,
        "{ks:?}"
    );
}
