//! Writers for `reports/`: Markdown per paper, a summary table, `summary.json`, SVG plots
//! ([`svg`]). No physics.
//!
//! Files are rendered in memory, written to a temporary folder beside the target and only then
//! moved into place, so a run that fails leaves the old reports untouched.

mod findings;
pub mod formulas;
mod outcome;
pub mod plot;
pub mod svg;

use findings::findings_section;
pub use findings::{Finding, findings};
pub use outcome::{Corrected, Outcome, PaperInfo, Power, Verdict};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One claim in `summary.json`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct SummaryClaim {
    /// Claim id.
    pub id: String,
    /// Seed number ("000").
    pub paper: String,
    /// Equation as printed, "(22)".
    pub equation: String,
    /// Verdict.
    pub verdict: Verdict,
    /// Detail.
    pub detail: String,
    /// What a kind adds (`probability`: `{p, lo, hi, n}`; `valid_fraction`).
    #[serde(flatten)]
    pub extra: BTreeMap<String, serde_json::Value>,
    /// The power of its check, when measured (`verify --power`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub power: Option<Power>,
    /// A misprint of its printed side survives its check ([`Power::weak`]).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub weak: bool,
    /// What it tests beyond the paper (`extends`), when it does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
    /// The printed side as checked (the formula language), read from the paper or typed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub printed: Option<String>,
    /// The paper's LaTeX it was read from, when read from the paper.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub printed_latex: Option<String>,
    /// Why its printed side is typed by hand, not read from the paper's LaTeX (`retyped`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub retyped: Option<String>,
}

/// `summary.json`: sorted by id ([`natural_cmp`]), no timestamps or timings.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Summary {
    /// Every claim.
    pub claims: Vec<SummaryClaim>,
    /// The distinct errors the claims show ([`findings`]).
    #[serde(default)]
    pub findings: Vec<Finding>,
    /// The power of the checks per printed formula ([`formulas::formula_power`]).
    #[serde(default)]
    pub formulas: Vec<formulas::FormulaPower>,
    /// The version that wrote it.
    pub generated_by: GeneratedBy,
}

/// Claim ids in the order a reader expects: runs of digits compared as numbers, so `eq2`
/// comes before `eq10` and `eq1.2` before `eq1.12`; the rest as text.
pub fn natural_cmp(a: &str, b: &str) -> std::cmp::Ordering {
    use std::cmp::Ordering;
    fn runs(s: &str) -> Vec<(bool, &str)> {
        let mut out = Vec::new();
        let mut start = 0;
        let b = s.as_bytes();
        for i in 1..=b.len() {
            if i == b.len() || b[i].is_ascii_digit() != b[start].is_ascii_digit() {
                out.push((b[start].is_ascii_digit(), &s[start..i]));
                start = i;
            }
        }
        out
    }
    for (x, y) in runs(a).into_iter().zip(runs(b)) {
        let o = match (x, y) {
            ((true, x), (true, y)) => {
                let (tx, ty) = (x.trim_start_matches('0'), y.trim_start_matches('0'));
                tx.len()
                    .cmp(&ty.len())
                    .then(tx.cmp(ty))
                    .then(x.len().cmp(&y.len()))
            }
            ((_, x), (_, y)) => x.cmp(y),
        };
        if o != Ordering::Equal {
            return o;
        }
    }
    runs(a).len().cmp(&runs(b).len()).then(a.cmp(b))
}

/// Who wrote the summary.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct GeneratedBy {
    /// Crate version.
    pub version: String,
}

/// Builds the summary from outcomes.
pub fn summary(outcomes: &[Outcome]) -> Summary {
    let mut claims: Vec<SummaryClaim> = outcomes
        .iter()
        .map(|o| SummaryClaim {
            id: o.id.clone(),
            paper: o.paper.clone(),
            equation: o.equation.clone(),
            verdict: o.verdict,
            detail: o.detail.clone(),
            extra: o.extra.clone(),
            power: o.power.clone(),
            weak: o.power.as_ref().is_some_and(Power::weak),
            extends: o.extends.clone(),
            printed: o.printed.clone(),
            printed_latex: o.printed_latex.clone(),
            retyped: o.retyped.clone(),
        })
        .collect();
    claims.sort_by(|a, b| natural_cmp(&a.id, &b.id));
    Summary {
        claims,
        findings: findings(outcomes),
        formulas: formulas::formula_power(outcomes),
        generated_by: GeneratedBy {
            version: env!("CARGO_PKG_VERSION").to_string(),
        },
    }
}

