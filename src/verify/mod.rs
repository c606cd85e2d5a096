//! The verifier: the papers' claims as data (`verify/*.toml`), each checked by a computation.
//!
//! A claim names a check; the check computes the verdict ([`Verdict`]) and a detail with the
//! derived and printed values. No verdict is stored in the claim files: it comes from running the
//! check, so a verdict of `fails` is always the output of exact algebra or of numerics with a
//! stated error.

pub mod accuracy;
pub mod hard_cases;
pub mod paper000;
pub mod paper001;
pub mod paper002;
pub mod series_numeric;

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One paper's claim file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperClaims {
    /// The seed's number, "000".
    pub paper: String,
    /// The seed's file name.
    pub file: String,
    /// The paper's title.
    pub title: String,
    /// The report's file name under `reports/`.
    pub report: String,
    /// The claims.
    pub claim: Vec<ClaimSpec>,
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
    /// Which check computes it.
    pub check: String,
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
    /// Scene file used (relative to the repository root).
    #[serde(default)]
    pub scene: Option<String>,
}

/// What a check found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Verdict {
    /// The printed statement is what the computation gives.
    Holds,
    /// It is not; the detail gives derived and printed values and the difference.
    Fails,
    /// The printed form fails but a corrected form, given in the detail, holds.
    HoldsWithCorrection,
    /// The tool cannot check it (the detail says why).
    NotCheckable,
}

impl Verdict {
    /// The verdict as written in reports.
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::HoldsWithCorrection => "holds-with-correction",
            Verdict::NotCheckable => "not-checkable",
        }
    }
}

/// A checked claim, ready for the report.
#[derive(Clone, Debug)]
pub struct Outcome {
    /// Claim id.
    pub id: String,
    /// Seed number.
    pub paper: String,
    /// Equation as printed.
    pub equation: String,
    /// The paper's statement.
    pub quote: String,
    /// The verdict.
    pub verdict: Verdict,
    /// One-paragraph detail: derived vs printed, by how much.
    pub detail: String,
    /// The printed expression in LaTeX, if any.
    pub printed_latex: Option<String>,
    /// The derived expression in LaTeX, if any.
    pub derived_latex: Option<String>,
    /// Extra Markdown (tables, plot links) for the paper's report.
    pub extra_md: Option<String>,
    /// Extra files (plots) to write beside the report: `(file name, contents)`.
    pub files: Vec<(String, String)>,
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
    }
}

impl Outcome {
    /// Attaches a plot written beside the report, shown under `caption`.
    pub(crate) fn with_plot(mut self, caption: &str, name: String, svg: String) -> Outcome {
        self.extra_md = Some(format!("![{caption}]({name})"));
        self.files = vec![(name, svg)];
        self
    }
}

/// `Holds` or `Fails`.
pub(crate) fn holds(b: bool) -> Verdict {
    if b { Verdict::Holds } else { Verdict::Fails }
}

/// Reads every `*.toml` claim file in `dir`, sorted by file name.
pub fn load_claims(dir: &Path) -> Result<Vec<PaperClaims>, VerifyError> {
    let io = |path: &Path, source| VerifyError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).map_err(|e| io(p, e))?;
            toml::from_str::<PaperClaims>(&text).map_err(|e| VerifyError::BadClaims {
                path: p.clone(),
                message: e.to_string(),
            })
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

/// Runs every claim of every paper; scenes named by claims are read relative to `root`.
pub fn run_all(papers: &[PaperClaims], root: &Path) -> Result<Vec<Outcome>, VerifyError> {
    let mut out = Vec::new();
    for p in papers {
        match p.paper.as_str() {
            "000" => {
                let mut ctx = paper000::Context::new(root);
                for c in &p.claim {
                    out.push(paper000::check(&mut ctx, p, c)?);
                }
            }
            "001" => {
                for c in &p.claim {
                    out.push(paper001::check(p, c)?);
                }
            }
            "002" => {
                for c in &p.claim {
                    out.push(paper002::check(p, c)?);
                }
            }
            "hard" => {
                for c in &p.claim {
                    out.push(hard_cases::check(p, c, root)?);
                }
            }
            other => {
                for c in &p.claim {
                    out.push(Outcome {
                        id: c.id.clone(),
                        paper: other.to_string(),
                        equation: c.equation.clone(),
                        quote: c.quote.clone(),
                        verdict: Verdict::NotCheckable,
                        detail: format!("no checks are implemented yet for paper {other}"),
                        printed_latex: None,
                        derived_latex: None,
                        extra_md: None,
                        files: vec![],
                    });
                }
            }
        }
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    Ok(out)
}
