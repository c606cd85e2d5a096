//! Scene files: parse, validate, pick effects.
//!
//! A scene is a TOML file naming a model, its parameters in SI units and how to solve it. Every
//! field is checked with its allowed range; unknown keys are rejected with a suggestion for a near
//! miss; the error names the file, the field and what is allowed.

use crate::integrate::Method;
use std::path::Path;

/// Why a scene could not be used.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{path}: cannot read: {message}")]
    Io {
        /// File.
        path: String,
        /// Reason.
        message: String,
    },
    /// Malformed or truncated TOML.
    #[error("{path}: not valid TOML: {message}")]
    Parse {
        /// File.
        path: String,
        /// Parser message.
        message: String,
    },
    /// A field is out of its allowed range.
    #[error("{path}: {field} = {value} is out of range; allowed: {allowed}")]
    OutOfRange {
        /// File.
        path: String,
        /// Dotted field name.
        field: String,
        /// Value given.
        value: String,
        /// Allowed range.
        allowed: String,
    },
    /// A required field is missing.
    #[error("{path}: missing field {field} ({allowed})")]
    Missing {
        /// File.
        path: String,
        /// Dotted field name.
        field: String,
        /// What it should be.
        allowed: String,
    },
    /// A key that no model knows.
    #[error("{path}: unknown key {key}{suggestion}; allowed here: {allowed}")]
    UnknownKey {
        /// File.
        path: String,
        /// Dotted key.
        key: String,
        /// ", did you mean ...?" or empty.
        suggestion: String,
        /// Keys allowed in that table.
        allowed: String,
    },
}

/// How to solve.
#[derive(Clone, Debug)]
pub struct SolveSpec {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Method.
    pub method: Method,
    /// End time (s); `None` for "until contact ends".
    pub t_end: Option<f64>,
}

/// The `hertz` scene.
#[derive(Clone, Debug)]
pub struct HertzScene {
    /// Impactor mass (kg).
    pub mass: f64,
    /// Impact speed (m/s).
    pub v0: f64,
    /// Contact stiffness (N/m^1.5).
    pub k: f64,
    /// Hunt-Crossley coefficient (s/m).
    pub damping: f64,
    /// Solver settings.
    pub solve: SolveSpec,
}

/// A validated scene.
#[derive(Clone, Debug)]
pub enum Scene {
    /// Sphere on a rigid-backed half-space.
    Hertz(HertzScene),
}

const MODELS: &str = "hertz";

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur.push(sub.min(prev[j + 1] + 1).min(cur[j] + 1));
        }
        prev = cur;
    }
    prev[b.len()]
}

struct Reader<'a> {
    path: &'a str,
}

