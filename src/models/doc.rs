//! Each model documents itself: its scene keys (unit, allowed range, default, meaning) and its
//! outcomes (unit, meaning, sign convention), as data beside its code ([`super::Model::DOC`]).
//! `impact describe MODEL` prints it; `verify/MODELS.md` is [`markdown`] of every model, and a
//! test keeps the file current and checks that every key of every example scene and every
//! number of every run is documented.
//!
//! A key or outcome path may end in `.*` (any name below: `parameters.*`, `outcome.*`) and
//! writes an array of tables as `[]` (`body[].mass`).

use serde::Serialize;

/// One scene key.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Key {
    /// Dotted path (`impactor.mass`, `body[].mass`, `parameters.*`).
    pub key: &'static str,
    /// SI unit, `1` for a pure number, `-` for text or a choice.
    pub unit: &'static str,
    /// What is allowed.
    pub range: &'static str,
    /// The default, or `required`.
    pub default: &'static str,
    /// What it is.
    pub meaning: &'static str,
}

/// One outcome of `impact run --format json`.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Out {
    /// Dotted JSON path (`contact.duration`, `impulse[]`, `outcome.*`).
    pub path: &'static str,
    /// SI unit, `1` for a pure number, `-` for text, a flag or a count.
    pub unit: &'static str,
    /// What it is, with its sign convention.
    pub meaning: &'static str,
}

/// A model's reference.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct ModelDoc {
    /// The name scenes give it (`model = "hertz"`).
    pub name: &'static str,
    /// One paragraph: what it models, from which paper and equations.
    pub summary: &'static str,
    /// Sign conventions and frames.
    pub conventions: &'static [&'static str],
    /// An example scene in `scenes/`.
    pub example: &'static str,
    /// Its scene keys, in groups (the shared `[solve]` keys are one group).
    pub keys: &'static [&'static [Key]],
    /// Its outcomes, in groups.
    pub outcomes: &'static [&'static [Out]],
}

impl ModelDoc {
    /// Every key, groups flattened.
    pub fn all_keys(&self) -> impl Iterator<Item = &Key> {
        self.keys.iter().flat_map(|g| g.iter())
    }

    /// Every outcome, groups flattened.
    pub fn all_outcomes(&self) -> impl Iterator<Item = &Out> {
        self.outcomes.iter().flat_map(|g| g.iter())
    }
}

/// Whether the documented `pattern` covers the concrete `path` (`.*` covers any name below,
/// `[]` stands for every index).
pub fn covers(pattern: &str, path: &str) -> bool {
    match pattern.strip_suffix(".*") {
        Some(prefix) => path
            .strip_prefix(prefix)
            .is_some_and(|rest| rest.starts_with('.') && rest.len() > 1),
        None => pattern == path,
    }
}

/// The unit of every number of a run's JSON `out`, by its dotted path (`contact.duration`,
/// `impulse.2`, `outcome.t2`), as the model documents it: a documented unit that names a map of
/// the run (`outcome_units.*`: a text model's units, derived from its formulas) is read there. A
/// number whose unit is text, a count, a flag or a phrase (`-`, `derived`, `1 (f N)`) is left
/// out: the claims file must give it.
pub fn outcome_units(
    doc: &ModelDoc,
    out: &serde_json::Value,
) -> std::collections::BTreeMap<String, crate::algebra::units::Unit> {
    use serde_json::Value;
    fn walk(v: &Value, path: &str, shape: &str, leaf: &mut dyn FnMut(&str, &str)) {
        let join = |a: &str, k: &str| {
            if a.is_empty() {
                k.to_string()
            } else {
                format!("{a}.{k}")
            }
        };
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    walk(x, &join(path, k), &join(shape, k), leaf);
                }
            }
            Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    let at = join(path, &i.to_string());
                    if x.is_object() || x.is_array() {
                        walk(x, &at, &format!("{shape}[]"), leaf);
                    } else {
                        leaf(&at, &format!("{shape}[]"));
                    }
                }
            }
            Value::Number(_) => leaf(path, shape),
            _ => {}
        }
    }
    let mut units = std::collections::BTreeMap::new();
    walk(out, "", "", &mut |path, shape| {
        let bare = shape.strip_suffix("[]").unwrap_or(shape);
        let Some(o) = doc
            .all_outcomes()
            .find(|o| covers(o.path, shape) || covers(o.path, bare))
        else {
            return;
        };
        let text = match o.unit.strip_suffix(".*") {
            Some(map) => {
                let name = path.rsplit('.').next().unwrap_or(path);
                match out
                    .get(map)
                    .and_then(|m| m.get(name))
                    .and_then(Value::as_str)
                {
                    Some(u) => u.to_string(),
                    None => return,
                }
            }
            None => o.unit.to_string(),
        };
        if let Ok(u) = crate::algebra::units::Unit::parse(&text) {
            units.insert(path.to_string(), u);
        }
    });
    units
}

