//! What a checked claim is, as the report renders it: plain data that the verifier fills (the
//! report knows nothing of claims files or kinds).

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

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
    /// A definition, found consistent: its units agree and the equations that use it hold with
    /// it substituted (kind `definition`).
    Definition,
    /// It holds under an assumption the claim names (`assumption`), which the text does not
    /// state or the computation cannot decide.
    HoldsWithAssumption,
}

impl Verdict {
    /// The verdict as written in reports.
    pub fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::Fails => "fails",
            Verdict::HoldsWithCorrection => "holds-with-correction",
            Verdict::NotCheckable => "not-checkable",
            Verdict::Definition => "definition",
            Verdict::HoldsWithAssumption => "holds-with-assumption",
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
    /// The paper's words (checked against its text when found; empty without a quote).
    pub quote: String,
    /// The claims file's reading of what is checked (not the paper's words).
    pub reading: Option<String>,
    /// The verdict.
    pub verdict: Verdict,
    /// One-paragraph detail: derived vs printed, by how much.
    pub detail: String,
    /// The printed expression in LaTeX, if any.
    pub printed_latex: Option<String>,
    /// The printed side as the claim checks it (the formula language), when it has one: read
    /// from the paper's LaTeX (`printed_from`, `printed_tex`) or typed in the claims file.
    pub printed: Option<String>,
    /// The derived expression in LaTeX, if any.
    pub derived_latex: Option<String>,
    /// Extra Markdown (tables, plot links) for the paper's report.
    pub extra_md: Option<String>,
    /// Extra files (plots) to write beside the report: `(file name, contents)`.
    pub files: Vec<(String, String)>,
    /// How the verdict was computed: the claim's kind, and for `check` the Rust check's name.
    pub kind: String,
    /// Numbers a kind adds to the JSON of the claim (`probability`, `valid_fraction`).
    pub extra: BTreeMap<String, serde_json::Value>,
    /// The power of the claim's check, when measured (`verify --power`).
    pub power: Option<Power>,
    /// The error it shows, named as every claim that shows it names it (`finding`).
    pub finding: Option<String>,
    /// What the claim tests beyond the paper (`extends`): its verdict is the tool's extension.
    pub extends: Option<String>,
    /// Why its printed side is typed by hand, not read from the paper's LaTeX (`retyped`).
    pub retyped: Option<String>,
}

/// The power of a claim's check: how many misprints of its printed side it sees.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Power {
    /// Misprints run (equivalent and merely weakening ones not counted).
    pub mutants: usize,
    /// Misprints whose verdict differs from the claim's.
    pub killed: usize,
    /// The misprints that kept the verdict: which key, and what was changed.
    pub survivors: Vec<String>,
    /// Misprints of an inequality that only weaken it (still true; not counted).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub excused: usize,
    /// Why the power was not measured (a failing claim, no printed side in the claims file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub not_measured: Option<String>,
    /// What the check cannot see, as its claim or kind states it (`blind`), given when a
    /// misprint survives.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blind: Option<String>,
    /// The one text its misprints were made in, when they were all made in one (a claim's
    /// `require`, `printed`): claims of a paper misprinting the same text are one formula
    /// ([`super::formulas`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub formula: Option<String>,
    /// The misprints it killed, named as `survivors` (so that a formula's misprint is caught
    /// when any claim on it killed it, [`super::formulas`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub killed_names: Vec<String>,
    /// The misprints not run because they state the same as the printed side (a side against
    /// zero times a factor), named as `survivors`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub equivalent: Vec<String>,
    /// The misprints of an inequality that only weakened it (`excused`), named as `survivors`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub weaker: Vec<String>,
    /// The misprints that could not be applied, each with why (a printed key that is not a
    /// formula, such as a value the claim computes, `@series.a1`): a gap, so the claim is not
    /// called strong.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub not_applied: Vec<String>,
    /// What it was measured from (`verify::power_cache`): the main job reuses it while
    /// the key is the same.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub key: Option<String>,
    /// The claim checked with its finding's correction applied (`verify::correction`), for a
    /// claim that fails or holds only with a correction and states one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub correction: Option<Corrected>,
}

/// A claim checked with its finding's correction applied.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Corrected {
    /// Whether it then holds.
    pub holds: bool,
    /// Its verdict then.
    pub verdict: Verdict,
    /// Its detail then.
    pub detail: String,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Outcome {
    /// The outcome of claim `id` of `paper` at `equation`: its verdict and detail, nothing else.
    pub(crate) fn new(
        id: &str,
        paper: &str,
        equation: &str,
        verdict: Verdict,
        detail: String,
    ) -> Outcome {
        Outcome {
            id: id.into(),
            paper: paper.into(),
            equation: equation.into(),
            quote: String::new(),
            reading: None,
            verdict,
            detail,
            printed_latex: None,
            printed: None,
            derived_latex: None,
            extra_md: None,
            files: vec![],
            kind: String::new(),
            extra: BTreeMap::new(),
            power: None,
            finding: None,
            extends: None,
            retyped: None,
        }
    }

    /// A bare outcome of claim `id` of paper `p` (for the report writers' tests).
    #[cfg(test)]
    pub(crate) fn bare(id: &str, verdict: Verdict) -> Outcome {
        Outcome::new(id, "p", "(1)", verdict, String::new())
    }
}

impl Power {
    /// Power that was not measured, and why.
    pub fn not_measured(why: String) -> Power {
        Power {
            not_measured: Some(why),
            ..Power::default()
        }
    }

    /// Whether a misprint survived: the check cannot see it.
    pub fn weak(&self) -> bool {
        !self.survivors.is_empty() || !self.not_applied.is_empty()
    }

    /// The share of the mutants killed (`None` when none was run).
    pub fn score(&self) -> Option<f64> {
        (self.mutants > 0).then(|| self.killed as f64 / self.mutants as f64)
    }
}

/// What the report needs of a paper: its short name, title, source file and report file name.
#[derive(Clone, Debug)]
pub struct PaperInfo {
    /// Short name ("002").
    pub paper: String,
    /// Title.
    pub title: String,
    /// Where its text is (a seed file name, or free text).
    pub file: String,
    /// The report's file name.
    pub report: String,
}
