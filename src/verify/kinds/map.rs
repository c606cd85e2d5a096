//! Kind `map`: the region of a two-axis grid where an inequality (`require`) holds, or where the
//! printed formula is within `rtol` of the model's quantity; `holds` when it is the whole grid.

use super::scene::{self, Axis, Scene};
use super::{Checked, Kind, Session, Where, g4};
use crate::algebra::expr::{Expr, Inequality};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;
use std::collections::BTreeMap;

/// The keys of a `map` claim: `require`, or `quantity`, `printed` and `rtol`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MapSpec {
    /// The scene, relative to the claims file.
    scene: String,
    /// Scene fields set before the grid.
    #[serde(default)]
    set: BTreeMap<String, toml::Value>,
    /// Formula symbol -> scene field.
    #[serde(default)]
    bind: BTreeMap<String, String>,
    /// Named runs of the scene compared in one formula (`a.quantity`, `b.quantity`).
    #[serde(default)]
    runs: scene::Runs,
    /// The grid's two axes, `FIELD=START:STOP:COUNT[:log]` each.
    #[serde(default)]
    vary: Vec<String>,
    /// The inequality whose region is mapped.
    #[serde(default)]
    require: Option<String>,
    /// Without `require`: the outcome quantity compared.
    #[serde(default)]
    quantity: Option<String>,
    /// Without `require`: the printed formula.
    #[serde(default)]
    printed: Option<String>,
    /// Without `require`: the relative tolerance of "within".
    #[serde(default)]
    rtol: Option<f64>,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// What a map shows.
enum Region {
    /// Where the inequality holds.
    Holds(Inequality),
    /// Where the printed formula is within `rtol` of the quantity.
    Within {
        quantity: String,
        printed_text: String,
        printed: Expr,
        rtol: f64,
    },
}

/// A checked `map` claim.
pub struct Map {
    scene: Scene,
    axes: Vec<Axis>,
    vary: Vec<String>,
    region: Region,
}

impl Kind for Map {
    const NAME: &'static str = "map";
    const PRINTED: &'static [&'static str] = &["require", "printed"];
    type Spec = MapSpec;

    fn validate(cx: &Checked, c: &Head, s: MapSpec) -> Result<Self, VerifyError> {
        let err = |field: &str, m: String| super::claim_err(cx.file, c, field, m);
        let scene = Scene::open(cx, c, &s.scene, &s.set, s.bind, s.runs)?;
        if s.vary.len() != 2 {
            return Err(err(
                "vary",
                format!(
                    "a map has two axes, FIELD=START:STOP:COUNT[:log] each; {} given",
                    s.vary.len()
                ),
            ));
        }
        let (axes, probe) = scene::axes(cx, c, &s.vary)?;
        let region = match s.require {
            Some(text) => {
                let ineq = scene::inequality(cx, c, &s.where_, "require", &text)?;
                scene.probe(
                    cx,
                    c,
                    &probe,
                    &[("require", &ineq.lhs), ("require", &ineq.rhs)],
                )?;
                Region::Holds(ineq)
            }
            None => {
                let missing = |k: &str, what: &str| {
                    err(
                        k,
                        format!("missing; kind `map` without `require` needs it ({what})"),
                    )
                };
                let quantity = s
                    .quantity
                    .ok_or_else(|| missing("quantity", "a dotted path of the outcome"))?;
                let rtol = s
                    .rtol
                    .ok_or_else(|| missing("rtol", "a relative tolerance"))?;
                scene::check_rtol(cx, c, rtol)?;
                let printed_text = s.printed.ok_or_else(|| missing("printed", "a formula"))?;
                let printed = cx.formula(c, &s.where_, "printed", &printed_text)?;
                let outcome = scene.probe(cx, c, &probe, &[("printed", &printed)])?;
                scene::check_quantity(cx, c, &outcome, &quantity)?;
                // a formula read from the paper is named by its equation (the report shows
                // its LaTeX); a typed one is quoted
                let printed_text = match &c.tex {
                    Some(_) => format!("{} as printed", c.equation),
                    None => format!("`{printed_text}`"),
                };
                Region::Within {
                    quantity,
                    printed_text,
                    printed,
                    rtol,
                }
            }
        };
        Ok(Map {
            scene,
            axes,
            vary: s.vary,
            region,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let axes = &self.axes;
        let quantity_sym;
        let sides = match &self.region {
            Region::Holds(i) => (&i.lhs, &i.rhs),
            Region::Within {
                quantity, printed, ..
            } => {
                quantity_sym = Expr::Sym(quantity.clone());
                (&quantity_sym, printed)
            }
        };
        let (points, rows) = scene::grid(&self.scene, axes, sides);
        let inside = |l: f64, r: f64| match &self.region {
            Region::Holds(i) => i.rel.holds(l, r),
            Region::Within { rtol, .. } => (r - l).abs() <= rtol * l.abs(),
        };
        // cells in the order of the grid (first axis slowest): reorder so that y is slowest
        let (nx, ny) = (axes[0].values.len(), axes[1].values.len());
        let mut cells = vec![None; nx * ny];
        for (idx, r) in rows.iter().enumerate() {
            let (i, j) = (idx / ny, idx % ny);
            cells[j * nx + i] = r.as_ref().ok().map(|(l, r)| inside(*l, *r));
        }
        let valid = cells.iter().filter(|c| **c == Some(true)).count();
        let share = valid as f64 / points.len() as f64;
        let what = self.what();
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
        if let Some(f) = super::scene::failed_points(&points, &rows) {
            detail.push_str(&format!("; {f}"));
        }
        detail.push_str(&boundary(axes, &cells));
        let verdict = if valid == points.len() {
            Verdict::Holds
        } else {
            Verdict::Fails
        };
        let mut o = outcome(cx.file, c, verdict, detail);
        o.extra
            .insert("valid_fraction".into(), serde_json::json!(share));
        let values: Vec<Option<(f64, f64)>> =
            rows.iter().map(|r| r.as_ref().ok().copied()).collect();
        self.figure(c, &mut o, &cells, &points, &values);
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `map`. Scene `{}`; grid {}.",
            self.scene.name,
            self.vary.join(" x ")
        )
    }
}

