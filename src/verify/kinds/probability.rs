//! Kind `probability`: the probability of an inequality (`event`) over seeded samples of the
//! scene fields, with its Clopper-Pearson interval; against `expect` (`"<= 0.15"`) when given.

use super::scene::{self, Samples, Scene, clopper_pearson};
use super::{Checked, Kind, Session, Where, claim_err, g4};
use crate::algebra::expr::{Inequality, Rel};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The keys of a `probability` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProbabilitySpec {
    /// The scene, relative to the claims file.
    scene: String,
    /// Scene fields set before sampling.
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    /// Formula symbol -> scene field.
    #[serde(default)]
    bind: BTreeMap<String, String>,
    /// Named runs of the scene compared in one formula (`a.quantity`, `b.quantity`).
    #[serde(default)]
    runs: scene::Runs,
    /// Scene field -> distribution.
    #[serde(default)]
    sample: BTreeMap<String, String>,
    /// Number of samples.
    count: usize,
    /// Seed of the generator.
    seed: u64,
    /// The inequality whose probability is estimated.
    event: String,
    /// The claim on the probability (`"<= 0.15"`).
    #[serde(default)]
    expect: Option<String>,
    /// The confidence of the Clopper-Pearson interval (default 0.95).
    #[serde(default)]
    confidence: Option<f64>,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// A checked `probability` claim.
pub struct Probability {
    scene: Scene,
    samples: Samples,
    event: Inequality,
    /// `expect` as written, and read.
    expect: Option<(String, Rel, f64)>,
    confidence: f64,
}

impl Kind for Probability {
    const NAME: &'static str = "probability";
    const PRINTED: &'static [&'static str] = &["event"];
    type Spec = ProbabilitySpec;

    fn validate(cx: &Checked, c: &Head, s: ProbabilitySpec) -> Result<Self, VerifyError> {
        let scene = Scene::open(cx, c, &s.scene, &s.set, s.bind, s.runs)?;
        let samples = Samples::read(cx, c, s.sample, s.count, s.seed)?;
        let expect = match s.expect {
            Some(e) => {
                let (rel, x) =
                    scene::parse_expectation(&e).map_err(|m| claim_err(cx.file, c, "expect", m))?;
                Some((e, rel, x))
            }
            None => None,
        };
        let confidence = s.confidence.unwrap_or(0.95);
        if !(confidence > 0.0 && confidence < 1.0) {
            return Err(claim_err(
                cx.file,
                c,
                "confidence",
                format!("{confidence} is out of range; allowed: 0 < confidence < 1"),
            ));
        }
        let event = scene::inequality(cx, c, &s.where_, "event", &s.event)?;
        scene.probe(
            cx,
            c,
            &samples.probe(),
            &[("event", &event.lhs), ("event", &event.rhs)],
        )?;
        Ok(Probability {
            scene,
            samples,
            event,
            expect,
            confidence,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let ineq = &self.event;
        let (_, rows) = self.samples.run(Some(&self.scene), ineq);
        let n = rows.iter().filter(|r| r.is_ok()).count();
        let failed = rows.len() - n;
        let k = rows
            .iter()
            .filter(|r| matches!(r, Ok((l, r)) if ineq.rel.holds(*l, *r)))
            .count();
        let conf = self.confidence;
        let (lo, hi) = clopper_pearson(k, n, conf);
        let p = if n > 0 { k as f64 / n as f64 } else { f64::NAN };
        let mut detail = format!(
            "`{ineq}` in {k} of {n} samples (seed {}): p = {}, {:.0} % Clopper-Pearson interval [{}, {}]",
            self.samples.seed,
            g4(p),
            100.0 * conf,
            g4(lo),
            g4(hi)
        );
        let verdict = match &self.expect {
            None => Verdict::Holds,
            Some((e, rel, x)) => {
                let meets = |v: f64| rel.holds(v, *x);
                // "never" (p <= 0) and "always" (p >= 1): no interval of finite samples lies
                // inside, so a sample that shows the event (or misses it) refutes the
                // statement, and none holds it as far as n samples can tell
                let never = *x <= 0.0 && *rel == Rel::Le;
                let always = *x >= 1.0 && *rel == Rel::Ge;
                if never || always {
                    let against = if never { k } else { n - k };
                    if n > 0 && against == 0 {
                        detail.push_str(&format!(
                            "; p {e} as stated: no sample of {n} goes against it (p is at {} {} at {:.0} %)",
                            if never { "most" } else { "least" },
                            g4(if never { hi } else { lo }),
                            100.0 * conf
                        ));
                        Verdict::Holds
                    } else if n > 0 {
                        detail.push_str(&format!(
                            "; p {e} is refuted by {against} sample(s) of {n}, each a computed counterexample"
                        ));
                        Verdict::Fails
                    } else {
                        detail.push_str("; no sample ran");
                        Verdict::NotCheckable
                    }
                } else if meets(lo) && meets(hi) {
                    detail.push_str(&format!("; the whole interval is {e}"));
                    Verdict::Holds
                } else if !meets(lo) && !meets(hi) {
                    detail.push_str(&format!("; no part of the interval is {e}"));
                    Verdict::Fails
                } else {
                    let need = samples_needed(p, *x, n, conf);
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
        let mut o = outcome(cx.file, c, verdict, detail);
        o.extra.insert(
            "probability".into(),
            serde_json::json!({"p": p, "lo": lo, "hi": hi, "n": n}),
        );
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `probability`. Scene `{}`; sampled: {}; event: `{}`{}.",
            self.scene.name,
            self.samples.described(),
            self.event,
            self.expect
                .as_ref()
                .map(|(e, ..)| format!("; expected: p {e}"))
                .unwrap_or_default()
        )
    }
}

/// Samples needed for the interval's half-width to reach |p - x| (normal approximation, z of
/// the confidence).
fn samples_needed(p: f64, x: f64, n: usize, conf: f64) -> f64 {
    use statrs::distribution::{ContinuousCDF, Normal};
    let z = Normal::new(0.0, 1.0).map_or(1.96, |d| d.inverse_cdf(0.5 + conf / 2.0));
    let gap = (p - x).abs().max(1e-6);
    let floor = 1.0 / n.max(1) as f64;
    (z * z * p.max(floor) * (1.0 - p).max(floor) / (gap * gap)).ceil()
}

#[cfg(test)]
mod tests {
    #[test]
    fn samples_needed_is_the_normal_approximations_count() {
        // z^2 p (1 - p)/(p - x)^2 with z = 1.959964 (95 %): 3.841459 * 0.21/0.0025 = 322.68,
        // rounded up (by hand); a gap twice as wide needs a quarter of them, 80.67 -> 81
        assert!((super::samples_needed(0.3, 0.35, 100, 0.95) - 323.0).abs() < 1e-9);
        assert!((super::samples_needed(0.3, 0.4, 100, 0.95) - 81.0).abs() < 1e-9);
        // p = 0 is floored at 1/n: (1.959964^2 (1/50)(49/50))/0.1^2 = 7.53 -> 8
        assert!((super::samples_needed(0.0, 0.1, 50, 0.95) - 8.0).abs() < 1e-9);
    }
}
