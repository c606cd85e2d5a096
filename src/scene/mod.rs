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
    /// Times at which to report the solution (s).
    pub samples: Vec<f64>,
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
    /// Hunt-Crossley coefficient (s/m), or the dashpot (N s/m) of the linear law.
    pub damping: f64,
    /// Force law: Hertz (default) or a linear spring-dashpot.
    pub law: crate::models::hertz::ContactLaw,
    /// Solver settings.
    pub solve: SolveSpec,
}

/// The `cone-plate` scene of 000_92d54b11128ea1ec.txt.
#[derive(Clone, Debug)]
pub struct ConePlateScene {
    /// Parameters (SI).
    pub params: crate::models::cone_plate::Params,
    /// Effects named.
    pub effects: crate::models::cone_plate::Effects,
    /// Variant.
    pub variant: crate::models::cone_plate::Variant,
    /// Viscoelastic law.
    pub law: crate::models::cone_plate::Law,
    /// Solver settings.
    pub solve: SolveSpec,
}

/// The `rigid-impact` scene of 002_b53e4779673eb6ed.txt.
#[derive(Clone, Debug)]
pub struct RigidImpactScene {
    /// The two bodies.
    pub bodies: [crate::models::rigid_impact::Body; 2],
    /// Contact normal, into the first body.
    pub normal: nalgebra::Vector3<f64>,
    /// Friction coefficient.
    pub mu: f64,
    /// Restitution law.
    pub law: crate::models::rigid_impact::Law,
    /// Coefficient of restitution.
    pub e: f64,
    /// Relative velocity at C before impact (m/s).
    pub v_rel: nalgebra::Vector3<f64>,
    /// Relative tolerance.
    pub rtol: f64,
    /// The second body's support, if any.
    pub support: Option<crate::models::support::Support>,
    /// Velocity of the support point A before impact (m/s).
    pub v_support: nalgebra::Vector3<f64>,
    /// A fixed point or axis: (body index 0|1, G->O, optional axis).
    pub fixed: Option<(
        usize,
        nalgebra::Vector3<f64>,
        Option<nalgebra::Vector3<f64>>,
    )>,
}

/// The `pendulum-wall` scene: 002_b53e4779673eb6ed.txt (2.14)-(2.15), the paper's geometry
/// (|GO| = |G'C| = `length`, |GG'| = |OO'|) with linear elements.
#[derive(Clone, Debug)]
pub struct PendulumWallScene {
    /// Central radius of inertia (m).
    pub rho: f64,
    /// Stiffness ratio c1/c2 (contact over suspension).
    pub sigma: f64,
    /// |GO| (m).
    pub length: f64,
    /// Approach speed of the contact point (m/s).
    pub v0: f64,
    /// Mass (kg).
    pub mass: f64,
    /// Suspension stiffness c2 (N/m).
    pub stiffness_o: f64,
    /// Relative tolerance.
    pub rtol: f64,
}

/// The `balls-wall` scene: section 3's closing experiment of 002_b53e4779673eb6ed.txt.
#[derive(Clone, Debug)]
pub struct BallsWallScene {
    /// Ball radius (m).
    pub radius: f64,
    /// Ball mass (kg).
    pub mass: f64,
    /// Exponent: 1.5 (Hertz) or 1 (linear).
    pub exponent: f64,
    /// Speed of the striking ball (m/s).
    pub v0: f64,
    /// Wall contact stiffness over ball-ball contact stiffness.
    pub wall_stiffness_ratio: f64,
    /// Ball-ball stiffness (N/m^p), if known (gives the contact time in seconds).
    pub stiffness: Option<f64>,
    /// Relative tolerance.
    pub rtol: f64,
}

