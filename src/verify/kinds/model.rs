//! Kind `model`: a printed formula, its symbols bound to scene fields, against a quantity the
//! model produces, over a grid; `holds` when the largest relative difference is at most `rtol`.

use super::scene::{self, Axis, Scene, bind_text};
use super::{Checked, Kind, Session, Where};
use crate::algebra::expr::Expr;
use crate::algebra::units;
use crate::verify::{Head, Outcome, VerifyError, outcome};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The keys of a `model` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelSpec {
    /// The scene, relative to the claims file.
    scene: String,
    /// Scene fields set before the grid (a number or a string).
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    /// Formula symbol -> scene field.
    #[serde(default)]
    bind: BTreeMap<String, String>,
    /// Named runs of the scene compared in one formula (`a.quantity`, `b.quantity`).
    #[serde(default)]
    runs: scene::Runs,
    /// The grid, `FIELD=START:STOP:COUNT[:log]` per axis.
    #[serde(default)]
    vary: Vec<String>,
    /// The dotted path of the outcome quantity compared.
    quantity: String,
    /// The printed formula.
    printed: String,
    /// The largest relative difference allowed.
    rtol: f64,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
    /// The printed formula is an approximation right to this order in `small`
    /// ([`super::approximation`]).
    #[serde(default)]
    order: Option<f64>,
    /// The small parameter of an approximation, a formula of bound symbols.
    #[serde(default)]
    small: Option<String>,
    /// The largest value of `small` where `rtol` is claimed (default: the whole grid).
    #[serde(default)]
    small_max: Option<f64>,
}

/// A checked `model` claim.
pub struct Model {
    scene: Scene,
    axes: Vec<Axis>,
    vary: Vec<String>,
    quantity: String,
    printed_text: String,
    printed: Expr,
    rtol: f64,
    /// The printed formula's unit against the quantity's, when both have one.
    units_note: Option<String>,
    /// An approximation's order and small parameter, when the claim states them.
    order: Option<super::approximation::Order>,
}

impl Kind for Model {
    const NAME: &'static str = "model";
    const PRINTED: &'static [&'static str] = &["printed"];
    type Spec = ModelSpec;

    fn validate(cx: &Checked, c: &Head, s: ModelSpec) -> Result<Self, VerifyError> {
        let scene = Scene::open(cx, c, &s.scene, &s.set, s.bind, s.runs)?;
        scene::check_rtol(cx, c, s.rtol)?;
        let (axes, probe) = scene::axes(cx, c, &s.vary)?;
        let printed = cx.formula(c, &s.where_, "printed", &s.printed)?;
        let outcome = scene.probe(cx, c, &probe, &[("printed", &printed)])?;
        scene::check_quantity(cx, c, &outcome, &s.quantity)?;
        // the quantity's unit: the model's own (every model states the unit of each number it
        // produces; a text model derives it from its formulas), else the claims file's; a
        // declared unit that contradicts the model's is an error naming both
        let quantity = Expr::Sym(s.quantity.clone());
        scene.declared_against_model(cx, c, "quantity", &quantity, &outcome)?;
        let model_units = scene.model_units(&outcome);
        let units_note = match (
            model_units
                .get(&s.quantity)
                .copied()
                .or_else(|| cx.declared(&s.quantity)),
            units::dimension(
                &cx.formula(c, &cx.where_for_units(&s.where_), "printed", &s.printed)?,
                &cx.unit_fn_in(&model_units),
            ),
        ) {
            (Some(u), Ok(pu)) if pu != u => {
                Some(format!("; units: the formula is {pu}, the quantity {u}"))
            }
            _ => None,
        };
        let order = super::approximation::Order::read(
            cx,
            c,
            s.order,
            s.small.as_deref(),
            s.small_max,
            &|sym| scene.bind.contains_key(sym),
        )?;
        Ok(Model {
            order,
            scene,
            axes,
            vary: s.vary,
            quantity: s.quantity,
            printed_text: s.printed,
            printed,
            rtol: s.rtol,
            units_note,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let quantity = &self.quantity;
        let q = Expr::Sym(quantity.clone());
        let (points, rows) = scene::grid(&self.scene, &self.axes, (&q, &self.printed));
        let what = format!("model {quantity}");
        let (verdict, mut detail) = match &self.order {
            None => super::rows::compare_rows(&points, &rows, self.rtol, &what),
            Some(order) => {
                let smalls: Vec<Result<f64, String>> = points
                    .iter()
                    .map(|pt| self.scene.bound_value(pt, &order.small))
                    .collect();
                order.judge(&points, &rows, &smalls, self.rtol, &what)
            }
        };
        if let Some(u) = &self.units_note {
            detail.push_str(u);
        }
        let mut o = outcome(cx.file, c, verdict, detail);
        if self.axes.len() == 1 && rows.iter().filter(|r| r.is_ok()).count() > 1 {
            let labels = (
                self.scene.field_label(&self.axes[0].field),
                self.scene.quantity_label(&self.quantity),
            );
            curve_figure(
                c,
                &mut o,
                &self.axes[0],
                &rows,
                (&labels.0, &labels.1),
                &self.quantity,
                &self.printed.to_string(),
            );
        }
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `model`. Scene `{}`; `{}` against `{}`{}; grid {}.",
            self.scene.name,
            self.quantity,
            self.printed_text,
            bind_text(&self.scene.bind),
            self.vary.join(" x ")
        )
    }
}

