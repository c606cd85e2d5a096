//! Kind `threshold`: where a model's behaviour changes along one parameter (sticks or slides,
//! stays or lifts off, stable or unstable), located by bisection at each point of a grid of the
//! other parameters and compared with the printed formula for that value.
//!
//! The behaviour is either a value of the run's JSON (`changes = "phases.1.kind"`: its text, or
//! `none` where the run has no such value) or an inequality over the model's numbers and the bound
//! symbols (`when = "v_rel_after.0 > 0"`: true or false). At every grid point it must differ at
//! the two ends of `along = "FIELD=LOW:HIGH"`; bisection then halves the bracket until it is
//! narrower than `rtol/16` of the value, and the middle of the last bracket is the model's
//! threshold. `holds` when the printed formula is within `rtol` of it at every point.

use super::scene::{self, Axis, Scene, bind_text, exact_point_text};
use super::{Checked, Kind, Session, Where, claim_err, g4};
use crate::algebra::expr::{Expr, Inequality};
use crate::verify::{Head, Outcome, VerifyError, outcome};
use serde::Deserialize;
use serde_json::Value;
use std::collections::BTreeMap;

/// The keys of a `threshold` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThresholdSpec {
    /// The scene, relative to the claims file.
    scene: String,
    /// Scene fields set before the grid (a number or a string).
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    /// Formula symbol -> scene field.
    #[serde(default)]
    bind: BTreeMap<String, String>,
    /// The parameter searched and its bracket, `FIELD=LOW:HIGH`.
    along: String,
    /// The value of the run's JSON whose change is located (a dotted path).
    #[serde(default)]
    changes: Option<String>,
    /// Or the inequality whose truth changes.
    #[serde(default)]
    when: Option<String>,
    /// The grid of the other parameters, `FIELD=START:STOP:COUNT[:log]` per axis (none: one
    /// point, the scene as it is).
    #[serde(default)]
    vary: Vec<String>,
    /// The printed formula for the threshold value of the `along` parameter.
    printed: String,
    /// The largest relative difference allowed (> 0: the bisection stops at `rtol/16`).
    rtol: f64,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// What is watched along the parameter.
enum Test {
    /// A value of the run's JSON, as text.
    Changes(String),
    /// An inequality's truth.
    When(Inequality),
}

/// A checked `threshold` claim.
pub struct Threshold {
    scene: Scene,
    axes: Vec<Axis>,
    vary: Vec<String>,
    field: String,
    low: f64,
    high: f64,
    test: Test,
    printed_text: String,
    printed: Expr,
    rtol: f64,
}

/// One grid point's result: (the model's threshold, the printed value), and the behaviour
/// below and above it.
type Located = Result<((f64, f64), (String, String)), String>;

