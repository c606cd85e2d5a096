//! The generic check kinds of a claims file: a printed formula, written as text in the paper's
//! notation, checked without Rust written for it.
//!
//! - `identity`: `printed` against `derived` (a formula, or `@name[k=v,...]` for a derivation of
//!   [`crate::algebra`], see [`DERIVATIONS`]), both exact ([`crate::algebra::expr`]); `holds` when
//!   the difference is exactly zero, `fails` with the simplified difference otherwise. With
//!   `corrected`, a failing printed form whose correction holds is `holds-with-correction`.
//! - `dimension`: the unit of `printed` (units from the file's `[symbols]`) against `expect`.
//! - `model`: `printed`, with symbols bound to scene fields (`bind`), against an outcome
//!   `quantity` of the model over the grid `vary`; `holds` when the largest relative difference is
//!   at most `rtol`.
//! - `bound`: `require`, an inequality over outcome quantities and bound symbols, on `count`
//!   samples of the scene fields drawn from `sample` (statrs quantiles of a seeded generator);
//!   `holds` when no sample violates it.
//!
//! [`validate`] reads every formula, unit, scene and quantity before anything runs, so a bad claim
//! stops `verify` with the file, the claim and the key named, and nothing written.

use super::{ClaimSpec, Outcome, PaperClaims, Verdict, VerifyError, outcome};
use crate::algebra::expr::{self, Expr, Inequality};
use crate::algebra::poly::{Q, Sym};
use crate::algebra::ratfunc::RatFunc;
use crate::algebra::units::{self, Unit};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

mod exact;
mod scenes;
mod validate;

pub use scenes::clopper_pearson;
use scenes::{numeric_paths, parse_expectation};

/// The kinds a claim may have.
pub const KINDS: &[&str] = &[
    "identity",
    "dimension",
    "model",
    "bound",
    "probability",
    "map",
    "definition",
    "not-checkable",
    "check",
];

/// One generic claim kind: its name, its validation (before anything runs) and its check. A new
/// kind is one validation and one check on [`Checked`] plus one line here (and its name in
/// [`KINDS`]).
pub(crate) struct Kind {
    /// The name claims give it (`kind = "identity"`).
    pub(crate) name: &'static str,
    /// Checks the claim's keys, formulas, units and scenes.
    validate: fn(&Checked, &ClaimSpec) -> Result<(), VerifyError>,
    /// Computes the verdict.
    check: fn(&Checked, &ClaimSpec, &mut Derivations) -> Result<Outcome, VerifyError>,
}

/// The kinds, by name.
pub(crate) const KIND_TABLE: &[Kind] = &[
    Kind {
        name: "identity",
        validate: |k, c| k.validate_identity(c),
        check: |k, c, der| k.identity(c, der),
    },
    Kind {
        name: "dimension",
        validate: |k, c| k.validate_dimension(c),
        check: |k, c, _| k.dimension(c),
    },
    Kind {
        name: "model",
        validate: |k, c| k.validate_scene_kind(c, true, None),
        check: |k, c, _| k.model(c),
    },
    Kind {
        name: "bound",
        validate: |k, c| k.validate_bound(c),
        check: |k, c, _| k.bound(c),
    },
    Kind {
        name: "probability",
        validate: |k, c| k.validate_scene_kind(c, false, Some("event")),
        check: |k, c, _| k.probability(c),
    },
    Kind {
        name: "map",
        validate: |k, c| k.validate_scene_kind(c, true, c.require.as_ref().map(|_| "require")),
        check: |k, c, _| k.map(c),
    },
    Kind {
        name: "definition",
        validate: |k, c| k.validate_definition(c),
        check: |k, c, der| k.definition(c, der),
    },
    Kind {
        name: "not-checkable",
        validate: |k, c| k.validate_not_checkable(c),
        check: |k, c, _| Ok(k.not_checkable(c)),
    },
    Kind {
        name: "check",
        validate: |k, c| k.validate_check(c),
        // named Rust checks run through their paper's registry (`verify::PAPERS`)
        check: |k, c, _| {
            Err(claim_err(
                k.file,
                c,
                "kind",
                "a named check runs through its paper's registry, not as a generic kind".into(),
            ))
        },
    },
];

