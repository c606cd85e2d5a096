//! Where a claim's misprints go: its printed keys (`printed`, `printed_equations[2]`,
//! `printed_matrix[0][1]`) and the `where` entries the paper prints (`printed_where`), each with
//! its path in the claim's keys, and the claim's keys with one of them replaced
//! ([`super::power`]).

use super::ClaimSpec;

/// A printed key of a claim: where it is in the claim's keys, and its text.
#[derive(Clone, Debug)]
pub(super) struct Target {
    /// `printed`, `printed_equations[2]`, `printed_matrix[0][1]`.
    pub(super) path: Vec<PathPart>,
    pub(super) text: String,
}

#[derive(Clone, Debug)]
pub(super) enum PathPart {
    Key(String),
    Index(usize),
}

pub(super) fn targets(keys: &toml::Table, names: &[&str]) -> Vec<Target> {
    fn go(v: &toml::Value, path: Vec<PathPart>, out: &mut Vec<Target>) {
        match v {
            toml::Value::String(s) => out.push(Target {
                path,
                text: s.clone(),
            }),
            toml::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    let mut p = path.clone();
                    p.push(PathPart::Index(i));
                    go(x, p, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for name in names {
        if let Some(v) = keys.get(*name) {
            go(v, vec![PathPart::Key(name.to_string())], &mut out);
        }
    }
    out
}

/// The printed keys `keys` of a claim, and the entries of its `where` that the paper prints
/// (`printed_where`: a definition the paper gives, not a test input), when its printed side is
/// measured (not its `corrected` one).
pub(super) fn claim_targets(spec: &ClaimSpec, keys: &[&str]) -> Vec<Target> {
    let mut out = targets(&spec.keys, keys);
    if keys != ["corrected"] {
        for name in &spec.head.printed_where {
            if let Some(text) = spec
                .keys
                .get("where")
                .and_then(|w| w.get(name.as_str()))
                .and_then(|v| v.as_str())
            {
                out.push(Target {
                    path: vec![PathPart::Key("where".into()), PathPart::Key(name.clone())],
                    text: text.to_string(),
                });
            }
        }
    }
    out
}

pub(super) fn path_text(path: &[PathPart]) -> String {
    path.iter()
        .enumerate()
        .map(|(n, p)| match p {
            PathPart::Key(k) if n > 0 => format!(".{k}"),
            PathPart::Key(k) => k.clone(),
            PathPart::Index(i) => format!("[{i}]"),
        })
        .collect()
}

pub(super) fn replaced(keys: &toml::Table, path: &[PathPart], text: String) -> toml::Table {
    fn put(v: &mut toml::Value, path: &[PathPart], text: String) {
        match path.split_first() {
            None => *v = toml::Value::String(text),
            Some((PathPart::Index(i), rest)) => {
                if let Some(x) = v.as_array_mut().and_then(|a| a.get_mut(*i)) {
                    put(x, rest, text);
                }
            }
            Some((PathPart::Key(k), rest)) => {
                if let Some(x) = v.as_table_mut().and_then(|t| t.get_mut(k)) {
                    put(x, rest, text);
                }
            }
        }
    }
    let mut v = toml::Value::Table(keys.clone());
    put(&mut v, path, text);
    match v {
        toml::Value::Table(t) => t,
        _ => keys.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_misprint_replaces_the_one_value_its_path_names() {
        let keys: toml::Table = toml::from_str(
            "printed = \"a\"\nprinted_equations = [\"b\", \"c\"]\nwhere = { x = \"d\", y = \"e\" }",
        )
        .unwrap();
        let get = |t: &toml::Table, path: &[&str]| -> String {
            let mut v = t.get(path[0]).unwrap();
            for p in &path[1..] {
                v = match p.parse::<usize>() {
                    Ok(i) => &v.as_array().unwrap()[i],
                    Err(_) => v.get(*p).unwrap(),
                };
            }
            v.as_str().unwrap().to_string()
        };
        let k = replaced(
            &keys,
            &[PathPart::Key("where".into()), PathPart::Key("x".into())],
            "2*d".into(),
        );
        assert_eq!(get(&k, &["where", "x"]), "2*d");
        assert_eq!(get(&k, &["where", "y"]), "e");
        assert_eq!(get(&k, &["printed"]), "a");
        let k = replaced(
            &keys,
            &[
                PathPart::Key("printed_equations".into()),
                PathPart::Index(1),
            ],
            "-c".into(),
        );
        assert_eq!(get(&k, &["printed_equations", "1"]), "-c");
        assert_eq!(get(&k, &["printed_equations", "0"]), "b");
        // the targets: the printed keys, then the `where` entries the paper prints
        let spec: ClaimSpec = toml::from_str(
            "id = \"t.a\"\nequation = \"(1)\"\nkind = \"identity\"\nprinted_where = [\"x\"]\nprinted = \"a\"\nwhere = { x = \"d\", y = \"e\" }",
        )
        .unwrap();
        let t = claim_targets(&spec, &["printed"]);
        let named: Vec<(String, &str)> = t
            .iter()
            .map(|t| (path_text(&t.path), t.text.as_str()))
            .collect();
        assert_eq!(
            named,
            [("printed".to_string(), "a"), ("where.x".to_string(), "d")]
        );
        // a `corrected` side is measured alone: the paper's `where` is no part of it
        assert_eq!(claim_targets(&spec, &["corrected"]).len(), 0);
    }
}
