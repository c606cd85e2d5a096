//! The kinds that run scenes: `model` (a grid), `bound` and `probability` (seeded samples) and
//! `map` (the region of a grid where a formula holds).

use super::*;

impl Checked<'_> {
    /// The grid of `vary` (first axis slowest) and, at each point, the two sides compared: the
    /// model's quantity and the printed formula, or both sides of an inequality.
    #[allow(clippy::type_complexity)]
    pub(super) fn grid(
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
    pub(super) fn quantity_and_printed(&self, c: &ClaimSpec) -> Result<(Expr, Expr), VerifyError> {
        let quantity = c.quantity.clone().unwrap_or_default();
        let printed = self.formula(c, "printed", c.printed.as_deref().unwrap_or_default())?;
        Ok((Expr::Sym(quantity), printed))
    }

    pub(super) fn model(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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
    pub(super) fn inequality(&self, c: &ClaimSpec, field: &str) -> Result<Inequality, VerifyError> {
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
    pub(super) fn sampled(
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

    pub(super) fn probability(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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

    pub(super) fn map(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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

    pub(super) fn bound(&self, c: &ClaimSpec) -> Result<Outcome, VerifyError> {
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
pub(super) fn parse_expectation(text: &str) -> Result<(expr::Rel, f64), String> {
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

pub(super) fn point_text(pt: &[(String, f64)]) -> String {
    pt.iter()
        .map(|(k, v)| format!("{k} = {}", g4(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every dotted path of `v` that holds a number, for error messages.
pub(super) fn numeric_paths(v: &Value) -> Vec<String> {
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
