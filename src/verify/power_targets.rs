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
