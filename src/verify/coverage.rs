//! Coverage: which numbered equations of a paper have a claim. The equations are the `\tag{...}`
//! labels of the paper's text (its `file`); a claim covers the labels written in parentheses in
//! its `equation` field (`"(2.3)"`, `"(2.6)-(2.10)"` covers 2.6 and 2.10). Computed on every run,
//! so the table in `reports/README.md` stays true when a claim is added or removed.

use super::{Outcome, PaperClaims};
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

/// The `\tag{...}` labels of a text, in order, once each.
pub fn tags(text: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut rest = text;
    while let Some(i) = rest.find("\\tag{") {
        rest = &rest[i + 5..];
        let Some(end) = rest.find('}') else { break };
        let label = rest[..end].trim().to_string();
        if !label.is_empty() && !out.contains(&label) {
            out.push(label);
        }
        rest = &rest[end..];
    }
    out
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

/// Where the paper's text is: beside the claims file, or among the seeds (`../shared/seeds/`
/// beside the repository).
pub fn text_path(p: &PaperClaims) -> Option<PathBuf> {
    if p.file.is_empty() {
        return None;
    }
    let dir = p.source.parent().unwrap_or(Path::new("."));
    let mut candidates = vec![dir.join(&p.file)];
    if let Some(root) = dir.parent() {
        candidates.push(root.join("../shared/seeds").join(&p.file));
    }
    candidates.push(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/seeds")
            .join(&p.file),
    );
    candidates.into_iter().find(|c| c.is_file())
}

/// The coverage of `p` given its text (`None`: not found).
pub fn of_text(p: &PaperClaims, text: Option<&str>, where_: Option<String>) -> Coverage {
    let equations = text.map(tags).unwrap_or_default();
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

/// The coverage of every paper that names its text.
pub fn compute(papers: &[PaperClaims]) -> Vec<Coverage> {
    papers
        .iter()
        .filter(|p| !p.file.is_empty() && p.paper != "hard")
        .map(|p| {
            let path = text_path(p);
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
        "## Coverage of the papers\n\nNumbered equations are the `\\tag{...}` labels of each paper's text; a claim covers the \
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
    fn labels_are_the_parenthesised_parts() {
        assert_eq!(labels("(2.6)-(2.10)"), vec!["2.6", "2.10"]);
        assert_eq!(labels("sec. 2"), Vec::<String>::new());
    }
}
