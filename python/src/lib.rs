//! The native half of the Python package `impactcheck` (issue 55): each function calls the same
//! library code as its command-line twin and hands back that command's JSON as text, which the
//! Python half (`impactcheck/__init__.py`) turns into dicts, arrays and frames. Errors become
//! `impactcheck.ImpactcheckError` with the command line's message (file, line, key); so does a
//! panic ([`guarded`]), which never unwinds into the interpreter.

use anyhow::Context;
use impactcheck::cli::{self, Format};
use impactcheck::paper::audit::shelf;
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

create_exception!(
    _impactcheck,
    ImpactcheckError,
    PyException,
    "Bad input or a failed job, with the command line's message."
);

fn err(e: impl std::fmt::Display) -> PyErr {
    ImpactcheckError::new_err(e.to_string())
}

/// Runs a job with the interpreter released. Its error becomes `ImpactcheckError` with the
/// command line's message (a chain of causes written out, as `{:#}` writes them); a panic, which
/// would be a bug, is caught here and becomes `ImpactcheckError` too, so that no panic unwinds
/// into the interpreter and `except Exception` sees it (pyo3's own `PanicException` derives
/// from `BaseException`).
fn guarded<T, E>(py: Python<'_>, job: impl FnOnce() -> Result<T, E> + Send) -> PyResult<T>
where
    T: Send,
    E: std::fmt::Display + Send,
{
    py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(job)))
        .map_err(|payload| {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".into());
            err(format!(
                "internal error (a bug in impactcheck; please report it with the input): {what}"
            ))
        })?
        .map_err(|e| err(format!("{e:#}")))
}

/// Panics inside [`guarded`], with `message`: how the tests show that a panic reaches Python as
/// `ImpactcheckError` and leaves the interpreter alive. Not part of the package's interface.
#[pyfunction]
fn _panic_for_test(py: Python<'_>, message: String) -> PyResult<()> {
    guarded(py, || -> Result<(), String> { panic!("{message}") })
}

/// `impact describe [MODEL] --format json`.
#[pyfunction]
#[pyo3(signature = (model=None))]
fn describe_json(py: Python<'_>, model: Option<&str>) -> PyResult<String> {
    guarded(py, || match model {
        Some(m) => impactcheck::scene::describe(m)
            .and_then(|d| serde_json::to_string(d).map_err(|e| e.to_string())),
        None => {
            serde_json::to_string(&impactcheck::scene::DOCS.to_vec()).map_err(|e| e.to_string())
        }
    })
}

/// `impact run SCENE --format json --trace FILE.json`: the outcome's JSON (what the command
/// prints) and the path's (what it writes), or why there is no path (what `--trace` says).
#[pyfunction]
fn run_traced_json(
    py: Python<'_>,
    scene: PathBuf,
) -> PyResult<(String, Option<String>, Option<String>)> {
    guarded(py, || {
        let (outcome, trace) = cli::run_scene_traced(&scene, Format::Json)?;
        Ok::<_, cli::RunError>(match trace {
            Ok(t) => (
                outcome,
                Some(serde_json::to_string(&t).unwrap_or_default()),
                None,
            ),
            Err(why) => (outcome, None, Some(why)),
        })
    })
}

/// `impact sweep SCENE --vary VARY [--log] [--shard K/N] --format FORMAT`: the runs in index
/// order, as `json` (one run per line) or `csv` (the rows).
#[pyfunction]
#[pyo3(signature = (scene, vary, format, log=false, shard=None))]
fn sweep_text(
    py: Python<'_>,
    scene: PathBuf,
    vary: &str,
    format: &str,
    log: bool,
    shard: Option<&str>,
) -> PyResult<String> {
    let format = match format {
        "json" => Format::Json,
        "csv" => Format::Csv,
        other => return Err(err(format!("format {other:?}: a sweep is json or csv"))),
    };
    guarded(py, || {
        let sv = cli::parse_vary(vary, log)?;
        let sv = match shard {
            Some(s) => sv.shard(s)?,
            None => sv,
        };
        let mut out = Vec::new();
        cli::sweep(&scene, &sv, format, false, &mut out)?;
        Ok::<_, cli::RunError>(String::from_utf8_lossy(&out).into_owned())
    })
}

