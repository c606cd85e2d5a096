//! The verifier: the papers' claims as data (`verify/*.toml`), each checked by a computation.
//!
//! A claim names a check; the check computes the verdict ([`Verdict`]) and a detail with the
//! derived and printed values. No verdict is stored in the claim files: it comes from running the
//! check, so a verdict of `fails` is always the output of exact algebra or of numerics with a
//! stated error.

pub mod accuracy;
pub mod audit_reports;
pub mod correction;
pub mod coverage;
mod fingerprint;
/// FNV-1a with a 128-bit state: a stable hash for change detection (the keys of
/// [`power_cache`]), shared with `build.rs`, which `include!`s this file to hash the
/// code. Written by hand: it is ten lines, its only job is to notice a change (not to resist an
/// adversary, where a SHA crate would be the tool), and std's `DefaultHasher` is not stable
/// across Rust releases, so a key written by one toolchain could not be read by another.
pub mod fnv;
pub mod hard_cases;
pub mod kinds;
pub mod paper000;
pub mod paper001;
pub mod paper002;
pub mod phases;
pub mod power;
pub mod power_cache;
mod power_targets;
pub mod series_numeric;
pub mod tex_claims;

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
    /// Named formulas read from the paper's LaTeX (`a1_22 = { tag = "(22)", lhs = "a_{1}(t)" }`,
    /// or `{ after = "(2.9)", lhs = "\\delta" }` for the untagged display after an equation):
    /// resolved into `definitions` ([`tex_claims`]).
    #[serde(default)]
    pub definitions_from: BTreeMap<String, toml::Value>,
    /// The LaTeX each definition of `definitions_from` was read from, for the report.
    #[serde(skip)]
    pub definitions_latex: BTreeMap<String, String>,
    /// The paper's numbered equations (its `\\tag{...}` labels, in order), taken from the text
    /// once: coverage is counted from this list, and checked against the text when it is found.
    #[serde(default)]
    pub equations: Vec<String>,
    /// LaTeX spellings mapped to symbols for `printed_tex` and `printed_from`
    /// (`"\\tilde{E}" = "Et"`, `"z(t)" = "z"`; [`tex_claims`]).
    #[serde(default)]
    pub tex_symbols: BTreeMap<String, String>,
    /// Units of symbols that only `verify audit` uses (symbols of the paper's relations that no
    /// claim names: kept apart from `[symbols]`, whose units the power measurement draws its
    /// symbol swaps from).
    #[serde(default)]
    pub audit_symbols: BTreeMap<String, String>,
    /// The claims (none in a scaffold of a paper none of whose relations the audit could judge).
    #[serde(default)]
    pub claim: Vec<ClaimSpec>,
    /// Where the file was read from (scenes of generic claims are relative to it).
    #[serde(skip)]
    pub source: PathBuf,
    /// Where the papers' texts are looked for first (`verify --papers DIR`), before the folder
    /// of the claims file.
    #[serde(skip)]
    pub papers_dir: Option<PathBuf>,
}

/// What every claim has, whatever its kind.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Head {
    /// Stable id, e.g. `000.eq22.a1.t2`.
    pub id: String,
    /// Equation number as printed, "(22)", or "Fig. 2".
    pub equation: String,
    /// The paper's own words for what the claim checks (checked against the paper's text
    /// when it is found: whitespace, `$` and LaTeX spacing aside; `...` stands for words left
    /// out). Empty when the claim has only a `reading`.
    #[serde(default)]
    pub quote: String,
    /// What the claim checks, in the claims file's words (a formula the paper prints is read
    /// with `printed_from`, a statement it makes in prose is its `quote`): the report shows it
    /// as a reading, never as the paper's words.
    #[serde(default)]
    pub reading: Option<String>,
    /// How it is checked: a kind of [`kinds::BUILTIN`] (`identity`, `model`, ..., or `check`,
    /// a named Rust check).
    pub kind: String,
    /// What the verdict assumes beyond the text; a `holds` becomes `holds-with-assumption` and
    /// the detail names it.
    #[serde(default)]
    pub assumption: Option<String>,
    /// What the claim's check cannot see: the misprints of its printed side that keep its
    /// verdict, and why ([`power`]; the report gives it beside a weak claim).
    #[serde(default)]
    pub blind: Option<String>,
    /// The error the claim shows, as a short name shared by every claim that shows it (a
    /// wrong coefficient seen in seven terms of one equation is one finding): the reports count
    /// distinct findings beside claims.
    #[serde(default)]
    pub finding: Option<String>,
    /// What the claim tests beyond what the paper states (a range, a model, a condition the
    /// paper's assumptions exclude): its verdict is the tool's extension, not the paper's error,
    /// and a fail of it is no finding.
    #[serde(default)]
    pub extends: Option<String>,
    /// The finding's correction: the claim's keys as the paper should have printed them
    /// (`correction = { printed = "..." }`), each replacing the key of its name; applied, the
    /// claim must hold ([`correction`]).
    #[serde(default)]
    pub correction: Option<toml::Table>,
    /// The entries of the claim's `where` that the paper prints (its definitions, not test
    /// inputs): misprinted by [`power`] as the printed side is.
    #[serde(default)]
    pub printed_where: Vec<String>,
    /// Why the printed side is typed by hand rather than read from the paper's LaTeX
    /// (`printed_from`): a formula printed in prose, a number read off a figure, a form the
    /// reader has no construct for. The report shows it; reports/README.md counts both.
    #[serde(default)]
    pub retyped: Option<String>,
    /// The LaTeX the printed side was read from (`printed_tex`, `printed_from`), for the report.
    #[serde(skip)]
    pub tex: Option<String>,
    /// The printed keys read from the paper as conditions, `left - right` (`form =
    /// "difference"`: `printed`, `printed_equations[0]`): `c (left - right) = 0` states the same.
    #[serde(skip)]
    pub conditions: Vec<String>,
}

