//! `verify audit DIR` (issue 66): every paper under a folder audited, one row each and the
//! totals. A paper is a `.tex` file that opens a document (`\documentclass` or
//! `\begin{document}`, its class perhaps in an input header) that no other paper inputs, or a
//! `.md` note with display math; the files a paper inputs are read as its parts, not as papers.

use serde::Serialize;
use std::path::{Path, PathBuf};

/// One paper's audit in a row.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ShelfRow {
    /// The paper, as a path under the folder.
    pub paper: String,
    /// Its relations.
    pub relations: usize,
    /// Those read (not unreadable).
    pub read: usize,
    /// Consistent with every side in a physical unit.
    pub consistent_in_a_unit: usize,
    /// Consistent only as relations of pure numbers.
    pub consistent_pure: usize,
    /// Inconsistent.
    pub inconsistent: usize,
    /// Undetermined.
    pub undetermined: usize,
    /// Why the audit failed, when it did (the paper cannot be read).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The papers under `dir`, sorted: `.tex` files with `\documentclass` or `\begin{document}`
/// that no other such file inputs (a header with the class, a chapter of `subfiles`), `.md`
/// files with display math. Hidden folders are passed over.
pub fn papers_in(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(&d)?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .collect();
        entries.sort();
        for p in entries {
            let hidden = p
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with('.'));
            if hidden {
                continue;
            }
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
            let Ok(text) = crate::paper::source::files::read_text(&p) else {
                continue;
            };
            let paper = match ext {
                "tex" => {
                    let text = crate::paper::source::files::strip_comments(&text);
                    text.contains("\\documentclass") || text.contains("\\begin{document}")
                }
                "md" => text.contains("$$") || text.contains("\\begin{equation"),
                _ => false,
            };
            if paper {
                out.push(p);
            }
        }
    }
    out.sort();
    // a file another paper reads is a part of that paper
    let mut parts = std::collections::BTreeSet::new();
    for p in &out {
        if p.extension().is_some_and(|e| e == "tex") {
            parts.extend(inputs_of(p));
        }
    }
    out.retain(|p| !parts.contains(p));
    Ok(out)
}

/// The files the paper `p` reads through its inputs (as the audit follows them), as paths
/// beside `p`.
fn inputs_of(p: &Path) -> Vec<PathBuf> {
    let Ok(text) = crate::paper::source::files::read_text(p) else {
        return Vec::new();
    };
    let dir = p.parent().unwrap_or(Path::new("."));
    let load = crate::paper::source::blocks::folder_loader(dir);
    let (_, spans, _) = crate::paper::source::files::assemble(&text, &load);
    spans
        .iter()
        .filter(|s| !s.file.is_empty())
        .map(|s| dir.join(&s.file))
        .filter(|f| f != p)
        .collect()
}

/// The row of an audit.
pub fn row_of(paper: String, a: &super::Audit) -> ShelfRow {
    let c = a.counts();
    let n = |k: &str| c.get(k).copied().unwrap_or(0);
    ShelfRow {
        paper,
        relations: a.relations.len(),
        read: a.relations.len() - n("unreadable"),
        consistent_in_a_unit: a.consistent_in_a_unit,
        consistent_pure: a.consistent_pure,
        inconsistent: n("inconsistent"),
        undetermined: n("undetermined"),
        error: None,
    }
}

/// The totals of `rows`.
pub fn total(rows: &[ShelfRow]) -> ShelfRow {
    let mut t = ShelfRow {
        paper: format!("all ({} papers)", rows.len()),
        ..ShelfRow::default()
    };
    for r in rows {
        t.relations += r.relations;
        t.read += r.read;
        t.consistent_in_a_unit += r.consistent_in_a_unit;
        t.consistent_pure += r.consistent_pure;
        t.inconsistent += r.inconsistent;
        t.undetermined += r.undetermined;
    }
    t
}

