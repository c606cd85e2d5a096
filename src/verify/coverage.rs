//! Coverage: which numbered equations of a paper have a claim. The equations are the claims
//! file's `equations` list (facts taken from the paper once: its `\tag{...}` labels), so that the
//! reports do not depend on where the papers lie; when the paper's text is found (`--papers DIR`,
//! beside the claims file, or `../shared/seeds/`), the list is checked against its labels and a
//! mismatch is an error. A claim covers the labels written in parentheses in its `equation` field
//! (`"(2.3)"`, `"(2.6)-(2.10)"` covers 2.6 and 2.10). Computed on every run, so the table in
//! `reports/README.md` stays true when a claim is added or removed.

use super::{Outcome, PaperClaims};
use crate::paper::source::blocks::numbers_at;
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The coverage of one paper.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Eq)]
pub struct Coverage {
    /// The paper ("000").
    pub paper: String,
    /// Where its text was read, or `None` when it was not found.
    pub text: Option<String>,
    /// Its numbered equations, in the order of the text, once each.
    pub equations: Vec<String>,
    /// Those without a claim.
    pub missing: Vec<String>,
    /// Claims of the paper.
    pub claims: usize,
    /// Claims whose equation field names no numbered equation of the text (a section, a figure,
    /// a table, a result stated in words).
    pub other_claims: usize,
}

impl Coverage {
    /// Numbered equations with a claim.
    pub fn covered(&self) -> usize {
        self.equations.len() - self.missing.len()
    }
}

/// The labels an `equation` field names: every `(...)` in it.
pub fn labels(equation: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = equation;
    while let Some(i) = rest.find('(') {
        rest = &rest[i + 1..];
        let Some(end) = rest.find(')') else { break };
        out.push(rest[..end].trim().to_string());
        rest = &rest[end..];
    }
    out
}

/// Where the paper's text is: in `papers` (`--papers DIR`), beside the claims file, or among the
/// seeds (`../shared/seeds/` beside the repository).
pub fn text_path(p: &PaperClaims, papers: Option<&Path>) -> Option<PathBuf> {
    looked_in(p, papers).into_iter().find(|c| c.is_file())
}

/// The places [`text_path`] looks for the paper's text, in order (none when the claims name no
/// file).
pub fn looked_in(p: &PaperClaims, papers: Option<&Path>) -> Vec<PathBuf> {
    if p.file.is_empty() {
        return Vec::new();
    }
    let dir = p.source.parent().unwrap_or(Path::new("."));
    let mut candidates: Vec<PathBuf> = papers.map(|d| d.join(&p.file)).into_iter().collect();
    candidates.push(dir.join(&p.file));
    if let Some(root) = dir.parent() {
        candidates.push(root.join("../shared/seeds").join(&p.file));
    }
    candidates.push(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/seeds")
            .join(&p.file),
    );
    candidates
}

/// Said once when papers' texts are missing (`None` when every named text was found): which
/// papers, the folders looked in, and what is not checked without them.
pub fn missing_texts(papers: &[PaperClaims], dir: Option<&Path>) -> Option<String> {
    let missing: Vec<&PaperClaims> = papers
        .iter()
        // a `file` that names a source in words (the classics' textbooks) is no file to find
        .filter(|p| {
            let f = p.file.trim();
            !f.is_empty()
                && !f.contains(char::is_whitespace)
                && Path::new(f).extension().is_some()
                && text_path(p, dir).is_none()
        })
        .collect();
    let first = missing.first()?;
    let mut folders: Vec<String> = Vec::new();
    for p in &missing {
        for c in looked_in(p, dir) {
            let folder = match c.parent() {
                Some(f) if f.as_os_str().is_empty() => PathBuf::from("."),
                Some(f) => f.to_path_buf(),
                None => c.clone(),
            };
            // `..` resolved where the folder exists, shown as given where it does not
            let shown = folder
                .canonicalize()
                .unwrap_or(folder)
                .display()
                .to_string();
            if !folders.contains(&shown) {
                folders.push(shown);
            }
        }
    }
    Some(format!(
        "the text of {} paper(s) was not found ({}{}; looked in {}; --papers DIR names another folder): \
         their `equations` lists and quotes are not checked against it, and their audits from \
         the paper's words are kept from the last run that had it",
        missing.len(),
        first.file,
        if missing.len() > 1 { ", ..." } else { "" },
        folders.join(", ")
    ))
}

