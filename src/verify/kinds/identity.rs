//! Kind `identity`: `printed` against `derived` (a formula, or `@name[k=v,...]` for a derivation
//! of [`crate::algebra`]), exact where both sides are rational (or exponential polynomials in
//! t), in floating point at seeded points otherwise; `corrected` gives the verdict
//! `holds-with-correction` when the printed form fails and the correction holds.

use super::derivations::{DerivationRef, split_refs};
use super::{Checked, Kind, Session, Where, claim_err, g4, parse_formula};
use crate::algebra::expr::{self, Expr};
use crate::algebra::poly::{Q, Sym};
use crate::algebra::ratfunc::RatFunc;
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The keys of an `identity` claim.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct IdentitySpec {
    /// The formula as printed.
    pub(super) printed: String,
    /// The derived side: a formula or `@name[k=v,...]`.
    pub(super) derived: String,
    /// A corrected formula.
    #[serde(default)]
    pub(super) corrected: Option<String>,
    /// Plate modes `(m, n)` at which the sides are compared.
    #[serde(default)]
    pub(super) modes: Vec<[u32; 2]>,
    /// Exponential polynomials: the part compared (`"t^2"`, `"exp(-alpha*t)"`).
    #[serde(default)]
    pub(super) part: Option<String>,
    /// Exponential polynomials: compare the first `taylor` Taylor coefficients at t = 0.
    #[serde(default)]
    pub(super) taylor: Option<u32>,
    /// The time symbol of an exponential polynomial (default `t`).
    #[serde(default)]
    pub(super) variable: Option<String>,
    /// Compared in floating point: an absolute tolerance besides the relative 1e-12.
    #[serde(default)]
    pub(super) atol: Option<f64>,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    pub(super) where_: Where,
    /// A text model (`model = "ode"`, relative to the claims file) whose solution's Taylor
    /// series `@taylor.STATE[order=N]` reaches.
    #[serde(default)]
    pub(super) scene: Option<String>,
}

/// A formula with its `@` references replaced by placeholders, expanded.
struct Side {
    text: String,
    expr: Expr,
    refs: Vec<DerivationRef>,
}

/// A checked `identity` claim.
pub struct Identity {
    printed: Side,
    derived: Side,
    corrected: Option<Side>,
    /// The parameter sets (one per mode; one empty set without modes).
    modes: Vec<Vec<(String, Q)>>,
    part: Option<(String, Expr)>,
    taylor: Option<u32>,
    variable: String,
    atol: Option<f64>,
    /// The Taylor polynomials of a text model's solution, by placeholder (`@taylor.x`).
    solved: BTreeMap<String, RatFunc>,
}

