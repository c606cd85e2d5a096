//! What the `impact` subcommands compute and print, reachable from tests.
//!
//! The binary parses arguments and calls these; each returns the text to print or an error that
//! names the bad argument and what is allowed.

use crate::algebra::AlgebraError;
use crate::algebra::eval::{self, EvalError, Evaluator};
use crate::algebra::expo::Expo;
use crate::algebra::galerkin;
use crate::algebra::poly::{Q, parse_q};
use crate::algebra::ratfunc::RatFunc;
use crate::algebra::series::{self, SeriesParams, Viscous};
use crate::scene::cells::{Cells, Leaf};
use crate::scene::row::Node;
use serde_json::{Value, json};
use std::collections::BTreeMap;

/// Output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Plain text.
    Text,
    /// LaTeX (series only).
    Latex,
    /// JSON.
    Json,
    /// Comma-separated values (sweeps).
    Csv,
}

/// Errors of the command layer.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// From the exact algebra.
    #[error(transparent)]
    Algebra(#[from] AlgebraError),
    /// From float evaluation.
    #[error(transparent)]
    Eval(#[from] EvalError),
    /// A malformed argument.
    #[error("{arg}: {message}")]
    BadArgument {
        /// The argument.
        arg: String,
        /// What is wrong and what is allowed.
        message: String,
    },
}

/// Parses `NAME=VALUE,NAME=VALUE` into exact rationals, naming the bad item on error.
pub fn parse_assignments(arg: &str, text: &str) -> Result<Vec<(String, Q)>, CliError> {
    let mut out = Vec::new();
    for item in text.split(',').filter(|s| !s.trim().is_empty()) {
        let (name, value) = item.split_once('=').ok_or_else(|| CliError::BadArgument {
            arg: arg.into(),
            message: format!("`{item}` is not NAME=VALUE"),
        })?;
        let v = parse_q(value).ok_or_else(|| AlgebraError::BadRational {
            text: value.trim().into(),
        })?;
        out.push((name.trim().to_string(), v));
    }
    Ok(out)
}

/// Parses a comma-separated list of times (s).
pub fn parse_times(text: &str) -> Result<Vec<f64>, CliError> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|s| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite() && *t >= 0.0)
                .ok_or_else(|| CliError::BadArgument {
                    arg: "--eval-t".into(),
                    message: format!("`{s}` is not a finite time >= 0 in seconds"),
                })
        })
        .collect()
}

fn rf_json(r: &RatFunc) -> String {
    match r.as_constant() {
        Some(c) => q_text(&c),
        None => r.to_text(),
    }
}

pub use crate::algebra::poly::q_text;

/// `impact series`.
pub fn series(
    order: usize,
    viscous: Viscous,
    at: &[(String, Q)],
    eval_t: &[f64],
    format: Format,
) -> Result<String, CliError> {
    if order > 8 {
        return Err(CliError::BadArgument {
            arg: "--order".into(),
            message: format!("{order} is too large; allowed: 0..=8"),
        });
    }
    let mut p = SeriesParams::symbolic();
    for (name, v) in at {
        p.set(name, v.clone())?;
    }
    let terms = series::adomian_terms(&p, order, viscous);
    let values = if eval_t.is_empty() {
        vec![]
    } else {
        let ev = Evaluator::new(&series::partial_sum(&terms))?;
        eval_t
            .iter()
            .map(|t| Ok((*t, ev.eval(*t)?)))
            .collect::<Result<Vec<_>, EvalError>>()?
    };
    Ok(match format {
        Format::Json => {
            let terms_json: Vec<Value> = terms
                .iter()
                .enumerate()
                .map(|(k, e)| json!({"k": k, "parts": parts_json(e)}))
                .collect();
            let mut v = json!({"order": order, "viscous": viscous.name(), "terms": terms_json});
            if !eval_t.is_empty() {
                v["values"] = values
                    .iter()
                    .map(|(t, z)| json!({"t": t, "z": z}))
                    .collect();
            }
            serde_json::to_string_pretty(&v).unwrap_or_default()
        }
        Format::Text | Format::Csv => {
            let mut s = String::new();
            for (k, e) in terms.iter().enumerate() {
                s.push_str(&format!("a{k}(t) = {}\n", e.to_text()));
            }
            for (t, z) in &values {
                s.push_str(&format!("z({t}) = {z:.17e}\n"));
            }
            s
        }
        Format::Latex => {
            let mut s = String::new();
            for (k, e) in terms.iter().enumerate() {
                s.push_str(&format!("a_{{{k}}}(t) = {}\n\n", e.to_latex()));
            }
            s
        }
    })
}

