//! Each model documents itself, completely: `verify/MODELS.md` is what `impact describe` prints
//! today, every key of every scene in `scenes/` is listed in its model's reference, and every
//! value of its run's JSON is listed among the model's outcomes (so a key or an outcome added to
//! a model without its documentation fails here).

use impactcheck::models::doc::{covers, markdown};
use impactcheck::scene;
use serde_json::Value;
use std::path::Path;

/// Dotted paths of the leaves of a TOML or JSON tree; an array of tables or arrays is `[]`,
/// an array of scalars a leaf.
fn leaves(v: &Value, at: &str, out: &mut Vec<String>) {
    let join = |k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                leaves(x, &join(k), out);
            }
        }
        Value::Array(a) if a.iter().any(|x| x.is_object() || x.is_array()) => {
            for x in a {
                leaves(x, &format!("{at}[]"), out);
            }
        }
        _ => out.push(at.to_string()),
    }
}

fn documented(patterns: &[&str], path: &str) -> bool {
    let bare = path.strip_suffix("[]").unwrap_or(path);
    patterns.iter().any(|p| covers(p, path) || covers(p, bare))
}

#[test]
fn models_md_is_what_describe_prints() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let want = markdown(scene::DOCS);
    let have = std::fs::read_to_string(root.join("verify/MODELS.md")).unwrap_or_default();
    assert!(
        have == want,
        "verify/MODELS.md is out of date: run `cargo run --release --bin impact -- describe --format markdown > verify/MODELS.md`"
    );
}

#[test]
fn every_scene_key_and_every_outcome_is_documented() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes: Vec<_> = std::fs::read_dir(root.join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    scenes.sort();
    let mut seen_models = std::collections::BTreeSet::new();
    let mut missing = Vec::new();
    for path in &scenes {
        let table = scene::read_table(path).expect("reads");
        let model = table["model"].as_str().expect("model").to_string();
        let doc = scene::describe(&model).expect("documented model");
        seen_models.insert(model.clone());
        let keys: Vec<&str> = doc.all_keys().map(|k| k.key).collect();
        let mut found = Vec::new();
        leaves(&serde_json::to_value(&table).expect("json"), "", &mut found);
        for k in found.iter().filter(|k| !documented(&keys, k)) {
            missing.push(format!("{}: scene key `{k}` of {model}", path.display()));
        }
        let Ok(s) = scene::load(path) else { continue };
        let Ok((json, _)) = s.run() else { continue };
        let outs: Vec<&str> = doc.all_outcomes().map(|o| o.path).collect();
        let mut found = Vec::new();
        leaves(&json, "", &mut found);
        for o in found.iter().filter(|o| !documented(&outs, o)) {
            missing.push(format!("{}: outcome `{o}` of {model}", path.display()));
        }
    }
    assert!(missing.is_empty(), "undocumented:\n{}", missing.join("\n"));
    // every model has a scene that exercises its documentation
    for d in scene::DOCS {
        assert!(
            seen_models.contains(d.name),
            "no scene of {} in scenes/",
            d.name
        );
        assert!(
            root.join(d.example).is_file(),
            "{}: example {}",
            d.name,
            d.example
        );
    }
}