/// Checks the claims file's `equations` against the `\tag{...}` labels of the paper's text, when
/// the text is found; `Ok(Some(path))` names the text checked.
pub fn check_equations(
    p: &PaperClaims,
    papers: Option<&Path>,
) -> Result<Option<PathBuf>, super::VerifyError> {
    let Some(path) = text_path(p, papers) else {
        return Ok(None);
    };
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(None);
    };
    let tagged = numbers_at(&p.file, &text, path.parent());
    if p.equations == tagged {
        return Ok(Some(path));
    }
    let missing: Vec<&String> = tagged.iter().filter(|t| !p.equations.contains(t)).collect();
    let extra: Vec<&String> = p.equations.iter().filter(|t| !tagged.contains(t)).collect();
    Err(super::VerifyError::BadClaims {
        path: p.source.clone(),
        message: format!(
            "equations: the list differs from the numbers of {} (in their order: {:?}); not listed: {missing:?}; not in the text: {extra:?}",
            path.display(),
            tagged
        ),
    })
}

/// The text a quote is compared in: `$`, LaTeX spacing (`\,` `\;` `\:` `\!` `\quad`
/// `\qquad` `~`) and braces dropped, whitespace runs made one space, letters lower-cased.
pub fn normalise_quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(c) = rest.chars().next() {
        let skip = ["\\qquad", "\\quad", "\\,", "\\;", "\\:", "\\!", "\\ "]
            .iter()
            .find(|p| rest.starts_with(**p))
            .map(|p| p.len());
        if let Some(n) = skip {
            out.push(' ');
            rest = &rest[n..];
            continue;
        }
        match c {
            '$' | '~' => out.push(' '),
            '{' | '}' => {}
            c if c.is_whitespace() => out.push(' '),
            c => out.extend(c.to_lowercase()),
        }
        rest = &rest[c.len_utf8()..];
    }
    let mut squeezed = String::with_capacity(out.len());
    for w in out.split_whitespace() {
        if !squeezed.is_empty() {
            squeezed.push(' ');
        }
        squeezed.push_str(w);
    }
    squeezed
}

/// Whether `quote` stands in `text` (both [`normalise_quote`]d): its pieces between `...`, in
/// their order.
pub fn quote_found(quote: &str, text: &str) -> bool {
    let text = normalise_quote(text);
    let mut from = 0;
    for piece in quote.split("...").map(normalise_quote) {
        if piece.is_empty() {
            continue;
        }
        match text[from..].find(&piece) {
            Some(i) => from += i + piece.len(),
            None => return false,
        }
    }
    true
}

/// Checks every claim's `quote` against the paper's text, when the text is found: a quote that
/// is not the paper's words is an error naming the claim (the claims file's own words belong in
/// `reading`).
pub fn check_quotes(p: &PaperClaims, papers: Option<&Path>) -> Result<(), super::VerifyError> {
    let Some(text) = text_path(p, papers).and_then(|t| std::fs::read_to_string(t).ok()) else {
        return Ok(());
    };
    for c in &p.claim {
        if !c.quote.trim().is_empty() && !quote_found(&c.quote, &text) {
            return Err(super::VerifyError::Claim {
                file: p.source.display().to_string(),
                id: c.id.clone(),
                field: "quote".into(),
                message: format!(
                    "{:?} is not in the paper's text ({}); a quote is the paper's words (whitespace, $ and LaTeX spacing aside, `...` for words left out); the claims file's own words go in `reading`",
                    c.quote, p.file
                ),
            });
        }
    }
    Ok(())
}

/// The coverage of `p`: its equations are its `equations` list, or, without one, the labels of
/// its text (`None`: not found).
pub fn of_text(p: &PaperClaims, text: Option<&str>, where_: Option<String>) -> Coverage {
    let equations = if p.equations.is_empty() {
        text.map(|t| numbers_at(&p.file, t, None))
            .unwrap_or_default()
    } else {
        p.equations.clone()
    };
    let claimed: BTreeSet<String> = p.claim.iter().flat_map(|c| labels(&c.equation)).collect();
    let missing = equations
        .iter()
        .filter(|e| !claimed.contains(*e))
        .cloned()
        .collect();
    let other_claims = p
        .claim
        .iter()
        .filter(|c| !labels(&c.equation).iter().any(|l| equations.contains(l)))
        .count();
    Coverage {
        paper: p.paper.clone(),
        text: where_,
        equations,
        missing,
        claims: p.claim.len(),
        other_claims,
    }
}

/// The coverage of every paper that names its text. A paper with an `equations` list is
/// counted from the list alone, whether its text is found or not (the text is only read for
/// [`check_equations`]), so the table is the same on a machine without the papers.
pub fn compute(papers: &[PaperClaims], dir: Option<&Path>) -> Vec<Coverage> {
    papers
        .iter()
        .filter(|p| !p.file.is_empty() && p.paper != "hard")
        .map(|p| {
            if !p.equations.is_empty() {
                return of_text(p, None, Some(p.file.clone()));
            }
            let path = text_path(p, dir);
            let text = path.as_ref().and_then(|x| std::fs::read_to_string(x).ok());
            of_text(
                p,
                text.as_deref(),
                path.map(|_| p.file.clone()).filter(|_| text.is_some()),
            )
        })
        .collect()
}