impl Kind for Threshold {
    const NAME: &'static str = "threshold";
    const PRINTED: &'static [&'static str] = &["printed"];
    type Spec = ThresholdSpec;

    fn validate(cx: &Checked, c: &Head, s: ThresholdSpec) -> Result<Self, VerifyError> {
        let err = |key: &str, m: String| claim_err(cx.file, c, key, m);
        let scene = Scene::open(cx, c, &s.scene, &s.set, s.bind, BTreeMap::new())?;
        scene::check_rtol(cx, c, s.rtol)?;
        if s.rtol <= 0.0 {
            return Err(err(
                "rtol",
                "0: a threshold is located to a width; give rtol > 0".into(),
            ));
        }
        let (field, low, high) = parse_along(&s.along).map_err(|m| err("along", m))?;
        if let Some((sym, _)) = scene.bind.iter().find(|(_, f)| **f == field) {
            return Err(err(
                &format!("bind.{sym}"),
                format!(
                    "`{sym}` is bound to `{field}`, the parameter searched: the printed threshold is a formula of the others"
                ),
            ));
        }
        let (axes, mut probe) = if s.vary.is_empty() {
            (Vec::new(), Vec::new())
        } else {
            scene::axes(cx, c, &s.vary)?
        };
        if axes.iter().any(|a| a.field == field) {
            return Err(err(
                "vary",
                format!("`{field}` is the parameter searched (`along`); vary the others"),
            ));
        }
        let printed = cx.formula(c, &s.where_, "printed", &s.printed)?;
        let test = match (&s.changes, &s.when) {
            (Some(path), None) => Test::Changes(path.clone()),
            (None, Some(text)) => Test::When(scene::inequality(cx, c, &s.where_, "when", text)?),
            _ => {
                return Err(err(
                    "changes",
                    "give `changes` (a value of the run that changes: \"phases.1.kind\") or `when` (an inequality that turns: \"v_rel_after.0 > 0\"), one of them".into(),
                ));
            }
        };
        // one run at each end of the bracket (at the grid's first point) reads every symbol
        let mut sides: Vec<(&str, &Expr)> = vec![("printed", &printed)];
        if let Test::When(i) = &test {
            sides.push(("when", &i.lhs));
            sides.push(("when", &i.rhs));
        }
        probe.push(("along".to_string(), field.clone(), low));
        let at_low = scene.probe(cx, c, &probe, &sides)?;
        if let Test::Changes(path) = &test {
            probe.pop();
            probe.push(("along".to_string(), field.clone(), high));
            let at_high = scene.probe(cx, c, &probe, &sides)?;
            if value_at(&at_low, path).is_none() && value_at(&at_high, path).is_none() {
                return Err(err(
                    "changes",
                    format!(
                        "`{path}`: the run has no such value at either end of `{field}`; it has: {}",
                        scene::numeric_paths(&at_low).join(", ")
                    ),
                ));
            }
        }
        Ok(Threshold {
            scene,
            axes,
            vary: s.vary,
            field,
            low,
            high,
            test,
            printed_text: s.printed,
            printed,
            rtol: s.rtol,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        use rayon::prelude::*;
        let points = scene::grid_points(&self.axes);
        let located: Vec<Located> = points.par_iter().map(|pt| self.locate(pt)).collect();
        let rows: Vec<Result<(f64, f64), String>> = located
            .iter()
            .map(|r| r.as_ref().map(|(v, _)| *v).map_err(Clone::clone))
            .collect();
        let what = format!("the model's threshold of {}", self.field);
        let (verdict, mut detail) = super::rows::compare_rows(&points, &rows, self.rtol, &what);
        // what the behaviour is on each side, over the points (a stick or a reversed slip)
        let (mut below, mut above) = (Vec::new(), Vec::new());
        for (b, a) in located.iter().flatten().map(|(_, s)| s) {
            if !below.contains(b) {
                below.push(b.clone());
            }
            if !above.contains(a) {
                above.push(a.clone());
            }
        }
        if !below.is_empty() {
            detail.push_str(&format!(
                "; {}: {} below the threshold, {} above",
                self.test_text(),
                below.join(" or "),
                above.join(" or ")
            ));
        }
        let mut o = outcome(cx.file, c, verdict, detail);
        if self.axes.len() == 1 && rows.iter().filter(|r| r.is_ok()).count() > 1 {
            let quantity = format!("threshold of {}", self.field);
            let labels = (
                self.scene.field_label(&self.axes[0].field),
                self.scene.field_label(&self.field),
            );
            super::model::curve_figure(
                c,
                &mut o,
                &self.axes[0],
                &rows,
                (&labels.0, &format!("threshold of {}", labels.1)),
                &quantity,
                &self.printed.to_string(),
            );
        }
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `threshold`. Scene `{}`; where {} changes along {} in [{}, {}] (bisection to rtol/16), against `{}`{}; grid {}.",
            self.scene.name,
            self.test_text(),
            self.field,
            g4(self.low),
            g4(self.high),
            self.printed_text,
            bind_text(&self.scene.bind),
            if self.vary.is_empty() {
                "one point (the scene as it is)".to_string()
            } else {
                self.vary.join(" x ")
            }
        )
    }
}

impl Threshold {
    /// What is watched, in words.
    fn test_text(&self) -> String {
        match &self.test {
            Test::Changes(path) => format!("`{path}`"),
            Test::When(i) => format!("`{i}`"),
        }
    }

