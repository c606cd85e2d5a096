//! `impact sweep`: a scene run once per value of a field, in parallel, its rows written in
//! index order as they finish ([`rows::ordered`]), each point's scene the field set in place
//! on one copy of the base per run of points.

use super::rows::{self, Rows};
use super::{Format, RunError, SweepValues, csv_columns, csv_header, render_run, run_validated};
use crate::scene::Scene;
use crate::scene::cells::Trail;
use serde_json::json;

/// Consecutive points run by one thread with their rows in one buffer.
pub(super) const SWEEP_RUN: usize = 64;

/// Runs of points made at most ahead of the one being written (8192 points): memory stays
/// bounded at any sweep size.
pub(super) const SWEEP_WINDOW: usize = 128;

/// A varied `parameters.X` or `state.X` of a text model (`model = "ode"`) that the scene does
/// not have: an error naming it and listing what the scene has (setting it would add a
/// parameter without a unit, and the message would be about its unit).
fn unknown_text_field(table: &toml::Table, param: &str, label: &str) -> Result<(), RunError> {
    if table.get("model").and_then(toml::Value::as_str) != Some("ode") {
        return Ok(());
    }
    let Some((section, key)) = param.split_once('.') else {
        return Ok(());
    };
    if !matches!(section, "parameters" | "state") {
        return Ok(());
    }
    let have: Vec<&str> = table
        .get(section)
        .and_then(toml::Value::as_table)
        .map(|t| t.keys().map(String::as_str).collect())
        .unwrap_or_default();
    if have.contains(&key) {
        return Ok(());
    }
    Err(RunError::BadArgument {
        arg: "--vary".into(),
        message: format!(
            "`{param}` is not in {label}: its {section}: {}",
            have.iter()
                .map(|k| format!("{section}.{k}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    })
}

/// What a run of points keeps from one point to the next: its scene, the varied field set in
/// place (one copy of the base per run, not one per point), and the buffers of its cells.
#[derive(Default)]
struct Carry {
    held: Option<Scene>,
    reuse: crate::scene::cells::Reuse,
}

/// The scene of the point at `v` in `held`, which holds the scene of the point before in the
/// same run of points: the field set in place when the model sets it on its typed parameters
/// ([`Scene::set_number`]: the scene [`Scene::with_number`] gives), else `fresh(v)`.
fn scene_in<'h>(
    held: &'h mut Option<Scene>,
    v: f64,
    param: &str,
    label: &str,
    fresh: &dyn Fn(f64) -> Result<Scene, RunError>,
) -> Result<&'h Scene, RunError> {
    match held.as_mut().and_then(|s| s.set_number(param, v, label)) {
        Some(Ok(())) => {}
        Some(Err(e)) => return Err(e.into()),
        None => *held = None,
    }
    match held {
        Some(scene) => Ok(scene),
        slot @ None => Ok(slot.insert(fresh(v)?)),
    }
}

/// Runs `scene` once per value of the varied field, in parallel, and writes the rows to `out`
/// as they finish (in index order, at most [`SWEEP_WINDOW`] runs of points made ahead). The base
/// scene is validated once; a model that sets the field on its typed parameters
/// ([`crate::models::Model::set_number`]) skips the scene table, others re-read it per point.
pub fn sweep(
    path: &std::path::Path,
    sv: &SweepValues,
    format: Format,
    progress: bool,
    out: &mut dyn std::io::Write,
) -> Result<(), RunError> {
    sweep_counted(path, sv, format, progress, out).map(|_| ())
}

/// [`sweep`], returning the number of points whose run failed (each has its row, with the
/// error).
pub(super) fn sweep_counted(
    path: &std::path::Path,
    sv: &SweepValues,
    format: Format,
    progress: bool,
    out: &mut dyn std::io::Write,
) -> Result<usize, RunError> {
    let base_table = crate::scene::read_table(path)?;
    let label = path.display().to_string();
    let param = sv.param.as_str();
    let base = crate::scene::parse_table(&base_table, &label)?;
    unknown_text_field(&base_table, param, &label)?;
    let scene_at = |v: f64| -> Result<Scene, RunError> {
        let at = || format!("{label} with {param} = {v}");
        if let Some(r) = base.with_number(param, v, &label) {
            return Ok(r?);
        }
        let mut t = base_table.clone();
        crate::scene::set_field(&mut t, param, v, &label)?;
        Ok(crate::scene::parse_table(&t, &at())?)
    };
    // a bad value is an error before anything is written, as for a single run: the values are
    // checked on this thread while the other cores make the first rows, on one copy of the
    // scene (the field set in place: a range check per point on the typed parameters); the
    // first bad value in order is the one reported
    let validate = || -> Result<(), RunError> {
        let mut held = None;
        sv.values
            .iter()
            .try_for_each(|&v| scene_in(&mut held, v, param, &label, &scene_at).map(drop))
    };
    let total = sv.values.len();
    let bar = if progress {
        let b = indicatif::ProgressBar::new(total as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template(&format!(
                "sweep {param} [{{bar:40}}] {{human_pos}}/{{human_len}} ({{msg}}, {{eta}} left)"
            ))
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        b
    } else {
        indicatif::ProgressBar::hidden()
    };
    let io = |e: std::io::Error| RunError::BadArgument {
        arg: "output".into(),
        message: format!("writing the sweep failed: {e}"),
    };
    // the CSV columns: those of the first point's outcome (every point of a model has them)
    let columns = if format == Format::Csv {
        let first = sv.values.first().map(|&v| {
            scene_at(v)
                .and_then(|scene| scene.run_node())
                .map_err(|e| e.to_string())
        });
        // an outcome that echoes the swept field (balls-wall's `wall_stiffness_ratio`) is not
        // written twice: the first column holds it
        let mut cols = csv_columns(first.as_slice());
        cols.retain(|c| c != param);
        cols
    } else {
        Vec::new()
    };
    // the first point's trail: the other points' walks follow it while they meet its steps
    let plan: Trail = match (format, sv.values.first()) {
        (Format::Csv, Some(&v)) => scene_at(v)
            .and_then(|scene| {
                let mut into = crate::scene::cells::Reuse::default();
                scene
                    .run_cells(&columns, &Trail::default(), &mut into)
                    .map(|c| c.trail.clone())
            })
            .unwrap_or_default(),
        _ => Trail::default(),
    };
    // one point, formatted where it ran (in parallel) and appended to the rows of its run of
    // points: for CSV its warnings apart (said once per wording, in index order)
    let row = |rows: &mut Rows, carry: &mut Carry, v: f64, i: usize| {
        let scene = scene_in(&mut carry.held, v, param, &label, &scene_at);
        match format {
            Format::Json => {
                // one run per line (compact): a sweep of 10^7 runs stays greppable and small;
                // the outcome written from its light tree, as its `Value` would be
                match scene.and_then(|scene| scene.run_node()) {
                    Ok(res) => {
                        let line = rows.open(",\n    ", false);
                        line.extend_from_slice(b"{\"index\":");
                        let _ = serde_json::to_writer(&mut *line, &i);
                        line.extend_from_slice(b",\"value\":");
                        let _ = serde_json::to_writer(&mut *line, &v);
                        line.extend_from_slice(b",\"result\":");
                        res.write_json(line);
                        line.push(b'}');
                    }
                    Err(e) => rows.line(
                        ",\n    ",
                        &json!({"index": i, "value": v, "error": e.to_string()}).to_string(),
                        true,
                    ),
                }
            }
            Format::Csv => {
                // the cells straight from the outcome (no tree), the first point's walk as plan
                // (the run's buffers reused from point to point)
                match scene {
                    Ok(scene) => {
                        let r = scene.run_cells(&columns, &plan, &mut carry.reuse);
                        rows.csv(v, i, r.map_err(|e| e.to_string()), columns.len());
                    }
                    Err(e) => rows.csv(v, i, Err(e.to_string()), columns.len()),
                }
            }
            _ => match scene.and_then(run_validated) {
                Ok((res, _)) => {
                    let text = render_run(&res, Format::Text);
                    rows.line("\n", &format!("{param} = {}\n{text}\n", json!(v)), false);
                }
                Err(e) => rows.line("\n", &format!("{param} = {}\nerror: {e}\n", json!(v)), true),
            },
        }
        if progress {
            bar.inc(1);
        }
    };
    let mut said = crate::scene::warnings::Said::default();
    let started = std::time::Instant::now();
    let mut failed = 0;
    // the values checked, then the head of the output, before the first row is written (or
    // at the end, when there is none)
    let open = |out: &mut dyn std::io::Write| -> Result<(), RunError> {
        validate()?;
        if format == Format::Json {
            write!(
                out,
                "{{\n  \"param\": {},\n  \"total\": {},\n  \"runs\": [",
                serde_json::to_string(param).unwrap_or_default(),
                sv.total
            )
            .map_err(io)?;
        }
        if format == Format::Csv {
            out.write_all(csv_header(param, &columns).as_bytes())
                .map_err(io)?;
        }
        Ok(())
    };
    let mut opened = false;
    // the separator before the first row of the sweep is left out (JSON and text rows open
    // with one; a CSV row does not)
    let mut skip = usize::from(format != Format::Csv);
    let make = |k: usize, rows: &mut Rows| {
        let at = k * SWEEP_RUN..total.min((k + 1) * SWEEP_RUN);
        let mut carry = Carry::default();
        for (&v, &i) in sv.values[at.clone()].iter().zip(&sv.indices[at]) {
            row(rows, &mut carry, v, i);
        }
    };
    let mut k = 0usize;
    let write = |rows: &Rows| -> Result<(), RunError> {
        if !opened {
            open(out)?;
            opened = true;
        }
        failed += rows.failed;
        rows.write_to(out, &mut said, skip).map_err(io)?;
        skip = 0;
        // the rate as a reader says it: whole points per second (indicatif's `per_sec` prints
        // "83,589.898/s"), every window of runs
        k += 1;
        let secs = started.elapsed().as_secs_f64();
        if k.is_multiple_of(SWEEP_WINDOW) && secs > 0.0 {
            bar.set_message(format!("{:.0} points/s", bar.position() as f64 / secs));
        }
        Ok(())
    };
    rows::ordered(total.div_ceil(SWEEP_RUN), SWEEP_WINDOW, make, write)?;
    if !opened {
        open(out)?;
    }
    if format == Format::Json {
        out.write_all(b"\n  ]\n}\n").map_err(io)?;
    }
    out.flush().map_err(io)?;
    bar.finish_and_clear();
    for line in said.summary() {
        eprintln!("sweep: {line}");
    }
    if failed > 0 {
        eprintln!("sweep: {failed} of {total} points failed (their rows carry the error)");
    }
    Ok(failed)
}