fn parts_json(e: &Expo) -> Vec<Value> {
    e.parts()
        .map(|((rate, k), c)| {
            let rate = match rate.as_constant() {
                Some(r) => q_text(&r),
                None => rate.to_text(),
            };
            json!({"t_power": k, "rate": rate, "coeff": rf_json(c)})
        })
        .collect()
}

/// Fills `lambda = E/eta` and `zeta = (1-2 nu)/(4 lambda)` when not given, as (16) defines them.
fn complete_values(values: &mut BTreeMap<String, f64>) {
    if !values.contains_key("lambda")
        && let (Some(e), Some(eta)) = (values.get("E"), values.get("eta"))
    {
        values.insert("lambda".into(), e / eta);
    }
    if !values.contains_key("zeta")
        && let (Some(nu), Some(l)) = (values.get("nu"), values.get("lambda"))
    {
        values.insert("zeta".into(), (1.0 - 2.0 * nu) / (4.0 * l));
    }
}

/// `impact galerkin`.
pub fn galerkin(m: u32, n: u32, at: &[(String, Q)], format: Format) -> Result<String, CliError> {
    let g = galerkin::derive(m, n)?;
    let mut values: BTreeMap<String, f64> =
        at.iter().map(|(k, v)| (k.clone(), eval_q(v))).collect();
    complete_values(&mut values);
    let with_values = !at.is_empty();
    let verdict = |b: bool| if b { "agrees" } else { "differs" };
    let mut coeffs = Vec::new();
    for c in &g.coefficients {
        let mut v = json!({
            "name": c.name,
            "derived": c.derived.to_text(),
            "printed": c.printed.to_text(),
            "verdict": verdict(c.agrees),
            "derived_corrected_operator": c.derived_corrected_operator.to_text(),
        });
        if with_values {
            v["derived_value"] = json!(eval::ratfunc_f64(&c.derived, &values)?);
            v["printed_value"] = json!(eval::ratfunc_f64(&c.printed, &values)?);
        }
        coeffs.push(v);
    }
    let out = json!({
        "m": m,
        "n": n,
        "coefficients": coeffs,
        "load_sign": {"derived": g.load_sign, "printed": 1, "verdict": verdict(g.load_sign == 1)},
    });
    Ok(match format {
        Format::Json => serde_json::to_string_pretty(&out).unwrap_or_default(),
        _ => {
            let mut s = format!("Galerkin coefficients of (16), mode (m, n) = ({m}, {n})\n");
            for (c, v) in g.coefficients.iter().zip(&coeffs) {
                s.push_str(&format!(
                    "{}: {}\n  derived: {}\n  printed: {}\n",
                    c.name,
                    verdict(c.agrees),
                    c.derived,
                    c.printed
                ));
                if with_values {
                    s.push_str(&format!(
                        "  values: derived {:.6e}, printed {:.6e}\n",
                        v["derived_value"].as_f64().unwrap_or(f64::NAN),
                        v["printed_value"].as_f64().unwrap_or(f64::NAN)
                    ));
                }
            }
            s.push_str(&format!(
                "load sign: derived {}, printed +1: {}\n",
                g.load_sign,
                verdict(g.load_sign == 1)
            ));
            s
        }
    })
}

fn eval_q(v: &Q) -> f64 {
    use num_traits::ToPrimitive;
    v.to_f64().unwrap_or(f64::NAN)
}

