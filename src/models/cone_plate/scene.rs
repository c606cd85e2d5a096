//! The cone-plate scene file: its keys, read into the model's parameters and effects, and the
//! outcome `impact run` prints.

use super::*;
use crate::models::doc as d;
use crate::models::trace::{Trace, Traced, or_why};

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

/// The `cone-plate` scene of 000_92d54b11128ea1ec.txt: only the effects it names become states.
#[derive(Clone, Debug)]
pub struct ConePlateScene {
    /// Parameters (SI).
    pub params: Params,
    /// Effects named.
    pub effects: Effects,
    /// Variant.
    pub variant: Variant,
    /// Viscoelastic law.
    pub law: Law,
    /// Solver settings.
    pub solve: crate::models::SolveSpec,
}

type Value = toml::Value;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)]
struct RawScene {
    model: Option<Value>,
    variant: Option<Value>,
    viscoelastic_law: Option<Value>,
    effects: Option<Value>,
    impactor: Option<Value>,
    material: Option<Value>,
    plate: Option<Value>,
    foundation: Option<Value>,
    inplane: Option<Value>,
    solve: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImpactor {
    mass: Option<Value>,
    theta_deg: Option<Value>,
    v0: Option<Value>,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
struct RawMaterial {
    E: Option<Value>,
    nu: Option<Value>,
    eta: Option<Value>,
}

#[derive(serde::Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawPlate {
    a: Option<Value>,
    b: Option<Value>,
    h: Option<Value>,
    rho: Option<Value>,
    modes: Option<Value>,
}

#[derive(serde::Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawFoundation {
    kw: Option<Value>,
    kg: Option<Value>,
    ct: Option<Value>,
}

#[derive(serde::Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawInplane {
    p1: Option<Value>,
    p2: Option<Value>,
}

/// The energy books of a run.
#[derive(Clone, Debug, serde::Serialize)]
pub struct EnergyOutcome {
    /// Kinetic energy at impact (J).
    pub initial: f64,
    /// Kinetic plus stored energy at the end (J).
    #[serde(rename = "final")]
    pub final_: f64,
    /// Dissipated energy (J).
    pub dissipated: f64,
    /// Work of the memory operators (J).
    pub operator_work: f64,
    /// Smallest operator work seen (J).
    pub operator_work_min: f64,
    /// Work injected by the load with the paper's absolute indentation (J).
    pub injected: f64,
    /// Energy balance error (relative).
    pub balance_error: f64,
}

/// What `impact run` prints for a `cone-plate` scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ConePlateOutcome {
    /// `"cone-plate"`.
    pub model: &'static str,
    /// `"as-printed"` or `"corrected"`.
    pub variant: &'static str,
    /// `"constant-bulk"` or `"constant-poisson"`.
    pub viscoelastic_law: &'static str,
    /// The effects simulated.
    pub effects: Vec<String>,
    /// The plate modes.
    pub modes: Vec<(u32, u32)>,
    /// States integrated.
    pub state_dim: usize,
    /// The method.
    pub method: &'static str,
    /// Samples at the requested times.
    pub samples: Vec<Sample>,
    /// The contact.
    pub contact: crate::models::ContactOutcome,
    /// The energy books.
    pub energy: EnergyOutcome,
    /// Work done.
    pub stats: Stats,
    /// What the report must say.
    pub warnings: Vec<String>,
}