/// The `disk-friction` scene: 001_989b2e860c39ca83.txt (2.3), a disk of radius `a` sliding with
/// speed `v` (along x) and spinning with `omega`; the centre of pressure at `c` along y.
#[derive(Clone, Debug)]
pub struct DiskFrictionScene {
    /// Disk radius (m).
    pub a: f64,
    /// Sliding speed of the centre (m/s).
    pub v: f64,
    /// Spin (rad/s).
    pub omega: f64,
    /// Offset of the centre of pressure (m), 0 <= c <= a/4.
    pub c: f64,
}

/// A validated scene.
#[derive(Clone, Debug)]
pub enum Scene {
    /// Two rigid bodies, one contact, Coulomb friction.
    RigidImpact(Box<RigidImpactScene>),
    /// Sphere on a rigid-backed half-space.
    Hertz(HertzScene),
    /// Cone on a viscoelastic plate.
    ConePlate(Box<ConePlateScene>),
    /// Pendulum with deformable elements striking a smooth wall.
    PendulumWall(PendulumWallScene),
    /// Two balls in a line against a wall.
    BallsWall(BallsWallScene),
    /// Friction on a sliding, spinning disk.
    DiskFriction(DiskFrictionScene),
}

/// The model names a scene may give.
pub const MODELS: &str =
    "hertz, cone-plate, rigid-impact, pendulum-wall, balls-wall, disk-friction";
/// The effects a cone-plate scene may name.
pub const EFFECTS: &[&str] = &[
    "viscoelastic",
    "plate",
    "winkler",
    "pasternak",
    "damper",
    "membrane",
    "inplane",
    "modes",
    "relative-indentation",
];

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

    fn solve(
        &self,
        root: &toml::Table,
        default_end: &str,
        with_samples: bool,
    ) -> Result<SolveSpec, SceneError> {
        let empty = toml::Table::new();
        let t = match root.get("solve") {
            None => &empty,
            Some(_) => self.table(root, "solve")?,
        };
        let keys: &[&str] = if with_samples {
            &["rtol", "atol", "method", "t_end", "samples"]
        } else {
            &["rtol", "atol", "method", "t_end"]
        };
        self.check_keys(t, "solve", keys)?;
        let mut samples = Vec::new();
        if let Some(v) = t.get("samples") {
            let arr = v.as_array().ok_or_else(|| SceneError::OutOfRange {
                path: self.path.into(),
                field: "solve.samples".into(),
                value: v.to_string(),
                allowed: "a list of times >= 0 in s".into(),
            })?;
            for x in arr {
                let val = x.as_float().or_else(|| x.as_integer().map(|i| i as f64));
                match val {
                    Some(f) if f.is_finite() && f >= 0.0 => samples.push(f),
                    _ => {
                        return Err(SceneError::OutOfRange {
                            path: self.path.into(),
                            field: "solve.samples".into(),
                            value: x.to_string(),
                            allowed: "times >= 0 in s".into(),
                        });
                    }
                }
            }
        }
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
            samples,
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
            r.check_keys(con, "contact", &["k", "damping", "law"])?;
            let law = match string_choice(&r, con, "law", &["hertz", "linear"], "hertz") {
                Ok(l) if l == "linear" => crate::models::hertz::ContactLaw::Linear,
                Ok(_) => crate::models::hertz::ContactLaw::Hertz,
                Err(SceneError::OutOfRange { value, .. }) => {
                    return Err(SceneError::OutOfRange {
                        path: path.into(),
                        field: "contact.law".into(),
                        value,
                        allowed:
                            "\"hertz\" (F = k z^1.5 (1 + c z')) or \"linear\" (F = k z + c z')"
                                .into(),
                    });
                }
                Err(e) => return Err(e),
            };
            Ok(Scene::Hertz(HertzScene {
                law,
                mass: r.num(imp, "impactor.mass", None, |v| v > 0.0, "mass > 0 (kg)")?,
                v0: r.num(
                    imp,
                    "impactor.v0",
                    None,
                    |v| v > 0.0,
                    "v0 > 0 (m/s), toward the surface",
                )?,
                k: r.num(
                    con,
                    "contact.k",
                    None,
                    |v| v > 0.0,
                    "k > 0 (N/m^1.5 for hertz, N/m for linear)",
                )?,
                damping: r.num(
                    con,
                    "contact.damping",
                    Some(0.0),
                    |v| v >= 0.0,
                    "damping >= 0 (s/m for hertz, N s/m for linear)",
                )?,
                solve: r.solve(root, "contact-end", false)?,
            }))
        }
        "cone-plate" => cone_plate(&r, root),
        "rigid-impact" => rigid_impact(&r, root),
        "pendulum-wall" => pendulum_wall(&r, root),
        "balls-wall" => balls_wall(&r, root),
        "disk-friction" => disk_friction(&r, root),
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