impl Head {
    /// The keys of a head; every other key of a claim belongs to its kind.
    const KEYS: [&str; 12] = [
        "id",
        "equation",
        "quote",
        "reading",
        "kind",
        "assumption",
        "blind",
        "finding",
        "extends",
        "retyped",
        "correction",
        "printed_where",
    ];
}

/// One claim as listed in `verify/`: its [`Head`] and the keys of its kind, which the kind's
/// spec reads ([`kinds::Kind::Spec`], `deny_unknown_fields`).
#[derive(Clone, Debug)]
pub struct ClaimSpec {
    /// The claim's head.
    pub head: Head,
    /// The kind's keys, as written.
    pub keys: toml::Table,
}

impl std::ops::Deref for ClaimSpec {
    type Target = Head;
    fn deref(&self) -> &Head {
        &self.head
    }
}

impl<'de> Deserialize<'de> for ClaimSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let mut keys = toml::Table::deserialize(d)?;
        let mut head = toml::Table::new();
        for k in Head::KEYS {
            if let Some(v) = keys.remove(k) {
                head.insert(k.to_string(), v);
            }
        }
        let id = head
            .get("id")
            .and_then(|v| v.as_str())
            .unwrap_or("?")
            .to_string();
        let head: Head = toml::Value::Table(head)
            .try_into()
            .map_err(|e: toml::de::Error| {
                D::Error::custom(format!("claim {id}: {}", e.message()))
            })?;
        Ok(ClaimSpec { head, keys })
    }
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
    /// A claim file could not be read (the OS error is in the message, not a `source`, so that
    /// a chain of causes prints it once).
    #[error("{path}: cannot read: {error}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The error.
        error: std::io::Error,
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
pub(crate) fn with_assumption(mut o: Outcome, c: &Head) -> Outcome {
    if let Some(a) = &c.assumption {
        if o.verdict == Verdict::Holds {
            o.verdict = Verdict::HoldsWithAssumption;
        }
        o.detail = format!("assuming {a}: {}", o.detail);
    }
    o
}

pub(crate) fn outcome(paper: &PaperClaims, c: &Head, verdict: Verdict, detail: String) -> Outcome {
    Outcome {
        quote: c.quote.clone(),
        reading: c.reading.clone(),
        finding: c.finding.clone(),
        extends: c.extends.clone(),
        retyped: c.retyped.clone(),
        ..Outcome::new(&c.id, &paper.paper, &c.equation, verdict, detail)
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
    load_claims_with(path, None)
}

/// [`load_claims`], with the papers' texts looked for in `papers` first (`verify --papers`).
pub fn load_claims_with(
    path: &Path,
    papers: Option<&Path>,
) -> Result<Vec<PaperClaims>, VerifyError> {
    let io = |path: &Path, error| VerifyError::Io {
        path: path.to_path_buf(),
        error,
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
                    message: crate::scene::toml_message(&e, &text),
                })?;
            claims.source = p.clone();
            claims.papers_dir = papers.map(Path::to_path_buf);
            tex_claims::resolve(&mut claims)?;
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
        if let Some(f) = &c.finding
            && !safe_name(f)
        {
            return Err(VerifyError::Claim {
                file: file.source.display().to_string(),
                id: c.id.clone(),
                field: "finding".into(),
                message: format!(
                    "{f:?}: allowed: a short name of letters, digits, '.', '-' and '_' (e.g. \"000-missing-h\")"
                ),
            });
        }
        if c.quote.trim().is_empty() && c.reading.as_deref().is_none_or(|r| r.trim().is_empty()) {
            return Err(VerifyError::Claim {
                file: file.source.display().to_string(),
                id: c.id.clone(),
                field: "quote".into(),
                message: "a claim says what it checks: `quote` (the paper's words, checked against its text) or `reading` (the claims file's words)".into(),
            });
        }
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
pub struct Named<'a> {
    pub(crate) root: &'a Path,
    pub(crate) paper000: paper000::Context,
}

