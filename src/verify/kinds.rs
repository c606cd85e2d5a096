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

    fn validate_claim(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        match c.kind.as_str() {
            "check" => {
                // a named check may still read its printed formulas from the file
                for (i, row) in c.printed_matrix.iter().enumerate() {
                    for (j, text) in row.iter().enumerate() {
                        let field = format!("printed_matrix[{i}][{j}]");
                        let e = parse_formula(f, c, &field, text)?;
                        self.units_of(c, &field, &e, &[])?;
                    }
                }
                if let Some(text) = &c.printed {
                    let e = parse_formula(f, c, "printed", text)?;
                    self.units_of(c, "printed", &e, &[])?;
                }
                for (i, text) in c.printed_equations.iter().enumerate() {
                    let field = format!("printed_equations[{i}]");
                    let e = parse_formula(f, c, &field, text)?;
                    self.units_of(c, &field, &e, &[])?;
                }
                if c.check.is_empty() {
                    return Err(claim_err(
                        f,
                        c,
                        "check",
                        "missing; kind `check` names a Rust check".into(),
                    ));
                }
            }
            "identity" => {
                let p = parse_formula(
                    f,
                    c,
                    "printed",
                    required(f, c, "printed", &c.printed, "a formula")?,
                )?;
                self.units_of(c, "printed", &p, &["m", "n"])?;
                if let Some(sel) = &c.part {
                    parse_formula(f, c, "part", sel)?;
                }
                let d = required(f, c, "derived", &c.derived, "a formula or @derivation")?;
                let (text, _) = split_refs(d).map_err(|m| claim_err(f, c, "derived", m))?;
                let de = parse_formula(f, c, "derived", &text)?;
                self.units_of(c, "derived", &de, &["m", "n"])?;
                if let Some(k) = &c.corrected {
                    let (text, _) = split_refs(k).map_err(|m| claim_err(f, c, "corrected", m))?;
                    let ke = parse_formula(f, c, "corrected", &text)?;
                    self.units_of(c, "corrected", &ke, &["m", "n"])?;
                }
            }
            "dimension" => {
                let p = parse_formula(
                    f,
                    c,
                    "printed",
                    required(f, c, "printed", &c.printed, "a formula")?,
                )?;
                self.units_of(c, "printed", &p, &[])?;
                let e = required(f, c, "expect", &c.expect, "a unit such as \"N\"")?;
                Unit::parse(e).map_err(|m| claim_err(f, c, "expect", m))?;
            }
            "definition" => {
                let p = parse_formula(
                    f,
                    c,
                    "printed",
                    required(f, c, "printed", &c.printed, "the defining formula")?,
                )?;
                self.units_of(c, "printed", &p, &["m", "n"])?;
                if let Some(d) = &c.defines
                    && !self.units.contains_key(d)
                {
                    return Err(claim_err(
                        f,
                        c,
                        "defines",
                        format!("`{d}`: give its unit in [symbols]"),
                    ));
                }
                if c.defines.is_none() && c.agrees.is_empty() {
                    return Err(claim_err(
                        f,
                        c,
                        "agrees",
                        "a definition needs `defines` (the symbol, whose unit is checked) or `agrees` (identities from the equations that use it), or both".into(),
                    ));
                }
                for (i, [l, r]) in c.agrees.iter().enumerate() {
                    for (side, text) in [("printed", l), ("derived", r)] {
                        let field = format!("agrees[{i}].{side}");
                        let e = parse_formula(f, c, &field, text)?;
                        self.units_of(c, &field, &e, &["m", "n"])?;
                    }
                }
            }
            "not-checkable" => {
                required(f, c, "reason", &c.reason, "what the text lacks for a check")?;
            }
            "bound" if c.scene.is_none() => {
                // a bound on formulas alone: the samples are the symbols' values
                count_and_seed(f, c)?;
                required(f, c, "require", &c.require, "an inequality")?;
                for (sym, d) in &c.sample {
                    let key = format!("sample.{sym}");
                    parse_dist(d).map_err(|m| claim_err(f, c, &key, m))?;
                    if !self.units.contains_key(sym) {
                        return Err(claim_err(
                            f,
                            c,
                            &key,
                            format!("`{sym}`: give its unit in [symbols]"),
                        ));
                    }
                }
                let ineq = self.inequality(c, "require")?;
                for e in [&ineq.lhs, &ineq.rhs] {
                    self.units_of(c, "require", e, &[])?;
                    for s in e.free_symbols() {
                        if !c.sample.contains_key(&s) {
                            return Err(claim_err(
                                f,
                                c,
                                "require",
                                format!(
                                    "`{s}` is not sampled: without a scene every symbol is drawn (sample.{s} = \"uniform(a, b)\")"
                                ),
                            ));
                        }
                    }
                }
            }
            "model" | "bound" | "probability" | "map" => {
                let path = self.scene_path(c)?;
                let (_, mut table) = self.scene_table(c)?;
                let gridded = c.kind == "model" || c.kind == "map";
                // which inequality a claim has, if any: bound `require`, probability `event`, a map
                // of a region `require`
                let ineq_field = match c.kind.as_str() {
                    "bound" => Some("require"),
                    "probability" => Some("event"),
                    "map" if c.require.is_some() => Some("require"),
                    _ => None,
                };
                if gridded {
                    if ineq_field.is_none() {
                        required(
                            f,
                            c,
                            "quantity",
                            &c.quantity,
                            "a dotted path of the outcome",
                        )?;
                        let rtol = *required(f, c, "rtol", &c.rtol, "a relative tolerance")?;
                        if !(rtol.is_finite() && rtol >= 0.0) {
                            return Err(claim_err(
                                f,
                                c,
                                "rtol",
                                format!("{rtol} is not a tolerance >= 0"),
                            ));
                        }
                    }
                    if c.kind == "map" && c.vary.len() != 2 {
                        return Err(claim_err(
                            f,
                            c,
                            "vary",
                            format!(
                                "a map has two axes, FIELD=START:STOP:COUNT[:log] each; {} given",
                                c.vary.len()
                            ),
                        ));
                    }
                    if c.vary.is_empty() {
                        return Err(claim_err(
                            f,
                            c,
                            "vary",
                            "missing; give at least one FIELD=START:STOP:COUNT[:log]".into(),
                        ));
                    }
                    for spec in &c.vary {
                        let a = parse_axis(spec).map_err(|m| claim_err(f, c, "vary", m))?;
                        set_fields(&mut table, &a.field, a.values[0], "scene")
                            .map_err(|m| claim_err(f, c, "vary", m))?;
                    }
                } else {
                    count_and_seed(f, c)?;
                    if c.sample.is_empty() {
                        return Err(claim_err(
                            f,
                            c,
                            "sample",
                            "missing; give at least one FIELD = \"uniform(a, b)\"".into(),
                        ));
                    }
                    for (fields, d) in &c.sample {
                        let key = format!("sample.{fields}");
                        let d = parse_dist(d).map_err(|m| claim_err(f, c, &key, m))?;
                        set_fields(&mut table, fields, d.quantile(0.5), "scene")
                            .map_err(|m| claim_err(f, c, &key, m))?;
                    }
                }
                if c.kind == "probability" {
                    if let Some(e) = &c.expect {
                        parse_expectation(e).map_err(|m| claim_err(f, c, "expect", m))?;
                    }
                    if let Some(conf) = c.confidence
                        && !(conf > 0.0 && conf < 1.0)
                    {
                        return Err(claim_err(
                            f,
                            c,
                            "confidence",
                            format!("{conf} is out of range; allowed: 0 < confidence < 1"),
                        ));
                    }
                }
                for (sym, field) in &c.bind {
                    if field_value(&table, field).is_none() {
                        return Err(claim_err(
                            f,
                            c,
                            &format!("bind.{sym}"),
                            format!(
                                "scene field `{field}` is not a number in {}",
                                path.display()
                            ),
                        ));
                    }
                }
                // one run of the scene, to know what the model produces
                let outcome = run_table(&table, &path.display().to_string())
                    .map_err(|m| claim_err(f, c, "scene", m))?;
                let mut formulas: Vec<(&str, Expr)> = Vec::new();
                match ineq_field {
                    None => {
                        let q = c.quantity.as_deref().unwrap_or_default();
                        if lookup(&outcome, q).is_none() {
                            return Err(claim_err(
                                f,
                                c,
                                "quantity",
                                format!(
                                    "`{q}`: the model does not produce this number; it produces: {}",
                                    numeric_paths(&outcome).join(", ")
                                ),
                            ));
                        }
                        formulas.push((
                            "printed",
                            self.formula(
                                c,
                                "printed",
                                required(f, c, "printed", &c.printed, "a formula")?,
                            )?,
                        ));
                    }
                    Some(field) => {
                        let text = if field == "event" {
                            &c.event
                        } else {
                            &c.require
                        };
                        required(f, c, field, text, "an inequality")?;
                        let ineq = self.inequality(c, field)?;
                        formulas.push((field, ineq.lhs));
                        formulas.push((field, ineq.rhs));
                    }
                }
                for (field, e) in &formulas {
                    for s in e.free_symbols() {
                        if !c.bind.contains_key(&s) && lookup(&outcome, &s).is_none() {
                            return Err(claim_err(
                                f,
                                c,
                                field,
                                format!(
                                    "`{s}` is neither bound to a scene field (bind) nor a number the model produces ({})",
                                    numeric_paths(&outcome).join(", ")
                                ),
                            ));
                        }
                    }
                    self.units_of(c, field, e, &[])?;
                }
            }
            other => {
                return Err(claim_err(
                    f,
                    c,
                    "kind",
                    format!("unknown kind `{other}`; allowed: {}", KINDS.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// Runs one generic claim (`kind` other than `check`).
    pub fn check(&self, c: &ClaimSpec, der: &mut Derivations) -> Result<Outcome, VerifyError> {
        let mut o = match c.kind.as_str() {
            "identity" => self.identity(c, der)?,
            "dimension" => self.dimension(c)?,
            "model" => self.model(c)?,
            "map" => self.map(c)?,
            "probability" => self.probability(c)?,
            "definition" => self.definition(c, der)?,
            "not-checkable" => {
                let mut o = outcome(
                    self.file,
                    c,
                    Verdict::NotCheckable,
                    c.reason.clone().unwrap_or_default(),
                );
                o.extra_md =
                    Some("Kind `not-checkable`: the reason is what the text lacks.".into());
                o
            }
            _ => self.bound(c)?,
        };
        o.kind = c.kind.clone();
        Ok(super::with_assumption(o, c))
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

    /// A definition: the unit of `defines` against the printed formula's, then each identity of
    /// `agrees` with the definition substituted (exact where rational).
    fn definition(&self, c: &ClaimSpec, der: &mut Derivations) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let text = c.printed.as_deref().unwrap_or_default();
        let p = self.formula(c, "printed", text)?;
        let mut ok = true;
        let mut parts = Vec::new();
        if let Some(d) = &c.defines {
            let want = self.units[d];
            match units::dimension(&p, &self.unit_fn()) {
                Ok(u) if u == want => parts.push(format!("`{d}` and `{p}` are both {u}")),
                Ok(u) => {
                    ok = false;
                    parts.push(format!("`{d}` is {want} but `{p}` is {u}"));
                }
                Err(e) => {
                    ok = false;
                    parts.push(format!("`{p}` has no single unit: {e}"));
                }
            }
        }
        for (i, [l, r]) in c.agrees.iter().enumerate() {
            let mut sub = c.clone();
            sub.kind = "identity".into();
            sub.printed = Some(l.clone());
            sub.derived = Some(r.clone());
            sub.corrected = None;
            sub.assumption = None;
            if let Some(d) = &c.defines {
                sub.where_.insert(d.clone(), text.to_string());
            }
            let o = self.identity(&sub, der)?;
            let held = o.verdict == Verdict::Holds;
            ok &= held;
            parts.push(format!(
                "use {}: `{l}` {} `{r}` ({})",
                i + 1,
                if held { "=" } else { "!=" },
                o.detail
            ));
        }
        let verdict = if ok {
            Verdict::Definition
        } else {
            Verdict::Fails
        };
        let mut o = outcome(f, c, verdict, parts.join("; "));
        o.extra_md = Some(format!(
            "Kind `definition`{}: `{text}`; checked for units and against {} use(s).",
            c.defines
                .as_deref()
                .map(|d| format!(" of `{d}`"))
                .unwrap_or_default(),
            c.agrees.len()
        ));
        Ok(o)
    }

    fn dimension(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let text = c.printed.as_deref().unwrap_or_default();
        let p = parse_formula(f, c, "printed", text)?;
        let want = Unit::parse(c.expect.as_deref().unwrap_or_default())
            .map_err(|m| claim_err(f, c, "expect", m))?;
        // a definition the formula uses that has no unit of its own is named first
        let bad_defs: Vec<String> = p
            .symbols()
            .iter()
            .filter_map(|s| match self.def_units.get(s) {
                Some(Err(e)) => Some(format!(
                    "`{s}` (defined as `{}`) has no single unit: {e}",
                    self.defs[s]
                )),
                _ => None,
            })
            .collect();
        // the unit of every term of the top-level sum, so that the odd one is seen
        let terms = || -> String {
            top_terms(&p)
                .iter()
                .map(|t| match units::dimension(t, &self.unit_fn()) {
                    Ok(u) if u == want => format!("`{t}`: {u}"),
                    Ok(u) => format!("`{t}`: {u} (not {want})"),
                    Err(units::DimError::Unknown(s)) if self.defs.contains_key(&s) => {
                        format!("`{t}`: none (`{s}` has none)")
                    }
                    Err(e) => format!("`{t}`: none ({e})"),
                })
                .collect::<Vec<_>>()
                .join("; ")
        };
        let several = top_terms(&p).len() > 1;
        let (verdict, detail) = match units::dimension(&p, &self.unit_fn()) {
            _ if !bad_defs.is_empty() => (
                Verdict::Fails,
                format!(
                    "{}{}",
                    bad_defs.join("; "),
                    if several {
                        format!("; the terms: {}", terms())
                    } else {
                        String::new()
                    }
                ),
            ),
            Ok(u) if u == want => (Verdict::Holds, format!("`{p}` is {u}, as expected")),
            Ok(u) => (
                Verdict::Fails,
                format!(
                    "`{p}` is {u}, not {want} (expected `{}`)",
                    c.expect.as_deref().unwrap_or_default()
                ),
            ),
            Err(e) if several => (
                Verdict::Fails,
                format!("no single unit: {e}; the terms: {}", terms()),
            ),
            Err(e) => (Verdict::Fails, format!("`{p}` has no single unit: {e}")),
        };
        let mut o = outcome(f, c, verdict, detail);
        o.extra_md = Some(format!(
            "Kind `dimension`. Printed: `{p}`; expected unit: `{}`.",
            c.expect.as_deref().unwrap_or_default()
        ));
        Ok(o)
    }

    /// The derived side (with derivations substituted) minus the printed, exact; `None` when one
    /// side is not rational.
    fn exact_difference(
        &self,
        c: &ClaimSpec,
        field: &str,
        printed: &Expr,
        derived_text: &str,
        params: &[(String, Q)],
        der: &mut Derivations,
    ) -> Result<Option<(RatFunc, RatFunc, RatFunc)>, VerifyError> {
        let f = self.file;
        let (text, refs) = split_refs(derived_text).map_err(|m| claim_err(f, c, field, m))?;
        let subst = |e: &Expr| {
            e.substitute(&|s: &str| {
                params
                    .iter()
                    .find(|(k, _)| k == s)
                    .map(|(_, v)| Expr::Num(v.clone()))
            })
        };
        let d = subst(&self.formula(c, field, &text)?);
        let (p, d) = (subst(printed), d);
        let (Some(p), Some(mut d)) = (p.to_ratfunc(), d.to_ratfunc()) else {
            // functions as opaque symbols: proves a difference zero, or says nothing
            if refs.is_empty()
                && let (Some(p), Some(d)) = (p.to_ratfunc_opaque(), d.to_ratfunc_opaque())
                && (&d - &p).is_zero()
            {
                return Ok(Some((&d - &p, d, p)));
            }
            return Ok(None);
        };
        for r in &refs {
            let v = der.get(r, params).map_err(|m| claim_err(f, c, field, m))?;
            d = d.subst(Sym::new(&r.placeholder), &v).ok_or_else(|| {
                claim_err(
                    f,
                    c,
                    field,
                    format!("`@{}` makes a denominator zero", r.name),
                )
            })?;
        }
        Ok(Some((&d - &p, d, p)))
    }

    fn identity(&self, c: &ClaimSpec, der: &mut Derivations) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let printed_text = c.printed.as_deref().unwrap_or_default();
        let printed = self.formula(c, "printed", printed_text)?;
        let derived_text = c.derived.as_deref().unwrap_or_default();
        let modes: Vec<Vec<(String, Q)>> = if c.modes.is_empty() {
            vec![vec![]]
        } else {
            c.modes
                .iter()
                .map(|[m, n]| {
                    vec![
                        ("m".to_string(), Q::from_integer((*m).into())),
                        ("n".to_string(), Q::from_integer((*n).into())),
                    ]
                })
                .collect()
        };
        if let Some(o) = self.expo_identity(c, &printed, derived_text, der)? {
            return Ok(o);
        }
        let mut lines = Vec::new();
        let mut all_printed = true;
        let mut all_corrected = true;
        for params in &modes {
            let at = if params.is_empty() {
                String::new()
            } else {
                format!(
                    "({}): ",
                    params
                        .iter()
                        .map(|(_, v)| v.to_string())
                        .collect::<Vec<_>>()
                        .join(",")
                )
            };
            match self.exact_difference(c, "derived", &printed, derived_text, params, der)? {
                Some((diff, d, _)) if diff.is_zero() => {
                    lines.push(format!("{at}printed = derived = {d}"))
                }
                Some((diff, d, p)) => {
                    all_printed = false;
                    let mut line = format!("{at}derived {d}; derived - printed = {diff}");
                    // a ratio says more than a difference when it is shorter (a factor 2)
                    if let Some(ratio) = d.div(&p).filter(|_| !d.is_zero())
                        && ratio.to_text().len() < diff.to_text().len()
                    {
                        line.push_str(&format!("; derived/printed = {ratio}"));
                    }
                    if let Some(k) = &c.corrected {
                        let ke = self.formula(
                            c,
                            "corrected",
                            &split_refs(k)
                                .map_err(|m| claim_err(f, c, "corrected", m))?
                                .0,
                        )?;
                        match self.exact_difference(c, "derived", &ke, derived_text, params, der)? {
                            Some((kd, ..)) if kd.is_zero() => {
                                line.push_str("; the corrected form holds exactly")
                            }
                            Some((kd, ..)) => {
                                all_corrected = false;
                                line.push_str(&format!("; the corrected form differs by {kd}"));
                            }
                            None => all_corrected = false,
                        }
                    } else {
                        all_corrected = false;
                    }
                    lines.push(line);
                }
                None => {
                    let (ok, mut line) =
                        self.numeric_identity(c, &printed, derived_text, params)?;
                    all_printed &= ok;
                    match &c.corrected {
                        Some(k) if !ok => {
                            let ke = self.formula(c, "corrected", k)?;
                            let (kok, kline) =
                                self.numeric_identity(c, &ke, derived_text, params)?;
                            all_corrected &= kok;
                            line.push_str(&format!("; the corrected form: {kline}"));
                        }
                        _ => all_corrected &= ok,
                    }
                    lines.push(format!("{at}{line}"));
                }
            }
        }
        let verdict = if all_printed {
            Verdict::Holds
        } else if c.corrected.is_some() && all_corrected {
            Verdict::HoldsWithCorrection
        } else {
            Verdict::Fails
        };
        let mut o = outcome(f, c, verdict, lines.join("; "));
        let mut md = format!("Kind `identity`. Printed: `{printed}`; derived: `{derived_text}`.");
        if let Some(k) = &c.corrected {
            md.push_str(&format!(" Corrected: `{k}`."));
        }
        o.extra_md = Some(md);
        Ok(o)
    }

    /// An identity whose derived side is an exponential polynomial in t (`@series.a1`): the
    /// printed side is read as one too, and compared whole or, with `part` (`"t^2"`,
    /// `"exp(-alpha*t)"`), that part's coefficient alone. `None` when `derived` is not such a
    /// derivation.
    fn expo_identity(
        &self,
        c: &ClaimSpec,
        printed: &Expr,
        derived_text: &str,
        der: &Derivations,
    ) -> Result<Option<Outcome>, VerifyError> {
        use crate::algebra::expo::Expo;
        let f = self.file;
        let (text, refs) = split_refs(derived_text).map_err(|m| claim_err(f, c, "derived", m))?;
        let expo_ref = refs.first().and_then(|r| der.expo(r));
        if expo_ref.is_none() && c.taylor.is_none() {
            return Ok(None);
        }
        let t = c.variable.clone().unwrap_or_else(|| "t".into());
        let whole = self.formula(c, "derived", &text)?;
        let not_expo = |field: &str| {
            claim_err(
                f,
                c,
                field,
                format!("not an exponential polynomial in {t} (sums of c {t}^k exp(-b {t}))"),
            )
        };
        let d = match expo_ref {
            None => whole.to_expo(&t).ok_or_else(|| not_expo("derived"))?,
            Some(d_ref) => {
                // the derivation enters as one added term (`v0*t + @series.a1`); the rest is a
                // formula
                let placeholder = Expr::sym(&refs[0].placeholder);
                let added: Vec<bool> = signed_terms(&whole, true)
                    .into_iter()
                    .filter(|(_, e)| *e == placeholder)
                    .map(|(plus, _)| plus)
                    .collect();
                if refs.len() != 1 || added != [true] {
                    return Err(claim_err(
                        f,
                        c,
                        "derived",
                        format!(
                            "`@{}` is an exponential polynomial: write it alone or as an added term (`v0*t + @{}`)",
                            refs[0].name, refs[0].name
                        ),
                    ));
                }
                let rest = whole
                    .substitute(&|s: &str| {
                        (s == refs[0].placeholder).then(|| Expr::Num(Q::from_integer(0.into())))
                    })
                    .to_expo(&t)
                    .ok_or_else(|| not_expo("derived"))?;
                &rest + &d_ref
            }
        };
        let p = printed.to_expo(&t).ok_or_else(|| {
            claim_err(
                f,
                c,
                "printed",
                format!("not an exponential polynomial in {t} (sums of c {t}^k exp(-b {t}))"),
            )
        })?;
        let coeff = |e: &Expo, key: &(crate::algebra::poly::Poly, u32)| {
            e.parts()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| v.clone())
                .unwrap_or_else(RatFunc::zero)
        };
        let (verdict, detail) = match &c.part {
            _ if c.taylor.is_some() => {
                let n = c.taylor.unwrap_or(0);
                let mut lines = Vec::new();
                let mut all = true;
                for k in 0..n {
                    let (dk, pk) = (d.taylor_coeff(k), p.taylor_coeff(k));
                    let same = (&dk - &pk).is_zero();
                    all &= same;
                    lines.push(if same {
                        format!("coefficient of {t}^{k} at 0: printed = derived = {dk}")
                    } else {
                        format!("coefficient of {t}^{k} at 0: derived {dk}, printed {pk}")
                    });
                }
                (
                    if all { Verdict::Holds } else { Verdict::Fails },
                    lines.join("; "),
                )
            }
            Some(sel) => {
                let key = parse_formula(f, c, "part", sel)?
                    .to_expo(&t)
                    .filter(|e| e.len() == 1)
                    .and_then(|e| e.parts().next().map(|(k, _)| k.clone()))
                    .ok_or_else(|| {
                        claim_err(
                            f,
                            c,
                            "part",
                            format!("`{sel}`: expected one part such as {t}^2 or exp(-alpha*{t})"),
                        )
                    })?;
                let (dp, pp) = (coeff(&d, &key), coeff(&p, &key));
                let diff = &dp - &pp;
                if diff.is_zero() {
                    (
                        Verdict::Holds,
                        format!("the {sel} part: printed = derived = {dp}"),
                    )
                } else {
                    (
                        Verdict::Fails,
                        format!(
                            "the {sel} part: derived {dp}; printed {pp}; derived - printed = {diff}"
                        ),
                    )
                }
            }
            None => {
                let diff = &d - &p;
                if diff.is_zero() {
                    (
                        Verdict::Holds,
                        format!("printed = derived = {}", d.to_text()),
                    )
                } else {
                    let mut keys: Vec<_> =
                        d.parts().chain(p.parts()).map(|(k, _)| k.clone()).collect();
                    keys.sort();
                    keys.dedup();
                    (
                        Verdict::Fails,
                        format!(
                            "{} of {} parts (powers of {t} times exponentials) differ; derived - printed = {}",
                            diff.len(),
                            keys.len(),
                            diff.to_text()
                        ),
                    )
                }
            }
        };
        let mut o = outcome(f, c, verdict, detail);
        o.extra_md = Some(format!(
            "Kind `identity` (exponential polynomials in {t}). Printed: `{printed}`; derived: `{derived_text}`{}.",
            c.part
                .as_ref()
                .map(|p| format!("; part `{p}`"))
                .unwrap_or_default()
        ));
        Ok(Some(o))
    }

    /// A non-rational identity (sqrt, exp of a non-linear argument, rational powers) compared in
    /// `f64` at seeded random points, each symbol in [0.5, 2]: holds when every relative
    /// difference is below 1e-12.
    fn numeric_identity(
        &self,
        c: &ClaimSpec,
        printed: &Expr,
        derived_text: &str,
        params: &[(String, Q)],
    ) -> Result<(bool, String), VerifyError> {
        let f = self.file;
        if derived_text.contains('@') {
            return Err(claim_err(
                f,
                c,
                "derived",
                "a derivation can be compared only with a rational printed form".into(),
            ));
        }
        let d = self.formula(c, "derived", derived_text)?;
        let mut syms = printed.symbols();
        syms.extend(d.symbols());
        syms.sort();
        syms.dedup();
        let mut rng = crate::rng::Rng(0x1D_E27);
        let mut worst: f64 = 0.0;
        let mut worst_abs: f64 = 0.0;
        for _ in 0..8 {
            let vals: BTreeMap<String, f64> = syms
                .iter()
                .map(|s| {
                    let fixed = params.iter().find(|(k, _)| k == s).map(|(_, v)| {
                        use num_traits::ToPrimitive;
                        v.to_f64().unwrap_or(f64::NAN)
                    });
                    (s.clone(), fixed.unwrap_or_else(|| rng.range(0.5, 2.0)))
                })
                .collect();
            let get = |s: &str| vals.get(s).copied();
            let (a, b) = (printed.eval(&get), d.eval(&get));
            let (a, b) = (
                a.map_err(|m| claim_err(f, c, "printed", m))?,
                b.map_err(|m| claim_err(f, c, "derived", m))?,
            );
            // the difference beyond the absolute tolerance, relative to the larger side
            let atol = c.atol.unwrap_or(0.0);
            let excess = ((a - b).abs() - atol).max(0.0);
            let rel = excess / a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
            worst = worst.max(if rel.is_nan() { f64::INFINITY } else { rel });
            worst_abs = worst_abs.max((a - b).abs());
        }
        let ok = worst <= 1e-12;
        Ok((
            ok,
            match c.atol {
                Some(atol) => format!(
                    "not rational: compared in floating point at 8 seeded points in [0.5, 2]; largest difference {} (atol {}), largest relative excess {}",
                    g4(worst_abs),
                    g4(atol),
                    g4(worst)
                ),
                None => format!(
                    "not rational: compared in floating point at 8 seeded points in [0.5, 2]; largest relative difference {}",
                    g4(worst)
                ),
            },
        ))
    }

    /// The grid of `vary` (first axis slowest) and, at each point, the two sides compared: the
    /// model's quantity and the printed formula, or both sides of an inequality.
    #[allow(clippy::type_complexity)]
    fn grid(
        &self,
        c: &ClaimSpec,
        sides: &(Expr, Expr),
    ) -> Result<
        (
            Vec<Axis>,
            Vec<Vec<(String, f64)>>,
            Vec<Result<(f64, f64), String>>,
        ),
        VerifyError,
    > {
        use rayon::prelude::*;
        let f = self.file;
        let (label, base) = self.scene_table(c)?;
        let axes: Vec<Axis> = c
            .vary
            .iter()
            .map(|s| parse_axis(s).map_err(|m| claim_err(f, c, "vary", m)))
            .collect::<Result<_, _>>()?;
        let mut points: Vec<Vec<(String, f64)>> = vec![vec![]];
        for a in &axes {
            points = points
                .into_iter()
                .flat_map(|p| {
                    a.values.iter().map(move |v| {
                        let mut q = p.clone();
                        q.push((a.field.clone(), *v));
                        q
                    })
                })
                .collect();
        }
        let rows = points
            .par_iter()
            .map(|pt| run_point(c, &base, &label, pt, (&sides.0, &sides.1)))
            .collect();
        Ok((axes, points, rows))
    }

    /// The model's quantity (as a formula of one symbol) and the printed formula of a claim.
    fn quantity_and_printed(&self, c: &ClaimSpec) -> Result<(Expr, Expr), VerifyError> {
        let quantity = c.quantity.clone().unwrap_or_default();
        let printed = self.formula(c, "printed", c.printed.as_deref().unwrap_or_default())?;
        Ok((Expr::Sym(quantity), printed))
    }

    fn model(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let sides = self.quantity_and_printed(c)?;
        let printed = sides.1.clone();
        let quantity = c.quantity.clone().unwrap_or_default();
        let rtol = c.rtol.unwrap_or(0.0);
        let (axes, points, rows) = self.grid(c, &sides)?;
        let mut worst: Option<(f64, usize)> = None;
        let mut errors = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            match r {
                Ok((m, p)) => {
                    let rel = (p - m).abs() / m.abs().max(f64::MIN_POSITIVE);
                    let rel = if rel.is_nan() { f64::INFINITY } else { rel };
                    if worst.is_none_or(|(w, _)| rel > w) {
                        worst = Some((rel, i));
                    }
                }
                Err(e) => errors.push(format!("at {}: {e}", point_text(&points[i]))),
            }
        }
        let n = points.len();
        let (verdict, mut detail) = match worst {
            Some((w, i)) => {
                let (m, p) = rows[i].clone().unwrap_or((f64::NAN, f64::NAN));
                (
                    if w <= rtol && errors.is_empty() {
                        Verdict::Holds
                    } else {
                        Verdict::Fails
                    },
                    format!(
                        "{n} grid points: largest relative difference {} (rtol {}) at {}: model {quantity} = {}, printed {}",
                        g4(w),
                        g4(rtol),
                        point_text(&points[i]),
                        g4(m),
                        g4(p)
                    ),
                )
            }
            None => (Verdict::NotCheckable, format!("{n} grid points, none ran")),
        };
        if !errors.is_empty() {
            detail.push_str(&format!(
                "; {} point(s) failed: {}",
                errors.len(),
                errors[0]
            ));
            if worst.is_some() && verdict == Verdict::Fails {
                detail.push_str(" (a failed point counts against the claim)");
            }
        }
        // dimension of the printed formula against the quantity's unit, when it has one
        if let Some(u) = self.units.get(&quantity)
            && let Ok(pu) = units::dimension(&printed, &self.unit_fn())
            && pu != *u
        {
            detail.push_str(&format!("; units: the formula is {pu}, the quantity {u}"));
        }
        let mut o = outcome(f, c, verdict, detail);
        let mut md = format!(
            "Kind `model`. Scene `{}`; `{quantity}` against `{}`{}; grid {}.",
            c.scene.clone().unwrap_or_default(),
            c.printed.as_deref().unwrap_or_default(),
            if c.bind.is_empty() {
                String::new()
            } else {
                format!(
                    " with {}",
                    c.bind
                        .iter()
                        .map(|(k, v)| format!("{k} = {v}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            },
            c.vary.join(" x ")
        );
        if axes.len() == 1 && rows.iter().filter(|r| r.is_ok()).count() > 1 {
            let a = &axes[0];
            let mut model_curve = Vec::new();
            let mut printed_curve = Vec::new();
            for (v, r) in a.values.iter().zip(&rows) {
                if let Ok((m, p)) = r {
                    model_curve.push((*v, *m));
                    printed_curve.push((*v, *p));
                }
            }
            let scale = if a.log {
                crate::report::svg::Scale::Log
            } else {
                crate::report::svg::Scale::Linear
            };
            let name = format!("{}.svg", c.id.replace('.', "_"));
            let svg = crate::report::svg::plot_curves(
                &format!("{}: {quantity} (model) and the printed formula", c.id),
                &a.field,
                &quantity,
                scale,
                crate::report::svg::Scale::Linear,
                &[
                    ("model".to_string(), model_curve.clone()),
                    ("printed".to_string(), printed_curve.clone()),
                ],
            );
            let csv_name = format!("{}.csv", c.id.replace('.', "_"));
            let mut csv = format!("{},model {quantity},printed\n", a.field);
            for ((x, m), (_, p)) in model_curve.iter().zip(&printed_curve) {
                csv.push_str(&format!("{x:e},{m:e},{p:e}\n"));
            }
            md.push_str(&format!(
                "\n\n![{}: the model's {quantity} and the printed formula against {}]({name})\n\n*Figure: claim {}, the model's {quantity} and the printed `{printed}` against {} (data: [{csv_name}]({csv_name})).*",
                c.id, a.field, c.id, a.field
            ));
            o.files.push((name, svg));
            o.files.push((csv_name, csv));
        }
        o.extra_md = Some(md);
        Ok(o)
    }

    /// The claim's inequality (`require`, or `event` for `probability`), definitions expanded.
    fn inequality(&self, c: &ClaimSpec, field: &str) -> Result<Inequality, VerifyError> {
        let text = if field == "event" {
            c.event.as_deref()
        } else {
            c.require.as_deref()
        }
        .unwrap_or_default();
        let mut ineq: Inequality = expr::parse_inequality(text)
            .map_err(|e| claim_err(self.file, c, field, format!("`{text}`: {e}")))?;
        ineq.lhs = self.expand_all(c, &ineq.lhs)?;
        ineq.rhs = self.expand_all(c, &ineq.rhs)?;
        Ok(ineq)
    }

    /// The seeded draws of `sample` and, for each, both sides of `ineq` (or why it did not run).
    #[allow(clippy::type_complexity)]
    fn sampled(
        &self,
        c: &ClaimSpec,
        ineq: &Inequality,
    ) -> Result<(Vec<Vec<(String, f64)>>, Vec<Result<(f64, f64), String>>), VerifyError> {
        use rayon::prelude::*;
        let f = self.file;
        let dists: Vec<(String, Dist)> = c
            .sample
            .iter()
            .map(|(k, v)| {
                parse_dist(v)
                    .map(|d| (k.clone(), d))
                    .map_err(|m| claim_err(f, c, &format!("sample.{k}"), m))
            })
            .collect::<Result<_, _>>()?;
        let count = c.count.unwrap_or(0);
        let mut rng = crate::rng::Rng(c.seed.unwrap_or(0));
        let half = 0.5 / (1u64 << 53) as f64;
        let draws: Vec<Vec<(String, f64)>> = (0..count)
            .map(|_| {
                dists
                    .iter()
                    .map(|(k, d)| (k.clone(), d.quantile(rng.next() + half)))
                    .collect()
            })
            .collect();
        if c.scene.is_none() {
            // formulas alone: the draws are the symbols' values
            let rows = draws
                .iter()
                .map(|pt| {
                    let value = |s: &str| pt.iter().find(|(k, _)| k == s).map(|(_, v)| *v);
                    Ok((ineq.lhs.eval(&value)?, ineq.rhs.eval(&value)?))
                })
                .collect();
            return Ok((draws, rows));
        }
        let (label, base) = self.scene_table(c)?;
        let rows = draws
            .par_iter()
            .map(|pt| run_point(c, &base, &label, pt, (&ineq.lhs, &ineq.rhs)))
            .collect();
        Ok((draws, rows))
    }

    fn probability(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let ineq = self.inequality(c, "event")?;
        let (draws, rows) = self.sampled(c, &ineq)?;
        let n = rows.iter().filter(|r| r.is_ok()).count();
        let failed = rows.len() - n;
        let k = rows
            .iter()
            .filter(|r| matches!(r, Ok((l, r)) if ineq.rel.holds(*l, *r)))
            .count();
        let conf = c.confidence.unwrap_or(0.95);
        let (lo, hi) = clopper_pearson(k, n, conf);
        let p = if n > 0 { k as f64 / n as f64 } else { f64::NAN };
        let mut detail = format!(
            "`{ineq}` in {k} of {n} samples (seed {}): p = {}, {:.0} % Clopper-Pearson interval [{}, {}]",
            c.seed.unwrap_or(0),
            g4(p),
            100.0 * conf,
            g4(lo),
            g4(hi)
        );
        let verdict = match &c.expect {
            None => Verdict::Holds,
            Some(e) => {
                let (rel, x) = parse_expectation(e).map_err(|m| claim_err(f, c, "expect", m))?;
                let meets = |v: f64| rel.holds(v, x);
                if meets(lo) && meets(hi) {
                    detail.push_str(&format!("; the whole interval is {e}"));
                    Verdict::Holds
                } else if !meets(lo) && !meets(hi) {
                    detail.push_str(&format!("; no part of the interval is {e}"));
                    Verdict::Fails
                } else {
                    // samples needed for the interval's half-width to reach |p - x| (normal
                    // approximation, z of the confidence)
                    use statrs::distribution::{ContinuousCDF, Normal};
                    let z = Normal::new(0.0, 1.0).map_or(1.96, |d| d.inverse_cdf(0.5 + conf / 2.0));
                    let gap = (p - x).abs().max(1e-6);
                    let need = (z
                        * z
                        * p.max(1.0 / n.max(1) as f64)
                        * (1.0 - p).max(1.0 / n.max(1) as f64)
                        / (gap * gap))
                        .ceil();
                    detail.push_str(&format!(
                        "; the interval straddles {e}: about {} samples (now {n}) would decide it",
                        g4(need)
                    ));
                    Verdict::NotCheckable
                }
            }
        };
        if failed > 0 {
            detail.push_str(&format!(
                "; {failed} sample(s) did not run and are left out"
            ));
        }
        let _ = draws;
        let mut o = outcome(f, c, verdict, detail);
        o.extra.insert(
            "probability".into(),
            serde_json::json!({"p": p, "lo": lo, "hi": hi, "n": n}),
        );
        o.extra_md = Some(format!(
            "Kind `probability`. Scene `{}`; sampled: {}; event: `{ineq}`{}.",
            c.scene.clone().unwrap_or_default(),
            c.sample
                .iter()
                .map(|(k, v)| format!("{k} ~ {v}"))
                .collect::<Vec<_>>()
                .join(", "),
            c.expect
                .as_ref()
                .map(|e| format!("; expected: p {e}"))
                .unwrap_or_default()
        ));
        Ok(o)
    }

    fn map(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
        let f = self.file;
        // the region of an inequality, or where the printed formula is within rtol of the model
        let ineq = match c.require {
            Some(_) => Some(self.inequality(c, "require")?),
            None => None,
        };
        let sides = match &ineq {
            Some(i) => (i.lhs.clone(), i.rhs.clone()),
            None => self.quantity_and_printed(c)?,
        };
        let rtol = c.rtol.unwrap_or(0.0);
        let (axes, points, rows) = self.grid(c, &sides)?;
        let inside = |l: f64, r: f64| match &ineq {
            Some(i) => i.rel.holds(l, r),
            None => (r - l).abs() <= rtol * l.abs(),
        };
        // cells in the order of the grid (first axis slowest): reorder so that y is slowest
        let (nx, ny) = (axes[0].values.len(), axes[1].values.len());
        let mut cells = vec![None; nx * ny];
        for (idx, r) in rows.iter().enumerate() {
            let (i, j) = (idx / ny, idx % ny);
            cells[j * nx + i] = r.as_ref().ok().map(|(l, r)| inside(*l, *r));
        }
        let ran = cells.iter().filter(|c| c.is_some()).count();
        let valid = cells.iter().filter(|c| **c == Some(true)).count();
        let share = valid as f64 / points.len() as f64;
        let what = match &ineq {
            Some(i) => format!("`{i}` holds"),
            None => format!(
                "`{}` is within {} of the model's {}",
                c.printed.as_deref().unwrap_or_default(),
                g4(rtol),
                c.quantity.clone().unwrap_or_default()
            ),
        };
        let bounds = |a: &Axis| {
            format!(
                "{} in [{}, {}]",
                a.field,
                g4(a.values[0]),
                g4(*a.values.last().unwrap_or(&f64::NAN))
            )
        };
        let mut detail = format!(
            "{what} on {valid} of {} grid points ({:.1} %) over {} x {}",
            points.len(),
            100.0 * share,
            bounds(&axes[0]),
            bounds(&axes[1])
        );
        if ran < points.len() {
            detail.push_str(&format!("; {} point(s) did not run", points.len() - ran));
        }
        let verdict = if valid == points.len() {
            Verdict::Holds
        } else {
            Verdict::Fails
        };
        let name = format!("{}.svg", c.id.replace('.', "_"));
        fn axis(a: &Axis) -> crate::report::svg::MapAxis<'_> {
            crate::report::svg::MapAxis {
                label: a.field.as_str(),
                values: a.values.as_slice(),
                log: a.log,
            }
        }
        let svg = crate::report::svg::region_map(
            &format!("{}: where {}", c.id, what.replace('`', "")),
            &axis(&axes[0]),
            &axis(&axes[1]),
            &cells,
        );
        let mut o = outcome(f, c, verdict, detail);
        o.extra
            .insert("valid_fraction".into(), serde_json::json!(share));
        o.extra_md = Some(format!(
            "Kind `map`. Scene `{}`; grid {}.\n\n![{}: the region where {} (blue), over {} and {}]({name})\n\n*Figure: claim {}, where the claim holds (blue) and fails (orange) on the grid (data: {}.csv).*",
            c.scene.clone().unwrap_or_default(),
            c.vary.join(" x "),
            c.id,
            what.replace('`', ""),
            axes[0].field,
            axes[1].field,
            c.id,
            c.id.replace('.', "_")
        ));
        o.files.push((name, svg));
        // the map's data: every grid point, inside (1), outside (0) or not run (empty)
        let csv_name = format!("{}.csv", c.id.replace('.', "_"));
        let mut csv = format!("{},{},inside\n", axes[0].field, axes[1].field);
        for (idx, pt) in points.iter().enumerate() {
            let (i, j) = (idx / ny, idx % ny);
            let cell = match cells[j * nx + i] {
                Some(true) => "1",
                Some(false) => "0",
                None => "",
            };
            csv.push_str(&format!("{:e},{:e},{cell}\n", pt[0].1, pt[1].1));
        }
        o.files.push((csv_name, csv));
        Ok(o)
    }

    fn bound(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
        let f = self.file;
        let ineq = self.inequality(c, "require")?;
        let count = c.count.unwrap_or(0);
        let (draws, rows) = self.sampled(c, &ineq)?;
        let mut violations = 0;
        let mut worst: Option<(f64, usize)> = None;
        let mut errors = Vec::new();
        for (i, r) in rows.iter().enumerate() {
            match r {
                Ok((l, rr)) => {
                    if !ineq.rel.holds(*l, *rr) {
                        violations += 1;
                    }
                    let m = ineq.margin(*l, *rr);
                    if worst.is_none_or(|(w, _)| m < w) {
                        worst = Some((m, i));
                    }
                }
                Err(e) => errors.push((i, e.clone())),
            }
        }
        let ran = count - errors.len();
        let mut detail = format!(
            "{ran} of {count} samples ran (seed {}): {violations} violate `{ineq}`",
            c.seed.unwrap_or(0)
        );
        if let Some((m, i)) = worst {
            let (l, r) = rows[i].clone().unwrap_or((f64::NAN, f64::NAN));
            detail.push_str(&format!(
                "; {} sample: {} ({} {} {}, margin {})",
                if violations > 0 { "worst" } else { "closest" },
                point_text(&draws[i]),
                g4(l),
                ineq.rel.symbol(),
                g4(r),
                g4(m)
            ));
        }
        if let Some((i, e)) = errors.first() {
            detail.push_str(&format!(
                "; {} sample(s) failed to run, first at {}: {e}",
                errors.len(),
                point_text(&draws[*i])
            ));
        }
        let verdict = if violations > 0 {
            Verdict::Fails
        } else if errors.is_empty() && ran > 0 {
            Verdict::Holds
        } else {
            Verdict::NotCheckable
        };
        let mut o = outcome(f, c, verdict, detail);
        o.extra_md = Some(format!(
            "Kind `bound`. {}; sampled: {}; required: `{ineq}`.",
            c.scene
                .as_ref()
                .map(|s| format!("Scene `{s}`"))
                .unwrap_or_else(|| "Formulas alone (no scene)".into()),
            c.sample
                .iter()
                .map(|(k, v)| format!("{k} ~ {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
        Ok(o)
    }
}

/// A claim on a probability: `<= 0.15`, `< 0.15`, `>= 0.9`, `> 0.9`.
fn parse_expectation(text: &str) -> Result<(expr::Rel, f64), String> {
    let t = text.trim();
    let help = "expected <= p, < p, >= p or > p with 0 <= p <= 1, e.g. \"<= 0.15\"";
    let (rel, rest) = if let Some(r) = t.strip_prefix("<=") {
        (expr::Rel::Le, r)
    } else if let Some(r) = t.strip_prefix(">=") {
        (expr::Rel::Ge, r)
    } else if let Some(r) = t.strip_prefix('<') {
        (expr::Rel::Lt, r)
    } else if let Some(r) = t.strip_prefix('>') {
        (expr::Rel::Gt, r)
    } else {
        return Err(format!("`{text}`: {help}"));
    };
    let p: f64 = rest
        .trim()
        .parse()
        .map_err(|_| format!("`{text}`: {help}"))?;
    if !(0.0..=1.0).contains(&p) {
        return Err(format!("`{text}`: {help}"));
    }
    Ok((rel, p))
}

/// The Clopper-Pearson interval of a binomial proportion: `k` successes in `n` trials at
/// `confidence` (the exact interval from the Beta quantiles, statrs):
/// $[B^{-1}(\alpha/2; k, n-k+1),\ B^{-1}(1-\alpha/2; k+1, n-k)]$, with 0 and 1 at the ends.
pub fn clopper_pearson(k: usize, n: usize, confidence: f64) -> (f64, f64) {
    use statrs::distribution::{Beta, ContinuousCDF};
    let alpha = 1.0 - confidence;
    let (kf, nf) = (k as f64, n as f64);
    let lo = if k == 0 {
        0.0
    } else {
        Beta::new(kf, nf - kf + 1.0).map_or(f64::NAN, |b| b.inverse_cdf(alpha / 2.0))
    };
    let hi = if k >= n {
        1.0
    } else {
        Beta::new(kf + 1.0, nf - kf).map_or(f64::NAN, |b| b.inverse_cdf(1.0 - alpha / 2.0))
    };
    (lo, hi)
}

/// The terms of a top-level sum with their signs (`a - (b - c)` gives `+a`, `-b`, `+c`).
fn signed_terms(e: &Expr, plus: bool) -> Vec<(bool, Expr)> {
    match e {
        Expr::Bin(expr::Op::Add, a, b) => {
            let mut v = signed_terms(a, plus);
            v.extend(signed_terms(b, plus));
            v
        }
        Expr::Bin(expr::Op::Sub, a, b) => {
            let mut v = signed_terms(a, plus);
            v.extend(signed_terms(b, !plus));
            v
        }
        Expr::Neg(a) => signed_terms(a, !plus),
        other => vec![(plus, other.clone())],
    }
}

/// The terms of a top-level sum (`a + b - c` gives `a`, `b`, `c`).
fn top_terms(e: &Expr) -> Vec<Expr> {
    match e {
        Expr::Bin(expr::Op::Add | expr::Op::Sub, a, b) => {
            let mut v = top_terms(a);
            v.extend(top_terms(b));
            v
        }
        other => vec![other.clone()],
    }
}

fn point_text(pt: &[(String, f64)]) -> String {
    pt.iter()
        .map(|(k, v)| format!("{k} = {}", g4(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every dotted path of `v` that holds a number, for error messages.
fn numeric_paths(v: &Value) -> Vec<String> {
    fn go(prefix: &str, v: &Value, out: &mut Vec<String>) {
        match v {
            Value::Number(_) | Value::Bool(_) => out.push(prefix.to_string()),
            Value::Object(m) => {
                for (k, x) in m {
                    let p = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    go(&p, x, out);
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    go("", v, &mut out);
    out
}