fn escape_cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn short(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        format!("{}...", s.chars().take(n).collect::<String>())
    }
}

fn anchor(id: &str) -> String {
    id.replace('.', "").to_lowercase()
}

/// Renders every file of `reports/` as `(file name, contents)`.
pub fn render(papers: &[PaperInfo], outcomes: &[Outcome]) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let by_paper: BTreeMap<&str, Vec<&Outcome>> =
        outcomes.iter().fold(BTreeMap::new(), |mut m, o| {
            m.entry(o.paper.as_str()).or_insert_with(Vec::new).push(o);
            m
        });
    // summary table
    let mut readme = String::from(
        "# impactcheck reports\n\nWritten by `cargo run --release --bin verify`; every verdict below is computed \
         (exact algebra, or numerics with a stated error), none is typed in. Verdicts: `holds`, `fails`, \
         `holds-with-correction`, `holds-with-assumption` (the assumption is named), `definition` (a definition whose \
         units and uses were checked), `not-checkable` (what is missing is named).\n\n",
    );
    readme.push_str(
        "Also: [what accuracy costs in time](timing/accuracy_cost.md) (work-precision of every model and method) and \
         [performance against SciPy](performance.md).\n\n\
         Running `verify` twice gives byte-identical reports: the measured times are kept apart, in `timing/` (written \
         only by `verify --timing`) and `performance*` (written by `benches/peers/run.sh`), so that the main job \
         leaves a clean checkout clean.\n\n",
    );
    // the papers' claims, and apart from them the solver robustness cases (hard.*)
    let count = |hard: bool| {
        let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
        let mut n = 0;
        for o in outcomes.iter().filter(|o| (o.paper == "hard") == hard) {
            *counts.entry(o.verdict.as_str()).or_default() += 1;
            n += 1;
        }
        let list = counts
            .iter()
            .map(|(k, v)| format!("{v} {k}"))
            .collect::<Vec<_>>()
            .join(", ");
        (n, list)
    };
    let (n_papers, papers_list) = count(false);
    let (n_hard, hard_list) = count(true);
    let paper_findings: Vec<Finding> = findings(
        &outcomes
            .iter()
            .filter(|o| o.paper != "hard")
            .cloned()
            .collect::<Vec<_>>(),
    );
    let showing: usize = paper_findings.iter().map(|f| f.claims.len()).sum();
    let extending: Vec<&Outcome> = outcomes.iter().filter(|o| o.extends.is_some()).collect();
    let confirmed = paper_findings
        .iter()
        .filter(|f| f.correction_holds())
        .count();
    readme.push_str(&format!(
        "{n_papers} claims of the papers: {papers_list}. The {showing} claims that fail or hold only with a correction show **{} distinct findings** (claims that show the same error share one: `findings` in `summary.json`, listed in each paper's report). {confirmed} of them are confirmed by their correction: each of their claims, checked again with the correction applied (its `correction`, or its `corrected` form), holds. {} claims test more than the paper states (`extends`: a range, a model or a condition the paper does not claim); their verdicts are the tool's extension, not the paper's errors ({} of them fail).",
        paper_findings.len(),
        extending.len(),
        extending.iter().filter(|o| o.verdict == Verdict::Fails).count()
    ));
    if n_hard > 0 {
        readme.push_str(&format!(
            " Apart from them, {n_hard} solver robustness cases (`hard.*`): {hard_list}."
        ));
    }
    readme.push_str("\n\n");
    let of_papers = || {
        outcomes
            .iter()
            .filter(|o| o.paper != "hard" && o.paper != "classics")
    };
    readme.push_str(&format!(
        "Printed sides in the three papers' claims: {} read from the paper's LaTeX (`printed_from`, \
         `printed_equations_from`, `printed_matrix_from`, or a definition read with \
         `definitions_from`; each report shows the LaTeX), {} typed by hand, each saying why \
         (`retyped`: printed in prose, read off a figure, a form the reader has no construct for).\n\n",
        of_papers().filter(|o| o.printed_latex.is_some()).count(),
        of_papers().filter(|o| o.retyped.is_some()).count(),
    ));
    let generic = outcomes
        .iter()
        .filter(|o| !o.kind.is_empty() && !o.kind.starts_with("check"))
        .count();
    readme.push_str(&format!(
        "{generic} of them are checked by a generic kind from formulas written as text in `verify/*.toml` \
         (identity, dimension, model, bound: see `verify/README.md`); the others by a named Rust check.\n\n"
    ));
    readme.push_str(&power_section(papers, outcomes));
    readme.push_str(&formulas::section(
        &formulas::formula_power(outcomes),
        &|paper| report_of(papers, paper),
    ));
    readme.push_str(
        "## Every claim\n\n| claim | paper | equation | verdict | detail |\n|---|---|---|---|---|\n",
    );
    for p in papers {
        for o in by_paper.get(p.paper.as_str()).into_iter().flatten() {
            readme.push_str(&format!(
                "| [{}]({}#{}) | {} | {} | **{}** | {} |\n",
                o.id,
                p.report,
                anchor(&o.id),
                o.paper,
                o.equation,
                o.verdict.as_str(),
                escape_cell(&short(&o.detail, 160))
            ));
        }
    }
    files.push(("README.md".to_string(), readme));
    // one report per paper
    for p in papers {
        let source = if p.file.is_empty() {
            "No source named (the claims file has no `file`).".to_string()
        } else if p.file.ends_with(".txt") {
            format!("Source: `../shared/seeds/{}`.", p.file)
        } else {
            format!("Source: `{}`.", p.file)
        };
        let mut md = format!(
            "# {} — {}\n\n{source} Each claim: what the paper (or the catalogue) states, what impactcheck \
             computes, and the verdict.\n\n",
            p.paper, p.title
        );
        md.push_str("| claim | equation | verdict |\n|---|---|---|\n");
        let list = by_paper.get(p.paper.as_str()).cloned().unwrap_or_default();
        for o in &list {
            md.push_str(&format!(
                "| [{}](#{}) | {} | **{}** |\n",
                o.id,
                anchor(&o.id),
                o.equation,
                o.verdict.as_str()
            ));
        }
        md.push('\n');
        md.push_str(&findings_section(&list));
        for o in &list {
            let by = if o.kind.starts_with("check") {
                format!(
                    "a named Rust {} (not yet a formula in the claims file)",
                    o.kind
                )
            } else if o.kind.is_empty() {
                "a named Rust check".to_string()
            } else {
                format!(
                    "the generic kind `{}`, from the formulas in the claims file",
                    o.kind
                )
            };
            let mut said = String::new();
            if !o.quote.is_empty() {
                said.push_str(&format!(" The paper: \"{}\"", o.quote));
            }
            if let Some(r) = &o.reading {
                said.push_str(&format!(" Read as (the claims file's words): `{r}`"));
            }
            md.push_str(&format!(
                "## {}\n\nEquation {}.{said}\n\nVerdict: **{}** (checked by {by})\n\n{}\n\n",
                o.id,
                o.equation,
                o.verdict.as_str(),
                o.detail
            ));
            if let Some(line) = o.power.as_ref().map(power_line) {
                md.push_str(&line);
            }
            if let Some(p) = &o.printed_latex {
                md.push_str(&format!("Printed:\n\n$$\n{p}\n$$\n\n"));
            }
            if let Some(why) = &o.retyped {
                md.push_str(&format!(
                    "Printed side typed by hand, not read from the paper's LaTeX: {why}\n\n"
                ));
            }
            if let Some(d) = &o.derived_latex {
                md.push_str(&format!("Derived:\n\n$$\n{d}\n$$\n\n"));
            }
            if let Some(x) = &o.extra_md {
                md.push_str(x);
                md.push_str("\n\n");
            }
            for (name, text) in &o.files {
                files.push((name.clone(), text.clone()));
            }
        }
        files.push((p.report.clone(), md));
    }
    let json = serde_json::to_string_pretty(&summary(outcomes)).unwrap_or_default();
    files.push(("summary.json".to_string(), json + "\n"));
    files
}