impl Reader<'_> {
    fn check_keys(
        &self,
        table: &toml::Table,
        prefix: &str,
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        for key in table.keys() {
            if !allowed.contains(&key.as_str()) {
                let best = allowed
                    .iter()
                    .map(|a| (edit_distance(key, a), *a))
                    .min()
                    .filter(|(d, _)| *d <= 2)
                    .map(|(_, a)| {
                        format!(
                            ", did you mean {}{a}?",
                            if prefix.is_empty() {
                                String::new()
                            } else {
                                format!("{prefix}.")
                            }
                        )
                    })
                    .unwrap_or_default();
                return Err(SceneError::UnknownKey {
                    path: self.path.into(),
                    key: if prefix.is_empty() {
                        key.clone()
                    } else {
                        format!("{prefix}.{key}")
                    },
                    suggestion: best,
                    allowed: allowed.join(", "),
                });
            }
        }
        Ok(())
    }

    fn table<'t>(&self, root: &'t toml::Table, name: &str) -> Result<&'t toml::Table, SceneError> {
        match root.get(name) {
            Some(toml::Value::Table(t)) => Ok(t),
            Some(other) => Err(SceneError::OutOfRange {
                path: self.path.into(),
                field: name.into(),
                value: other.to_string(),
                allowed: "a table".into(),
            }),
            None => Err(SceneError::Missing {
                path: self.path.into(),
                field: format!("[{name}]"),
                allowed: "a table".into(),
            }),
        }
    }

    /// A finite number satisfying `ok`, or the default when absent.
    fn num(
        &self,
        t: &toml::Table,
        field: &str,
        default: Option<f64>,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<f64, SceneError> {
        let key = field.rsplit('.').next().unwrap_or(field);
        let v = match t.get(key) {
            None => {
                return default.ok_or_else(|| SceneError::Missing {
                    path: self.path.into(),
                    field: field.into(),
                    allowed: allowed.into(),
                });
            }
            Some(toml::Value::Float(f)) => *f,
            Some(toml::Value::Integer(i)) => *i as f64,
            Some(other) => {
                return Err(SceneError::OutOfRange {
                    path: self.path.into(),
                    field: field.into(),
                    value: other.to_string(),
                    allowed: format!("a number, {allowed}"),
                });
            }
        };
        if !v.is_finite() || !ok(v) {
            return Err(SceneError::OutOfRange {
                path: self.path.into(),
                field: field.into(),
                value: v.to_string(),
                allowed: allowed.into(),
            });
        }
        Ok(v)
    }

    fn solve(&self, root: &toml::Table, default_end: &str) -> Result<SolveSpec, SceneError> {
        let empty = toml::Table::new();
        let t = match root.get("solve") {
            None => &empty,
            Some(_) => self.table(root, "solve")?,
        };
        self.check_keys(t, "solve", &["rtol", "atol", "method", "t_end"])?;
        let rtol = self.num(
            t,
            "solve.rtol",
            Some(1e-9),
            |v| v > 0.0 && v < 1.0,
            "0 < rtol < 1",
        )?;
        let atol = self.num(t, "solve.atol", Some(1e-12), |v| v > 0.0, "atol > 0")?;
        let method = match t.get("method") {
            None => Method::Dop853,
            Some(toml::Value::String(s)) => {
                Method::parse(s).ok_or_else(|| SceneError::OutOfRange {
                    path: self.path.into(),
                    field: "solve.method".into(),
                    value: format!("\"{s}\""),
                    allowed: "\"dop853\", \"dopri5\", \"radau5\", \"auto\"".into(),
                })?
            }
            Some(other) => {
                return Err(SceneError::OutOfRange {
                    path: self.path.into(),
                    field: "solve.method".into(),
                    value: other.to_string(),
                    allowed: "\"dop853\", \"dopri5\", \"radau5\", \"auto\"".into(),
                });
            }
        };
        let t_end = match t.get("t_end") {
            None => None,
            Some(toml::Value::String(s)) if s == default_end => None,
            Some(_) => Some(self.num(
                t,
                "solve.t_end",
                None,
                |v| v > 0.0,
                &format!("\"{default_end}\" or a time > 0 in s"),
            )?),
        };
        Ok(SolveSpec {
            rtol,
            atol,
            method,
            t_end,
        })
    }
}

/// Parses and validates scene text; `path` names the file in messages.
pub fn parse(text: &str, path: &str) -> Result<Scene, SceneError> {
    let root: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| SceneError::Parse {
            path: path.into(),
            message: e.to_string().trim().replace('\n', " "),
        })?;
    parse_table(&root, path)
}

