//! The native half of the Python package `impactcheck` (issue 55): each function calls the same
//! library code as its command-line twin and hands back that command's JSON as text, which the
//! Python half (`impactcheck/__init__.py`) turns into dicts, arrays and frames. Errors become
//! `impactcheck.ImpactcheckError` with the command line's message (file, line, key); a panic
//! becomes pyo3's `PanicException` and never unwinds into the interpreter.

use impactcheck::cli::{self, Format};
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

/// `impact describe [MODEL] --format json`.
#[pyfunction]
#[pyo3(signature = (model=None))]
fn describe_json(model: Option<&str>) -> PyResult<String> {
    let text = match model {
        Some(m) => serde_json::to_string(impactcheck::scene::describe(m).map_err(err)?),
        None => serde_json::to_string(&impactcheck::scene::DOCS.to_vec()),
    };
    text.map_err(err)
}

/// `impact run SCENE --format json`.
#[pyfunction]
fn run_json(py: Python<'_>, scene: PathBuf) -> PyResult<String> {
    py.detach(|| cli::run_scene(&scene, Format::Json, None))
        .map_err(err)
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
    py.detach(|| {
        let sv = cli::parse_vary(vary, log)?;
        let sv = match shard {
            Some(s) => sv.shard(s)?,
            None => sv,
        };
        let mut out = Vec::new();
        cli::sweep(&scene, &sv, format, false, &mut out)?;
        Ok::<_, cli::RunError>(String::from_utf8_lossy(&out).into_owned())
    })
    .map_err(err)
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
    py.detach(|| -> Result<String, String> {
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
    .map_err(ImpactcheckError::new_err)
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
    py.detach(|| {
        let at = cli::parse_assignments("--at", at)?;
        let times = cli::parse_times(eval_t)?;
        cli::series(order, viscous, &at, &times, Format::Json)
    })
    .map_err(err)
}

/// The paper read and audited as `verify audit` (or, `init`, `verify init`) does; what the
/// command prints on stderr goes to stderr.
fn read_paper(
    paper: &Path,
    units: Option<&Path>,
    preamble: &[PathBuf],
    vocabulary: &[PathBuf],
    init: bool,
) -> anyhow::Result<impactcheck::verify::audit_paper::PaperAudit> {
    impactcheck::verify::audit_paper::audit_paper(
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
    py.detach(|| {
        let p = read_paper(&paper, units.as_deref(), &preamble, &vocabulary, false)?;
        Ok::<_, anyhow::Error>(serde_json::to_string_pretty(&p.audit)?)
    })
    .map_err(|e| err(format!("{e:#}")))
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
    py.detach(|| {
        let p = read_paper(&paper, units.as_deref(), &preamble, &vocabulary, true)?;
        Ok::<_, anyhow::Error>(impactcheck::verify::audit_paper::init_claims(&p, id))
    })
    .map_err(|e| err(format!("{e:#}")))
}

/// A scene given as a dict (its JSON) as TOML text, for the scene reader.
#[pyfunction]
fn toml_of_json(text: &str) -> PyResult<String> {
    let v: serde_json::Value = serde_json::from_str(text).map_err(err)?;
    let t: toml::Value =
        serde_json::from_value(v).map_err(|e| err(format!("a scene dict: {e}")))?;
    match t {
        toml::Value::Table(t) => toml::to_string(&t).map_err(|e| err(format!("a scene dict: {e}"))),
        other => Err(err(format!("a scene is a table, not {}", other.type_str()))),
    }
}

#[pymodule]
fn _impactcheck(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ImpactcheckError", m.py().get_type::<ImpactcheckError>())?;
    m.add_function(wrap_pyfunction!(describe_json, m)?)?;
    m.add_function(wrap_pyfunction!(run_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_text, m)?)?;
    m.add_function(wrap_pyfunction!(verify_json, m)?)?;
    m.add_function(wrap_pyfunction!(toml_of_json, m)?)?;
    m.add_function(wrap_pyfunction!(series_json, m)?)?;
    m.add_function(wrap_pyfunction!(audit_json, m)?)?;
    m.add_function(wrap_pyfunction!(init_text, m)?)?;
    Ok(())
}