/// The folder `check` claims name scenes from, as `verify` takes it: the one above the claims
/// folder (or above the claims file's folder).
fn claims_root(claims: &Path) -> PathBuf {
    let p = claims
        .canonicalize()
        .unwrap_or_else(|_| claims.to_path_buf());
    let dir = if p.is_file() {
        p.parent().map(Path::to_path_buf).unwrap_or(p)
    } else {
        p
    };
    dir.parent().map(Path::to_path_buf).unwrap_or(dir)
}

/// `verify [--claims PATH] [--only PREFIX] [--power] --format json`: the summary, nothing
/// written.
#[pyfunction]
#[pyo3(signature = (claims=None, only=None, power=false))]
fn verify_json(
    py: Python<'_>,
    claims: Option<PathBuf>,
    only: Option<&str>,
    power: bool,
) -> PyResult<String> {
    // the repository's own claims when none are named: the one this package was built from
    let claims = claims.unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../verify"));
    guarded(py, || -> Result<String, String> {
        let all = impactcheck::verify::load_claims_with(&claims, None)
            .map_err(|e| format!("reading claims from {}: {e}", claims.display()))?;
        let papers = impactcheck::verify::select(&all, only);
        if papers.is_empty() {
            return Err(format!(
                "no claims match --only {}",
                only.unwrap_or_default()
            ));
        }
        impactcheck::verify::validate_all(&papers).map_err(|e| e.to_string())?;
        let mut outcomes = impactcheck::verify::run_measured(
            &papers,
            &claims_root(&claims),
            impactcheck::verify::kinds::BUILTIN,
            &|_| power,
        )
        .map_err(|e| e.to_string())?;
        outcomes.sort_by(|a, b| impactcheck::report::natural_cmp(&a.id, &b.id));
        serde_json::to_string(&impactcheck::report::summary(&outcomes)).map_err(|e| e.to_string())
    })
}

/// `impact series --order N [--viscous zz|2zz] [--at A] [--eval-t T] --format json`: the
/// Adomian terms of 000 (18)-(20), exactly.
#[pyfunction]
#[pyo3(signature = (order, viscous="2zz", at="", eval_t=""))]
fn series_json(
    py: Python<'_>,
    order: usize,
    viscous: &str,
    at: &str,
    eval_t: &str,
) -> PyResult<String> {
    let viscous = match viscous {
        "2zz" => impactcheck::algebra::series::Viscous::TwoZZ,
        "zz" => impactcheck::algebra::series::Viscous::ZZ,
        other => return Err(err(format!("viscous {other:?}: \"2zz\" or \"zz\""))),
    };
    guarded(py, || {
        let at = cli::parse_assignments("--at", at)?;
        let times = cli::parse_times(eval_t)?;
        cli::series(order, viscous, &at, &times, Format::Json)
    })
}

/// The paper read and audited as `verify audit` (or, `init`, `verify init`) does; what the
/// command prints on stderr goes to stderr.
fn read_paper(
    paper: &Path,
    units: Option<&Path>,
    preamble: &[PathBuf],
    vocabulary: &[PathBuf],
    init: bool,
) -> anyhow::Result<impactcheck::paper::audit::paper::PaperAudit> {
    impactcheck::paper::audit::paper::audit_paper(
        paper,
        units,
        preamble,
        vocabulary,
        init,
        &mut |line| eprintln!("verify: {line}"),
    )
}

/// `verify audit PAPER [--units FILE] [--preamble F]... [--vocabulary F]... --format json`; what
/// the command prints on stderr goes to stderr.
#[pyfunction]
#[pyo3(signature = (paper, units=None, preamble=vec![], vocabulary=vec![]))]
fn audit_json(
    py: Python<'_>,
    paper: PathBuf,
    units: Option<PathBuf>,
    preamble: Vec<PathBuf>,
    vocabulary: Vec<PathBuf>,
) -> PyResult<String> {
    guarded(py, || {
        let p = read_paper(&paper, units.as_deref(), &preamble, &vocabulary, false)?;
        Ok::<_, anyhow::Error>(serde_json::to_string_pretty(&p.audit)?)
    })
}