/// The scene's `effects`: known names only (a near miss is suggested), and the plate's effects
/// only with the plate.
fn read_effects(
    f: &crate::models::params::Fields,
    raw: &RawScene,
) -> Result<Effects, crate::models::SceneError> {
    let mut fx = Effects::default();
    let names: Vec<String> = match &raw.effects {
        None => vec![],
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_str().map(str::to_string).ok_or_else(|| {
                    f.out_of_range(
                        "effects",
                        v.to_string(),
                        &format!("names from: {}", EFFECTS.join(", ")),
                    )
                })
            })
            .collect::<Result<_, _>>()?,
        Some(other) => {
            return Err(f.out_of_range(
                "effects",
                other.to_string(),
                &format!("a list of names from: {}", EFFECTS.join(", ")),
            ));
        }
    };
    for name in &names {
        if !fx.switch_on(name) {
            let near = EFFECTS
                .iter()
                .find(|e| crate::models::params::edit_distance(e, name) <= 2)
                .map(|e| format!(" (did you mean \"{e}\"?)"))
                .unwrap_or_default();
            return Err(f.out_of_range(
                "effects",
                format!("\"{name}\"{near}"),
                &format!("names from: {}", EFFECTS.join(", ")),
            ));
        }
    }
    let needs_plate = fx.winkler
        || fx.pasternak
        || fx.damper
        || fx.membrane
        || fx.inplane
        || fx.relative_indentation;
    if needs_plate && !fx.plate {
        return Err(f.out_of_range(
            "effects",
            format!("{names:?}"),
            "winkler, pasternak, damper, membrane, inplane and relative-indentation act on the plate: add \"plate\"",
        ));
    }
    Ok(fx)
}

impl crate::models::Model for ConePlateScene {
    const NAME: &'static str = "cone-plate";
    const DOC: &'static d::ModelDoc = &DOC;
    type Outcome = ConePlateOutcome;