    /// The behaviour of the model at the grid point `pt` with the searched parameter at `x`.
    fn state(&self, pt: &[(String, f64)], x: f64) -> Result<String, String> {
        let mut at = pt.to_vec();
        at.push((self.field.clone(), x));
        let (t, out) = self.scene.run_point(&at)?;
        match &self.test {
            Test::Changes(path) => Ok(value_at(&out, path).unwrap_or_else(|| "none".into())),
            Test::When(i) => {
                let value = |s: &str| self.scene.value(&t, &out, s);
                let (l, r) = (i.lhs.eval(&value)?, i.rhs.eval(&value)?);
                Ok(if i.rel.holds(l, r) { "true" } else { "false" }.into())
            }
        }
    }

    /// The model's threshold at the grid point `pt`, by bisection, and the printed formula
    /// there (its symbols read at the threshold's run).
    fn locate(&self, pt: &[(String, f64)]) -> Located {
        let (mut a, mut b) = (self.low, self.high);
        let below = self.state(pt, a)?;
        let above = self.state(pt, b)?;
        if below == above {
            return Err(format!(
                "{} is {below} at both ends of {} in [{}, {}]: no change to locate",
                self.test_text(),
                self.field,
                g4(a),
                g4(b)
            ));
        }
        let width = self.rtol / 16.0;
        for _ in 0..200 {
            if b - a <= width * a.abs().max(b.abs()).max(f64::MIN_POSITIVE) {
                break;
            }
            let m = 0.5 * (a + b);
            if self.state(pt, m)? == below {
                a = m;
            } else {
                b = m;
            }
        }
        let x = 0.5 * (a + b);
        let mut at = pt.to_vec();
        at.push((self.field.clone(), x));
        let (t, out) = self.scene.run_point(&at)?;
        let printed = self
            .printed
            .eval(&|s: &str| self.scene.value(&t, &out, s))
            .map_err(|e| format!("the printed formula at {}: {e}", exact_point_text(&at)))?;
        Ok(((x, printed), (below, above)))
    }
}

/// `FIELD=LOW:HIGH`, with LOW < HIGH, both finite.
fn parse_along(text: &str) -> Result<(String, f64, f64), String> {
    let help = "FIELD=LOW:HIGH, the parameter searched and a bracket where the behaviour differs at its ends (\"initial.v_rel.0=0.01:10\")";
    let (field, range) = text
        .split_once('=')
        .ok_or_else(|| format!("`{text}`: expected {help}"))?;
    let (lo, hi) = range
        .split_once(':')
        .ok_or_else(|| format!("`{text}`: expected {help}"))?;
    let num = |s: &str| {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("`{s}` is not a finite number; expected {help}"))
    };
    let (lo, hi) = (num(lo)?, num(hi)?);
    if lo >= hi || field.trim().is_empty() {
        return Err(format!("`{text}`: expected {help}, with LOW < HIGH"));
    }
    Ok((field.trim().to_string(), lo, hi))
}

/// The value at a dotted path of a run's JSON, as text (a string without its quotes).
fn value_at(v: &Value, path: &str) -> Option<String> {
    match scene::at_path(v, path)? {
        Value::Null => None,
        Value::String(s) => Some(s.clone()),
        other => Some(other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn along_is_a_field_and_a_bracket() {
        assert_eq!(
            parse_along("initial.v_rel.0 = 0.01:10").unwrap(),
            ("initial.v_rel.0".to_string(), 0.01, 10.0)
        );
        for bad in ["x=1:1", "x=2:1", "x=1", "=1:2", "x=a:2", "x=1:inf"] {
            assert!(parse_along(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn values_are_text_and_none_where_absent() {
        let v: Value = serde_json::from_str(
            r#"{"phases":[{"kind":"slip"},{"kind":"stick"}],"x":1.5,"n":null}"#,
        )
        .unwrap();
        assert_eq!(value_at(&v, "phases.1.kind").as_deref(), Some("stick"));
        assert_eq!(value_at(&v, "phases.2.kind"), None);
        assert_eq!(value_at(&v, "x").as_deref(), Some("1.5"));
        assert_eq!(value_at(&v, "n"), None);
    }
}