impl Map {
    /// What the region is, in words.
    fn what(&self) -> String {
        match &self.region {
            Region::Holds(i) => format!("`{i}` holds"),
            Region::Within {
                quantity,
                printed_text,
                rtol,
                ..
            } => format!(
                "{printed_text} is within {} % (relative) of the model's {quantity}",
                crate::report::svg::short_number(rtol * 100.0)
            ),
        }
    }

    /// The region as a map (SVG) and its data: every grid point with the two sides compared
    /// (the model's value and the printed one, or the inequality's sides), their difference
    /// (relative to the model's value for a tolerance, left - right for an inequality) and
    /// inside (1), outside (0) or not run (empty).
    fn figure(
        &self,
        c: &Head,
        o: &mut Outcome,
        cells: &[Option<bool>],
        points: &[Vec<(String, f64)>],
        values: &[Option<(f64, f64)>],
    ) {
        let axes = &self.axes;
        let what = self.what();
        let (nx, ny) = (axes[0].values.len(), axes[1].values.len());
        let name = format!("{}.svg", c.id.replace('.', "_"));
        let labels = [
            self.scene.field_label(&axes[0].field),
            self.scene.field_label(&axes[1].field),
        ];
        let axis = |k: usize| crate::report::svg::MapAxis {
            label: &labels[k],
            values: axes[k].values.as_slice(),
            log: axes[k].log,
        };
        let title = match &c.reading {
            Some(r) if !r.trim().is_empty() => format!(
                "{}: {}. Blue where {}",
                c.equation,
                r.trim(),
                what.replace('`', "")
            ),
            _ => format!("{}: where {}", c.equation, what.replace('`', "")),
        };
        let svg = crate::report::svg::region_map(&title, &axis(0), &axis(1), cells);
        o.extra_md = Some(format!(
            "\n\n![{}: the region where {} (blue), over {} and {}]({name})\n\n*Figure: claim {}, where the claim holds (blue) and fails (orange) on the grid (data: {}.csv).*",
            c.id,
            what.replace('`', ""),
            axes[0].field,
            axes[1].field,
            c.id,
            c.id.replace('.', "_")
        ));
        o.files.push((name, svg));
        let csv_name = format!("{}.csv", c.id.replace('.', "_"));
        let (left, right, diff) = match &self.region {
            Region::Holds(_) => ("left", "right", "left_minus_right"),
            Region::Within { .. } => ("model", "printed", "relative_difference"),
        };
        let mut csv = format!(
            "{},{},{left},{right},{diff},inside\n",
            axes[0].field, axes[1].field
        );
        for (idx, pt) in points.iter().enumerate() {
            let (i, j) = (idx / ny, idx % ny);
            let cell = match cells[j * nx + i] {
                Some(true) => "1",
                Some(false) => "0",
                None => "",
            };
            let sides = match values.get(idx).copied().flatten() {
                Some((l, r)) => {
                    let d = match &self.region {
                        Region::Holds(_) => l - r,
                        Region::Within { .. } => (r - l) / l.abs(),
                    };
                    format!("{l:e},{r:e},{d:e}")
                }
                None => ",,".to_string(),
            };
            csv.push_str(&format!("{:e},{:e},{sides},{cell}\n", pt[0].1, pt[1].1));
        }
        o.files.push((csv_name, csv));
    }
}

/// Where the region's boundary lies on the grid: for each value of the first axis whose column
/// changes between inside and outside, the neighbouring values of the second axis it changes
/// between (the first four such columns, and how many more).
fn boundary(axes: &[Axis], cells: &[Option<bool>]) -> String {
    let (nx, ny) = (axes[0].values.len(), axes[1].values.len());
    let mut found = Vec::new();
    for i in 0..nx {
        let mut changes = Vec::new();
        for j in 1..ny {
            if let (Some(a), Some(b)) = (cells[(j - 1) * nx + i], cells[j * nx + i])
                && a != b
            {
                changes.push(format!(
                    "{} between {} and {}",
                    if b { "enters" } else { "leaves" },
                    g4(axes[1].values[j - 1]),
                    g4(axes[1].values[j])
                ));
            }
        }
        if !changes.is_empty() {
            found.push(format!(
                "at {} = {}: {}",
                axes[0].field,
                g4(axes[0].values[i]),
                changes.join(", ")
            ));
        }
    }
    if found.is_empty() {
        return String::new();
    }
    let more = found.len().saturating_sub(4);
    found.truncate(4);
    format!(
        "; the boundary along {}: {}{}",
        axes[1].field,
        found.join("; "),
        if more > 0 {
            format!("; and {more} more value(s) of {}", axes[0].field)
        } else {
            String::new()
        }
    )
}