impl Kind for Identity {
    const NAME: &'static str = "identity";
    const PRINTED: &'static [&'static str] = &["printed"];
    type Spec = IdentitySpec;

    fn validate(cx: &Checked, c: &Head, s: IdentitySpec) -> Result<Self, VerifyError> {
        let side = |field: &str, text: &str| -> Result<Side, VerifyError> {
            let (plain, refs) = split_refs(text).map_err(|m| claim_err(cx.file, c, field, m))?;
            let raw = parse_formula(cx.file, c, field, &plain)?;
            cx.units_of(c, field, &raw, &["m", "n"])?;
            Ok(Side {
                text: text.to_string(),
                expr: cx.expand_all(c, &s.where_, &raw)?,
                refs,
            })
        };
        let printed = side("printed", &s.printed)?;
        let derived = side("derived", &s.derived)?;
        let corrected = s
            .corrected
            .as_deref()
            .map(|k| side("corrected", k))
            .transpose()?;
        let part = match &s.part {
            Some(sel) => Some((sel.clone(), parse_formula(cx.file, c, "part", sel)?)),
            None => None,
        };
        let modes = if s.modes.is_empty() {
            vec![vec![]]
        } else {
            let q = |v: u32| Q::from_integer(v.into());
            s.modes
                .iter()
                .map(|[m, n]| vec![("m".to_string(), q(*m)), ("n".to_string(), q(*n))])
                .collect()
        };
        let solved = taylor_refs(cx, c, s.scene.as_deref(), &derived.refs)?;
        Ok(Identity {
            solved,
            printed,
            derived,
            corrected,
            modes,
            part,
            taylor: s.taylor,
            variable: s.variable.unwrap_or_else(|| "t".into()),
            atol: s.atol,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, run: &mut Session) -> Result<Outcome, VerifyError> {
        let der = &mut run.derivations;
        if let Some(o) = self.expo_identity(cx, c, der)? {
            return Ok(o);
        }
        let mut lines = Vec::new();
        let mut all_printed = true;
        let mut all_corrected = true;
        for params in &self.modes {
            let at = if params.is_empty() {
                String::new()
            } else {
                let vals: Vec<String> = params.iter().map(|(_, v)| v.to_string()).collect();
                format!("({}): ", vals.join(","))
            };
            match self.exact_difference(cx, c, &self.printed.expr, params, der)? {
                Some((diff, d, _)) if diff.is_zero() => {
                    lines.push(format!("{at}printed = derived = {d}"))
                }
                Some((diff, d, p)) => {
                    all_printed = false;
                    let mut line = format!("{at}derived {d}; derived - printed = {diff}");
                    // its size in the quantity's own terms: a share of the derived value
                    if let Some(share) = share_of(&diff, &d) {
                        line.push_str(&format!(
                            " (up to {} % of the derived value at 8 seeded points, every symbol in [0.5, 2])",
                            g4(100.0 * share)
                        ));
                    }
                    // a ratio says more than a difference when it is shorter (a factor 2), and
                    // a constant one is a coefficient misprint's signature
                    if let Some(ratio) = d.div(&p).filter(|_| !d.is_zero()) {
                        if let Some(k) = ratio.as_constant() {
                            line.push_str(&format!(
                                "; derived/printed = {k}: {}",
                                factor_text(&k.to_string())
                            ));
                        } else if ratio.to_text().len() < diff.to_text().len() {
                            line.push_str(&format!("; derived/printed = {ratio}"));
                        }
                    }
                    match &self.corrected {
                        Some(k) => match self.exact_difference(cx, c, &k.expr, params, der)? {
                            Some((kd, ..)) if kd.is_zero() => {
                                line.push_str("; the corrected form holds exactly")
                            }
                            Some((kd, ..)) => {
                                all_corrected = false;
                                line.push_str(&format!("; the corrected form differs by {kd}"));
                            }
                            None => all_corrected = false,
                        },
                        None => all_corrected = false,
                    }
                    lines.push(line);
                }
                None => {
                    let (ok, mut line) = self.numeric(cx, c, &self.printed.expr, params)?;
                    all_printed &= ok;
                    match &self.corrected {
                        Some(k) if !ok => {
                            let (kok, kline) = self.numeric(cx, c, &k.expr, params)?;
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
        } else if self.corrected.is_some() && all_corrected {
            Verdict::HoldsWithCorrection
        } else {
            Verdict::Fails
        };
        Ok(outcome(cx.file, c, verdict, lines.join("; ")))
    }

    fn report(&self, _: &Head) -> String {
        if self.is_expo() {
            return format!(
                "Kind `identity` (exponential polynomials in {}). Printed: `{}`; derived: `{}`{}.",
                self.variable,
                self.printed.expr,
                self.derived.text,
                self.part
                    .as_ref()
                    .map(|(p, _)| format!("; part `{p}`"))
                    .unwrap_or_default()
            );
        }
        let mut md = format!(
            "Kind `identity`. Printed: `{}`; derived: `{}`.",
            self.printed.expr, self.derived.text
        );
        if let Some(k) = &self.corrected {
            md.push_str(&format!(" Corrected: `{}`.", k.text));
        }
        md
    }
}

impl Identity {
    /// An identity of `printed` and `derived` (and `modes`, `where`) alone, as a definition's
    /// uses are checked ([`super::definition`]).
    pub(super) fn of(cx: &Checked, c: &Head, s: IdentitySpec) -> Result<Self, VerifyError> {
        <Self as Kind>::validate(cx, c, s)
    }

    /// Whether the derived side is an exponential polynomial in t (a `@series.*` derivation
    /// first, or a Taylor comparison).
    fn is_expo(&self) -> bool {
        self.taylor.is_some()
            || self
                .derived
                .refs
                .first()
                .is_some_and(super::derivations::is_expo)
    }

    /// The derived side (with derivations substituted) minus `printed`, exact; `None` when one
    /// side is not rational.
    fn exact_difference(
        &self,
        cx: &Checked,
        c: &Head,
        printed: &Expr,
        params: &[(String, Q)],
        der: &mut super::Derivations,
    ) -> Result<Option<(RatFunc, RatFunc, RatFunc)>, VerifyError> {
        let refs = &self.derived.refs;
        let subst = |e: &Expr| {
            e.substitute(&|s: &str| {
                params
                    .iter()
                    .find(|(k, _)| k == s)
                    .map(|(_, v)| Expr::Num(v.clone()))
            })
        };
        let (p, d) = (subst(printed), subst(&self.derived.expr));
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
        for r in refs {
            let v = match self.solved.get(&r.placeholder) {
                Some(v) => v.clone(),
                None => der
                    .get(r, params)
                    .map_err(|m| claim_err(cx.file, c, "derived", m))?,
            };
            d = d.subst(Sym::new(&r.placeholder), &v).ok_or_else(|| {
                claim_err(
                    cx.file,
                    c,
                    "derived",
                    format!("`@{}` makes a denominator zero", r.name),
                )
            })?;
        }
        Ok(Some((&d - &p, d, p)))
    }

    /// A non-rational identity (sqrt, exp of a non-linear argument, rational powers) compared
    /// in `f64` at seeded random points, each symbol in [0.5, 2]: holds when every relative
    /// difference is below 1e-12, plus twice the largest estimated relative error of a numeric
    /// `int` ([`crate::algebra::expr::calculus::integral_with_error`]), which the detail states.
    fn numeric(
        &self,
        cx: &Checked,
        c: &Head,
        printed: &Expr,
        params: &[(String, Q)],
    ) -> Result<(bool, String), VerifyError> {
        if !self.derived.refs.is_empty() {
            return Err(claim_err(
                cx.file,
                c,
                "derived",
                "a derivation can be compared only with a rational printed form".into(),
            ));
        }
        let d = &self.derived.expr;
        let mut syms = printed.symbols();
        syms.extend(d.symbols());
        syms.sort();
        syms.dedup();
        let mut rng = crate::rng::Rng(0x1D_E27);
        let (mut worst, mut worst_abs): (f64, f64) = (0.0, 0.0);
        let atol = self.atol.unwrap_or(0.0);
        let mut undefined = 0;
        // derived/printed at each point: one constant is a coefficient misprint's signature
        let mut ratios = Vec::new();
        // the quadratures of `int` evaluated below, and their error estimates
        let _ = crate::algebra::expr::calculus::quadrature_log();
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
            let a = printed
                .eval(&get)
                .map_err(|m| claim_err(cx.file, c, "printed", m))?;
            let b = d
                .eval(&get)
                .map_err(|m| claim_err(cx.file, c, "derived", m))?;
            // the difference beyond the absolute tolerance, relative to the larger side; a side
            // that is not a finite number there (outside a function's domain) is no agreement
            // (`f64::max` would drop a NaN)
            if !(a.is_finite() && b.is_finite()) {
                undefined += 1;
                worst = f64::INFINITY;
                worst_abs = f64::INFINITY;
                continue;
            }
            ratios.push(b / a);
            let excess = ((a - b).abs() - atol).max(0.0);
            let rel = excess / a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
            worst = worst.max(rel);
            worst_abs = worst_abs.max((a - b).abs());
        }
        // a numeric integral widens the tolerance by twice its estimated error
        let quad = crate::algebra::expr::calculus::quadrature_log();
        let tol = 1e-12 + 2.0 * quad.worst_rel;
        let mut text = match self.atol {
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
        };
        if undefined > 0 {
            text.push_str(&format!(
                "; at {undefined} of the 8 points a side is not a finite number (outside a function's domain)"
            ));
        }
        if worst > tol
            && let Some(k) = constant_factor(&ratios, tol)
        {
            text.push_str(&format!(
                "; derived/printed = {} at every point: {}",
                g4(k),
                factor_text(&g4(k))
            ));
        }
        if quad.count > 0 {
            text.push_str(&format!(
                "; {} integral(s) by tanh-sinh quadrature, largest estimated relative error {}, so the tolerance is {}",
                quad.count,
                g4(quad.worst_rel),
                g4(tol)
            ));
        }
        Ok((worst <= tol, text))
    }
}

/// The Taylor polynomials `@taylor.STATE[order=N]` of `derived`, from the text model `scene`
/// (exact, [`crate::models::ode::OdeScene::taylor`]), by placeholder.
/// The largest share |diff / d| at 8 seeded points (every symbol drawn in [0.5, 2]), or `None`
/// where either is not a finite number or the derived value is 0 there.
fn share_of(diff: &RatFunc, d: &RatFunc) -> Option<f64> {
    let de = expr::parse(&diff.to_text()).ok()?;
    let dd = expr::parse(&d.to_text()).ok()?;
    let mut syms = de.symbols();
    syms.extend(dd.symbols());
    syms.sort();
    syms.dedup();
    let mut rng = crate::rng::Rng(0x5_4A2E);
    let mut worst: f64 = 0.0;
    for _ in 0..8 {
        let vals: BTreeMap<String, f64> = syms
            .iter()
            .map(|s| (s.clone(), rng.range(0.5, 2.0)))
            .collect();
        let get = |s: &str| vals.get(s).copied();
        let (x, y) = (de.eval(&get).ok()?, dd.eval(&get).ok()?);
        if !(x.is_finite() && y.is_finite()) || y == 0.0 {
            return None;
        }
        worst = worst.max((x / y).abs());
    }
    Some(worst)
}

fn taylor_refs(
    cx: &Checked,
    c: &Head,
    scene: Option<&str>,
    refs: &[DerivationRef],
) -> Result<BTreeMap<String, RatFunc>, VerifyError> {
    use crate::models::Model;
    let wanted: Vec<&DerivationRef> = refs
        .iter()
        .filter(|r| r.name.starts_with("taylor."))
        .collect();
    let Some(name) = scene else {
        if let Some(r) = wanted.first() {
            return Err(claim_err(
                cx.file,
                c,
                "derived",
                format!(
                    "`@{}` is the Taylor series of a text model's solution: give the model as `scene`",
                    r.name
                ),
            ));
        }
        return Ok(BTreeMap::new());
    };
    let err = |m: String| claim_err(cx.file, c, "scene", m);
    if wanted.is_empty() {
        return Err(err(
            "an identity's `scene` serves `@taylor.STATE[order=N]` in `derived`, and there is none"
                .into(),
        ));
    }
    let path = cx.dir.join(name);
    let label = path.display().to_string();
    let table = crate::scene::read_table(&path).map_err(|e| err(format!("`{name}`: {e}")))?;
    if table.get("model").and_then(|m| m.as_str()) != Some("ode") {
        return Err(err(format!(
            "`{name}` is not a text model (model = \"ode\"): only a text model's equations are read"
        )));
    }
    let ode =
        crate::models::ode::OdeScene::from_table(&table, &label).map_err(|e| err(e.to_string()))?;
    let mut out = BTreeMap::new();
    for r in wanted {
        let state = r.name.trim_start_matches("taylor.");
        let order = match r.params.as_slice() {
            [(k, v)] if k == "order" && v.is_integer() && *v >= Q::from_integer(0.into()) => {
                use num_traits::ToPrimitive;
                v.to_integer().to_u32().unwrap_or(u32::MAX)
            }
            _ => {
                return Err(claim_err(
                    cx.file,
                    c,
                    "derived",
                    format!("`@{}` takes one parameter, [order=N] with N >= 0", r.name),
                ));
            }
        };
        let poly = ode.taylor(state, order).map_err(|m| {
            claim_err(
                cx.file,
                c,
                "derived",
                format!("`@{}[order={order}]`: {m}", r.name),
            )
        })?;
        out.insert(r.placeholder.clone(), poly);
    }
    Ok(out)
}

/// What a constant ratio between two sides says: the opposite sign, or a factor.
pub(super) fn factor_text(k: &str) -> String {
    if k == "-1" || k == "-1.000" {
        "the opposite sign (a sign misprint?)".into()
    } else {
        format!("a constant factor of {k} (a coefficient misprint?)")
    }
}

/// The common value of `ratios` when they agree to `tol` (relative, at least 1e-12) and
/// differ from 1 by more: a constant factor between two sides; `None` otherwise.
pub(super) fn constant_factor(ratios: &[f64], tol: f64) -> Option<f64> {
    let tol = tol.max(1e-12);
    let first = *ratios.first()?;
    let same = ratios
        .iter()
        .all(|r| r.is_finite() && (r - first).abs() <= tol * first.abs());
    (same && ratios.len() > 1 && (first - 1.0).abs() > tol && first.abs() > 0.0).then_some(first)
}

/// The terms of a top-level sum with their signs (`a - (b - c)` gives `+a`, `-b`, `+c`).
pub(super) fn signed_terms(e: &Expr, plus: bool) -> Vec<(bool, Expr)> {
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

impl Identity {
    /// An identity whose derived side is an exponential polynomial in t (`@series.a1`): the
    /// printed side is read as one too, and compared whole or, with `part` (`"t^2"`,
    /// `"exp(-alpha*t)"`), that part's coefficient alone, or by its first `taylor` Taylor
    /// coefficients. `None` when `derived` is not such a derivation.
    fn expo_identity(
        &self,
        cx: &Checked,
        c: &Head,
        der: &super::Derivations,
    ) -> Result<Option<Outcome>, VerifyError> {
        use crate::algebra::expo::Expo;
        if !self.is_expo() {
            return Ok(None);
        }
        let (t, refs) = (&self.variable, &self.derived.refs);
        let whole = &self.derived.expr;
        let not_expo = |field: &str| {
            claim_err(
                cx.file,
                c,
                field,
                format!("not an exponential polynomial in {t} (sums of c {t}^k exp(-b {t}))"),
            )
        };
        let d = match refs.first().and_then(|r| der.expo(r)) {
            None => whole.to_expo(t).ok_or_else(|| not_expo("derived"))?,
            Some(d_ref) => {
                // the derivation enters as one added term (`v0*t + @series.a1`); the rest is a
                // formula
                let placeholder = Expr::sym(&refs[0].placeholder);
                let added: Vec<bool> = signed_terms(whole, true)
                    .into_iter()
                    .filter(|(_, e)| *e == placeholder)
                    .map(|(plus, _)| plus)
                    .collect();
                if refs.len() != 1 || added != [true] {
                    return Err(claim_err(
                        cx.file,
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
                    .to_expo(t)
                    .ok_or_else(|| not_expo("derived"))?;
                &rest + &d_ref
            }
        };
        let p = self
            .printed
            .expr
            .to_expo(t)
            .ok_or_else(|| not_expo("printed"))?;
        let (verdict, detail) = match (&self.part, self.taylor) {
            (_, Some(n)) => {
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
                (super::super::holds(all), lines.join("; "))
            }
            (Some((sel, sel_expr)), None) => {
                let key = sel_expr
                    .to_expo(t)
                    .filter(|e| e.len() == 1)
                    .and_then(|e| e.parts().next().map(|(k, _)| k.clone()))
                    .ok_or_else(|| {
                        claim_err(
                            cx.file,
                            c,
                            "part",
                            format!("`{sel}`: expected one part such as {t}^2 or exp(-alpha*{t})"),
                        )
                    })?;
                let coeff = |e: &Expo| {
                    e.parts()
                        .find(|(k, _)| **k == key)
                        .map(|(_, v)| v.clone())
                        .unwrap_or_else(RatFunc::zero)
                };
                let (dp, pp) = (coeff(&d), coeff(&p));
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
            (None, None) => whole_difference(&d, &p, t),
        };
        Ok(Some(outcome(cx.file, c, verdict, detail)))
    }
}

/// Two exponential polynomials compared whole.
fn whole_difference(
    d: &crate::algebra::expo::Expo,
    p: &crate::algebra::expo::Expo,
    t: &str,
) -> (Verdict, String) {
    let diff = d - p;
    if diff.is_zero() {
        return (
            Verdict::Holds,
            format!("printed = derived = {}", d.to_text()),
        );
    }
    let mut keys: Vec<_> = d.parts().chain(p.parts()).map(|(k, _)| k.clone()).collect();
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