/// The Markdown table of `reports/README.md`, with verdict counts per paper.
pub fn table(cov: &[Coverage], outcomes: &[Outcome]) -> String {
    let mut md = String::from(
        "## Coverage of the papers\n\nNumbered equations are the `\\tag{...}` labels of each paper's text, listed once in its claims file (`equations`, checked against the text when it is found); a claim covers the \
         labels in parentheses in its `equation` field. Computed by `verify` on every run. The solver robustness \
         cases (`hard.*`) are not counted here.\n\n\
         | paper | numbered equations | with a claim | claims | holds | fails | holds-with-correction | holds-with-assumption | definition | not-checkable | equations without a claim |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for c in cov {
        let mine: Vec<&Outcome> = outcomes.iter().filter(|o| o.paper == c.paper).collect();
        let count = |v: &str| mine.iter().filter(|o| o.verdict.as_str() == v).count();
        let missing = if c.text.is_none() {
            "(the paper's text was not found)".to_string()
        } else if c.missing.is_empty() {
            "none".to_string()
        } else {
            c.missing
                .iter()
                .map(|m| format!("({m})"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let share = if c.text.is_none() || c.equations.is_empty() {
            String::new()
        } else {
            format!(
                " ({:.0} %)",
                100.0 * c.covered() as f64 / c.equations.len() as f64
            )
        };
        md.push_str(&format!(
            "| {} | {} | {}{share} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            c.paper,
            c.equations.len(),
            c.covered(),
            c.claims,
            count("holds"),
            count("fails"),
            count("holds-with-correction"),
            count("holds-with-assumption"),
            count("definition"),
            count("not-checkable"),
            missing
        ));
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paper::source::blocks::tags;

    fn paper(equations: &[&str]) -> PaperClaims {
        let claims: String = equations
            .iter()
            .enumerate()
            .map(|(i, e)| {
                format!(
                    "[[claim]]\nid = \"p.{i}\"\nequation = \"{e}\"\nquote = \"q\"\nkind = \"check\"\ncheck = \"x\"\n"
                )
            })
            .collect();
        toml::from_str(&format!(
            "paper = \"p\"\ntitle = \"t\"\nreport = \"p.md\"\nfile = \"p.txt\"\n{claims}"
        ))
        .expect("claims")
    }

    #[test]
    fn a_claims_file_that_misses_an_equation_is_reported() {
        let text = "a $$x \\tag{1}$$ b $$y \\tag{2.1}$$ c $$z \\tag{2.1}$$ d \\tag{3}";
        assert_eq!(tags(text), vec!["1", "2.1", "3"]);
        let c = of_text(
            &paper(&["(1)", "(2.1)-(2.4)", "Fig. 2"]),
            Some(text),
            Some("p.txt".into()),
        );
        assert_eq!(c.equations, vec!["1", "2.1", "3"]);
        assert_eq!(c.missing, vec!["3"]);
        assert_eq!((c.covered(), c.claims, c.other_claims), (2, 3, 1));
        let all = of_text(
            &paper(&["(1)", "(2.1)", "(3)"]),
            Some(text),
            Some("p.txt".into()),
        );
        assert!(all.missing.is_empty());
    }

    #[test]
    fn the_equations_list_counts_without_the_text_and_is_checked_against_it() {
        let dir = std::env::temp_dir().join(format!("impactcheck-cov-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        std::fs::write(dir.join("p.txt"), "a $$x \\tag{1}$$ b $$y \\tag{2}$$").expect("write");
        let mut p = paper(&["(1)"]);
        p.source = dir.join("claims.toml");
        p.equations = vec!["1".into(), "2".into()];
        // counted from the list: the same with and without the text
        let with = compute(std::slice::from_ref(&p), Some(&dir));
        let mut no_text = p.clone();
        no_text.source = dir.join("elsewhere/claims.toml");
        let without = compute(std::slice::from_ref(&no_text), Some(&dir.join("none")));
        assert_eq!(with[0].equations, without[0].equations);
        assert_eq!(with[0].missing, vec!["2"]);
        assert_eq!(table(&with, &[]), table(&without, &[]));
        // the list is checked against the text: a missing label is an error naming it
        assert!(check_equations(&p, Some(&dir)).expect("agrees").is_some());
        p.equations = vec!["1".into()];
        let err = check_equations(&p, Some(&dir)).unwrap_err().to_string();
        assert!(err.contains("not listed: [\"2\"]"), "{err}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn labels_are_the_parenthesised_parts() {
        assert_eq!(labels("(2.6)-(2.10)"), vec!["2.6", "2.10"]);
        assert_eq!(labels("sec. 2"), Vec::<String>::new());
    }
}