/// The derivations `@name[...]` reaches, with their parameters and what they are.
pub const DERIVATIONS: &[(&str, &str, &str)] = &[
    (
        "galerkin.bend",
        "m, n (odd)",
        "000 (2),(12): the projection of the bending term D~ Delta^2 w onto sin(m pi x/a) sin(n pi y/b), the coefficient of E~/(1-nu~^2)[f]",
    ),
    (
        "galerkin.load_sign",
        "m, n (odd)",
        "000 (2),(12): the sign sin(m pi/2) sin(n pi/2) with which the point load under the cone enters the projected equation",
    ),
    (
        "galerkin.airy_x",
        "m, n (odd)",
        "000 (3),(12): the coefficient of E~ f^2 cos(2 m pi x/a) in the Airy function solved from (3)",
    ),
    (
        "galerkin.airy_y",
        "m, n (odd)",
        "000 (3),(12): the coefficient of E~ f^2 cos(2 n pi y/b) in the Airy function solved from (3)",
    ),
    (
        "galerkin.a3",
        "m, n (odd)",
        "000 (2),(8),(12): the projected coefficient of f (in-plane loads p1, p2, Winkler Kw, Pasternak KG)",
    ),
    (
        "galerkin.ct",
        "m, n (odd)",
        "000 (2),(12): the projected coefficient of f' (the foundation damper CT)",
    ),
    (
        "galerkin.a4",
        "m, n (odd)",
        "000 (2),(12): the projected coefficient of f'' (inertia rho h)",
    ),
    (
        "galerkin.cubic",
        "m, n (odd)",
        "000 (2),(3),(12): the projected membrane coefficient of f E~[f^2], with the Airy function solved from (3)",
    ),
    (
        "series.a1",
        "",
        "000 (18)-(20): the second term a1(t) of the Adomian series, an exponential polynomial in t, with the viscous term d(z^2)/dt = 2 z z'",
    ),
    (
        "series.a1.zz",
        "",
        "000 (18)-(20): a1(t) with the viscous term z z' as printed in (18)",
    ),
    (
        "operator",
        "",
        "000 sec. 2: E~/(1-nu~^2) derived from E~ = E(1 + D/lambda) and a constant bulk modulus, as a rational function of D = d/dt",
    ),
    (
        "operator.constant",
        "",
        "000 sec. 2: the constant c of E~/(1-nu~^2) = c (1 + D/lambda)[L(alpha) - L(gamma)], from the partial fractions of @operator",
    ),
];

fn claim_err(file: &PaperClaims, c: &ClaimSpec, field: &str, message: String) -> VerifyError {
    VerifyError::Claim {
        file: file.source.display().to_string(),
        id: c.id.clone(),
        field: field.into(),
        message,
    }
}

/// A reference `@name[k=v,...]` inside a derived formula.
#[derive(Clone, Debug)]
struct DerivationRef {
    placeholder: String,
    name: String,
    params: Vec<(String, Q)>,
}

