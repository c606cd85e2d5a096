//! Scene files: the registry of model names, and reading a scene file into the model it names.
//!
//! A scene is a TOML file naming a model (`model = "hertz"`), its parameters in SI units and how
//! to solve it. Each model owns its parameters, their validation, its run and its typed outcome
//! ([`crate::models::Model`]); this module only maps names to models ([`REGISTRY`]) and reads
//! files. Errors name the file, the field and what is allowed; unknown keys get a near-miss
//! suggestion.

pub mod cells;
pub mod row;
pub mod sweep;
pub mod warnings;

use crate::models::balls_wall::BallsWallScene;
use crate::models::cone_plate::ConePlateScene;
use crate::models::constrained::RigidImpactScene;
use crate::models::disk_friction::DiskFrictionScene;
use crate::models::hertz::HertzScene;
use crate::models::ode::OdeScene;
use crate::models::pendulum_wall::PendulumWallScene;
use crate::models::trace::Traced;
use crate::models::{Curves, Model, RunError};
use std::any::Any;
use std::path::Path;

pub use crate::models::cone_plate::EFFECTS;
pub use crate::models::params::{SceneError, SolveSpec};

/// Reads a table into a model.
type Loader = fn(&toml::Table, &str) -> Result<Scene, SceneError>;

fn loader<M: Model>(root: &toml::Table, path: &str) -> Result<Scene, SceneError> {
    Ok(Scene(Box::new(M::from_table(root, path)?)))
}

/// Every model a scene can name: one line per model.
pub const REGISTRY: &[(&str, Loader)] = &[
    (HertzScene::NAME, loader::<HertzScene>),
    (ConePlateScene::NAME, loader::<ConePlateScene>),
    (RigidImpactScene::NAME, loader::<RigidImpactScene>),
    (PendulumWallScene::NAME, loader::<PendulumWallScene>),
    (BallsWallScene::NAME, loader::<BallsWallScene>),
    (DiskFrictionScene::NAME, loader::<DiskFrictionScene>),
    (OdeScene::NAME, loader::<OdeScene>),
];

/// Every model's reference, in the order of [`REGISTRY`] (`impact describe`, `verify/MODELS.md`).
pub const DOCS: &[&crate::models::doc::ModelDoc] = &[
    HertzScene::DOC,
    ConePlateScene::DOC,
    RigidImpactScene::DOC,
    PendulumWallScene::DOC,
    BallsWallScene::DOC,
    DiskFrictionScene::DOC,
    OdeScene::DOC,
];

/// The reference of the model named `name` (an error lists the models).
pub fn describe(name: &str) -> Result<&'static crate::models::doc::ModelDoc, String> {
    DOCS.iter()
        .copied()
        .find(|d| d.name == name)
        .ok_or_else(|| format!("unknown model \"{name}\"; the models: {}", model_names()))
}

/// The model names, as listed in messages.
pub fn model_names() -> String {
    REGISTRY
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A model behind the registry: what `impact run`, sweeps and claims need of any model.
trait AnyModel: Send + Sync {
    fn name(&self) -> &'static str;
    fn run_value(&self) -> Result<(serde_json::Value, Curves), RunError>;
    fn run_node(&self) -> Result<row::Node, RunError>;
    fn run_cells<'r>(
        &self,
        cols: &[String],
        plan: &cells::Trail,
        into: &'r mut cells::Reuse,
    ) -> Result<&'r cells::Cells, RunError>;
    fn run_traced(&self) -> Result<(serde_json::Value, Traced), RunError>;
    fn as_any(&self) -> &dyn Any;
    fn with_number(&self, field: &str, v: f64, path: &str) -> Option<Result<Scene, SceneError>>;
    fn set_number(&mut self, field: &str, v: f64, path: &str) -> Option<Result<(), SceneError>>;
}

/// A model's outcome as its JSON (the `impact run` contract).
fn value_of<M: Model>(out: M::Outcome) -> Result<serde_json::Value, RunError> {
    serde_json::to_value(out).map_err(|e| RunError::BadArgument {
        arg: M::NAME.into(),
        message: format!("the outcome does not serialize: {e}"),
    })
}

