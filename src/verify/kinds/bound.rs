//! Kind `bound`: an inequality (`require`) over outcome quantities and bound symbols on
//! `count` seeded samples of the scene fields (or, without a scene, of the symbols themselves);
//! `holds` when no sample violates it.

use super::scene::{self, Samples, Scene, point_text};
use super::{Checked, Kind, Session, Where, claim_err, extreme, g4};
use crate::algebra::expr::{self, Expr, Inequality, Op, Rel};
use crate::algebra::units;
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use num_traits::Zero;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The keys of a `bound` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoundSpec {
    /// The scene, relative to the claims file; without one, a bound on formulas alone whose
    /// samples are the symbols' values.
    #[serde(default)]
    scene: Option<String>,
    /// Scene fields set before sampling.
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    /// Formula symbol -> scene field.
    #[serde(default)]
    bind: BTreeMap<String, String>,
    /// Named runs of the scene compared in one formula (`a.quantity`, `b.quantity`).
    #[serde(default)]
    runs: scene::Runs,
    /// Scene field (or symbol) -> distribution.
    #[serde(default)]
    sample: BTreeMap<String, String>,
    /// Number of samples.
    count: usize,
    /// Seed of the generator.
    seed: u64,
    /// The inequality every sample must satisfy.
    require: String,
    /// A slack for the integration error, not the paper's: the side `require` allows to be the
    /// larger gains it (`lhs <= rhs + allowance`, `lhs >= rhs - allowance`). Kept apart from
    /// `require`, so that the power measurement misprints the paper's inequality only.
    #[serde(default)]
    allowance: Option<String>,
    /// The bound is attained: the extreme found must come within [`SHARP`] (relative) of it.
    #[serde(default)]
    sharp: bool,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// A checked `bound` claim.
pub struct Bound {
    scene: Option<Scene>,
    samples: Samples,
    require: Inequality,
    /// `require` as the claim states it (in backquotes), its allowance apart (for the detail).
    stated: String,
    sharp: bool,
}

/// How close (relative margin) the extreme of a `sharp` bound must come to it.
pub const SHARP: f64 = 1e-3;

impl Bound {
    /// The search for the extreme from the [`extreme::STARTS`] samples with the least margin.
    fn search(&self, rows: &[Result<(f64, f64), String>]) -> Option<extreme::Extreme> {
        let units = self.samples.unit_draws();
        let mut order: Vec<(f64, usize)> = rows
            .iter()
            .enumerate()
            .filter_map(|(i, r)| {
                r.as_ref()
                    .ok()
                    .map(|(l, r)| (self.require.margin(*l, *r), i))
            })
            .filter(|(m, _)| m.is_finite())
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let starts: Vec<Vec<f64>> = order
            .iter()
            .take(extreme::STARTS)
            .map(|(_, i)| units[*i].clone())
            .collect();
        extreme::search(&self.samples, self.scene.as_ref(), &self.require, &starts)
    }
}

impl Kind for Bound {
    const NAME: &'static str = "bound";
    const PRINTED: &'static [&'static str] = &["require"];
    type Spec = BoundSpec;

    fn validate(cx: &Checked, c: &Head, s: BoundSpec) -> Result<Self, VerifyError> {
        let samples = Samples::read(cx, c, s.sample, s.count, s.seed)?;
        let mut require = scene::inequality(cx, c, &s.where_, "require", &s.require)?;
        let mut stated = format!("`{require}`");
        if let Some(text) = &s.allowance {
            require = with_allowance(cx, c, &s.where_, require, text)?;
            stated = format!("{stated} (allowance `{text}`)");
        }
        let scene = match &s.scene {
            Some(name) => {
                let scene = Scene::open(cx, c, name, &s.set, s.bind, s.runs)?;
                scene.probe(
                    cx,
                    c,
                    &samples.probe(),
                    &[("require", &require.lhs), ("require", &require.rhs)],
                )?;
                Some(scene)
            }
            None => {
                if !s.runs.is_empty() {
                    return Err(claim_err(
                        cx.file,
                        c,
                        "runs",
                        "runs compare runs of a scene; this claim has no `scene`".into(),
                    ));
                }
                formulas_alone(cx, c, &samples, &require)?;
                None
            }
        };
        Ok(Bound {
            scene,
            samples,
            require,
            stated,
            sharp: s.sharp,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let ineq = &self.require;
        let count = self.samples.count;
        let (draws, rows) = self.samples.run(self.scene.as_ref(), ineq);
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
            "{ran} of {count} samples ran (seed {}): {violations} violate {}",
            self.samples.seed, self.stated
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
        // the adversarial search, from the samples closest to the bound
        let found = if violations == 0 && worst.is_some() {
            self.search(&rows)
        } else {
            None
        };
        let mut least = worst.map(|(m, _)| m);
        let mut ratio =
            worst.and_then(|(_, i)| rows[i].as_ref().ok().and_then(|s| extreme::ratio(ineq, *s)));
        let mut searched_violation = false;
        if let Some(x) = &found {
            let holds = ineq.rel.holds(x.sides.0, x.sides.1);
            searched_violation = !holds;
            detail.push_str(&format!(
                "; a search for the extreme (Nelder-Mead from the {} closest samples, {} evaluations) {} at {} ({} {} {}, margin {})",
                extreme::STARTS,
                x.evaluations,
                if holds { "reached" } else { "found a violation" },
                point_text(&x.point),
                g4(x.sides.0),
                ineq.rel.symbol(),
                g4(x.sides.1),
                g4(x.margin)
            ));
            if least.is_none_or(|m| x.margin < m) {
                least = Some(x.margin);
                ratio = extreme::ratio(ineq, x.sides).or(ratio);
            }
        }
        if let Some(q) = ratio {
            detail.push_str(&format!("; largest ratio to the bound {}", g4(q)));
        }
        let sharp_missed = self.sharp && least.is_none_or(|m| m > SHARP);
        if self.sharp {
            detail.push_str(&match least {
                Some(m) if m <= SHARP => format!(
                    "; sharp: the bound is attained within {} (relative)",
                    g4(SHARP)
                ),
                Some(m) => format!(
                    "; NOT sharp: the extreme found stays {} (relative) from the bound, more than {}",
                    g4(m),
                    g4(SHARP)
                ),
                None => "; sharp: nothing ran to look for the extreme".into(),
            });
        }
        let verdict = if violations > 0 || searched_violation || sharp_missed {
            Verdict::Fails
        } else if errors.is_empty() && ran > 0 {
            Verdict::Holds
        } else {
            Verdict::NotCheckable
        };
        let mut o = outcome(cx.file, c, verdict, detail);
        if let Some(m) = least {
            o.extra.insert("least_margin".into(), serde_json::json!(m));
        }
        if let Some(q) = ratio {
            o.extra.insert("largest_ratio".into(), serde_json::json!(q));
        }
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `bound`. {}; sampled: {}; required: {}.",
            self.scene
                .as_ref()
                .map(|s| format!("Scene `{}`", s.name))
                .unwrap_or_else(|| "Formulas alone (no scene)".into()),
            self.samples.described(),
            self.stated
        )
    }
}

/// `require` with its `allowance` on the side that may be the larger; the allowance has the
/// sides' unit where the file gives their units.
fn with_allowance(
    cx: &Checked,
    c: &Head,
    w: &Where,
    ineq: Inequality,
    text: &str,
) -> Result<Inequality, VerifyError> {
    let slack = expr::parse(text)
        .map_err(|e| claim_err(cx.file, c, "allowance", format!("`{text}`: {e}")))?;
    let slack = cx.expand_all(c, w, &slack)?;
    // a side against zero (the literal 0) has the other side's unit
    let side = if is_zero(&ineq.rhs) {
        &ineq.lhs
    } else {
        &ineq.rhs
    };
    let unit = cx.unit_fn();
    if let (Ok(side), Ok(own)) = (
        units::dimension(side, &unit),
        units::dimension(&slack, &unit),
    ) && side != own
    {
        return Err(claim_err(
            cx.file,
            c,
            "allowance",
            format!("`{text}` is in {own}, but the sides of `require` are in {side}"),
        ));
    }
    let rhs = match ineq.rel {
        Rel::Lt | Rel::Le => Expr::Bin(Op::Add, Box::new(ineq.rhs), Box::new(slack)),
        Rel::Gt | Rel::Ge => Expr::Bin(Op::Sub, Box::new(ineq.rhs), Box::new(slack)),
    };
    Ok(Inequality { rhs, ..ineq })
}

/// Whether `e` is the literal 0 (a side against zero has no unit of its own).
fn is_zero(e: &Expr) -> bool {
    matches!(e, Expr::Num(q) if q.is_zero())
}

/// A bound without a scene: every sampled symbol has a unit and every symbol of the
/// inequality is sampled.
fn formulas_alone(
    cx: &Checked,
    c: &Head,
    samples: &Samples,
    ineq: &Inequality,
) -> Result<(), VerifyError> {
    for sym in samples.text.keys() {
        if !cx.units.contains_key(sym) {
            return Err(claim_err(
                cx.file,
                c,
                &format!("sample.{sym}"),
                format!("`{sym}`: give its unit in [symbols]"),
            ));
        }
    }
    for e in [&ineq.lhs, &ineq.rhs] {
        cx.units_of(c, "require", e, &[])?;
        for s in e.free_symbols() {
            if !samples.text.contains_key(&s) {
                return Err(claim_err(
                    cx.file,
                    c,
                    "require",
                    format!(
                        "`{s}` is not sampled: without a scene every symbol is drawn (sample.{s} = \"uniform(a, b)\")"
                    ),
                ));
            }
        }
    }
    Ok(())
}