/// A paper's named check (`kind = "check"`): one function.
pub type NamedFn = fn(&mut Named, &PaperClaims, &kinds::NamedCheck) -> Result<Outcome, VerifyError>;

/// The papers with named Rust checks, each with its table of checks by the name a claim's
/// `check` gives; a paper not listed has only the generic kinds.
pub const PAPERS: &[(&str, &[(&str, NamedFn)])] = &[
    ("000", paper000::CHECKS),
    ("001", paper001::CHECKS),
    ("002", paper002::CHECKS),
    ("hard", hard_cases::CHECKS),
];

/// Checks every claim of every paper with the kinds of [`kinds::BUILTIN`] ([`run_with`]).
pub fn run_all(papers: &[PaperClaims], root: &Path) -> Result<Vec<Outcome>, VerifyError> {
    run_with(papers, root, kinds::BUILTIN)
}

/// Checks every claim of every paper: first every file is validated with the kinds of `kinds`
/// ([`kinds::Checked`]: a bad claim stops here, before anything runs), then each claim runs.
/// Scenes named by `check` claims are read relative to `root`, those of the generic kinds
/// relative to their claims file.
pub fn run_with(
    papers: &[PaperClaims],
    root: &Path,
    kinds: &[kinds::KindEntry],
) -> Result<Vec<Outcome>, VerifyError> {
    run_measured(papers, root, kinds, &|_| false)
}

/// [`run_with`], and the power of every claim whose id `power` picks ([`power`]).
pub fn run_measured(
    papers: &[PaperClaims],
    root: &Path,
    kinds: &[kinds::KindEntry],
    power: &dyn Fn(&str) -> bool,
) -> Result<Vec<Outcome>, VerifyError> {
    run_with_progress(papers, root, kinds, power, &|_, _| {})
}

/// [`run_measured`], calling `tick(id, measured)` as each claim's verdict is in
/// (`measured = false`) and as each measured claim's power is (`true`): the progress of `verify`.
pub fn run_with_progress(
    papers: &[PaperClaims],
    root: &Path,
    kinds: &[kinds::KindEntry],
    power: &dyn Fn(&str) -> bool,
    tick: &dyn Fn(&str, bool),
) -> Result<Vec<Outcome>, VerifyError> {
    let checked: Vec<kinds::Checked> = papers
        .iter()
        .map(|p| kinds::Checked::validate_with(p, kinds))
        .collect::<Result<_, _>>()?;
    let new_session = || session(root);
    let mut session = new_session();
    let mut per_file = Vec::new();
    for file in &checked {
        per_file.push(file.check_all_ticking(&mut session, &|id| tick(id, false))?);
    }
    // every verdict first, then the power: the misprints' formulas must not reach the checks
    // (a symbol's first appearance orders the terms that details print)
    let mut out = Vec::new();
    for (file, mut outcomes) in checked.iter().zip(per_file) {
        file.measure_power(&mut outcomes, power, &new_session, &|id| tick(id, true));
        out.extend(outcomes);
    }
    out.sort_by(|a, b| crate::report::natural_cmp(&a.id, &b.id));
    Ok(out)
}

/// A fresh session of checks, with scenes of `check` claims read relative to `root`.
pub fn session(root: &Path) -> kinds::Session<'_> {
    kinds::Session {
        derivations: kinds::Derivations::default(),
        named: Named {
            root,
            paper000: paper000::Context::new(root),
        },
    }
}

/// A claims file written from `body` (after a header naming `paper`) to a fresh temporary
/// file, and loaded: for the unit tests of checks and kinds.
#[cfg(test)]
pub(crate) fn test_claims(paper: &str, body: &str) -> Result<(Vec<PaperClaims>, PathBuf), String> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let d = std::env::temp_dir().join(format!("impactcheck-unit-{}", std::process::id()));
    std::fs::create_dir_all(&d).map_err(|e| e.to_string())?;
    let f = d.join(format!("c{}.toml", NEXT.fetch_add(1, Ordering::Relaxed)));
    let text = format!("paper = \"{paper}\"\ntitle = \"t\"\nreport = \"t.md\"\n{body}");
    std::fs::write(&f, text).map_err(|e| e.to_string())?;
    let papers = load_claims(&f).map_err(|e| e.to_string())?;
    Ok((papers, d))
}