    fn from_table(root: &toml::Table, path: &str) -> Result<Self, crate::models::SceneError> {
        use crate::models::SceneError;
        let f = crate::models::params::Fields { path };
        let raw: RawScene = f.raw(root, "")?;
        let variant = match f
            .choice(
                raw.variant.as_ref(),
                "variant",
                &["as-printed", "corrected"],
                "corrected",
            )?
            .as_str()
        {
            "as-printed" => Variant::AsPrinted,
            _ => Variant::Corrected,
        };
        let law = match f
            .choice(
                raw.viscoelastic_law.as_ref(),
                "viscoelastic_law",
                &["constant-bulk", "constant-poisson"],
                "constant-bulk",
            )?
            .as_str()
        {
            "constant-poisson" => Law::ConstantPoisson,
            _ => Law::ConstantBulk,
        };
        let mut fx = read_effects(&f, &raw)?;
        let imp: RawImpactor = f.raw(f.table(raw.impactor.as_ref(), "impactor")?, "impactor")?;
        let mat: RawMaterial = f.raw(f.table(raw.material.as_ref(), "material")?, "material")?;
        // an optional table: required when its effect is on, checked for unknown keys always
        fn opt<T: serde::de::DeserializeOwned + Default>(
            f: &crate::models::params::Fields,
            v: Option<&Value>,
            name: &str,
            on: bool,
        ) -> Result<T, SceneError> {
            if on {
                return f.raw(f.table(v, name)?, name);
            }
            match v {
                Some(Value::Table(t)) => f.raw(t, name),
                _ => Ok(T::default()),
            }
        }
        let plate: RawPlate = opt(&f, raw.plate.as_ref(), "plate", fx.plate)?;
        let found: RawFoundation = opt(
            &f,
            raw.foundation.as_ref(),
            "foundation",
            fx.winkler || fx.pasternak || fx.damper,
        )?;
        let inpl: RawInplane = opt(&f, raw.inplane.as_ref(), "inplane", fx.inplane)?;
        let pos = |v: f64| v > 0.0;
        let need =
            |on: bool, v: &Option<Value>, field: &str, ok: &dyn Fn(f64) -> bool, allowed: &str| {
                if on {
                    f.num(v.as_ref(), field, None, ok, allowed)
                } else {
                    f.num(v.as_ref(), field, Some(0.0), |_| true, allowed)
                }
            };
        // a foundation's value, read only with its effect (a value >= 0)
        let when = |on: bool, v: &Option<Value>, field: &str, allowed: &str| {
            on.then(|| f.num(v.as_ref(), field, None, |x| x >= 0.0, allowed))
                .transpose()
        };
        if fx.plate {
            if let Some(m) = &plate.modes {
                let arr = m.as_array().ok_or_else(|| {
                    f.out_of_range(
                        "plate.modes",
                        m.to_string(),
                        "a list of odd pairs, e.g. [[1, 1], [1, 3]]",
                    )
                })?;
                for pair in arr {
                    let v: Vec<i64> = pair
                        .as_array()
                        .map(|p| p.iter().filter_map(|x| x.as_integer()).collect())
                        .unwrap_or_default();
                    if v.len() != 2 || v.iter().any(|x| *x < 1 || x % 2 == 0 || *x > 99) {
                        return Err(f.out_of_range(
                            "plate.modes",
                            pair.to_string(),
                            "pairs [m, n] of odd integers 1..99",
                        ));
                    }
                    fx.modes.push((v[0] as u32, v[1] as u32));
                }
            }
            if fx.modes.is_empty() {
                fx.modes.push((1, 1));
            }
        }
        let params = Params {
            mass: f.num(
                imp.mass.as_ref(),
                "impactor.mass",
                None,
                pos,
                "mass > 0 (kg)",
            )?,
            theta_deg: f.num(
                imp.theta_deg.as_ref(),
                "impactor.theta_deg",
                None,
                |v| v > 0.0 && v < 90.0,
                "0 < theta_deg < 90 (degrees)",
            )?,
            v0: f.num(
                imp.v0.as_ref(),
                "impactor.v0",
                None,
                pos,
                "v0 > 0 (m/s), toward the plate",
            )?,
            e: f.num(mat.E.as_ref(), "material.E", None, pos, "E > 0 (Pa)")?,
            nu: f.num(
                mat.nu.as_ref(),
                "material.nu",
                None,
                |v| v > -1.0 && v < 0.5,
                "-1 < nu < 0.5",
            )?,
            eta: need(
                fx.viscoelastic,
                &mat.eta,
                "material.eta",
                &pos,
                "eta > 0 (Pa s) with \"viscoelastic\"",
            )?,
            a: need(
                fx.plate,
                &plate.a,
                "plate.a",
                &pos,
                "a > 0 (m) with \"plate\"",
            )?,
            b: need(
                fx.plate,
                &plate.b,
                "plate.b",
                &pos,
                "b > 0 (m) with \"plate\"",
            )?,
            h: need(
                fx.plate,
                &plate.h,
                "plate.h",
                &pos,
                "h > 0 (m) with \"plate\"",
            )?,
            rho: need(
                fx.plate,
                &plate.rho,
                "plate.rho",
                &pos,
                "rho > 0 (kg/m^3) with \"plate\"",
            )?,
            kw: when(
                fx.winkler,
                &found.kw,
                "foundation.kw",
                "kw >= 0 (N/m^3) with \"winkler\"",
            )?,
            kg: when(
                fx.pasternak,
                &found.kg,
                "foundation.kg",
                "kg >= 0 (N/m) with \"pasternak\"",
            )?,
            ct: when(
                fx.damper,
                &found.ct,
                "foundation.ct",
                "ct >= 0 (N s/m^3) with \"damper\"",
            )?,
            inplane: if fx.inplane {
                let p = |v: &Option<Value>, field: &str, allowed: &str| {
                    f.num(v.as_ref(), field, None, |_| true, allowed)
                };
                Some((
                    p(&inpl.p1, "inplane.p1", "p1 (N/m) with \"inplane\"")?,
                    p(&inpl.p2, "inplane.p2", "p2 (N/m) with \"inplane\"")?,
                ))
            } else {
                None
            },
        };
        Ok(ConePlateScene {
            params,
            effects: fx,
            variant,
            law,
            solve: f.solve(raw.solve.as_ref(), "contact-end", true)?,
        })
    }

    fn run(&self) -> Result<(ConePlateOutcome, crate::models::Curves), crate::models::RunError> {
        self.go(false).map(|(out, curves, _)| (out, curves))
    }

