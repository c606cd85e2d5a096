//! Kind `bound`: an inequality (`require`) over outcome quantities and bound symbols on
//! `count` seeded samples of the scene fields (or, without a scene, of the symbols themselves);
//! `holds` when no sample violates it.

use super::scene::{self, Samples, Scene, point_text};
use super::{Checked, Kind, Session, Where, claim_err, g4};
use crate::algebra::expr::Inequality;
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
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
    /// Scene field (or symbol) -> distribution.
    #[serde(default)]
    sample: BTreeMap<String, String>,
    /// Number of samples.
    count: usize,
    /// Seed of the generator.
    seed: u64,
    /// The inequality every sample must satisfy.
    require: String,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// A checked `bound` claim.
pub struct Bound {
    scene: Option<Scene>,
    samples: Samples,
    require: Inequality,
}

impl Kind for Bound {
    const NAME: &'static str = "bound";
    const PRINTED: &'static [&'static str] = &["require"];
    type Spec = BoundSpec;

    fn validate(cx: &Checked, c: &Head, s: BoundSpec) -> Result<Self, VerifyError> {
        let samples = Samples::read(cx, c, s.sample, s.count, s.seed)?;
        let require = scene::inequality(cx, c, &s.where_, "require", &s.require)?;
        let scene = match &s.scene {
            Some(name) => {
                let scene = Scene::open(cx, c, name, &s.set, s.bind)?;
                scene.probe(
                    cx,
                    c,
                    &samples.probe(),
                    &[("require", &require.lhs), ("require", &require.rhs)],
                )?;
                Some(scene)
            }
            None => {
                formulas_alone(cx, c, &samples, &require)?;
                None
            }
        };
        Ok(Bound {
            scene,
            samples,
            require,
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
            "{ran} of {count} samples ran (seed {}): {violations} violate `{ineq}`",
            self.samples.seed
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
        let mut o = outcome(cx.file, c, verdict, detail);
        if let Some((m, _)) = worst {
            o.extra.insert("least_margin".into(), serde_json::json!(m));
        }
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `bound`. {}; sampled: {}; required: `{}`.",
            self.scene
                .as_ref()
                .map(|s| format!("Scene `{}`", s.name))
                .unwrap_or_else(|| "Formulas alone (no scene)".into()),
            self.samples.described(),
            self.require
        )
    }
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