pub use crate::models::{Curves, RunError};

/// Runs a validated scene: the JSON result (the model's typed outcome, serialized) and any curves
/// for `--plot`.
pub fn run_validated(scene: &crate::scene::Scene) -> Result<(Value, Curves), RunError> {
    scene.run()
}

fn render_run(v: &Value, format: Format) -> String {
    if format == Format::Json {
        return serde_json::to_string_pretty(v).unwrap_or_default();
    }
    let mut out = String::new();
    let obj = v.as_object().cloned().unwrap_or_default();
    for (k, val) in obj {
        match val {
            Value::Object(m) => {
                out.push_str(&format!("{k}:\n"));
                for (k2, v2) in m {
                    out.push_str(&format!("  {k2}: {v2}\n"));
                }
            }
            Value::Array(a) if a.iter().all(|x| x.is_object()) && !a.is_empty() => {
                out.push_str(&format!("{k}:\n"));
                for x in a {
                    out.push_str(&format!("  {x}\n"));
                }
            }
            Value::String(s) => out.push_str(&format!("{k}: {s}\n")),
            other => out.push_str(&format!("{k}: {other}\n")),
        }
    }
    out
}

/// `impact run SCENE.toml [--plot out.svg] [--trace out.json|out.csv]`.
pub fn run_scene(
    path: &std::path::Path,
    format: Format,
    plot: Option<&std::path::Path>,
    trace: Option<&std::path::Path>,
) -> Result<String, RunError> {
    let scene = crate::scene::load(path)?;
    let (v, curves) = match trace {
        Some(file) => {
            // the traced run gives the same outcome to the bit; its curves are not drawn
            let kind = trace_kind(file)?;
            let (v, tr) = run_traced(&scene)?;
            let text = match kind {
                Format::Csv => trace_csv(&tr),
                _ => serde_json::to_string(&tr).unwrap_or_default(),
            };
            write_made(file, "--trace", text)?;
            if plot.is_some() {
                (v, run_validated(&scene)?.1)
            } else {
                (v, Vec::new())
            }
        }
        None => run_validated(&scene)?,
    };
    if let Some(out) = plot {
        if curves.is_empty() {
            return Err(RunError::BadArgument {
                arg: "--plot".into(),
                message: "this model has no plot yet".into(),
            });
        }
        let svg = crate::report::svg::plot_curves(
            &format!("The run of {}: its curves against time", path.display()),
            "t (s)",
            "displacement (m)",
            crate::report::svg::Scale::Linear,
            crate::report::svg::Scale::Linear,
            &curves,
        );
        write_made(out, "--plot", svg)?;
    }
    Ok(render_run(&v, format))
}

/// Writes a file the user named, making its folder if it is not there; errors name the option.
fn write_made(out: &std::path::Path, arg: &str, text: String) -> Result<(), RunError> {
    let bad = |p: &std::path::Path, e: std::io::Error| RunError::BadArgument {
        arg: arg.into(),
        message: format!("{}: {e}", p.display()),
    };
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| bad(dir, e))?;
    }
    std::fs::write(out, text).map_err(|e| bad(out, e))
}

mod rows;
mod sweep;
mod trace;

use rows::{Rows, csv_quote};
pub use sweep::sweep;
use trace::trace_kind;
pub use trace::{TRACED, Trace, run_scene_traced, run_traced, trace_csv};

pub use crate::scene::sweep::{SweepValues, parse_values, parse_vary};