impl<M: Model> AnyModel for M {
    fn name(&self) -> &'static str {
        M::NAME
    }
    fn run_value(&self) -> Result<(serde_json::Value, Curves), RunError> {
        let (out, curves) = self.run()?;
        Ok((value_of::<M>(out)?, curves))
    }
    fn run_traced(&self) -> Result<(serde_json::Value, Traced), RunError> {
        let (out, trace) = Model::run_traced(self)?;
        Ok((value_of::<M>(out)?, trace))
    }
    fn run_node(&self) -> Result<row::Node, RunError> {
        let (out, _) = self.run()?;
        row::Node::of(&out).map_err(|e| RunError::BadArgument {
            arg: M::NAME.into(),
            message: format!("the outcome does not serialize: {e}"),
        })
    }
    fn run_cells<'r>(
        &self,
        cols: &[String],
        plan: &cells::Trail,
        into: &'r mut cells::Reuse,
    ) -> Result<&'r cells::Cells, RunError> {
        let (out, _) = self.run()?;
        cells::fill(&out, cols, plan, into).map_err(|e| RunError::BadArgument {
            arg: M::NAME.into(),
            message: format!("the outcome does not serialize: {e}"),
        })
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn with_number(&self, field: &str, v: f64, path: &str) -> Option<Result<Scene, SceneError>> {
        let mut m = self.clone();
        Some(m.set_number(field, v, path)?.map(|()| Scene(Box::new(m))))
    }
    fn set_number(&mut self, field: &str, v: f64, path: &str) -> Option<Result<(), SceneError>> {
        Model::set_number(self, field, v, path)
    }
}

/// A validated scene of any model.
pub struct Scene(Box<dyn AnyModel>);

impl Scene {
    /// The model's name.
    pub fn model(&self) -> &'static str {
        self.0.name()
    }

    /// Runs it: the outcome as JSON (the `impact run` contract) and the curves for `--plot`.
    pub fn run(&self) -> Result<(serde_json::Value, Curves), RunError> {
        self.0.run_value()
    }

    /// Runs it and records its path: the outcome as [`Scene::run`] gives it and the path, or
    /// why it has none, for `impact run --trace` and Python's `run`.
    pub fn run_traced(&self) -> Result<(serde_json::Value, Traced), RunError> {
        self.0.run_traced()
    }

    /// Runs it: the outcome as a light tree written as its JSON would be (the rows of
    /// `impact sweep`).
    pub fn run_node(&self) -> Result<row::Node, RunError> {
        self.0.run_node()
    }

    /// Runs it: the outcome's CSV cells under `cols` ([`cells::of`]; `plan`, the trail of an
    /// earlier run of the same model, makes the walk quicker and changes no cell), in the
    /// buffers of `into` (a run of points reuses them).
    pub fn run_cells<'r>(
        &self,
        cols: &[String],
        plan: &cells::Trail,
        into: &'r mut cells::Reuse,
    ) -> Result<&'r cells::Cells, RunError> {
        self.0.run_cells(cols, plan, into)
    }

    /// A copy with a numeric field set on the typed parameters (checked as when read from a
    /// table); `None` when the model does not set that field this way.
    pub fn with_number(
        &self,
        field: &str,
        v: f64,
        path: &str,
    ) -> Option<Result<Scene, SceneError>> {
        self.0.with_number(field, v, path)
    }

    /// Sets a numeric field on the typed parameters in place, as [`Scene::with_number`] does
    /// on its copy (the model sets that field alone, so the scene is then the copy
    /// `with_number` would give; a bad value leaves it as it was); `None` when the model does
    /// not set that field this way.
    pub fn set_number(
        &mut self,
        field: &str,
        v: f64,
        path: &str,
    ) -> Option<Result<(), SceneError>> {
        self.0.set_number(field, v, path)
    }

    /// The typed parameters, when the scene is of model `M`.
    pub fn get<M: Model>(&self) -> Option<&M> {
        self.0.as_any().downcast_ref::<M>()
    }
}

impl std::fmt::Debug for Scene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Scene({})", self.model())
    }
}

/// A TOML error as a reader wants it: the line and column, the parser's message, then the line
/// of the file and a caret under the place, each on a line of its own.
pub fn toml_message(e: &toml::de::Error, text: &str) -> String {
    let message = e.message().trim();
    let Some(span) = e.span() else {
        return message.to_string();
    };
    let at = span.start.min(text.len());
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    let line_no = text[..at].matches('\n').count() + 1;
    let column = text[line_start..at].chars().count() + 1;
    let source = text[line_start..line_end].trim_end_matches('\r');
    let width = line_no.to_string().len();
    let caret_len = text[at..span.end.clamp(at, line_end)]
        .chars()
        .count()
        .max(1);
    format!(
        "line {line_no}, column {column}: {message}\n  {line_no} | {source}\n  {:width$} | {}{}",
        "",
        " ".repeat(column - 1),
        "^".repeat(caret_len)
    )
}