/// Validates an already parsed scene table.
pub fn parse_table(root: &toml::Table, path: &str) -> Result<Scene, SceneError> {
    let r = Reader { path };
    let model = match root.get("model") {
        Some(toml::Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(SceneError::OutOfRange {
                path: path.into(),
                field: "model".into(),
                value: other.to_string(),
                allowed: format!("one of: {MODELS}"),
            });
        }
        None => {
            return Err(SceneError::Missing {
                path: path.into(),
                field: "model".into(),
                allowed: format!("one of: {MODELS}"),
            });
        }
    };
    match model.as_str() {
        "hertz" => {
            r.check_keys(root, "", &["model", "impactor", "contact", "solve"])?;
            let imp = r.table(root, "impactor")?;
            r.check_keys(imp, "impactor", &["mass", "v0"])?;
            let con = r.table(root, "contact")?;
            r.check_keys(con, "contact", &["k", "damping"])?;
            Ok(Scene::Hertz(HertzScene {
                mass: r.num(imp, "impactor.mass", None, |v| v > 0.0, "mass > 0 (kg)")?,
                v0: r.num(
                    imp,
                    "impactor.v0",
                    None,
                    |v| v > 0.0,
                    "v0 > 0 (m/s), toward the surface",
                )?,
                k: r.num(con, "contact.k", None, |v| v > 0.0, "k > 0 (N/m^1.5)")?,
                damping: r.num(
                    con,
                    "contact.damping",
                    Some(0.0),
                    |v| v >= 0.0,
                    "damping >= 0 (s/m)",
                )?,
                solve: r.solve(root, "contact-end")?,
            }))
        }
        other => {
            let near = MODELS
                .split(", ")
                .find(|m| edit_distance(m, other) <= 2)
                .map(|m| format!(" (did you mean \"{m}\"?)"))
                .unwrap_or_default();
            Err(SceneError::OutOfRange {
                path: path.into(),
                field: "model".into(),
                value: format!("\"{other}\"{near}"),
                allowed: format!("one of: {MODELS}"),
            })
        }
    }
}

/// Reads a scene file as a TOML table (for sweeps that override fields before validation).
pub fn read_table(path: &Path) -> Result<toml::Table, SceneError> {
    let label = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| SceneError::Io {
        path: label.clone(),
        message: e.to_string(),
    })?;
    text.parse()
        .map_err(|e: toml::de::Error| SceneError::Parse {
            path: label,
            message: e.to_string().trim().replace('\n', " "),
        })
}

/// Reads and validates a scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    parse_table(&read_table(path)?, &path.display().to_string())
}

/// Sets a dotted field (`impactor.v0`) of a scene table to a number.
pub fn set_field(
    root: &mut toml::Table,
    field: &str,
    value: f64,
    path: &str,
) -> Result<(), SceneError> {
    let mut parts: Vec<&str> = field.split('.').collect();
    let last = parts.pop().unwrap_or(field);
    let mut t = root;
    for p in parts {
        t = match t
            .entry(p.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
        {
            toml::Value::Table(tt) => tt,
            _ => {
                return Err(SceneError::OutOfRange {
                    path: path.into(),
                    field: field.into(),
                    value: value.to_string(),
                    allowed: "a field inside a table".into(),
                });
            }
        };
    }
    t.insert(last.to_string(), toml::Value::Float(value));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const OK: &str = "model = \"hertz\"\n[impactor]\nmass = 1.0\nv0 = 1.0\n[contact]\nk = 1.0\n";

    #[test]
    fn valid_scene_parses() {
        assert!(matches!(parse(OK, "s.toml"), Ok(Scene::Hertz(_))));
    }

    #[test]
    fn errors_name_file_field_and_range() {
        let e = parse(&OK.replace("mass = 1.0", "mass = -1.0"), "s.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("s.toml") && e.contains("impactor.mass") && e.contains("mass > 0"),
            "{e}"
        );
        let e = parse(&OK.replace("mass = 1.0", "mas = 1.0"), "s.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean impactor.mass"), "{e}");
        let e = parse(&OK.replace("hertz", "hetz"), "s.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("did you mean \"hertz\""), "{e}");
        let e = parse("model = \"hertz\"\n[impactor\n", "s.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("not valid TOML"), "{e}");
        let e = parse(&format!("{OK}[solve]\nmethod = \"rk4\"\n"), "s.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("solve.method") && e.contains("radau5"), "{e}");
        let e = parse(&OK.replace("v0 = 1.0", "v0 = nan"), "s.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("impactor.v0"), "{e}");
    }
}
