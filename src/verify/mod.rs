//! The verifier: the papers' claims as data (`verify/*.toml`), each checked by a computation.
//!
//! A claim names a check; the check computes the verdict ([`Verdict`]) and a detail with the
//! derived and printed values. No verdict is stored in the claim files: it comes from running the
//! check, so a verdict of `fails` is always the output of exact algebra or of numerics with a
//! stated error.

pub mod accuracy;
pub mod coverage;
pub mod hard_cases;
pub mod kinds;
pub mod paper000;
pub mod paper001;
pub mod paper002;
pub mod series_numeric;

use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One paper's claim file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperClaims {
    /// The paper's short name ("000", "classics"): the first part of every claim id.
    pub paper: String,
    /// The paper's text (a seed's file name, or a reference), if any.
    #[serde(default)]
    pub file: String,
    /// The paper's title.
    pub title: String,
    /// The report's file name under `reports/`.
    pub report: String,
    /// The unit of every symbol a formula uses (`"N/m^1.5"`, `"1"`).
    #[serde(default)]
    pub symbols: BTreeMap<String, String>,
    /// Named formulas (`A1 = "E*zeta*..."`), written once in the paper's notation and used by
    /// name in the claims; their units follow from their formulas.
    #[serde(default)]
    pub definitions: BTreeMap<String, String>,
    /// The claims.
    pub claim: Vec<ClaimSpec>,
    /// Where the file was read from (scenes of generic claims are relative to it).
    #[serde(skip)]
    pub source: PathBuf,
}

/// One claim as listed in `verify/`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClaimSpec {
    /// Stable id, e.g. `000.eq22.a1.t2`.
    pub id: String,
    /// Equation number as printed, "(22)", or "Fig. 2".
    pub equation: String,
    /// One-line quote of what the paper states.
    pub quote: String,
    /// How it is checked: `identity`, `dimension`, `model`, `bound` (generic, [`kinds`]) or
    /// `check` (a named Rust check).
    pub kind: String,
    /// For `kind = "check"`: which Rust check computes it.
    #[serde(default)]
    pub check: String,
    /// The formula as printed, in the paper's notation (`identity`, `dimension`, `model`).
    #[serde(default)]
    pub printed: Option<String>,
    /// Printed equations (their right-hand sides, in order), for checks of systems of equations.
    #[serde(default)]
    pub printed_equations: Vec<String>,
    /// A printed matrix (rows of formulas), for checks of matrix equations.
    #[serde(default)]
    pub printed_matrix: Vec<Vec<String>>,
    /// `identity`: the derived side, a formula or `@name[k=v,...]` (a derivation of the algebra).
    #[serde(default)]
    pub derived: Option<String>,
    /// `identity`: a corrected formula; when the printed one fails and this one holds, the
    /// verdict is `holds-with-correction`.
    #[serde(default)]
    pub corrected: Option<String>,
    /// `identity` of exponential polynomials: compare the first `taylor` Taylor coefficients at
    /// t = 0 (the values of the function and its derivatives there) instead of the functions.
    #[serde(default)]
    pub taylor: Option<u32>,
    /// `identity`: the time symbol of an exponential polynomial (default `t`).
    #[serde(default)]
    pub variable: Option<String>,
    /// `dimension`: the expected unit; `probability`: the claim on the probability
    /// (`"<= 0.15"`, `">= 0.9"`).
    #[serde(default)]
    pub expect: Option<String>,
    /// `model`: the dotted path of the outcome quantity compared.
    #[serde(default)]
    pub quantity: Option<String>,
    /// `model`, `bound`: scene fields set before anything is varied or sampled (a number or a
    /// string: `{ "contact.law" = "newton" }`).
    #[serde(default)]
    pub set: BTreeMap<String, toml::Value>,
    /// Definitions for this claim only (`alpha = "-2*(nu + 1)*lambda/(1 - 2*nu)"`): expanded in
    /// its formulas before the file's definitions, so they may use those and override symbols.
    #[serde(default, rename = "where")]
    pub where_: BTreeMap<String, String>,
    /// `model`, `bound`: formula symbol -> scene field.
    #[serde(default)]
    pub bind: BTreeMap<String, String>,
    /// `model`: the grid, `FIELD=START:STOP:COUNT[:log]` per axis.
    #[serde(default)]
    pub vary: Vec<String>,
    /// `model`: the largest relative difference allowed.
    #[serde(default)]
    pub rtol: Option<f64>,
    /// `bound`: scene field -> distribution (`uniform(a, b)`, `loguniform(a, b)`,
    /// `normal(mu, sigma)`).
    #[serde(default)]
    pub sample: BTreeMap<String, String>,
    /// `bound`: number of samples.
    #[serde(default)]
    pub count: Option<usize>,
    /// `bound`: seed of the generator.
    #[serde(default)]
    pub seed: Option<u64>,
    /// `bound`: the inequality every sample must satisfy (`map`: the region where it holds).
    #[serde(default)]
    pub require: Option<String>,
    /// `probability`: the inequality whose probability is estimated.
    #[serde(default)]
    pub event: Option<String>,
    /// `probability`: the confidence of the Clopper-Pearson interval (default 0.95).
    #[serde(default)]
    pub confidence: Option<f64>,
    /// Plate modes `(m, n)` to check, where relevant.
    #[serde(default)]
    pub modes: Vec<[u32; 2]>,
    /// Galerkin coefficient name, where relevant.
    #[serde(default)]
    pub coefficient: Option<String>,
    /// Part of a series term, where relevant.
    #[serde(default)]
    pub part: Option<String>,
    /// Highest power for identity checks.
    #[serde(default)]
    pub k_max: Option<u32>,
    /// Scene file used: for `kind = "check"` relative to the repository root, for the generic
    /// kinds relative to the claims file.
    #[serde(default)]
    pub scene: Option<String>,
    /// `definition`: the symbol the printed formula defines (its unit must be the formula's).
    #[serde(default)]
    pub defines: Option<String>,
    /// `definition`: identities `[printed, derived]` from the equations that use the definition;
    /// each must hold with the definition substituted.
    #[serde(default)]
    pub agrees: Vec<[String; 2]>,
    /// Any kind: what the verdict assumes beyond the text; a `holds` becomes
    /// `holds-with-assumption` and the detail names it.
    #[serde(default)]
    pub assumption: Option<String>,
    /// `identity` compared in floating point: an absolute tolerance besides the relative 1e-12,
    /// for a side that should be zero (`int(r^2*sin(lam), lam, 0, 2*pi)`).
    #[serde(default)]
    pub atol: Option<f64>,
    /// `not-checkable`: exactly what is missing from the text.
    #[serde(default)]
    pub reason: Option<String>,
}