    fn run_traced(&self) -> Result<(ConePlateOutcome, Traced), crate::models::RunError> {
        let (out, _, trace) = self.go(true)?;
        Ok((out, or_why(trace, "nothing was recorded")))
    }
}

/// The path of a run in the quantities a reader knows: the cone's depth and speed, the contact
/// force, the plate's deflection under the cone (with the plate); every accepted step is
/// recorded by the run anyway (its peak and tension checks read them).
fn trace_of(sys: &ConePlate, r: &super::Run) -> Trace {
    let mut names = vec![("z", "m"), ("dz/dt", "m/s"), ("P", "N")];
    if sys.centre_deflection(&sys.initial_state()).is_some() {
        names.push(("w(a/2, b/2)", "m"));
    }
    let row = |y: &[f64]| {
        // as the equations of motion take it: no force out of contact
        let p = if sys.indentation(y).0 > 0.0 {
            sys.contact_force(y)
        } else {
            0.0
        };
        let mut v = vec![y[0], y[1], p];
        v.extend(sys.centre_deflection(y));
        v
    };
    let mut tr = Trace::new(("t", "s"), &names);
    for (t, y) in &r.trajectory {
        tr.push(*t, &row(y));
    }
    for (name, t, y) in &r.events {
        tr.event(name, *t, &row(y));
    }
    tr
}

impl ConePlateScene {
    /// The run: its outcome, its `--plot` curves and, when `record` is set, its path.
    fn go(
        &self,
        record: bool,
    ) -> Result<(ConePlateOutcome, crate::models::Curves, Option<Trace>), crate::models::RunError>
    {
        use crate::models::RunError;
        let s = self;
        let sys =
            ConePlate::new(s.params.clone(), s.effects.clone(), s.variant, s.law).map_err(|e| {
                RunError::BadArgument {
                    arg: "scene".into(),
                    message: e.to_string(),
                }
            })?;
        let r = run(
            &sys,
            s.solve.t_end,
            &s.solve.samples,
            s.solve.rtol,
            s.solve.atol,
            s.solve.method,
        )
        .map_err(|e| {
            let (alpha, _) = sys.rates();
            let memory = s.law == Law::ConstantBulk || s.variant == Variant::AsPrinted;
            if s.effects.viscoelastic && memory && alpha < 0.0 {
                RunError::NotPassive {
                    source: e,
                    rate: -alpha,
                }
            } else {
                RunError::Integrate(e)
            }
        })?;
        let z: Vec<(f64, f64)> = r.trajectory.iter().map(|(t, y)| (*t, y[0])).collect();
        let p: Vec<(f64, f64)> = r
            .trajectory
            .iter()
            .map(|(t, y)| {
                (
                    *t,
                    sys.contact_force(y).max(0.0) / r.peak_force.max(f64::MIN_POSITIVE)
                        * r.max_indentation,
                )
            })
            .collect();
        let mut curves = vec![
            ("z (m)".to_string(), z),
            ("P scaled to max z".to_string(), p),
        ];
        if s.effects.plate {
            let f: Vec<(f64, f64)> = r
                .trajectory
                .iter()
                .map(|(t, y)| (*t, sys.centre_deflection(y).unwrap_or(0.0)))
                .collect();
            curves.push(("w(a/2, b/2) (m)".to_string(), f));
        }
        let trace = record.then(|| trace_of(&sys, &r));
        let out = ConePlateOutcome {
            model: <Self as crate::models::Model>::NAME,
            variant: if s.variant == Variant::AsPrinted {
                "as-printed"
            } else {
                "corrected"
            },
            viscoelastic_law: if s.law == Law::ConstantBulk {
                "constant-bulk"
            } else {
                "constant-poisson"
            },
            effects: s.effects.names(),
            modes: s.effects.modes.clone(),
            state_dim: sys.state_dim(),
            method: s.solve.method.name(),
            samples: r.samples,
            contact: crate::models::ContactOutcome {
                ended: r.ended,
                duration: r.duration,
                peak_force: r.peak_force,
                max_indentation: r.max_indentation,
            },
            energy: EnergyOutcome {
                initial: r.energy_initial,
                final_: r.energy_final,
                dissipated: r.dissipated,
                operator_work: r.operator_work,
                operator_work_min: r.operator_work_min,
                injected: r.injected,
                balance_error: r.balance_error,
            },
            stats: r.stats,
            warnings: r.warnings,
        };
        Ok((out, curves, trace))
    }
}