/// Splits the `@name[...]` references out of `text`, replacing each by a placeholder symbol.
fn split_refs(text: &str) -> Result<(String, Vec<DerivationRef>), String> {
    let mut out = String::new();
    let mut refs = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find('@') {
        out.push_str(&rest[..at]);
        let after = &rest[at + 1..];
        let end = after
            .find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_' || ch == '.'))
            .unwrap_or(after.len());
        let name = after[..end].to_string();
        if !DERIVATIONS.iter().any(|d| d.0 == name) {
            return Err(format!(
                "unknown derivation `@{name}`; known: {}",
                DERIVATIONS
                    .iter()
                    .map(|d| format!("@{}", d.0))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
        let mut params = Vec::new();
        let mut tail = &after[end..];
        if let Some(inner) = tail.strip_prefix('[') {
            let close = inner
                .find(']')
                .ok_or_else(|| format!("`@{name}[`: no closing `]`"))?;
            for kv in inner[..close].split(',').filter(|s| !s.trim().is_empty()) {
                let (k, v) = kv
                    .split_once('=')
                    .ok_or_else(|| format!("`@{name}[{kv}]`: expected NAME=VALUE"))?;
                let v = crate::algebra::poly::parse_q(v)
                    .ok_or_else(|| format!("`@{name}[{kv}]`: `{v}` is not an exact number"))?;
                params.push((k.trim().to_string(), v));
            }
            tail = &inner[close + 1..];
        }
        let placeholder = format!("at_ref_{}", refs.len());
        out.push_str(&placeholder);
        refs.push(DerivationRef {
            placeholder,
            name,
            params,
        });
        rest = tail;
    }
    out.push_str(rest);
    Ok((out, refs))
}

/// The derivations computed in one run, kept for the claims that share them.
#[derive(Default)]
pub struct Derivations {
    galerkin: BTreeMap<(u32, u32), crate::algebra::galerkin::Galerkin>,
    operator: Option<crate::algebra::operator::OperatorCheck>,
}

impl Derivations {
    /// The exponential polynomials in t (`@series.*`); `None` for a rational derivation.
    fn expo(&self, r: &DerivationRef) -> Option<crate::algebra::expo::Expo> {
        use crate::algebra::series::{SeriesParams, Viscous, adomian_terms};
        let visc = match r.name.as_str() {
            "series.a1" => Viscous::TwoZZ,
            "series.a1.zz" => Viscous::ZZ,
            _ => return None,
        };
        Some(adomian_terms(&SeriesParams::symbolic(), 1, visc).remove(1))
    }

    fn get(&mut self, r: &DerivationRef, defaults: &[(String, Q)]) -> Result<RatFunc, String> {
        let param = |k: &str| -> Result<u32, String> {
            let v = r
                .params
                .iter()
                .chain(defaults)
                .find(|(n, _)| n == k)
                .map(|(_, v)| v.clone())
                .ok_or_else(|| format!("`@{}` needs `{k}` (e.g. @{}[m=1,n=1])", r.name, r.name))?;
            use num_traits::ToPrimitive;
            v.to_integer()
                .to_u32()
                .filter(|_| v.is_integer())
                .ok_or_else(|| format!("`@{}`: {k} = {v} is not a positive integer", r.name))
        };
        if let Some(part) = r.name.strip_prefix("galerkin.") {
            let (m, n) = (param("m")?, param("n")?);
            let g = match self.galerkin.entry((m, n)) {
                std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
                std::collections::btree_map::Entry::Vacant(e) => {
                    e.insert(crate::algebra::galerkin::derive(m, n).map_err(|e| e.to_string())?)
                }
            };
            let p = &g.parts;
            return Ok(match part {
                "load_sign" => RatFunc::from_q(Q::from_integer(g.load_sign.into())),
                "airy_x" => g.airy_derived.0.clone(),
                "airy_y" => g.airy_derived.1.clone(),
                "bend" => p.bend.clone(),
                "a3" => p.a3.clone(),
                "ct" => p.ct.clone(),
                "a4" => p.a4.clone(),
                _ => p.cubic.clone(),
            });
        }
        let op = self
            .operator
            .get_or_insert_with(crate::algebra::operator::check);
        Ok(match r.name.as_str() {
            "operator" => crate::algebra::operator::derived_operator(),
            _ => op.derived_constant.clone(),
        })
    }
}

/// A claims file with its units read.
pub struct Checked<'a> {
    file: &'a PaperClaims,
    units: BTreeMap<String, Unit>,
    /// The file's definitions, each expanded to symbols with units.
    defs: BTreeMap<String, Expr>,
    /// The unit of each definition, or why it has none.
    def_units: BTreeMap<String, Result<Unit, String>>,
    dir: PathBuf,
}

fn parse_formula(
    file: &PaperClaims,
    c: &ClaimSpec,
    field: &str,
    text: &str,
) -> Result<Expr, VerifyError> {
    expr::parse(text).map_err(|e| claim_err(file, c, field, format!("`{text}`: {e}")))
}

fn required<'b, T>(
    file: &PaperClaims,
    c: &ClaimSpec,
    field: &str,
    v: &'b Option<T>,
    what: &str,
) -> Result<&'b T, VerifyError> {
    v.as_ref().ok_or_else(|| {
        claim_err(
            file,
            c,
            field,
            format!("missing; kind `{}` needs it ({what})", c.kind),
        )
    })
}

/// One grid axis or sampled field.
#[derive(Clone, Debug)]
struct Axis {
    field: String,
    values: Vec<f64>,
    log: bool,
}