pub use crate::report::{Outcome, Verdict};

/// What the report writer needs of a claims file ([`crate::report::PaperInfo`]).
pub fn paper_infos(papers: &[PaperClaims]) -> Vec<crate::report::PaperInfo> {
    papers
        .iter()
        .map(|p| crate::report::PaperInfo {
            paper: p.paper.clone(),
            title: p.title.clone(),
            file: p.file.clone(),
            report: p.report.clone(),
        })
        .collect()
}

/// Why verification could not run.
#[derive(Debug, thiserror::Error)]
pub enum VerifyError {
    /// A claim file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        source: std::io::Error,
    },
    /// A claim file is malformed.
    #[error("{path}: {message}")]
    BadClaims {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A claim of a claims file is bad (syntax, unknown symbol, unknown kind, missing scene, a
    /// quantity the model does not produce): found before anything runs.
    #[error("{file}: claim {id}: {field}: {message}")]
    Claim {
        /// The claims file.
        file: String,
        /// The claim.
        id: String,
        /// The key of the claim that is wrong.
        field: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// A claim names a check that does not exist or lacks a parameter.
    #[error("claim {id}: {message}")]
    BadClaim {
        /// The claim.
        id: String,
        /// What is wrong.
        message: String,
    },
    /// A scene named by a claim is bad.
    #[error("claim {id}: {message}")]
    Scene {
        /// The claim.
        id: String,
        /// What is wrong.
        message: String,
    },
    /// An exact computation failed.
    #[error("claim {id}: {source}")]
    Algebra {
        /// The claim.
        id: String,
        /// The error.
        source: crate::algebra::AlgebraError,
    },
}

/// An outcome with no LaTeX, extra Markdown or files.
/// A `holds` under the claim's `assumption` becomes `holds-with-assumption`, the assumption
/// named first in the detail.
pub(crate) fn with_assumption(mut o: Outcome, c: &ClaimSpec) -> Outcome {
    if let Some(a) = &c.assumption {
        if o.verdict == Verdict::Holds {
            o.verdict = Verdict::HoldsWithAssumption;
        }
        o.detail = format!("assuming {a}: {}", o.detail);
    }
    o
}

pub(crate) fn outcome(
    paper: &PaperClaims,
    c: &ClaimSpec,
    verdict: Verdict,
    detail: String,
) -> Outcome {
    Outcome {
        id: c.id.clone(),
        paper: paper.paper.clone(),
        equation: c.equation.clone(),
        quote: c.quote.clone(),
        verdict,
        detail,
        printed_latex: None,
        derived_latex: None,
        extra_md: None,
        files: vec![],
        kind: String::new(),
        extra: BTreeMap::new(),
    }
}

impl Outcome {
    /// Attaches a plot and its data (CSV, written beside it), shown under `caption`.
    pub(crate) fn with_plot(
        mut self,
        caption: &str,
        name: String,
        svg: String,
        csv: String,
    ) -> Outcome {
        let csv_name = name.replace(".svg", ".csv");
        self.extra_md = Some(format!(
            "![{}: {caption}]({name})\n\n*Figure: {caption} (claim {}; data: [{csv_name}]({csv_name})).*",
            self.id, self.id
        ));
        self.files = vec![(name, svg), (csv_name, csv)];
        self
    }
}

/// `Holds` or `Fails`.
pub(crate) fn holds(b: bool) -> Verdict {
    if b { Verdict::Holds } else { Verdict::Fails }
}

/// Reads a claims file, or every `*.toml` claims file of a folder (sorted by file name).
pub fn load_claims(path: &Path) -> Result<Vec<PaperClaims>, VerifyError> {
    let io = |path: &Path, source| VerifyError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut files: Vec<PathBuf> = if path.is_file() {
        vec![path.to_path_buf()]
    } else {
        std::fs::read_dir(path)
            .map_err(|e| io(path, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect()
    };
    files.sort();
    files
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).map_err(|e| io(p, e))?;
            let mut claims =
                toml::from_str::<PaperClaims>(&text).map_err(|e| VerifyError::BadClaims {
                    path: p.clone(),
                    message: e.to_string().trim().replace('\n', " "),
                })?;
            claims.source = p.clone();
            Ok(claims)
        })
        .collect()
}

/// Keeps the papers and claims selected by `only`: a paper number (`002`) or a claim-id prefix
/// (`000.eq22`); `None` keeps everything.
pub fn select(papers: &[PaperClaims], only: Option<&str>) -> Vec<PaperClaims> {
    let Some(only) = only else {
        return papers.to_vec();
    };
    papers
        .iter()
        .filter_map(|p| {
            let mut q = p.clone();
            if p.paper != only {
                q.claim.retain(|c| c.id.starts_with(only));
            }
            (!q.claim.is_empty()).then_some(q)
        })
        .collect()
}

/// Whether `name` may become (part of) a file name under the output folder: letters, digits,
/// `.`, `-` and `_`, not empty and not starting with `.` (so no `..`, no hidden file, no
/// separator: a claims file may come from anyone and never makes `verify` write outside `--out`).
pub fn safe_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_'))
}