/// The papers `verify audit FOLDER` audits, in its order: paths under `folder` as given. A
/// folder without a paper is an error, as for the command.
#[pyfunction]
fn papers_in(py: Python<'_>, folder: PathBuf) -> PyResult<Vec<String>> {
    guarded(py, || {
        let papers = shelf::papers_in(&folder)
            .with_context(|| format!("reading the folder {}", folder.display()))?;
        if papers.is_empty() {
            anyhow::bail!(
                "{}: no paper (a .tex with \\documentclass or a .md with display math)",
                folder.display()
            );
        }
        Ok(papers
            .iter()
            .map(|p| p.to_string_lossy().into_owned())
            .collect())
    })
}

/// One row of `verify audit FOLDER --format json`: `paper` (a path `papers_in(folder)` gave)
/// audited and named by its path under `folder`; a paper that cannot be read is a row with its
/// error, as in the command.
#[pyfunction]
#[pyo3(signature = (folder, paper, units=None, preamble=vec![], vocabulary=vec![]))]
fn audit_row_json(
    py: Python<'_>,
    folder: PathBuf,
    paper: PathBuf,
    units: Option<PathBuf>,
    preamble: Vec<PathBuf>,
    vocabulary: Vec<PathBuf>,
) -> PyResult<String> {
    guarded(py, || {
        let name = paper
            .strip_prefix(&folder)
            .unwrap_or(&paper)
            .to_string_lossy()
            .into_owned();
        let row = match impactcheck::paper::audit::paper::audit_paper(
            &paper,
            units.as_deref(),
            &preamble,
            &vocabulary,
            false,
            &mut |_| {},
        ) {
            Ok(p) => shelf::row_of(name, &p.audit),
            Err(e) => shelf::ShelfRow {
                paper: name,
                error: Some(format!("{e:#}")),
                ..Default::default()
            },
        };
        serde_json::to_string(&row)
    })
}

/// `verify init PAPER --paper ID [--units FILE] ...`: the claims file to start from, as text.
#[pyfunction]
#[pyo3(signature = (paper, id, units=None, preamble=vec![], vocabulary=vec![]))]
fn init_text(
    py: Python<'_>,
    paper: PathBuf,
    id: &str,
    units: Option<PathBuf>,
    preamble: Vec<PathBuf>,
    vocabulary: Vec<PathBuf>,
) -> PyResult<String> {
    guarded(py, || {
        let p = read_paper(&paper, units.as_deref(), &preamble, &vocabulary, true)?;
        Ok::<_, anyhow::Error>(impactcheck::paper::audit::paper::init_claims(&p, id))
    })
}

/// A scene given as a dict (its JSON) as TOML text, for the scene reader.
#[pyfunction]
fn toml_of_json(py: Python<'_>, text: &str) -> PyResult<String> {
    guarded(py, || {
        let v: serde_json::Value = serde_json::from_str(text).map_err(|e| e.to_string())?;
        let t: toml::Value = serde_json::from_value(v).map_err(|e| format!("a scene dict: {e}"))?;
        match t {
            toml::Value::Table(t) => toml::to_string(&t).map_err(|e| format!("a scene dict: {e}")),
            other => Err(format!("a scene is a table, not {}", other.type_str())),
        }
    })
}

#[pymodule]
fn _impactcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ImpactcheckError", m.py().get_type::<ImpactcheckError>())?;
    m.add_function(wrap_pyfunction!(describe_json, m)?)?;
    m.add_function(wrap_pyfunction!(run_traced_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_text, m)?)?;
    m.add_function(wrap_pyfunction!(verify_json, m)?)?;
    m.add_function(wrap_pyfunction!(toml_of_json, m)?)?;
    m.add_function(wrap_pyfunction!(series_json, m)?)?;
    m.add_function(wrap_pyfunction!(audit_json, m)?)?;
    m.add_function(wrap_pyfunction!(init_text, m)?)?;
    m.add_function(wrap_pyfunction!(papers_in, m)?)?;
    m.add_function(wrap_pyfunction!(audit_row_json, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_test, m)?)?;
    Ok(())
}