/// The report file of `paper`.
fn report_of(papers: &[PaperInfo], paper: &str) -> String {
    papers
        .iter()
        .find(|p| p.paper == paper)
        .map(|p| p.report.clone())
        .unwrap_or_default()
}

/// The first three surviving misprints, as code.
fn first_three(survivors: &[String]) -> String {
    survivors
        .iter()
        .take(3)
        .map(|s| format!("`{s}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The README's account of the checks' power: how many misprints they see, the weak claims
/// (a misprint survives) with what each cannot see, and why some were not measured.
fn power_section(papers: &[PaperInfo], outcomes: &[Outcome]) -> String {
    let measured: Vec<(&Outcome, &Power)> = outcomes
        .iter()
        .filter_map(|o| o.power.as_ref().map(|p| (o, p)))
        .collect();
    if measured.is_empty() {
        return String::new();
    }
    let run: Vec<&(&Outcome, &Power)> = measured
        .iter()
        .filter(|(_, p)| p.not_measured.is_none())
        .collect();
    let mutants: usize = run.iter().map(|(_, p)| p.mutants).sum();
    let killed: usize = run.iter().map(|(_, p)| p.killed).sum();
    let weak: Vec<&&(&Outcome, &Power)> = run.iter().filter(|(_, p)| p.weak()).collect();
    let mut md = format!(
        "## Power of the checks\n\nEach claim's printed side is misprinted the way misprints happen (a coefficient \
         x2, x1/2, x1.1, x0.9, a term printed with no number x2, x1/2; an exponent +-1; a sign; a dropped term; a \
         symbol swapped for another of the same unit; inside derivatives too; at most 40 per claim, and always the \
         paper's own misprint where a claim holds with a correction) and the claim is checked again: a misprint \
         that keeps the verdict survives, and a printed key that cannot be misprinted (not a formula) is a gap. \
         Not counted: a misprint that states the same (a side against zero times a positive factor) or only weakens \
         a true inequality; a claim's `allowance` for the integration error is not the paper's and is not misprinted. \
         {} claims measured: {mutants} misprints, {killed} killed ({:.0} %); {} claims see every misprint, \
         **{} are weak** (a misprint survives), {} not measured.\n\n",
        run.len(),
        100.0 * killed as f64 / mutants.max(1) as f64,
        run.len() - weak.len(),
        weak.len(),
        measured.len() - run.len()
    );
    // whether each verdict can move: a misprint that changes it, or a weakness declared
    let moved = run.iter().filter(|(_, p)| p.killed > 0).count();
    let moved_weak = run.iter().filter(|(_, p)| p.killed > 0 && p.weak()).count();
    let stuck: Vec<&&(&Outcome, &Power)> = run.iter().filter(|(_, p)| p.killed == 0).collect();
    let undeclared = run
        .iter()
        .filter(|(_, p)| p.weak() && p.blind.is_none())
        .count();
    let own = |names: &[String]| {
        names
            .iter()
            .filter(|n| n.ends_with("(the paper's own misprint)"))
            .count()
    };
    let own_tried: usize = run
        .iter()
        .map(|(_, p)| own(&p.killed_names) + own(&p.survivors))
        .sum();
    let own_killed: usize = run.iter().map(|(_, p)| own(&p.killed_names)).sum();
    let gaps: usize = run.iter().map(|(_, p)| p.not_applied.len()).sum();
    md.push_str(&format!(
        "**Can each verdict move?** Of the {} claims measured, {moved} change their verdict under some misprint of \
         their printed side ({moved_weak} of them also let some misprint through); {} change under none, each \
         declared weak with what its check cannot see; {undeclared} weak claim(s) say nothing of why. The paper's \
         own misprint, where a claim holds with a correction and the printed side is a misprint of it, is tried \
         {own_tried} time(s) and changes the verdict {own_killed} time(s). Misprints not applied (a printed key \
         that is no formula): {gaps}.\n\n",
        run.len(),
        stuck.len(),
    ));
    if !weak.is_empty() {
        md.push_str(
            "| weak claim | killed | surviving misprints (first 3) | what the check cannot see |\n|---|---|---|---|\n",
        );
        for (o, p) in &weak {
            md.push_str(&format!(
                "| [{}]({}#{}) | {}/{} | {} | {} |\n",
                o.id,
                report_of(papers, &o.paper),
                anchor(&o.id),
                p.killed,
                p.mutants,
                escape_cell(&first_three(if p.survivors.is_empty() {
                    &p.not_applied
                } else {
                    &p.survivors
                })),
                escape_cell(p.blind.as_deref().unwrap_or("**not stated**"))
            ));
        }
        md.push('\n');
    }
    let mut why: BTreeMap<&str, usize> = BTreeMap::new();
    for (_, p) in &measured {
        if let Some(w) = &p.not_measured {
            *why.entry(w.as_str()).or_default() += 1;
        }
    }
    if !why.is_empty() {
        md.push_str("Not measured:\n\n");
        for (w, n) in &why {
            md.push_str(&format!("- {n}: {w}\n"));
        }
        md.push('\n');
    }
    md
}

/// A claim's power in its paper's report.
fn power_line(p: &Power) -> String {
    if let Some(w) = &p.not_measured {
        return format!("Power: not measured ({w}).\n\n");
    }
    let mut line = format!(
        "Power: {} of {} misprints of the printed side change the verdict",
        p.killed, p.mutants
    );
    if p.excused > 0 {
        line.push_str(&format!(
            " ({} more only weaken the inequality and are not counted)",
            p.excused
        ));
    }
    if p.weak() {
        line.push_str(&format!(
            "; **weak**: {} survive ({}). What the check cannot see: {}",
            p.survivors.len(),
            p.survivors
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", "),
            p.blind.as_deref().unwrap_or("not stated")
        ));
    }
    if !p.not_applied.is_empty() {
        line.push_str(&format!(
            "; not applied: {}",
            p.not_applied
                .iter()
                .map(|s| format!("`{s}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    line.push_str(".\n\n");
    line
}

/// Unlinks, in every Markdown file of `files`, each relative link or image whose target is
/// neither one of `files` nor in `also` (files that stay in the output folder beside them):
/// `[text](target)` becomes `text`, `![alt](target)` becomes `alt`. A report written to
/// `--out DIR` then links only what is there.
pub fn keep_written_links(files: &mut [(String, String)], also: &[String]) {
    let written: std::collections::BTreeSet<String> = files
        .iter()
        .map(|(n, _)| n.clone())
        .chain(also.iter().cloned())
        .collect();
    for (name, text) in files.iter_mut() {
        if !name.ends_with(".md") {
            continue;
        }
        let dir = Path::new(name.as_str())
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        *text = unlink_missing(text, &|target: &str| {
            let mut parts: Vec<String> = dir
                .components()
                .map(|c| c.as_os_str().to_string_lossy().to_string())
                .collect();
            for part in target.split('/') {
                match part {
                    "" | "." => {}
                    ".." => {
                        if parts.pop().is_none() {
                            return false;
                        }
                    }
                    p => parts.push(p.to_string()),
                }
            }
            written.contains(&parts.join("/"))
        });
    }
}

/// `text` with the relative links whose file `exists` says is missing turned into their text.
fn unlink_missing(text: &str, exists: &dyn Fn(&str) -> bool) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(close) = rest.find("](") {
        // the link's text starts at the last `[` before `](` on its line
        let open = rest[..close].rfind('[');
        let end = rest[close + 2..].find(')').map(|e| close + 2 + e);
        let (Some(open), Some(end)) = (open, end) else {
            out.push_str(&rest[..close + 2]);
            rest = &rest[close + 2..];
            continue;
        };
        let target = &rest[close + 2..end];
        let file = target.split('#').next().unwrap_or("");
        let relative = !file.is_empty() && !file.contains("://") && !file.starts_with('/');
        if relative && !target.contains(char::is_whitespace) && !exists(file) {
            let image = open > 0 && rest.as_bytes()[open - 1] == b'!';
            out.push_str(&rest[..if image { open - 1 } else { open }]);
            out.push_str(&rest[open + 1..close]);
        } else {
            out.push_str(&rest[..=end]);
        }
        rest = &rest[end + 1..];
    }
    out.push_str(rest);
    out
}

/// Writes rendered files into `dir` through a temporary folder beside it.
///
/// Every file name must be a relative path of plain components (no `..`, no root): anything else
/// is refused before a file is written.
pub fn write_atomically(dir: &Path, files: &[(String, String)]) -> std::io::Result<()> {
    for (f, _) in files {
        let p = Path::new(f);
        let plain = p
            .components()
            .all(|c| matches!(c, std::path::Component::Normal(_)));
        if !plain || p.as_os_str().is_empty() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                format!(
                    "refusing to write {f:?}: not a plain relative path under the output folder"
                ),
            ));
        }
    }
    let parent = dir.parent().unwrap_or(Path::new("."));
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "reports".into());
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    if tmp.exists() {
        std::fs::remove_dir_all(&tmp)?;
    }
    std::fs::create_dir_all(&tmp)?;
    let staged = (|| {
        for (f, text) in files {
            if let Some(sub) = Path::new(f).parent() {
                std::fs::create_dir_all(tmp.join(sub))?;
                std::fs::create_dir_all(dir.join(sub))?;
            }
            std::fs::write(tmp.join(f), text)?;
        }
        std::fs::create_dir_all(dir)?;
        for (f, _) in files {
            std::fs::rename(tmp.join(f), dir.join(f))?;
        }
        Ok(())
    })();
    let _ = std::fs::remove_dir_all(&tmp);
    staged
}

/// Relative tolerance for numbers inside details: a value that moved less than this is the same.
pub const VALUE_RTOL: f64 = 1e-6;

/// Compares two details token by token; tokens that both parse as numbers are equal when they
/// agree to [`VALUE_RTOL`].
pub fn same_detail(a: &str, b: &str) -> bool {
    let split = |s: &str| -> Vec<String> {
        s.split(|c: char| {
            c.is_whitespace() || matches!(c, ',' | ';' | '(' | ')' | '[' | ']' | ':' | '=')
        })
        .filter(|t| !t.is_empty())
        .map(str::to_string)
        .collect()
    };
    let (ta, tb) = (split(a), split(b));
    ta.len() == tb.len()
        && ta.iter().zip(&tb).all(|(x, y)| {
            if x == y {
                return true;
            }
            match (
                x.trim_end_matches('.').parse::<f64>(),
                y.trim_end_matches('.').parse::<f64>(),
            ) {
                (Ok(u), Ok(v)) => (u - v).abs() <= VALUE_RTOL * u.abs().max(v.abs()),
                _ => false,
            }
        })
}

/// Differences between a baseline summary and a fresh one (only the claims present in `fresh`
/// when `partial`): `(id, what changed)`.
pub fn diff(baseline: &Summary, fresh: &Summary, partial: bool) -> Vec<(String, String)> {
    let old: BTreeMap<&str, &SummaryClaim> =
        baseline.claims.iter().map(|c| (c.id.as_str(), c)).collect();
    let new: BTreeMap<&str, &SummaryClaim> =
        fresh.claims.iter().map(|c| (c.id.as_str(), c)).collect();
    let mut out = Vec::new();
    for (id, n) in &new {
        match old.get(id) {
            None => out.push((
                id.to_string(),
                format!("new claim, verdict {}", n.verdict.as_str()),
            )),
            Some(o) if o.verdict != n.verdict => out.push((
                id.to_string(),
                format!("verdict {} -> {}", o.verdict.as_str(), n.verdict.as_str()),
            )),
            Some(o)
                if n.power.is_some()
                    && o.power.as_ref().map(|p| (p.killed, p.mutants))
                        != n.power.as_ref().map(|p| (p.killed, p.mutants)) =>
            {
                let text = |p: &Option<Power>| match p {
                    Some(p) if p.not_measured.is_none() => {
                        format!("{}/{} killed", p.killed, p.mutants)
                    }
                    Some(_) => "not measured".to_string(),
                    None => "not in the baseline".to_string(),
                };
                out.push((
                    id.to_string(),
                    format!("power {} -> {}", text(&o.power), text(&n.power)),
                ))
            }
            Some(o) if !same_detail(&o.detail, &n.detail) || o.equation != n.equation => {
                out.push((
                    id.to_string(),
                    format!(
                        "detail changed:\n    was: {}\n    now: {}",
                        o.detail, n.detail
                    ),
                ))
            }
            _ => {}
        }
    }
    for id in old.keys() {
        if !partial && !new.contains_key(id) {
            out.push((id.to_string(), "claim removed".into()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_to_unwritten_files_lose_their_target_only() {
        let mut files = vec![
            (
                "README.md".to_string(),
                "See [a](a.md#x), [b](b.md), ![fig](f.svg), [web](https://x.org/y.md), [here](#top)."
                    .to_string(),
            ),
            ("a.md".to_string(), String::new()),
            (
                "sub/c.md".to_string(),
                "[up](../a.md) [gone](../b.md) [kept](../k.md)".to_string(),
            ),
        ];
        keep_written_links(&mut files, &["k.md".to_string()]);
        assert_eq!(
            files[0].1,
            "See [a](a.md#x), b, fig, [web](https://x.org/y.md), [here](#top)."
        );
        assert_eq!(files[2].1, "[up](../a.md) gone [kept](../k.md)");
    }

    #[test]
    fn numbers_in_details_compare_with_tolerance() {
        assert!(same_detail(
            "error up to 8.82e-1 at t = 1e-3",
            "error up to 8.8200001e-1 at t = 1e-3"
        ));
        assert!(!same_detail("error up to 8.82e-1", "error up to 8.83e-1"));
        assert!(!same_detail("derived 2/alpha", "derived 3/alpha"));
        assert!(!same_detail("a b", "a b c"));
    }

    #[test]
    fn a_check_that_loses_power_is_a_change() {
        let claim = |power: Option<Power>| SummaryClaim {
            id: "p.x".into(),
            paper: "p".into(),
            equation: "(1)".into(),
            verdict: Verdict::Holds,
            detail: "d".into(),
            extra: BTreeMap::new(),
            weak: power.as_ref().is_some_and(Power::weak),
            power,
            extends: None,
            printed: None,
            printed_latex: None,
            retyped: None,
        };
        let sum = |power: Option<Power>| Summary {
            claims: vec![claim(power)],
            findings: vec![],
            formulas: vec![],
            generated_by: GeneratedBy {
                version: "0".into(),
            },
        };
        let strong = Power {
            mutants: 5,
            killed: 5,
            ..Power::default()
        };
        let weaker = Power {
            killed: 3,
            survivors: vec!["a".into(), "b".into()],
            ..strong.clone()
        };
        let changes = diff(&sum(Some(strong.clone())), &sum(Some(weaker)), false);
        assert_eq!(changes.len(), 1);
        assert_eq!(changes[0].1, "power 5/5 killed -> 3/5 killed");
        // not measured in the fresh run (no --power-sample): nothing to compare
        assert!(diff(&sum(Some(strong.clone())), &sum(None), false).is_empty());
        assert!(diff(&sum(Some(strong.clone())), &sum(Some(strong)), false).is_empty());
    }

    /// The README counts the papers' printed sides read from the LaTeX and typed by hand (not
    /// the classics' or the hard cases'), and a paper's report gives each reason.
    #[test]
    fn printed_sides_are_counted_by_source() {
        let o = |id: &str, paper: &str, latex: bool, why: Option<&str>| Outcome {
            id: id.into(),
            paper: paper.into(),
            equation: "(1)".into(),
            quote: String::new(),
            reading: None,
            verdict: Verdict::Holds,
            detail: "d".into(),
            printed_latex: latex.then(|| "a = b".to_string()),
            printed: None,
            derived_latex: None,
            extra_md: None,
            files: vec![],
            kind: "identity".into(),
            extra: BTreeMap::new(),
            power: None,
            finding: None,
            extends: None,
            retyped: why.map(str::to_string),
        };
        let out = [
            o("p.a", "p", true, None),
            o("p.b", "p", true, None),
            o("p.c", "p", false, Some("stated in the text")),
            o("c.a", "classics", true, None),
            o("c.b", "classics", false, Some("x")),
            o("h.a", "hard", false, Some("y")),
        ];
        let papers = [PaperInfo {
            paper: "p".into(),
            title: "P".into(),
            file: "p.txt".into(),
            report: "p.md".into(),
        }];
        let files = render(&papers, &out);
        let text = |name: &str| {
            files
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, t)| t.clone())
                .unwrap_or_else(|| panic!("{name} not written"))
        };
        assert!(
            text("README.md").contains("three papers' claims: 2 read from the paper's LaTeX"),
            "{}",
            text("README.md")
        );
        assert!(text("README.md").contains("LaTeX), 1 typed by hand"));
        assert!(text("p.md").contains(
            "Printed side typed by hand, not read from the paper's LaTeX: stated in the text"
        ));
        assert!(text("p.md").contains("Source: `../shared/seeds/p.txt`."));
        // a claims file without `file`: said so, not an empty source
        let mut none = papers.clone();
        none[0].file = String::new();
        let files = render(&none, &out);
        let p = &files.iter().find(|(n, _)| n == "p.md").expect("p.md").1;
        assert!(
            p.contains("No source named (the claims file has no `file`)."),
            "{p}"
        );
        assert!(!p.contains("Source: ``"), "{p}");
    }
}