fn parse_axis(spec: &str) -> Result<Axis, String> {
    let (spec, log) = match spec.strip_suffix(":log") {
        Some(s) => (s, true),
        None => (spec, false),
    };
    let sv = crate::scene::sweep::parse_vary(spec, log).map_err(|e| e.to_string())?;
    Ok(Axis {
        field: sv.param,
        values: sv.values,
        log,
    })
}

/// A distribution of `sample`.
#[derive(Clone, Copy, Debug)]
enum Dist {
    Uniform(f64, f64),
    LogUniform(f64, f64),
    Normal(f64, f64),
}

fn parse_dist(text: &str) -> Result<Dist, String> {
    let help = "expected uniform(a, b), loguniform(a, b) with 0 < a < b, or normal(mu, sigma) with sigma > 0";
    let t = text.trim();
    let open = t.find('(').ok_or_else(|| format!("`{text}`: {help}"))?;
    let inner = t[open + 1..]
        .strip_suffix(')')
        .ok_or_else(|| format!("`{text}`: {help}"))?;
    let args: Vec<f64> = inner
        .split(',')
        .map(|s| s.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{text}`: {help}"))?;
    let [a, b] = args[..] else {
        return Err(format!("`{text}`: two numbers are needed; {help}"));
    };
    if !a.is_finite() || !b.is_finite() {
        return Err(format!("`{text}`: {help}"));
    }
    match &t[..open] {
        "uniform" if a < b => Ok(Dist::Uniform(a, b)),
        "loguniform" if 0.0 < a && a < b => Ok(Dist::LogUniform(a, b)),
        "normal" if b > 0.0 => Ok(Dist::Normal(a, b)),
        _ => Err(format!("`{text}`: {help}")),
    }
}

impl Dist {
    /// The quantile at `u` in (0, 1) (statrs' inverse CDFs).
    fn quantile(self, u: f64) -> f64 {
        use statrs::distribution::{ContinuousCDF, Normal, Uniform};
        match self {
            Dist::Uniform(a, b) => Uniform::new(a, b).map_or(f64::NAN, |d| d.inverse_cdf(u)),
            Dist::LogUniform(a, b) => Uniform::new(a.ln(), b.ln())
                .map_or(f64::NAN, |d| d.inverse_cdf(u))
                .exp(),
            Dist::Normal(m, s) => Normal::new(m, s).map_or(f64::NAN, |d| d.inverse_cdf(u)),
        }
    }
}

/// The number at a dotted path of a model's outcome (`contact.duration`, `impulse.2`).
pub fn lookup(v: &Value, path: &str) -> Option<f64> {
    let mut cur = v;
    for part in path.split('.') {
        cur = match cur {
            Value::Object(m) => m.get(part)?,
            Value::Array(a) => a.get(part.parse::<usize>().ok()?)?,
            _ => return None,
        };
    }
    match cur {
        Value::Number(n) => n.as_f64(),
        Value::Bool(b) => Some(f64::from(u8::from(*b))),
        _ => None,
    }
}

use crate::scene::field_value;

/// Runs the scene `base` with the fields of one grid point or sample set, and evaluates two
/// formulas there: a symbol is a bound scene field (`bind`) or a number the model produces.
/// A sampled claim's `count` (1 to 10^6) and `seed`, both required.
fn count_and_seed(f: &PaperClaims, c: &ClaimSpec) -> Result<(), VerifyError> {
    let n = *required(f, c, "count", &c.count, "the number of samples")?;
    if !(1..=1_000_000).contains(&n) {
        return Err(claim_err(
            f,
            c,
            "count",
            format!("{n} is out of range; allowed: 1..=1000000"),
        ));
    }
    required(f, c, "seed", &c.seed, "the generator's seed")?;
    Ok(())
}

fn run_point(
    c: &ClaimSpec,
    base: &toml::Table,
    label: &str,
    pt: &[(String, f64)],
    sides: (&Expr, &Expr),
) -> Result<(f64, f64), String> {
    let mut t = base.clone();
    for (fields, v) in pt {
        set_fields(&mut t, fields, *v, label)?;
    }
    let out = run_table(&t, label)?;
    let value = |s: &str| match c.bind.get(s) {
        Some(field) => field_value(&t, field),
        None => lookup(&out, s),
    };
    Ok((sides.0.eval(&value)?, sides.1.eval(&value)?))
}

/// Sets every field of a `sample` key (one or more fields, separated by spaces, that share one
/// draw: the two off-diagonal entries of a symmetric inertia).
fn set_fields(t: &mut toml::Table, fields: &str, v: f64, label: &str) -> Result<(), String> {
    for field in fields.split_whitespace() {
        crate::scene::set_field(t, field, v, label).map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn run_table(t: &toml::Table, label: &str) -> Result<Value, String> {
    let scene = crate::scene::parse_table(t, label).map_err(|e| e.to_string())?;
    scene.run().map(|(v, _)| v).map_err(|e| e.to_string())
}

fn g4(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor();
    if (-3.0..5.0).contains(&e) {
        let digits = (3.0 - e).max(0.0) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

impl<'a> Checked<'a> {
    /// Reads the file's units and checks every generic claim's keys, formulas, scenes and
    /// quantities (running each named scene once), before any claim runs.
    pub fn validate(file: &'a PaperClaims) -> Result<Self, VerifyError> {
        super::check_names(file)?;
        let mut units = BTreeMap::new();
        for (name, text) in &file.symbols {
            let u = Unit::parse(text).map_err(|message| VerifyError::BadClaims {
                path: file.source.clone(),
                message: format!("symbols.{name}: {message}"),
            })?;
            units.insert(name.clone(), u);
        }
        let dir = file
            .source
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| PathBuf::from("."));
        let bad_def = |name: &str, message: String| VerifyError::BadClaims {
            path: file.source.clone(),
            message: format!("definitions.{name}: {message}"),
        };
        let mut raw = BTreeMap::new();
        for (name, text) in &file.definitions {
            let e = expr::parse(text).map_err(|e| bad_def(name, format!("`{text}`: {e}")))?;
            raw.insert(name.clone(), e);
        }
        // expand each definition until no defined name is left (a cycle never ends: refused)
        let mut defs = BTreeMap::new();
        for (name, e) in &raw {
            let mut cur = e.clone();
            for round in 0.. {
                if !cur.symbols().iter().any(|s| raw.contains_key(s)) {
                    break;
                }
                if round == 50 {
                    return Err(bad_def(
                        name,
                        "refers to itself (through other definitions)".into(),
                    ));
                }
                cur = cur.substitute(&|s: &str| raw.get(s).cloned());
            }
            for s in cur.symbols() {
                if !units.contains_key(&s) && !matches!(s.as_str(), "m" | "n") {
                    return Err(bad_def(
                        name,
                        format!("unknown symbol `{s}`: give its unit in [symbols]"),
                    ));
                }
            }
            defs.insert(name.clone(), cur);
        }
        let mut me = Checked {
            file,
            units,
            defs,
            def_units: BTreeMap::new(),
            dir,
        };
        let def_units = me
            .defs
            .iter()
            .map(|(k, e)| {
                let u = units::dimension(e, &me.unit_fn()).map_err(|e| e.to_string());
                (k.clone(), u)
            })
            .collect();
        me.def_units = def_units;
        for c in &file.claim {
            me.validate_claim(c)?;
        }
        Ok(me)
    }

    fn units_of(
        &self,
        c: &ClaimSpec,
        field: &str,
        e: &Expr,
        also: &[&str],
    ) -> Result<(), VerifyError> {
        for s in e.symbols() {
            if !self.units.contains_key(&s)
                && !self.defs.contains_key(&s)
                && !also.contains(&s.as_str())
                && !s.starts_with("at_ref_")
            {
                return Err(claim_err(
                    self.file,
                    c,
                    field,
                    format!(
                        "unknown symbol `{s}`: give its unit in [symbols] (e.g. {s} = \"m\"){}",
                        if self.units.is_empty() {
                            String::new()
                        } else {
                            format!(
                                "; known: {}",
                                self.units.keys().cloned().collect::<Vec<_>>().join(", ")
                            )
                        }
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The claim's scene as a table, and its path for messages.
    fn scene_table(&self, c: &ClaimSpec) -> Result<(String, toml::Table), VerifyError> {
        let path = self.scene_path(c)?;
        let mut base = crate::scene::read_table(&path)
            .map_err(|e| claim_err(self.file, c, "scene", e.to_string()))?;
        let label = path.display().to_string();
        for (field, v) in &c.set {
            crate::scene::set_value(&mut base, field, v.clone(), &label)
                .map_err(|e| claim_err(self.file, c, &format!("set.{field}"), e.to_string()))?;
        }
        Ok((label, base))
    }

    fn scene_path(&self, c: &ClaimSpec) -> Result<PathBuf, VerifyError> {
        let s = required(
            self.file,
            c,
            "scene",
            &c.scene,
            "a scene file, relative to the claims file",
        )?;
        let p = self.dir.join(s);
        if !p.is_file() {
            return Err(claim_err(
                self.file,
                c,
                "scene",
                format!("`{s}`: no such file ({})", p.display()),
            ));
        }
        Ok(p)
    }

    /// Runs one generic claim (`kind` other than `check`).
    pub fn check(&self, c: &ClaimSpec, der: &mut Derivations) -> Result<Outcome, VerifyError> {
        let mut o = match KIND_TABLE.iter().find(|k| k.name == c.kind) {
            Some(k) => (k.check)(self, c, der)?,
            None => {
                return Err(claim_err(
                    self.file,
                    c,
                    "kind",
                    format!("unknown kind `{}`; allowed: {}", c.kind, KINDS.join(", ")),
                ));
            }
        };
        o.kind = c.kind.clone();
        Ok(super::with_assumption(o, c))
    }

    /// A claim the tool cannot check: the reason is what the text lacks.
    fn not_checkable(&self, c: &ClaimSpec) -> Outcome {
        let mut o = outcome(
            self.file,
            c,
            Verdict::NotCheckable,
            c.reason.clone().unwrap_or_default(),
        );
        o.extra_md = Some("Kind `not-checkable`: the reason is what the text lacks.".into());
        o
    }

    fn unit_fn(&self) -> impl Fn(&str) -> Option<Unit> + '_ {
        |s: &str| {
            if let Some(Ok(u)) = self.def_units.get(s) {
                return Some(*u);
            }
            if s == "m" || s == "n" {
                self.units.get(s).copied().or(Some(Unit::one()))
            } else {
                self.units.get(s).copied()
            }
        }
    }

    /// A formula of a claim, with the claim's `where` and then the file's definitions expanded.
    fn formula(&self, c: &ClaimSpec, field: &str, text: &str) -> Result<Expr, VerifyError> {
        let e = parse_formula(self.file, c, field, text)?;
        self.expand_all(c, &e)
    }

    /// The claim's and the file's definitions expanded in `e` until none is left (a local
    /// definition may use a file definition that uses another local one).
    fn expand_all(&self, c: &ClaimSpec, e: &Expr) -> Result<Expr, VerifyError> {
        let mut cur = e.clone();
        for _ in 0..20 {
            let next = self.expand(&self.expand_local(c, &cur)?);
            if next == cur {
                return Ok(next);
            }
            cur = next;
        }
        Ok(cur)
    }

    /// The claim's own definitions (`where`) expanded in `e`, repeatedly (they may use each
    /// other; a cycle is refused).
    fn expand_local(&self, c: &ClaimSpec, e: &Expr) -> Result<Expr, VerifyError> {
        if c.where_.is_empty() {
            return Ok(e.clone());
        }
        let local: BTreeMap<String, Expr> = c
            .where_
            .iter()
            .map(|(k, v)| {
                parse_formula(self.file, c, &format!("where.{k}"), v).map(|x| (k.clone(), x))
            })
            .collect::<Result<_, _>>()?;
        let mut cur = e.clone();
        for _ in 0..50 {
            if !cur.symbols().iter().any(|s| local.contains_key(s)) {
                return Ok(cur);
            }
            cur = cur.substitute(&|s: &str| local.get(s).cloned());
        }
        Err(claim_err(
            self.file,
            c,
            "where",
            "a definition refers to itself".into(),
        ))
    }

    /// The file's definitions expanded in `e`.
    fn expand(&self, e: &Expr) -> Expr {
        e.substitute(&|s: &str| self.defs.get(s).cloned())
    }
}