fn string_choice(
    r: &Reader,
    root: &toml::Table,
    field: &str,
    choices: &[&str],
    default: &str,
) -> Result<String, SceneError> {
    match root.get(field) {
        None => Ok(default.to_string()),
        Some(toml::Value::String(s)) if choices.contains(&s.as_str()) => Ok(s.clone()),
        Some(other) => Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: field.into(),
            value: other.to_string(),
            allowed: choices
                .iter()
                .map(|c| format!("\"{c}\""))
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}

fn rtol(r: &Reader, root: &toml::Table) -> Result<f64, SceneError> {
    r.num(
        root,
        "rtol",
        Some(1e-10),
        |v| (1e-14..=1e-2).contains(&v),
        "1e-14 <= rtol <= 1e-2",
    )
}

fn pendulum_wall(r: &Reader, root: &toml::Table) -> Result<Scene, SceneError> {
    r.check_keys(
        root,
        "",
        &[
            "model",
            "rho",
            "sigma",
            "length",
            "v0",
            "mass",
            "stiffness_o",
            "rtol",
        ],
    )?;
    let length = r.num(
        root,
        "length",
        Some(1.0),
        |v| v > 0.0,
        "length = |GO| > 0 (m)",
    )?;
    Ok(Scene::PendulumWall(PendulumWallScene {
        rho: r.num(
            root,
            "rho",
            None,
            |v| v > 0.0 && v / length >= 1e-3 && v / length <= 1e3,
            "rho > 0 (m), central radius of inertia, 1e-3 <= rho/length <= 1e3",
        )?,
        sigma: r.num(
            root,
            "sigma",
            None,
            |v| (1e-8..=1e8).contains(&v),
            "1e-8 <= sigma <= 1e8, stiffness ratio c1/c2 (contact over suspension)",
        )?,
        length,
        v0: r.num(
            root,
            "v0",
            Some(1.0),
            |v| v > 0.0,
            "v0 > 0 (m/s), approach speed of C",
        )?,
        mass: r.num(root, "mass", Some(1.0), |v| v > 0.0, "mass > 0 (kg)")?,
        stiffness_o: r.num(
            root,
            "stiffness_o",
            Some(1.0),
            |v| v > 0.0,
            "stiffness_o > 0 (N/m), the suspension element c2",
        )?,
        rtol: rtol(r, root)?,
    }))
}

fn balls_wall(r: &Reader, root: &toml::Table) -> Result<Scene, SceneError> {
    r.check_keys(
        root,
        "",
        &[
            "model",
            "radius",
            "mass",
            "contact_law",
            "v0",
            "wall_stiffness_ratio",
            "stiffness",
            "rtol",
        ],
    )?;
    let law = string_choice(r, root, "contact_law", &["hertz", "linear"], "hertz")?;
    let stiffness = match root.get("stiffness") {
        None => None,
        Some(_) => Some(r.num(
            root,
            "stiffness",
            None,
            |v| v > 0.0,
            "stiffness > 0 (N/m^1.5 for hertz, N/m for linear), the ball-ball contact",
        )?),
    };
    Ok(Scene::BallsWall(BallsWallScene {
        radius: r.num(root, "radius", None, |v| v > 0.0, "radius > 0 (m)")?,
        mass: r.num(root, "mass", None, |v| v > 0.0, "mass > 0 (kg)")?,
        exponent: if law == "hertz" { 1.5 } else { 1.0 },
        v0: r.num(root, "v0", None, |v| v > 0.0, "v0 > 0 (m/s), toward the wall")?,
        wall_stiffness_ratio: r.num(
            root,
            "wall_stiffness_ratio",
            Some(2.0 * 2f64.sqrt()),
            |v| (1e-6..=1e8).contains(&v),
            "1e-6 <= wall_stiffness_ratio <= 1e8 (2 sqrt(2): identical elastic balls, rigid wall, Hertz)",
        )?,
        stiffness,
        rtol: rtol(r, root)?,
    }))
}

fn disk_friction(r: &Reader, root: &toml::Table) -> Result<Scene, SceneError> {
    r.check_keys(root, "", &["model", "k", "v", "omega", "a", "c"])?;
    let a = r.num(
        root,
        "a",
        Some(1.0),
        |v| v > 0.0,
        "a > 0 (m), the disk radius",
    )?;
    let has_k = root.contains_key("k");
    let has_vw = root.contains_key("v") || root.contains_key("omega");
    let (v, omega) = match (has_k, has_vw) {
        (true, true) => {
            return Err(SceneError::OutOfRange {
                path: r.path.into(),
                field: "k".into(),
                value: "given together with v/omega".into(),
                allowed: "either k, or v and omega (with a)".into(),
            });
        }
        (true, false) => {
            let k = r.num(root, "k", None, |v| v >= 0.0, "k = V/(a omega) >= 0")?;
            (k * a, 1.0)
        }
        _ => {
            let v = r.num(
                root,
                "v",
                None,
                |v| v >= 0.0,
                "v >= 0 (m/s), sliding speed of the centre; or give k = V/(a omega)",
            )?;
            let w = r.num(root, "omega", None, |v| v >= 0.0, "omega >= 0 (rad/s)")?;
            if v == 0.0 && w == 0.0 {
                return Err(SceneError::OutOfRange {
                    path: r.path.into(),
                    field: "v".into(),
                    value: "0 with omega = 0".into(),
                    allowed: "v > 0 or omega > 0 (a disk at rest has no kinetic friction)".into(),
                });
            }
            (v, w)
        }
    };
    Ok(Scene::DiskFriction(DiskFrictionScene {
        a,
        v,
        omega,
        c: r.num(
            root,
            "c",
            Some(0.0),
            |v| (0.0..=a / 4.0).contains(&v),
            &format!("0 <= c <= a/4 = {} (m), centre of pressure off the centre; beyond a/4 part of the disk lifts off (001 (1.8))", a / 4.0),
        )?,
    }))
}

fn cone_plate(r: &Reader, root: &toml::Table) -> Result<Scene, SceneError> {
    use crate::models::cone_plate::{Effects, Law, Params, Variant};
    r.check_keys(
        root,
        "",
        &[
            "model",
            "variant",
            "viscoelastic_law",
            "effects",
            "impactor",
            "material",
            "plate",
            "foundation",
            "inplane",
            "solve",
        ],
    )?;
    let variant = match string_choice(
        r,
        root,
        "variant",
        &["as-printed", "corrected"],
        "corrected",
    )?
    .as_str()
    {
        "as-printed" => Variant::AsPrinted,
        _ => Variant::Corrected,
    };
    let law = match string_choice(
        r,
        root,
        "viscoelastic_law",
        &["constant-bulk", "constant-poisson"],
        "constant-bulk",
    )?
    .as_str()
    {
        "constant-poisson" => Law::ConstantPoisson,
        _ => Law::ConstantBulk,
    };
    let mut fx = Effects::default();
    let names: Vec<String> = match root.get("effects") {
        None => vec![],
        Some(toml::Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_str()
                    .map(str::to_string)
                    .ok_or_else(|| SceneError::OutOfRange {
                        path: r.path.into(),
                        field: "effects".into(),
                        value: v.to_string(),
                        allowed: format!("names from: {}", EFFECTS.join(", ")),
                    })
            })
            .collect::<Result<_, _>>()?,
        Some(other) => {
            return Err(SceneError::OutOfRange {
                path: r.path.into(),
                field: "effects".into(),
                value: other.to_string(),
                allowed: format!("a list of names from: {}", EFFECTS.join(", ")),
            });
        }
    };
    for name in &names {
        match name.as_str() {
            "viscoelastic" => fx.viscoelastic = true,
            "plate" => fx.plate = true,
            "winkler" => fx.winkler = true,
            "pasternak" => fx.pasternak = true,
            "damper" => fx.damper = true,
            "membrane" => fx.membrane = true,
            "inplane" => fx.inplane = true,
            "modes" => {}
            "relative-indentation" => fx.relative_indentation = true,
            other => {
                let near = EFFECTS
                    .iter()
                    .find(|e| edit_distance(e, other) <= 2)
                    .map(|e| format!(" (did you mean \"{e}\"?)"))
                    .unwrap_or_default();
                return Err(SceneError::OutOfRange {
                    path: r.path.into(),
                    field: "effects".into(),
                    value: format!("\"{other}\"{near}"),
                    allowed: format!("names from: {}", EFFECTS.join(", ")),
                });
            }
        }
    }
    let needs_plate = fx.winkler
        || fx.pasternak
        || fx.damper
        || fx.membrane
        || fx.inplane
        || fx.relative_indentation;
    if needs_plate && !fx.plate {
        return Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: "effects".into(),
            value: format!("{names:?}"),
            allowed: "winkler, pasternak, damper, membrane, inplane and relative-indentation act on the plate: add \"plate\"".into(),
        });
    }
    let imp = r.table(root, "impactor")?;
    r.check_keys(imp, "impactor", &["mass", "theta_deg", "v0"])?;
    let mat = r.table(root, "material")?;
    r.check_keys(mat, "material", &["E", "nu", "eta"])?;
    let empty = toml::Table::new();
    let opt_table = |name: &str, on: bool, keys: &[&str]| -> Result<&toml::Table, SceneError> {
        if on {
            let t = r.table(root, name)?;
            r.check_keys(t, name, keys)?;
            Ok(t)
        } else {
            match root.get(name) {
                Some(toml::Value::Table(t)) => {
                    r.check_keys(t, name, keys)?;
                    Ok(t)
                }
                _ => Ok(&empty),
            }
        }
    };
    let plate = opt_table("plate", fx.plate, &["a", "b", "h", "rho", "modes"])?;
    let found = opt_table(
        "foundation",
        fx.winkler || fx.pasternak || fx.damper,
        &["kw", "kg", "ct"],
    )?;
    let inpl = opt_table("inplane", fx.inplane, &["p1", "p2"])?;
    let pos = |v: f64| v > 0.0;
    let need = |on: bool,
                t: &toml::Table,
                field: &str,
                ok: &dyn Fn(f64) -> bool,
                allowed: &str|
     -> Result<f64, SceneError> {
        if on {
            r.num(t, field, None, ok, allowed)
        } else {
            r.num(t, field, Some(0.0), |_| true, allowed)
        }
    };
    if fx.plate {
        if let Some(m) = plate.get("modes") {
            let arr = m.as_array().ok_or_else(|| SceneError::OutOfRange {
                path: r.path.into(),
                field: "plate.modes".into(),
                value: m.to_string(),
                allowed: "a list of odd pairs, e.g. [[1, 1], [1, 3]]".into(),
            })?;
            for pair in arr {
                let v: Vec<i64> = pair
                    .as_array()
                    .map(|p| p.iter().filter_map(|x| x.as_integer()).collect())
                    .unwrap_or_default();
                if v.len() != 2 || v.iter().any(|x| *x < 1 || x % 2 == 0 || *x > 99) {
                    return Err(SceneError::OutOfRange {
                        path: r.path.into(),
                        field: "plate.modes".into(),
                        value: pair.to_string(),
                        allowed: "pairs [m, n] of odd integers 1..99".into(),
                    });
                }
                fx.modes.push((v[0] as u32, v[1] as u32));
            }
        }
        if fx.modes.is_empty() {
            fx.modes.push((1, 1));
        }
    }
    let params = Params {
        mass: r.num(imp, "impactor.mass", None, pos, "mass > 0 (kg)")?,
        theta_deg: r.num(
            imp,
            "impactor.theta_deg",
            None,
            |v| v > 0.0 && v < 90.0,
            "0 < theta_deg < 90 (degrees)",
        )?,
        v0: r.num(
            imp,
            "impactor.v0",
            None,
            pos,
            "v0 > 0 (m/s), toward the plate",
        )?,
        e: r.num(mat, "material.E", None, pos, "E > 0 (Pa)")?,
        nu: r.num(
            mat,
            "material.nu",
            None,
            |v| v > -1.0 && v < 0.5,
            "-1 < nu < 0.5",
        )?,
        eta: need(
            fx.viscoelastic,
            mat,
            "material.eta",
            &pos,
            "eta > 0 (Pa s) with \"viscoelastic\"",
        )?,
        a: need(fx.plate, plate, "plate.a", &pos, "a > 0 (m) with \"plate\"")?,
        b: need(fx.plate, plate, "plate.b", &pos, "b > 0 (m) with \"plate\"")?,
        h: need(fx.plate, plate, "plate.h", &pos, "h > 0 (m) with \"plate\"")?,
        rho: need(
            fx.plate,
            plate,
            "plate.rho",
            &pos,
            "rho > 0 (kg/m^3) with \"plate\"",
        )?,
        kw: need(
            fx.winkler,
            found,
            "foundation.kw",
            &|v| v >= 0.0,
            "kw >= 0 (N/m^3) with \"winkler\"",
        )?,
        kg: need(
            fx.pasternak,
            found,
            "foundation.kg",
            &|v| v >= 0.0,
            "kg >= 0 (N/m) with \"pasternak\"",
        )?,
        ct: need(
            fx.damper,
            found,
            "foundation.ct",
            &|v| v >= 0.0,
            "ct >= 0 (N s/m^3) with \"damper\"",
        )?,
        p1: need(
            fx.inplane,
            inpl,
            "inplane.p1",
            &|_| true,
            "p1 (N/m) with \"inplane\"",
        )?,
        p2: need(
            fx.inplane,
            inpl,
            "inplane.p2",
            &|_| true,
            "p2 (N/m) with \"inplane\"",
        )?,
    };
    Ok(Scene::ConePlate(Box::new(ConePlateScene {
        params,
        effects: fx,
        variant,
        law,
        solve: r.solve(root, "contact-end", true)?,
    })))
}

