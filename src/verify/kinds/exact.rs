//! The exact kinds: `definition`, `dimension` and `identity` (exact algebra, with the numeric
//! comparison for sides that are not rational).

use super::*;

impl Checked<'_> {
    /// A definition: the unit of `defines` against the printed formula's, then each identity of
    /// `agrees` with the definition substituted (exact where rational).
    pub(super) fn definition(
        &self,
        c: &ClaimSpec,
        der: &mut Derivations,
    ) -> Result<Outcome, VerifyError> {
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

    pub(super) fn dimension(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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
    pub(super) fn exact_difference(
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

    pub(super) fn identity(
        &self,
        c: &ClaimSpec,
        der: &mut Derivations,
    ) -> Result<Outcome, VerifyError> {
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
    pub(super) fn expo_identity(
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
    pub(super) fn numeric_identity(
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

/// The terms of a top-level sum (`a + b - c` gives `a`, `b`, `c`).
pub(super) fn top_terms(e: &Expr) -> Vec<Expr> {
    match e {
        Expr::Bin(expr::Op::Add | expr::Op::Sub, a, b) => {
            let mut v = top_terms(a);
            v.extend(top_terms(b));
            v
        }
        other => vec![other.clone()],
    }
}