/// The `cone-plate` model's reference (`impact describe cone-plate`).
pub const DOC: d::ModelDoc = d::ModelDoc {
    name: "cone-plate",
    summary: "A rigid cone striking a viscoelastic plate on a Winkler-Pasternak-Kelvin-Voigt foundation (000, (1)-(17)): the cone m_s z'' = -P, the contact force P of (10) with the viscoelastic operator of sec. 2, the plate's Galerkin modes (12)-(16). Only the effects a scene names become states: without \"plate\" the cone meets a half-space; without \"viscoelastic\" the material is elastic.",
    conventions: &[
        "z is the cone's displacement, positive into the plate; z(0) = 0, z'(0) = v0",
        "the contact indentation is z - f (the plate's deflection under the cone) with \"relative-indentation\", else z as the paper writes it",
        "variant = \"as-printed\" integrates (17) with the printed zeta, A4 and (16); \"corrected\" with the derived ones (reports/000_cone_plate.md)",
    ],
    example: "scenes/cone_plate.toml",
    keys: &[
        &[
            d::Key {
                key: "model",
                unit: "-",
                range: "\"cone-plate\"",
                default: "required",
                meaning: "the model",
            },
            d::Key {
                key: "effects",
                unit: "-",
                range: "a list of: viscoelastic, plate, winkler, pasternak, damper, membrane, inplane, modes, relative-indentation (the plate's effects only with \"plate\")",
                default: "[]",
                meaning: "what is simulated",
            },
            d::Key {
                key: "variant",
                unit: "-",
                range: "\"as-printed\", \"corrected\"",
                default: "\"corrected\"",
                meaning: "the paper's formulas as printed, or corrected",
            },
            d::Key {
                key: "viscoelastic_law",
                unit: "-",
                range: "\"constant-bulk\", \"constant-poisson\"",
                default: "\"constant-bulk\"",
                meaning: "the paper's Kelvin-Voigt law with constant bulk modulus, or a constant Poisson ratio (passive)",
            },
            d::Key {
                key: "impactor.mass",
                unit: "kg",
                range: "mass > 0",
                default: "required",
                meaning: "cone mass m_s",
            },
            d::Key {
                key: "impactor.theta_deg",
                unit: "degree",
                range: "0 < theta_deg < 90",
                default: "required",
                meaning: "angle between the cone's surface and the plane",
            },
            d::Key {
                key: "impactor.v0",
                unit: "m/s",
                range: "v0 > 0",
                default: "required",
                meaning: "impact speed, toward the plate",
            },
            d::Key {
                key: "material.E",
                unit: "Pa",
                range: "E > 0",
                default: "required",
                meaning: "Young's modulus",
            },
            d::Key {
                key: "material.nu",
                unit: "1",
                range: "-1 < nu < 0.5",
                default: "required",
                meaning: "Poisson's ratio",
            },
            d::Key {
                key: "material.eta",
                unit: "Pa s",
                range: "eta > 0 with \"viscoelastic\"",
                default: "0",
                meaning: "viscosity",
            },
            d::Key {
                key: "plate.a",
                unit: "m",
                range: "a > 0 with \"plate\"",
                default: "0",
                meaning: "plate length",
            },
            d::Key {
                key: "plate.b",
                unit: "m",
                range: "b > 0 with \"plate\"",
                default: "0",
                meaning: "plate width",
            },
            d::Key {
                key: "plate.h",
                unit: "m",
                range: "h > 0 with \"plate\"",
                default: "0",
                meaning: "plate thickness",
            },
            d::Key {
                key: "plate.rho",
                unit: "kg/m^3",
                range: "rho > 0 with \"plate\"",
                default: "0",
                meaning: "plate density",
            },
            d::Key {
                key: "plate.modes",
                unit: "-",
                range: "pairs [m, n] of odd integers 1..99",
                default: "[[1, 1]]",
                meaning: "the Galerkin modes (with \"modes\")",
            },
            d::Key {
                key: "foundation.kw",
                unit: "N/m^3",
                range: "kw >= 0 with \"winkler\"",
                default: "required with it",
                meaning: "Winkler modulus",
            },
            d::Key {
                key: "foundation.kg",
                unit: "N/m",
                range: "kg >= 0 with \"pasternak\"",
                default: "required with it",
                meaning: "Pasternak shear modulus",
            },
            d::Key {
                key: "foundation.ct",
                unit: "N s/m^3",
                range: "ct >= 0 with \"damper\"",
                default: "required with it",
                meaning: "foundation damping",
            },
            d::Key {
                key: "inplane.p1",
                unit: "N/m",
                range: "a number, with \"inplane\"",
                default: "required with it",
                meaning: "in-plane load along x",
            },
            d::Key {
                key: "inplane.p2",
                unit: "N/m",
                range: "a number, with \"inplane\"",
                default: "required with it",
                meaning: "in-plane load along y",
            },
            d::Key {
                key: "solve.samples",
                unit: "s",
                range: "times >= 0",
                default: "[]",
                meaning: "times at which to report the solution",
            },
        ],
        d::SOLVE,
    ],
    outcomes: &[
        d::COMMON,
        d::CONTACT,
        &[
            d::Out {
                path: "energy.initial",
                unit: "J",
                meaning: "kinetic energy at impact",
            },
            d::Out {
                path: "energy.final",
                unit: "J",
                meaning: "kinetic plus stored energy at the end",
            },
            d::Out {
                path: "energy.dissipated",
                unit: "J",
                meaning: "dissipated energy",
            },
            d::Out {
                path: "energy.operator_work",
                unit: "J",
                meaning: "work of the memory operators",
            },
            d::Out {
                path: "energy.operator_work_min",
                unit: "J",
                meaning: "smallest operator work seen (negative: the operator gave energy)",
            },
            d::Out {
                path: "energy.injected",
                unit: "J",
                meaning: "work injected by the load with the paper's absolute indentation",
            },
            d::Out {
                path: "energy.balance_error",
                unit: "1",
                meaning: "energy balance error, relative",
            },
            d::Out {
                path: "samples[].t",
                unit: "s",
                meaning: "sample time",
            },
            d::Out {
                path: "samples[].z",
                unit: "m",
                meaning: "cone displacement",
            },
            d::Out {
                path: "samples[].zdot",
                unit: "m/s",
                meaning: "cone velocity",
            },
            d::Out {
                path: "samples[].f",
                unit: "m",
                meaning: "plate deflection under the cone (null without the plate)",
            },
            d::Out {
                path: "samples[].P",
                unit: "N",
                meaning: "contact force",
            },
            d::Out {
                path: "samples",
                unit: "-",
                meaning: "the samples (empty without solve.samples)",
            },
            d::Out {
                path: "effects",
                unit: "-",
                meaning: "the effects simulated",
            },
            d::Out {
                path: "modes",
                unit: "-",
                meaning: "the plate modes [m, n]",
            },
            d::Out {
                path: "modes[]",
                unit: "-",
                meaning: "one mode [m, n]",
            },
            d::Out {
                path: "state_dim",
                unit: "-",
                meaning: "states integrated",
            },
            d::Out {
                path: "variant",
                unit: "-",
                meaning: "as given",
            },
            d::Out {
                path: "viscoelastic_law",
                unit: "-",
                meaning: "as given",
            },
            d::Out {
                path: "method",
                unit: "-",
                meaning: "the integrator",
            },
            d::Out {
                path: "warnings",
                unit: "-",
                meaning: "what the report must say",
            },
        ],
        d::STATS,
    ],
};
