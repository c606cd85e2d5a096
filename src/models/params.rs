//! Scene parameters: what every model's `from_table` shares. Parse, then validate: serde turns a
//! scene table into a model's raw structs (`deny_unknown_fields`, leaves kept as TOML values), and
//! the helpers here turn raw leaves into typed parameters with errors that name the file, the
//! dotted field and the allowed range.
//!
//! Unknown keys are reported before serde sees the table, with the keys the raw struct declares
//! ([`keys_of`]) and a near-miss suggestion (`did you mean impactor.mass?`); serde's own
//! `deny_unknown_fields` then stands behind that check.

use crate::integrate::Method;
use serde::de::DeserializeOwned;

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
    /// A field whose value is not of its kind: not a number, an unknown unit, a name that
    /// names nothing.
    #[error("{path}: {field} = {value}: {problem}")]
    Invalid {
        /// File.
        path: String,
        /// Dotted field name.
        field: String,
        /// Value given.
        value: String,
        /// What is wrong, and what is allowed.
        problem: String,
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
    /// A formula of a text model that cannot be used (its units, its names, its syntax).
    #[error("{path}: {field} = \"{formula}\": {message}")]
    Formula {
        /// File.
        path: String,
        /// Dotted field name.
        field: String,
        /// The formula as written.
        formula: String,
        /// What is wrong and what is allowed.
        message: String,
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
    /// Times at which to report the solution (s).
    pub samples: Vec<f64>,
}

/// The field names a serde-derived struct declares (its `deserialize_struct` call), so that
/// unknown keys are named with today's messages before serde reads the table.
pub fn keys_of<T: DeserializeOwned>() -> &'static [&'static str] {
    use serde::de::{Error, Visitor};
    struct Probe<'a>(&'a mut &'static [&'static str]);
    impl<'de> serde::Deserializer<'de> for Probe<'_> {
        type Error = serde::de::value::Error;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
            Err(Self::Error::custom("not a struct"))
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Self::Error> {
            *self.0 = fields;
            Err(Self::Error::custom("probed"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
            option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
            ignored_any
        }
    }
    let mut fields: &'static [&'static str] = &[];
    let _ = T::deserialize(Probe(&mut fields));
    fields
}

pub(crate) use crate::algebra::units::edit_distance;

/// Reads the fields of one scene file; `path` names it in every message.
pub struct Fields<'a> {
    /// The file, as named in messages.
    pub path: &'a str,
}

type Value = toml::Value;