/// The names a claims file turns into output paths: its `report` (a plain `.md` file name) and
/// every claim `id` ([`safe_name`]).
pub(crate) fn check_names(file: &PaperClaims) -> Result<(), VerifyError> {
    if !safe_name(&file.report) || !file.report.ends_with(".md") {
        return Err(VerifyError::BadClaims {
            path: file.source.clone(),
            message: format!(
                "report = {:?} is not allowed; allowed: a plain file name ending in .md, of letters, digits, '.', '-' and '_', not starting with '.' (it is written under the output folder)",
                file.report
            ),
        });
    }
    for c in &file.claim {
        if !safe_name(&c.id) {
            return Err(VerifyError::Claim {
                file: file.source.display().to_string(),
                id: c.id.clone(),
                field: "id".into(),
                message: "allowed: letters, digits, '.', '-' and '_', not starting with '.' (an id names the claim's plot and data files under the output folder)".into(),
            });
        }
    }
    Ok(())
}

/// Validates every claims file ([`kinds::Checked`]): a bad claim is found before any claim runs.
pub fn validate_all(papers: &[PaperClaims]) -> Result<(), VerifyError> {
    papers
        .iter()
        .try_for_each(|p| kinds::Checked::validate(p).map(|_| ()))
}

/// What a paper's named checks may use: the folder scenes are read from, and 000's context
/// (its operator check, computed once).
struct Named<'a> {
    root: &'a Path,
    paper000: paper000::Context,
}

/// A paper's named checks (`kind = "check"`), by its short name.
type PaperChecks = fn(&mut Named, &PaperClaims, &ClaimSpec) -> Result<Outcome, VerifyError>;

/// The papers with named Rust checks; a paper not listed has only the generic kinds.
const PAPERS: &[(&str, PaperChecks)] = &[
    ("000", |n, p, c| paper000::check(&mut n.paper000, p, c)),
    ("001", |_, p, c| paper001::check(p, c)),
    ("002", |_, p, c| paper002::check(p, c)),
    ("hard", |n, p, c| hard_cases::check(p, c, n.root)),
];

/// Checks every claim of every paper: first every file is validated ([`kinds::Checked`]: a bad
/// claim stops here, before anything runs), then each claim runs. Scenes named by `check` claims
/// are read relative to `root`, those of the generic kinds relative to their claims file.
pub fn run_all(papers: &[PaperClaims], root: &Path) -> Result<Vec<Outcome>, VerifyError> {
    let checked: Vec<kinds::Checked> = papers
        .iter()
        .map(kinds::Checked::validate)
        .collect::<Result<_, _>>()?;
    let mut derivations = kinds::Derivations::default();
    let mut out = Vec::new();
    for (p, generic) in papers.iter().zip(&checked) {
        let mut ctx = Named {
            root,
            paper000: paper000::Context::new(root),
        };
        for c in &p.claim {
            if c.kind != "check" {
                out.push(generic.check(c, &mut derivations)?);
                continue;
            }
            let mut o = match PAPERS.iter().find(|(name, _)| *name == p.paper) {
                Some((_, run)) => run(&mut ctx, p, c)?,
                None => outcome(
                    p,
                    c,
                    Verdict::NotCheckable,
                    format!(
                        "no Rust checks exist for paper {}: use a generic kind",
                        p.paper
                    ),
                ),
            };
            o.kind = format!("check `{}`", c.check);
            out.push(with_assumption(o, c));
        }
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(out)
}