/// Parses and validates scene text; `path` names the file in messages.
pub fn parse(text: &str, path: &str) -> Result<Scene, SceneError> {
    let root: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| SceneError::Parse {
            path: path.into(),
            message: toml_message(&e, text),
        })?;
    parse_table(&root, path)
}

/// Validates an already parsed scene table: the model it names reads it.
pub fn parse_table(root: &toml::Table, path: &str) -> Result<Scene, SceneError> {
    let allowed = || format!("one of: {}", model_names());
    let model = match root.get("model") {
        Some(toml::Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(SceneError::OutOfRange {
                path: path.into(),
                field: "model".into(),
                value: other.to_string(),
                allowed: allowed(),
            });
        }
        None => {
            return Err(SceneError::Missing {
                path: path.into(),
                field: "model".into(),
                allowed: allowed(),
            });
        }
    };
    match REGISTRY.iter().find(|(n, _)| *n == model) {
        Some((_, load)) => load(root, path),
        None => {
            let near = REGISTRY
                .iter()
                .map(|(n, _)| *n)
                .find(|m| crate::models::params::edit_distance(m, &model) <= 2)
                .map(|m| format!(" (did you mean \"{m}\"?)"))
                .unwrap_or_default();
            Err(SceneError::OutOfRange {
                path: path.into(),
                field: "model".into(),
                value: format!("\"{model}\"{near}"),
                allowed: allowed(),
            })
        }
    }
}

/// Reads and validates a scene file of model `M` (an error names the model found otherwise).
pub fn load_as<M: Model + Clone>(path: &Path) -> Result<M, SceneError> {
    let scene = load(path)?;
    scene
        .get::<M>()
        .cloned()
        .ok_or_else(|| SceneError::OutOfRange {
            path: path.display().to_string(),
            field: "model".into(),
            value: format!("\"{}\"", scene.model()),
            allowed: format!("\"{}\" here", M::NAME),
        })
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
            message: toml_message(&e, &text),
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
    set_value(root, field, toml::Value::Float(value), path)
}

/// Sets a dotted field of a scene table to a value. A numeric part indexes an array that exists
/// (`body.0.mass`, `initial.v_rel.2`); a missing table on the way is created.
pub fn set_value(
    root: &mut toml::Table,
    field: &str,
    value: toml::Value,
    path: &str,
) -> Result<(), SceneError> {
    let bad = |value: &toml::Value, allowed: &str| SceneError::OutOfRange {
        path: path.into(),
        field: field.into(),
        value: value.to_string(),
        allowed: allowed.into(),
    };
    let parts: Vec<&str> = field.split('.').collect();
    let mut slot: &mut toml::Value = match root.get_mut(parts[0]) {
        Some(v) => v,
        None if parts.len() == 1 => {
            root.insert(parts[0].to_string(), value);
            return Ok(());
        }
        None => root
            .entry(parts[0].to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new())),
    };
    for (i, p) in parts.iter().enumerate().skip(1) {
        let last = i + 1 == parts.len();
        slot = match slot {
            toml::Value::Table(t) => {
                if last {
                    t.insert(p.to_string(), value);
                    return Ok(());
                }
                t.entry(p.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            }
            toml::Value::Array(a) => {
                let len = a.len();
                let k = p
                    .parse::<usize>()
                    .ok()
                    .filter(|k| *k < len)
                    .ok_or_else(|| {
                        bad(
                            &value,
                            &format!("an index 0..{len} of the array before `{p}`"),
                        )
                    })?;
                &mut a[k]
            }
            _ => return Err(bad(&value, "a field inside a table or an array")),
        };
    }
    *slot = value;
    Ok(())
}