/// `impact merge`: sweep outputs in JSON (from shards of one sweep) merged into one, in index
/// order; every index of the sweep must be present exactly once.
pub fn merge(paths: &[std::path::PathBuf], format: Format) -> Result<String, RunError> {
    let bad = |m: String| RunError::BadArgument {
        arg: "merge".into(),
        message: m,
    };
    let mut param: Option<String> = None;
    let mut total: Option<u64> = None;
    let mut runs: Vec<Value> = Vec::new();
    for p in paths {
        let text = std::fs::read_to_string(p).map_err(|e| bad(format!("{}: {e}", p.display())))?;
        let v: Value = serde_json::from_str(&text)
            .map_err(|e| bad(format!("{}: not a sweep's JSON output: {e}", p.display())))?;
        let this_param = v["param"].as_str().unwrap_or_default().to_string();
        let this_total = v["total"].as_u64();
        if param.get_or_insert(this_param.clone()) != &this_param
            || total.get_or_insert(this_total.unwrap_or(0)) != &this_total.unwrap_or(0)
        {
            return Err(bad(format!(
                "{}: a different sweep (param or total differs)",
                p.display()
            )));
        }
        runs.extend(v["runs"].as_array().cloned().unwrap_or_default());
    }
    runs.sort_by_key(|r| r["index"].as_u64().unwrap_or(u64::MAX));
    let total = total.unwrap_or(0);
    // one pass: count each index; every one of 0..total must appear exactly once
    let mut seen = vec![0u32; total as usize];
    let mut stray = 0usize;
    for r in &runs {
        match r["index"].as_u64().filter(|i| *i < total) {
            Some(i) => seen[i as usize] += 1,
            None => stray += 1,
        }
    }
    if stray > 0 || seen.iter().any(|c| *c != 1) {
        let missing: Vec<usize> = (0..seen.len()).filter(|i| seen[*i] == 0).take(10).collect();
        let twice = seen.iter().filter(|c| **c > 1).count();
        return Err(bad(format!(
            "the shards do not cover the sweep once: {} runs for {total} points; first missing indices {missing:?}; {twice} indices more than once; {stray} runs without a valid index",
            runs.len()
        )));
    }
    let param = param.unwrap_or_default();
    Ok(match format {
        Format::Csv => {
            let results: Vec<Result<Node, String>> = runs
                .iter()
                .map(|r| match r.get("result") {
                    Some(v) => Ok(Node::from_value(v)),
                    None => Err(r["error"].as_str().unwrap_or_default().to_string()),
                })
                .collect();
            let mut cols = csv_columns(&results);
            // as `sweep`: the swept field once, each warning's wording in full once
            cols.retain(|c| *c != param);
            let mut rows = Rows::default();
            for (r, res) in runs.iter().zip(&results) {
                let v = r["value"].as_f64().unwrap_or(f64::NAN);
                let i = r["index"].as_u64().unwrap_or(0) as usize;
                rows.csv(
                    v,
                    i,
                    node_cells(res, &cols).as_ref().map_err(Clone::clone),
                    cols.len(),
                );
            }
            let mut text = csv_header(&param, &cols).into_bytes();
            let mut said = crate::scene::warnings::Said::default();
            let _ = rows.write_to(&mut text, &mut said, 0);
            String::from_utf8(text).unwrap_or_default()
        }
        _ => serde_json::to_string_pretty(&json!({"param": param, "total": total, "runs": runs}))
            .unwrap_or_default(),
    })
}

