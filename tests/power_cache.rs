//! The reuse of measured power (issue 45, `src/verify/power_cache.rs`): a claim's key changes
//! when anything its power depends on changes (its own text, its file's `[symbols]`, the scene
//! it names) and not when another claim of the file changes; the main job reuses a power only
//! under the same key.

#[path = "support/scratch.rs"]
mod scratch;

use impactcheck::report::{Power, Summary};
use impactcheck::verify::{load_claims, power_cache};
use scratch::Scratch;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

const HEAD: &str = r#"paper = "k"
title = "keys"
report = "k.md"
[symbols]
x = "m"
y = "m"
"#;

fn claim(id: &str, printed: &str) -> String {
    format!(
        "\n[[claim]]\nid = \"{id}\"\nequation = \"(1)\"\nreading = \"r\"\nkind = \"dimension\"\nprinted = \"{printed}\"\nexpect = \"m\"\n"
    )
}

/// A claim that names a scene (`hertz.toml` beside it).
const MODEL: &str = r#"
[[claim]]
id = "k.model"
equation = "(2)"
reading = "the Hertz duration"
kind = "model"
scene = "hertz.toml"
quantity = "contact.duration"
printed = "3.2181*(m/k)^(2/5)*v0^(-1/5)"
bind = { m = "impactor.mass", k = "contact.k", v0 = "impactor.v0" }
vary = ["impactor.v0=0.5:2:2"]
rtol = 1e-3
"#;

fn keys_of(dir: &Path, head: &str, body: &str) -> BTreeMap<String, String> {
    let p = dir.join("claims.toml");
    std::fs::write(&p, format!("{head}{body}")).unwrap();
    let papers = load_claims(&p).expect("loads");
    power_cache::keys(&papers)
}

#[test]
fn a_key_changes_with_what_the_power_depends_on_and_nothing_else() {
    let dir = Scratch::new("power-keys");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/hertz.toml");
    std::fs::copy(&scene, dir.join("hertz.toml")).unwrap();
    let head =
        format!("{HEAD}m = \"kg\"\nk = \"N/m^1.5\"\nv0 = \"m/s\"\n\"contact.duration\" = \"s\"\n");
    let body = format!("{}{}{MODEL}", claim("k.a", "x + y"), claim("k.b", "x"));
    let k0 = keys_of(&dir, &head, &body);
    assert_eq!(k0.len(), 3, "{k0:?}");
    // the same files: the same keys (nothing random, no time, no absolute path)
    assert_eq!(keys_of(&dir, &head, &body), k0);
    // the claim's own text
    let edited = format!("{}{}{MODEL}", claim("k.a", "x - y"), claim("k.b", "x"));
    let k1 = keys_of(&dir, &head, &edited);
    assert_ne!(k1["k.a"], k0["k.a"]);
    assert_eq!(k1["k.b"], k0["k.b"]);
    assert_eq!(k1["k.model"], k0["k.model"]);
    // the file's [symbols]: every claim of the file
    let k2 = keys_of(&dir, &head.replace("y = \"m\"", "y = \"s\""), &body);
    assert!(k2.iter().all(|(id, k)| k0[id] != *k), "{k2:?}");
    // the scene a claim names: that claim only
    let text = std::fs::read_to_string(&scene).unwrap();
    std::fs::write(dir.join("hertz.toml"), format!("{text}\n# edited\n")).unwrap();
    let k3 = keys_of(&dir, &head, &body);
    assert_ne!(k3["k.model"], k0["k.model"]);
    assert_eq!(k3["k.a"], k0["k.a"]);
    // every key carries the code's hash (build.rs): 32 hex digits of it
    assert_eq!(power_cache::CODE.len(), 32);
    assert!(power_cache::CODE.chars().all(|c| c.is_ascii_hexdigit()));
}

#[test]
fn only_a_power_under_the_same_key_is_reused() {
    let power = |key: Option<&str>, killed: usize| Power {
        mutants: 4,
        killed,
        key: key.map(str::to_string),
        ..Power::default()
    };
    let claim = |id: &str, p: Option<Power>| {
        serde_json::json!({
            "id": id, "paper": "k", "equation": "(1)", "verdict": "holds", "detail": "",
            "power": p,
        })
    };
    let previous: Summary = serde_json::from_value(serde_json::json!({
        "claims": [
            claim("same", Some(power(Some("aa"), 4))),
            claim("changed", Some(power(Some("bb"), 3))),
            claim("no-key", Some(power(None, 2))),
            claim("unmeasured", None),
            claim("not-asked", Some(power(Some("ee"), 1))),
        ],
        "generated_by": {"version": "0"},
    }))
    .unwrap();
    let keys: BTreeMap<String, String> = [
        ("same", "aa"),
        ("changed", "b2"),
        ("no-key", "cc"),
        ("unmeasured", "dd"),
        ("not-asked", "ee"),
    ]
    .map(|(a, b)| (a.to_string(), b.to_string()))
    .into_iter()
    .collect();
    let mut measured: BTreeSet<String> = ["same", "changed", "no-key", "unmeasured", "new"]
        .map(str::to_string)
        .into_iter()
        .collect();
    let reused = power_cache::reuse(&previous, &keys, &mut measured);
    assert_eq!(reused.keys().collect::<Vec<_>>(), ["same"]);
    assert_eq!(reused["same"].killed, 4);
    let left: Vec<&str> = measured.iter().map(String::as_str).collect();
    assert_eq!(left, ["changed", "new", "no-key", "unmeasured"]);
}