/// The value at a dotted field of a scene table (numeric parts index arrays), if it is there.
pub fn field_raw<'t>(root: &'t toml::Table, field: &str) -> Option<&'t toml::Value> {
    let mut parts = field.split('.');
    let mut cur = root.get(parts.next()?)?;
    for p in parts {
        cur = match cur {
            toml::Value::Table(t) => t.get(p)?,
            toml::Value::Array(a) => a.get(p.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// The number at a dotted field of a scene table (numeric parts index arrays), if it is one.
pub fn field_value(root: &toml::Table, field: &str) -> Option<f64> {
    match field_raw(root, field)? {
        toml::Value::Float(x) => Some(*x),
        toml::Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OK: &str = "model = \"hertz\"\n[impactor]\nmass = 1.0\nv0 = 1.0\n[contact]\nk = 1.0\n";

    #[test]
    fn fields_inside_arrays_are_set_and_read() {
        let mut t: toml::Table =
            "[[body]]\nmass = 1.0\n[[body]]\nmass = 2.0\n[initial]\nv_rel = [0.0, 0.0, -1.0]\n"
                .parse()
                .expect("toml");
        set_field(&mut t, "body.1.mass", 5.0, "s").expect("set");
        set_field(&mut t, "initial.v_rel.2", -3.0, "s").expect("set");
        set_value(
            &mut t,
            "contact.law",
            toml::Value::String("newton".into()),
            "s",
        )
        .expect("set");
        assert_eq!(field_value(&t, "body.1.mass"), Some(5.0));
        assert_eq!(field_value(&t, "body.0.mass"), Some(1.0));
        assert_eq!(field_value(&t, "initial.v_rel.2"), Some(-3.0));
        assert!(set_field(&mut t, "initial.v_rel.3", 1.0, "s").is_err());
    }

    #[test]
    fn every_registered_model_documents_itself_in_the_same_order() {
        let names: Vec<&str> = REGISTRY.iter().map(|(n, _)| *n).collect();
        let documented: Vec<&str> = DOCS.iter().map(|d| d.name).collect();
        assert_eq!(names, documented);
        assert!(describe("hertz").is_ok());
        let e = describe("hetz").unwrap_err();
        assert!(e.contains("hertz") && e.contains("ode"), "{e}");
    }

    #[test]
    fn valid_scene_parses() {
        assert_eq!(parse(OK, "s.toml").map(|s| s.model()).ok(), Some("hertz"));
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

    /// A field set in place point after point on one copy, bad values among them, gives at
    /// each point the scene read from the table with that field written in it (the path of a
    /// field no model sets in place, which shares no code with `set_number`): the same
    /// outcome to the bit. Hertz's four numbers and a text model's parameter and initial
    /// state, with the degenerate values (no damping, a state at zero).
    #[test]
    fn a_number_set_in_place_is_the_scene_read_with_it() {
        let ode = "model = \"ode\"\n[parameters]\nm = 0.05\nk = 3e8\nv0 = 1.0\n\
                   [units]\nt = \"s\"\nm = \"kg\"\nk = \"N/m^1.5\"\nv0 = \"m/s\"\nz = \"m\"\n\
                   v = \"m/s\"\n[state]\nz = 0.0\nv = \"v0\"\n[equations]\nz = \"v\"\n\
                   v = \"-k*max(z, 0)^(3/2)/m\"\n[[event]]\nname = \"end\"\nwhen = \"z\"\n\
                   direction = \"down\"\naction = \"stop\"\n[outcome]\nt_end = \"t@end\"\n\
                   v_out = \"v@end\"\n[solve]\nt_end = 1.0\n";
        let hertz = format!("{OK}[solve]\nt_end = 20.0\n");
        let cases: [(&str, &str, &[f64]); 6] = [
            (&hertz, "impactor.mass", &[2.0, -1.0, 0.5, 1.0]),
            (&hertz, "impactor.v0", &[0.5, 0.0, 3.0]),
            (&hertz, "contact.k", &[4.0, 1e3]),
            (&hertz, "contact.damping", &[0.3, -2.0, 0.0, 0.1]),
            (ode, "parameters.v0", &[2.0, 0.0, 0.5]),
            (ode, "state.z", &[-1e-3, 0.0, 2e-3]),
        ];
        for (text, field, values) in cases {
            let table: toml::Table = text.parse().expect("toml");
            let base = parse_table(&table, "s.toml").expect("valid");
            let held = base.with_number(field, values[0], "s.toml").expect("typed");
            let mut held = held.expect("in range");
            for &v in values {
                let mut t = table.clone();
                set_field(&mut t, field, v, "s.toml").expect("a number field");
                let read = parse_table(&t, "s.toml");
                match (held.set_number(field, v, "s.toml").expect("typed"), read) {
                    (Ok(()), Ok(read)) => {
                        let (a, b) = (held.run(), read.run());
                        let (a, b) = (
                            a.map(|r| r.0).map_err(|e| e.to_string()),
                            b.map(|r| r.0).map_err(|e| e.to_string()),
                        );
                        assert_eq!(a, b, "{field} = {v}");
                    }
                    (Err(e), Err(r)) => assert_eq!(e.to_string(), r.to_string(), "{field} = {v}"),
                    (a, b) => panic!(
                        "{field} = {v}: in place {a:?}, read {:?}",
                        b.map(|s| s.model())
                    ),
                }
            }
        }
    }
}