/// The model's and the printed curve against a grid's one axis `a`, with their data, in the
/// claim's outcome: `quantity` names the model's value, `printed` the formula; `labels` are
/// the axes' titles (field and quantity with their units).
pub(super) fn curve_figure(
    c: &Head,
    o: &mut Outcome,
    a: &Axis,
    rows: &[Result<(f64, f64), String>],
    labels: (&str, &str),
    quantity: &str,
    printed: &str,
) {
    let mut model_curve = Vec::new();
    let mut printed_curve = Vec::new();
    for (v, r) in a.values.iter().zip(rows) {
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
    let title = match &c.reading {
        Some(r) if !r.trim().is_empty() => format!("{}: {}", c.equation, r.trim()),
        _ => format!(
            "{}: the model's {quantity} and the printed formula",
            c.equation
        ),
    };
    let printed_name = format!("printed: {printed}");
    let printed_name = if printed_name.chars().count() > 60 {
        "printed formula".to_string()
    } else {
        printed_name
    };
    let svg = crate::report::plot::figure(&crate::report::plot::Figure {
        title: &title,
        xlabel: labels.0,
        xs: scale,
        panels: vec![crate::report::plot::Panel {
            ylabel: labels.1,
            ys: crate::report::svg::Scale::Linear,
            series: vec![
                crate::report::svg::Series {
                    name: "model (integrated)",
                    points: model_curve.clone(),
                },
                crate::report::svg::Series {
                    name: &printed_name,
                    points: printed_curve.clone(),
                },
            ],
        }],
        caption: vec![format!(
            "Claim {} ({}): the model's {quantity} against the printed `{printed}`, over {}.",
            c.id,
            o.verdict.as_str(),
            a.field
        )],
    });
    let csv_name = format!("{}.csv", c.id.replace('.', "_"));
    let mut csv = format!("{},model {quantity},printed\n", a.field);
    for ((x, m), (_, p)) in model_curve.iter().zip(&printed_curve) {
        csv.push_str(&format!("{x:e},{m:e},{p:e}\n"));
    }
    o.extra_md = Some(format!(
        "\n\n![{}: the model's {quantity} and the printed formula against {}]({name})\n\n*Figure: claim {}, the model's {quantity} and the printed `{}` against {} (data: [{csv_name}]({csv_name})).*",
        c.id, a.field, c.id, printed, a.field
    ));
    o.files.push((name, svg));
    o.files.push((csv_name, csv));
}