fn vec3(r: &Reader, t: &toml::Table, field: &str) -> Result<nalgebra::Vector3<f64>, SceneError> {
    let key = field.rsplit('.').next().unwrap_or(field);
    let err = |v: String| SceneError::OutOfRange {
        path: r.path.into(),
        field: field.into(),
        value: v,
        allowed: "a 3-vector of finite numbers, e.g. [0.0, 0.0, 1.0]".into(),
    };
    let v = t.get(key).ok_or_else(|| SceneError::Missing {
        path: r.path.into(),
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

fn rigid_impact(r: &Reader, root: &toml::Table) -> Result<Scene, SceneError> {
    use crate::models::rigid_impact::{Body, Law};
    r.check_keys(
        root,
        "",
        &[
            "model", "body", "contact", "initial", "solve", "support", "fixed",
        ],
    )?;
    let bodies = match root.get("body") {
        Some(toml::Value::Array(a)) if a.len() == 2 => a,
        other => {
            return Err(SceneError::OutOfRange {
                path: r.path.into(),
                field: "[[body]]".into(),
                value: other.map_or("missing".into(), |v| {
                    format!("{} tables", v.as_array().map_or(0, |a| a.len()))
                }),
                allowed: "exactly two [[body]] tables".into(),
            });
        }
    };
    let mut out = Vec::new();
    for (k, b) in bodies.iter().enumerate() {
        let name = format!("body[{k}]");
        let t = b.as_table().ok_or_else(|| SceneError::OutOfRange {
            path: r.path.into(),
            field: name.clone(),
            value: b.to_string(),
            allowed: "a table".into(),
        })?;
        r.check_keys(t, &name, &["mass", "inertia", "contact_offset"])?;
        let mass = match t.get("mass") {
            Some(toml::Value::String(s)) if s == "inf" => None,
            _ => Some(r.num(
                t,
                &format!("{name}.mass"),
                None,
                |v| v > 0.0,
                "mass > 0 (kg), or \"inf\" for a fixed massive obstacle",
            )?),
        };
        let inertia = match (mass, t.get("inertia")) {
            (None, None) => nalgebra::Matrix3::identity(),
            (_, v) => {
                let err = |val: String| SceneError::OutOfRange {
                    path: r.path.into(),
                    field: format!("{name}.inertia"),
                    value: val,
                    allowed: "a symmetric positive-definite 3x3 array (kg m^2)".into(),
                };
                let v = v.ok_or_else(|| err("missing".into()))?;
                let rows = v.as_array().ok_or_else(|| err(v.to_string()))?;
                let mut m = nalgebra::Matrix3::zeros();
                if rows.len() != 3 {
                    return Err(err(v.to_string()));
                }
                for (i, row) in rows.iter().enumerate() {
                    let cols = row.as_array().ok_or_else(|| err(v.to_string()))?;
                    if cols.len() != 3 {
                        return Err(err(v.to_string()));
                    }
                    for (j, c) in cols.iter().enumerate() {
                        m[(i, j)] = c
                            .as_float()
                            .or_else(|| c.as_integer().map(|x| x as f64))
                            .filter(|x| x.is_finite())
                            .ok_or_else(|| err(v.to_string()))?;
                    }
                }
                let asym = (m - m.transpose()).abs().max();
                if asym > 1e-12 * m.abs().max() || m.cholesky().is_none() {
                    return Err(err(format!("{v} (not symmetric positive-definite)")));
                }
                m
            }
        };
        let offset = match (mass, t.get("contact_offset")) {
            (None, None) => nalgebra::Vector3::zeros(),
            _ => vec3(r, t, &format!("{name}.contact_offset"))?,
        };
        out.push(Body {
            mass,
            inertia,
            offset,
        });
    }
    if out.iter().all(|b| b.mass.is_none()) {
        return Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: "[[body]].mass".into(),
            value: "\"inf\" twice".into(),
            allowed: "at least one body with finite mass".into(),
        });
    }
    let c = r.table(root, "contact")?;
    r.check_keys(c, "contact", &["normal", "mu", "law", "e"])?;
    let normal = vec3(r, c, "contact.normal")?;
    if normal.norm() <= 0.0 || normal.norm().is_nan() {
        return Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: "contact.normal".into(),
            value: format!("{normal:?}"),
            allowed: "a non-zero vector pointing into the first body".into(),
        });
    }
    let law = match string_choice(r, c, "law", &["newton", "poisson", "energetic"], "poisson")?
        .as_str()
    {
        "newton" => Law::Newton,
        "energetic" => Law::Energetic,
        _ => Law::Poisson,
    };
    let mu = r.num(c, "contact.mu", Some(0.0), |v| v >= 0.0, "mu >= 0")?;
    let e = r.num(
        c,
        "contact.e",
        None,
        |v| (0.0..=1.0).contains(&v),
        "0 <= e <= 1",
    )?;
    let init = r.table(root, "initial")?;
    r.check_keys(init, "initial", &["v_rel", "v_support"])?;
    let v_rel = vec3(r, init, "initial.v_rel")?;
    let v_support = if init.contains_key("v_support") {
        vec3(r, init, "initial.v_support")?
    } else {
        nalgebra::Vector3::zeros()
    };
    let support = match root.get("support") {
        None => None,
        Some(_) => {
            let t = r.table(root, "support")?;
            r.check_keys(t, "support", &["offset", "normal", "mu"])?;
            let normal = vec3(r, t, "support.normal")?;
            if normal.norm() <= 0.0 {
                return Err(SceneError::OutOfRange {
                    path: r.path.into(),
                    field: "support.normal".into(),
                    value: format!("{normal:?}"),
                    allowed: "a non-zero vector from the support into the second body".into(),
                });
            }
            if out[1].mass.is_none() {
                return Err(SceneError::OutOfRange {
                    path: r.path.into(),
                    field: "[support]".into(),
                    value: "second body with mass \"inf\"".into(),
                    allowed: "a support under a second body of finite mass".into(),
                });
            }
            Some(crate::models::support::Support {
                offset: vec3(r, t, "support.offset")?,
                normal: normal.normalize(),
                mu: r.num(t, "support.mu", Some(0.0), |v| v >= 0.0, "mu >= 0")?,
            })
        }
    };
    let fixed = match root.get("fixed") {
        None => None,
        Some(_) => {
            let t = r.table(root, "fixed")?;
            r.check_keys(t, "fixed", &["offset", "axis", "body"])?;
            let body = match t.get("body") {
                None => 0,
                Some(toml::Value::Integer(1)) => 0,
                Some(toml::Value::Integer(2)) => 1,
                Some(other) => {
                    return Err(SceneError::OutOfRange {
                        path: r.path.into(),
                        field: "fixed.body".into(),
                        value: other.to_string(),
                        allowed: "1 or 2".into(),
                    });
                }
            };
            if out[body].mass.is_none() {
                return Err(SceneError::OutOfRange {
                    path: r.path.into(),
                    field: "fixed.body".into(),
                    value: (body + 1).to_string(),
                    allowed: "a body of finite mass (an immovable body needs no fixed point)"
                        .into(),
                });
            }
            let axis = if t.contains_key("axis") {
                let a = vec3(r, t, "fixed.axis")?;
                if a.norm() <= 0.0 {
                    return Err(SceneError::OutOfRange {
                        path: r.path.into(),
                        field: "fixed.axis".into(),
                        value: format!("{a:?}"),
                        allowed: "a non-zero direction".into(),
                    });
                }
                Some(a.normalize())
            } else {
                None
            };
            Some((body, vec3(r, t, "fixed.offset")?, axis))
        }
    };
    if support.is_some() && fixed.is_some() {
        return Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: "[support] and [fixed]".into(),
            value: "both present".into(),
            allowed: "one of them".into(),
        });
    }
    let n = normal.normalize();
    if v_rel.dot(&n) >= 0.0 || v_rel.dot(&n).is_nan() {
        return Err(SceneError::OutOfRange {
            path: r.path.into(),
            field: "initial.v_rel".into(),
            value: format!("[{}, {}, {}]", v_rel.x, v_rel.y, v_rel.z),
            allowed: "(v_rel, normal) < 0: the bodies approach at C".into(),
        });
    }
    let solve = r.solve(root, "impact-end", false)?;
    Ok(Scene::RigidImpact(Box::new(RigidImpactScene {
        bodies: [out[0].clone(), out[1].clone()],
        normal,
        mu,
        law,
        e,
        v_rel,
        rtol: solve.rtol,
        support,
        v_support,
        fixed,
    })))
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