impl Fields<'_> {
    /// An error for `field`.
    pub fn out_of_range(&self, field: &str, value: String, allowed: &str) -> SceneError {
        SceneError::OutOfRange {
            path: self.path.into(),
            field: field.into(),
            value,
            allowed: allowed.into(),
        }
    }

    /// An error for `field` whose value is not of its kind (`problem` says how).
    pub fn invalid(&self, field: &str, value: String, problem: &str) -> SceneError {
        SceneError::Invalid {
            path: self.path.into(),
            field: field.into(),
            value,
            problem: problem.into(),
        }
    }

    fn check_keys(
        &self,
        table: &toml::Table,
        prefix: &str,
        allowed: &[&str],
    ) -> Result<(), SceneError> {
        for key in table.keys() {
            if !allowed.contains(&key.as_str()) {
                let dotted = |k: &str| {
                    if prefix.is_empty() {
                        k.to_string()
                    } else {
                        format!("{prefix}.{k}")
                    }
                };
                let best = allowed
                    .iter()
                    .map(|a| (edit_distance(key, a), *a))
                    .min()
                    .filter(|(d, _)| *d <= 2)
                    .map(|(_, a)| format!(", did you mean {}?", dotted(a)))
                    .unwrap_or_default();
                return Err(SceneError::UnknownKey {
                    path: self.path.into(),
                    key: dotted(key),
                    suggestion: best,
                    allowed: allowed.join(", "),
                });
            }
        }
        Ok(())
    }

    /// A table's keys checked against the raw struct `T`, then `T` read by serde.
    pub fn raw<T: DeserializeOwned>(
        &self,
        table: &toml::Table,
        prefix: &str,
    ) -> Result<T, SceneError> {
        self.check_keys(table, prefix, keys_of::<T>())?;
        Value::Table(table.clone())
            .try_into()
            .map_err(|e: toml::de::Error| {
                self.out_of_range(
                    if prefix.is_empty() { "scene" } else { prefix },
                    "a table".into(),
                    e.to_string().trim(),
                )
            })
    }

    /// A required sub-table.
    pub fn table<'t>(
        &self,
        v: Option<&'t Value>,
        name: &str,
    ) -> Result<&'t toml::Table, SceneError> {
        match v {
            Some(Value::Table(t)) => Ok(t),
            Some(other) => Err(self.out_of_range(name, other.to_string(), "a table")),
            None => Err(SceneError::Missing {
                path: self.path.into(),
                field: format!("[{name}]"),
                allowed: "a table".into(),
            }),
        }
    }

    /// A finite number satisfying `ok`, or the default when absent.
    pub fn num(
        &self,
        v: Option<&Value>,
        field: &str,
        default: Option<f64>,
        ok: impl Fn(f64) -> bool,
        allowed: &str,
    ) -> Result<f64, SceneError> {
        let v = match v {
            None => {
                return default.ok_or_else(|| SceneError::Missing {
                    path: self.path.into(),
                    field: field.into(),
                    allowed: allowed.into(),
                });
            }
            Some(Value::Float(f)) => *f,
            Some(Value::Integer(i)) => *i as f64,
            Some(other) => {
                return Err(self.invalid(
                    field,
                    other.to_string(),
                    &format!(
                        "not a number; allowed: a number, {allowed} (SI units are implied: no unit is written)"
                    ),
                ));
            }
        };
        if !v.is_finite() || !ok(v) {
            return Err(self.out_of_range(field, v.to_string(), allowed));
        }
        Ok(v)
    }

    /// One of `choices` (a string), or the default when absent.
    pub fn choice(
        &self,
        v: Option<&Value>,
        field: &str,
        choices: &[&str],
        default: &str,
    ) -> Result<String, SceneError> {
        match v {
            None => Ok(default.to_string()),
            Some(Value::String(s)) if choices.contains(&s.as_str()) => Ok(s.clone()),
            Some(other) => Err(self.out_of_range(
                field,
                other.to_string(),
                &choices
                    .iter()
                    .map(|c| format!("\"{c}\""))
                    .collect::<Vec<_>>()
                    .join(", "),
            )),
        }
    }

    /// A 3-vector of finite numbers.
    pub fn vec3(
        &self,
        v: Option<&Value>,
        field: &str,
    ) -> Result<nalgebra::Vector3<f64>, SceneError> {
        let err = |v: String| {
            self.out_of_range(
                field,
                v,
                "a 3-vector of finite numbers, e.g. [0.0, 0.0, 1.0]",
            )
        };
        let v = v.ok_or_else(|| SceneError::Missing {
            path: self.path.into(),
            field: field.into(),
            allowed: "a 3-vector".into(),
        })?;
        let a = v.as_array().ok_or_else(|| err(v.to_string()))?;
        let xs: Vec<f64> = a
            .iter()
            .filter_map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64)))
            .collect();
        if xs.len() != 3 || a.len() != 3 || xs.iter().any(|x| !x.is_finite()) {
            return Err(err(v.to_string()));
        }
        Ok(nalgebra::Vector3::new(xs[0], xs[1], xs[2]))
    }

    /// The relative tolerance of a model solved in one piece (`rtol`, default 1e-10).
    pub fn rtol(&self, v: Option<&Value>) -> Result<f64, SceneError> {
        self.num(
            v,
            "rtol",
            Some(1e-10),
            |v| (1e-14..=1e-2).contains(&v),
            "1e-14 <= rtol <= 1e-2",
        )
    }

    /// The `[solve]` table; `default_end` is the word for "until the contact ends".
    pub fn solve(
        &self,
        v: Option<&Value>,
        default_end: &str,
        with_samples: bool,
    ) -> Result<SolveSpec, SceneError> {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Solve {
            rtol: Option<Value>,
            atol: Option<Value>,
            method: Option<Value>,
            t_end: Option<Value>,
            samples: Option<Value>,
        }
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct SolveToEnd {
            rtol: Option<Value>,
            atol: Option<Value>,
            method: Option<Value>,
            t_end: Option<Value>,
        }
        let empty = toml::Table::new();
        let t = match v {
            None => &empty,
            Some(_) => self.table(v, "solve")?,
        };
        let raw: Solve = if with_samples {
            self.raw(t, "solve")?
        } else {
            let s: SolveToEnd = self.raw(t, "solve")?;
            Solve {
                rtol: s.rtol,
                atol: s.atol,
                method: s.method,
                t_end: s.t_end,
                samples: None,
            }
        };
        let mut samples = Vec::new();
        if let Some(v) = &raw.samples {
            let arr = v.as_array().ok_or_else(|| {
                self.out_of_range("solve.samples", v.to_string(), "a list of times >= 0 in s")
            })?;
            for x in arr {
                match x.as_float().or_else(|| x.as_integer().map(|i| i as f64)) {
                    Some(f) if f.is_finite() && f >= 0.0 => samples.push(f),
                    _ => {
                        return Err(self.out_of_range(
                            "solve.samples",
                            x.to_string(),
                            "times >= 0 in s",
                        ));
                    }
                }
            }
        }
        let rtol = self.num(
            raw.rtol.as_ref(),
            "solve.rtol",
            Some(1e-9),
            |v| v > 0.0 && v < 1.0,
            "0 < rtol < 1",
        )?;
        let atol = self.num(
            raw.atol.as_ref(),
            "solve.atol",
            Some(1e-12),
            |v| v > 0.0,
            "atol > 0",
        )?;
        const METHODS: &str = "\"dop853\", \"dopri5\", \"radau5\", \"auto\"";
        let method = match &raw.method {
            None => Method::Dop853,
            Some(Value::String(s)) => Method::parse(s)
                .ok_or_else(|| self.out_of_range("solve.method", format!("\"{s}\""), METHODS))?,
            Some(other) => {
                return Err(self.out_of_range("solve.method", other.to_string(), METHODS));
            }
        };
        let t_end = match &raw.t_end {
            None => None,
            Some(Value::String(s)) if s == default_end => None,
            Some(_) => Some(self.num(
                raw.t_end.as_ref(),
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
            samples,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Two {
        mass: Option<Value>,
        v0: Option<Value>,
    }

    #[test]
    fn keys_come_from_the_serde_struct() {
        assert_eq!(keys_of::<Two>(), &["mass", "v0"]);
        let t: toml::Table = "mas = 1.0".parse().expect("toml");
        let e = Fields { path: "s.toml" }
            .raw::<Two>(&t, "impactor")
            .err()
            .map(|e| e.to_string());
        assert_eq!(
            e.as_deref(),
            Some(
                "s.toml: unknown key impactor.mas, did you mean impactor.mass?; allowed here: mass, v0"
            )
        );
    }
}