/// A share in per cent, `-` of nothing.
fn share(k: usize, n: usize) -> String {
    if n == 0 {
        "-".into()
    } else {
        format!("{:.1} %", 100.0 * k as f64 / n as f64)
    }
}

/// The rows as a table: `md` (Markdown) or `csv`, the totals last.
pub fn table(rows: &[ShelfRow], md: bool) -> String {
    let head = [
        "paper",
        "relations",
        "read",
        "decided with a unit",
        "consistent as pure numbers",
        "inconsistent",
        "undetermined",
        "error",
    ];
    let mut s = String::new();
    if md {
        s.push_str(&format!(
            "| {} |\n|{}\n",
            head.join(" | "),
            "---|".repeat(head.len())
        ));
    } else {
        s.push_str(&head.join(","));
        s.push('\n');
    }
    let all = total(rows);
    for r in rows.iter().chain(std::iter::once(&all)) {
        let cells = [
            r.paper.clone(),
            r.relations.to_string(),
            if md {
                format!("{} ({})", r.read, share(r.read, r.relations))
            } else {
                r.read.to_string()
            },
            if md {
                format!(
                    "{} ({})",
                    r.consistent_in_a_unit,
                    share(r.consistent_in_a_unit, r.relations)
                )
            } else {
                r.consistent_in_a_unit.to_string()
            },
            r.consistent_pure.to_string(),
            r.inconsistent.to_string(),
            r.undetermined.to_string(),
            r.error.clone().unwrap_or_default(),
        ];
        if md {
            s.push_str(&format!("| {} |\n", cells.join(" | ")));
        } else {
            let quoted: Vec<String> = cells
                .iter()
                .map(|c| {
                    if c.contains([',', '"', '\n']) {
                        format!("\"{}\"", c.replace('"', "\"\""))
                    } else {
                        c.clone()
                    }
                })
                .collect();
            s.push_str(&quoted.join(","));
            s.push('\n');
        }
    }
    s
}

/// The rows as text: a line per paper, then the totals.
pub fn to_text(rows: &[ShelfRow]) -> String {
    let mut s = String::new();
    let all = total(rows);
    for r in rows.iter().chain(std::iter::once(&all)) {
        match &r.error {
            Some(e) => s.push_str(&format!("{}: failed: {e}\n", r.paper)),
            None => s.push_str(&format!(
                "{}: {} relations, {} read ({}), {} decided with a unit ({}), {} inconsistent, {} undetermined\n",
                r.paper,
                r.relations,
                r.read,
                share(r.read, r.relations),
                r.consistent_in_a_unit,
                share(r.consistent_in_a_unit, r.relations),
                r.inconsistent,
                r.undetermined
            )),
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn totals_and_tables_by_hand() {
        let row = |p: &str, n: usize, read: usize, unit: usize, bad: usize| ShelfRow {
            paper: p.into(),
            relations: n,
            read,
            consistent_in_a_unit: unit,
            consistent_pure: 1,
            inconsistent: bad,
            undetermined: read - unit - bad - 1,
            error: None,
        };
        let rows = [row("a.tex", 10, 8, 4, 1), row("b,c.tex", 2, 2, 1, 0)];
        let t = total(&rows);
        let all = (
            t.relations,
            t.read,
            t.consistent_in_a_unit,
            t.consistent_pure,
        );
        assert_eq!(all, (12, 10, 5, 2));
        assert_eq!((t.inconsistent, t.undetermined), (1, 2));
        let csv = table(&rows, false);
        assert!(csv.contains("\"b,c.tex\",2,2,1,1,0,0,\n"), "{csv}");
        assert!(csv.ends_with("all (2 papers),12,10,5,2,1,2,\n"), "{csv}");
        let md = table(&rows, true);
        assert!(
            md.contains("| a.tex | 10 | 8 (80.0 %) | 4 (40.0 %) |"),
            "{md}"
        );
        assert!(to_text(&rows).contains("all (2 papers): 12 relations, 10 read (83.3 %)"));
    }
}
