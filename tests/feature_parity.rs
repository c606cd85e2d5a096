//! The set-up cost of a fresh clone (issue 54): `cargo test` after `cargo run` must reuse the
//! library and every dependency the run built. Cargo builds a crate once per feature set, and a
//! dev-dependency that switches on a feature of a shared crate (criterion turned on syn's
//! "full", zerocopy's "derive" and either's "use_std"; approx's "default"; usvg smallvec's
//! "const_generics") made the test step rebuild those crates and the library again: about two
//! minutes of a cold set-up on 2 cores. This test fails naming the crate and the features that
//! differ between the run's dependency graph and the tests'.

use std::collections::BTreeMap;
use std::process::Command;

/// `package version -> features` of the graph cargo resolves with the given edge kinds.
fn features(edges: &str) -> BTreeMap<String, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "tree",
            "--offline",
            "--locked",
            "-p",
            "impactcheck",
            "-e",
            edges,
            "--prefix",
            "none",
            "--no-dedupe",
            "-f",
            "{p}|{f}",
        ])
        .output()
        .expect("cargo tree runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let (p, f) = l.split_once('|')?;
            // a package by name and version (a proc-macro's marker and path dropped)
            let key: String = p.split_whitespace().take(2).collect::<Vec<_>>().join(" ");
            Some((key, f.to_string()))
        })
        .collect()
}

#[test]
fn the_tests_build_every_shared_crate_with_the_runs_features() {
    let run = features("normal,build");
    let tests = features("normal,build,dev");
    assert!(run.len() > 20, "the run's graph: {run:?}");
    let differ: Vec<String> = run
        .iter()
        .filter(|(p, _)| !p.starts_with("impactcheck "))
        .filter_map(|(p, f)| {
            let t = tests.get(p)?;
            (t != f).then(|| format!("{p}: run [{f}], tests [{t}]"))
        })
        .collect();
    assert!(
        differ.is_empty(),
        "a dev-dependency switches on features of crates the run builds, so `cargo test` \
         rebuilds them and the library: give the normal dependency the same features\n{}",
        differ.join("\n")
    );
}