/// The columns of an outcome: nested objects as `a.b`, numeric arrays as `a.0`, `a.1`;
/// strings and other arrays are left out of the CSV.
fn flatten_row(prefix: &str, v: &Node, out: &mut Vec<String>) {
    match v {
        Node::F64(_) | Node::U64(_) | Node::I64(_) | Node::Bool(_) => out.push(prefix.to_string()),
        Node::Obj(m) => {
            for (k, x) in m {
                let key = if prefix.is_empty() {
                    k.to_string()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten_row(&key, x, out);
            }
        }
        Node::Arr(a) if a.iter().all(Node::is_number) => {
            for (i, x) in a.iter().enumerate() {
                flatten_row(&format!("{prefix}.{i}"), x, out);
            }
        }
        _ => {}
    }
}

/// The CSV columns of some outcomes, in order of first appearance.
fn csv_columns(results: &[Result<Node, String>]) -> Vec<String> {
    let mut cols: Vec<String> = Vec::new();
    for res in results.iter().flatten() {
        let mut row = Vec::new();
        flatten_row("", res, &mut row);
        for k in row {
            if !cols.contains(&k) {
                cols.push(k);
            }
        }
    }
    cols
}

fn csv_header(param: &str, cols: &[String]) -> String {
    format!(
        "{},{},warnings,error,index\n",
        csv_quote(param),
        cols.iter()
            .map(|c| csv_quote(c))
            .collect::<Vec<_>>()
            .join(",")
    )
}

/// The cells of one outcome by column: its numeric and boolean leaves, walked once in the order
/// [`flatten_row`] made the columns (a leaf matches the next column, or is looked for among
/// them); the path of a leaf is built in one reused buffer.
fn csv_cells<'v>(
    v: &'v Node,
    path: &mut String,
    cols: &[String],
    cursor: &mut usize,
    cells: &mut [Option<&'v Node>],
) {
    use std::fmt::Write as _;
    match v {
        Node::F64(_) | Node::U64(_) | Node::I64(_) | Node::Bool(_) => {
            let at = if cols.get(*cursor).is_some_and(|c| c == path) {
                Some(*cursor)
            } else {
                cols.iter().position(|c| c == path)
            };
            if let Some(i) = at {
                cells[i] = Some(v);
                *cursor = i + 1;
            }
        }
        Node::Obj(m) => {
            for (k, x) in m {
                let len = path.len();
                if len > 0 {
                    path.push('.');
                }
                path.push_str(k);
                csv_cells(x, path, cols, cursor, cells);
                path.truncate(len);
            }
        }
        Node::Arr(a) => {
            for (i, x) in a.iter().enumerate() {
                let len = path.len();
                let _ = write!(path, ".{i}");
                csv_cells(x, path, cols, cursor, cells);
                path.truncate(len);
            }
        }
        _ => {}
    }
}

#[cfg(test)]
fn csv_row(v: f64, index: usize, r: &Result<Node, String>, cols: &[String]) -> String {
    let mut line = Vec::new();
    let cells = node_cells(r, cols);
    let (at, warnings) = rows::csv_line(
        &mut line,
        v,
        index,
        cells.as_ref().map_err(Clone::clone),
        cols.len(),
    );
    let (head, tail) = line.split_at(at);
    let (head, tail) = (String::from_utf8_lossy(head), String::from_utf8_lossy(tail));
    format!("{head}{}{tail}", csv_quote(&warnings.join("; ")))
}

/// The cells of an outcome's tree (a merged shard's rows), as [`crate::scene::cells::of`]
/// gives them from the outcome itself.
fn node_cells(r: &Result<Node, String>, cols: &[String]) -> Result<Cells, String> {
    let res = r.as_ref().map_err(Clone::clone)?;
    let mut found = vec![None; cols.len()];
    csv_cells(
        res,
        &mut String::with_capacity(64),
        cols,
        &mut 0,
        &mut found,
    );
    let warnings = match res.get("warnings") {
        Some(Node::Arr(w)) => w
            .iter()
            .filter_map(|x| match x {
                Node::Str(s) => Some(s.to_string()),
                _ => None,
            })
            .collect(),
        _ => Vec::new(),
    };
    Ok(Cells {
        leaves: found.into_iter().map(|n| n.and_then(Leaf::of)).collect(),
        warnings,
        trail: Default::default(),
    })
}

#[cfg(test)]
mod tests {
    use super::sweep::{SWEEP_RUN, SWEEP_WINDOW, sweep_counted};
    use super::*;

    /// A Hertz scene in a fresh folder (`atol` loose enough that each run warns it was tightened).
    fn hertz_scene(name: &str, atol: &str) -> std::path::PathBuf {
        scene_file(
            name,
            &format!(
                "model = \"hertz\"\n[impactor]\nmass = 0.05\nv0 = 1.0\n[contact]\nk = 3e8\n[solve]\nrtol = 1e-9\natol = {atol}\n"
            ),
        )
    }

    /// A scene of `text` in a fresh folder.
    fn scene_file(name: &str, text: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("impactcheck-cli-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&d).expect("a temporary folder");
        let f = d.join("scene.toml");
        std::fs::write(&f, text).expect("the scene written");
        f
    }

    /// A sweep over more than two blocks: every row in index order, each row's cells those of
    /// its outcome's tree (the reference: `run_node` and the tree's own walk, which share no code
    /// with the rows' walk), a warning said in full once and referred to after.
    #[test]
    fn a_sweep_writes_each_point_as_its_outcome_says_across_blocks() {
        let scene = hertz_scene("blocks", "1e-6");
        let n = 2 * SWEEP_WINDOW * SWEEP_RUN + 5;
        let sv = crate::scene::sweep::parse_vary(&format!("impactor.v0=0.5:2:{n}"), false)
            .expect("a range");
        let mut out = Vec::new();
        sweep(&scene, &sv, Format::Csv, false, &mut out).expect("the sweep runs");
        let text = String::from_utf8(out).expect("utf-8");
        let mut lines = text.lines();
        let header = lines.next().expect("a header");
        let cols: Vec<String> = header.split(',').skip(1).map(str::to_string).collect();
        let cols = &cols[..cols.len() - 3];
        assert!(header.ends_with(",warnings,error,index"), "{header}");
        let rows: Vec<&str> = lines.collect();
        assert_eq!(rows.len(), n);
        let base = crate::scene::parse_table(
            &crate::scene::read_table(&scene).expect("reads"),
            "hertz.toml",
        )
        .expect("valid");
        for (i, row) in rows.iter().enumerate() {
            assert!(row.ends_with(&format!(",{i}")), "row {i}: {row}");
            if i % 4099 == 0 || i == n - 1 {
                let v = sv.values[i];
                let tree = base
                    .with_number("impactor.v0", v, "hertz.toml")
                    .expect("a typed field")
                    .expect("in range")
                    .run_node()
                    .map_err(|e| e.to_string());
                let mut want = Vec::new();
                let cells = node_cells(&tree, cols);
                let cells = cells.as_ref().map_err(Clone::clone);
                let (at, _) = rows::csv_line(&mut want, v, i, cells, cols.len());
                let (head, tail) = want.split_at(at);
                let (head, tail) = (String::from_utf8_lossy(head), String::from_utf8_lossy(tail));
                assert!(row.starts_with(&*head), "row {i}: {row} against {head}");
                assert!(
                    row.ends_with(tail.trim_end()),
                    "row {i}: {row} against {tail}"
                );
            }
        }
        assert!(rows[0].contains("atol tightened"), "{}", rows[0]);
        assert!(rows[1].contains("like row 0"), "{}", rows[1]);
        // JSON and text: every point once, in order
        let mut json_out = Vec::new();
        sweep(&scene, &sv, Format::Json, false, &mut json_out).expect("runs");
        let all: Value = serde_json::from_slice(&json_out).expect("one JSON document");
        let runs = all["runs"].as_array().expect("runs");
        assert_eq!(runs.len(), n);
        assert!(runs.iter().enumerate().all(|(i, r)| r["index"] == json!(i)));
        let few = crate::scene::sweep::parse_vary("impactor.v0=0.5:2:3", false).expect("a range");
        let mut text_out = Vec::new();
        sweep(&scene, &few, Format::Text, false, &mut text_out).expect("runs");
        let text = String::from_utf8(text_out).expect("utf-8");
        assert_eq!(text.matches("impactor.v0 = ").count(), 3, "{text}");
    }

    /// A point whose run fails keeps its row, with its error, and is counted: the Hertz impact
    /// written as text, swept over m = -1, -0.5, 0, 0.5, 1. By hand: with m < 0 the force
    /// drives the indentation on (the step size collapses), with m = 0 the force over the mass
    /// is 0/0 at first touch (not finite); 0.5 and 1 rebound. 3 of 5.
    #[test]
    fn a_sweep_counts_the_points_that_failed() {
        let f = scene_file(
            "fail",
            "model = \"ode\"\n[parameters]\nm = 0.05\nk = 3e8\n[units]\nt = \"s\"\nm = \"kg\"\n\
             k = \"N/m^1.5\"\nz = \"m\"\nv = \"m/s\"\n[state]\nz = 0.0\nv = 1.0\n[equations]\n\
             z = \"v\"\nv = \"-k*max(z, 0)^(3/2)/m\"\n[[event]]\nname = \"end\"\nwhen = \"z\"\n\
             direction = \"down\"\naction = \"stop\"\n[solve]\nrtol = 1e-9\natol = 1e-16\nt_end = 1.0\n",
        );
        let sv = crate::scene::sweep::parse_vary("parameters.m=-1:1:5", false).expect("a range");
        for format in [Format::Csv, Format::Json, Format::Text] {
            let mut out = Vec::new();
            let failed = sweep_counted(&f, &sv, format, false, &mut out).expect("the sweep runs");
            assert_eq!(failed, 3, "{format:?}");
            let text = String::from_utf8(out).expect("utf-8");
            assert_eq!(text.matches("step size too small").count(), 2, "{text}");
            assert_eq!(text.matches("non-finite").count(), 1, "{text}");
        }
    }

    /// `impact merge` of a sweep's JSON gives the sweep's own CSV, byte for byte (the rows
    /// through the outcome's tree, not through the outcome: a second path to the same cells),
    /// warnings said once per wording alike; and its JSON holds every run once, in order.
    #[test]
    fn a_merged_json_sweep_is_the_sweeps_csv() {
        let scene = hertz_scene("merge", "1e-6");
        let sv = crate::scene::sweep::parse_vary("impactor.v0=0.5:2:7", false).expect("a range");
        let (mut csv, mut json_out) = (Vec::new(), Vec::new());
        sweep(&scene, &sv, Format::Csv, false, &mut csv).expect("runs");
        sweep(&scene, &sv, Format::Json, false, &mut json_out).expect("runs");
        let shard = scene.with_file_name("sweep.json");
        std::fs::write(&shard, &json_out).expect("written");
        let merged = merge(std::slice::from_ref(&shard), Format::Csv).expect("merges");
        assert_eq!(merged, String::from_utf8(csv).expect("utf-8"));
        assert!(merged.contains("like row 0"), "{merged}");
        let all: Value =
            serde_json::from_str(&merge(&[shard], Format::Json).expect("merges")).expect("JSON");
        let runs = all["runs"].as_array().expect("runs");
        assert!(runs.iter().enumerate().all(|(i, r)| r["index"] == json!(i)));
        assert_eq!(runs.len(), 7);
    }

    /// The expected rows are written out by hand from the outcome's fields.
    #[test]
    fn csv_rows_put_each_leaf_under_its_column() {
        let first = Node::from_value(&json!({
            "b": {"x": 1.5, "y": true}, "a": [1, 2], "warnings": ["w1", "w,2"], "s": "text"
        }));
        let cols = csv_columns(&[Ok(first.clone())]);
        assert_eq!(cols, ["a.0", "a.1", "b.x", "b.y"]);
        assert_eq!(
            csv_header("v", &cols),
            "v,a.0,a.1,b.x,b.y,warnings,error,index\n"
        );
        assert_eq!(
            csv_row(0.5, 3, &Ok(first), &cols),
            "0.5,1,2,1.5,true,\"w1; w,2\",,3\n"
        );
        // a later point without b.x, with a leaf no column has, and a non-number in the array
        let other = Node::from_value(&json!({"a": [null, -4], "b": {"y": false, "z": 9}}));
        assert_eq!(csv_row(2.0, 4, &Ok(other), &cols), "2.0,,-4,,false,,,4\n");
        assert_eq!(
            csv_row(1e-16, 5, &Err("bad, \"one\"".into()), &cols),
            "1e-16,,,,,,\"bad, \"\"one\"\"\",5\n"
        );
    }
}