/// `[solve]` of a model integrated to the end of contact or to `t_end`.
pub const SOLVE: &[Key] = &[
    Key {
        key: "solve.rtol",
        unit: "1",
        range: "0 < rtol < 1",
        default: "1e-9",
        meaning: "relative tolerance of the integrator",
    },
    Key {
        key: "solve.atol",
        unit: "as the states",
        range: "atol > 0",
        default: "1e-12",
        meaning: "absolute tolerance of the integrator",
    },
    Key {
        key: "solve.method",
        unit: "-",
        range: "\"dop853\", \"dopri5\", \"radau5\", \"auto\"",
        default: "\"dop853\"",
        meaning: "the integrator; \"auto\" starts with DOP853 and moves to Radau5 when stiffness is detected",
    },
    Key {
        key: "solve.t_end",
        unit: "s",
        range: "\"contact-end\" or a time > 0",
        default: "\"contact-end\"",
        meaning: "where the run ends: when contact ends, or at a time",
    },
];

/// The work counters every integrated model reports.
pub const STATS: &[Out] = &[
    Out {
        path: "stats.rhs_evals",
        unit: "-",
        meaning: "right-hand-side evaluations",
    },
    Out {
        path: "stats.jac_evals",
        unit: "-",
        meaning: "Jacobian evaluations (Radau5)",
    },
    Out {
        path: "stats.lu_decomps",
        unit: "-",
        meaning: "LU decompositions (Radau5)",
    },
    Out {
        path: "stats.steps",
        unit: "-",
        meaning: "accepted steps",
    },
    Out {
        path: "stats.rejected",
        unit: "-",
        meaning: "rejected steps",
    },
    Out {
        path: "stats.events",
        unit: "-",
        meaning: "events located",
    },
];

/// The contact of one impact, as every contact model reports it ([`super::ContactOutcome`]).
pub const CONTACT: &[Out] = &[
    Out {
        path: "contact.ended",
        unit: "-",
        meaning: "whether contact ended inside the window",
    },
    Out {
        path: "contact.duration",
        unit: "s",
        meaning: "contact duration (the window if it did not end)",
    },
    Out {
        path: "contact.peak_force",
        unit: "N",
        meaning: "largest contact force",
    },
    Out {
        path: "contact.max_indentation",
        unit: "m",
        meaning: "largest indentation",
    },
];

/// What every model's JSON starts with.
pub const COMMON: &[Out] = &[Out {
    path: "model",
    unit: "-",
    meaning: "the model's name",
}];

fn cell(s: &str) -> String {
    s.replace('|', "\\|")
}

/// One model as Markdown.
pub fn model_markdown(d: &ModelDoc) -> String {
    let mut s = format!(
        "## `{}`\n\n{}\n\nExample: `{}`.\n\n",
        d.name, d.summary, d.example
    );
    if !d.conventions.is_empty() {
        s.push_str("Conventions:\n\n");
        for c in d.conventions {
            s.push_str(&format!("- {c}\n"));
        }
        s.push('\n');
    }
    s.push_str("| scene key | unit | allowed | default | meaning |\n|---|---|---|---|---|\n");
    for k in d.all_keys() {
        s.push_str(&format!(
            "| `{}` | {} | {} | {} | {} |\n",
            k.key,
            cell(k.unit),
            cell(k.range),
            cell(k.default),
            cell(k.meaning)
        ));
    }
    s.push_str("\n| outcome (`impact run --format json`) | unit | meaning |\n|---|---|---|\n");
    for o in d.all_outcomes() {
        s.push_str(&format!(
            "| `{}` | {} | {} |\n",
            o.path,
            cell(o.unit),
            cell(o.meaning)
        ));
    }
    s.push('\n');
    s
}

/// The reference of every model (`verify/MODELS.md`).
pub fn markdown(docs: &[&ModelDoc]) -> String {
    let mut s = String::from(
        "# The models\n\nGenerated by `impact describe --format markdown` from each model's own documentation (`DOC` in its file under `src/models/`); a test keeps this file current and checks that every key of every scene in `scenes/` and every number of its run is listed here. Units are SI; `1` is a pure number, `-` text, a flag or a count. A path ending in `.*` stands for any name below it; `[]` for every index of an array.\n\n",
    );
    for d in docs {
        s.push_str(&model_markdown(d));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_cover_what_they_say() {
        assert!(covers("parameters.*", "parameters.k"));
        assert!(!covers("parameters.*", "parameters"));
        assert!(!covers("parameters.*", "parametersx.k"));
        assert!(covers("body[].mass", "body[].mass"));
        assert!(!covers("body[].mass", "body[].inertia[]"));
    }
}
