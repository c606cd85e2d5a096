//! `verify audit` and `verify init` as a library call (issue 55: the Python package's `audit`
//! and `init` run this same code): the paper read as LaTeX (its macros, with the preambles
//! given), the units of its symbols from a units file and from its own words (with the
//! vocabularies given), every relation audited; the claims file to start from.

use super::{Audit, Units};
use crate::paper::PaperError;
use crate::paper::source::blocks::{blocks_at, numbers};
use crate::paper::words::vocabulary::Vocabulary;
use std::path::{Path, PathBuf};

/// A paper read and audited.
pub struct PaperAudit {
    /// Every relation and symbol, as `verify audit --format json` prints it.
    pub audit: Audit,
    /// The paper's file name.
    pub name: String,
    /// The paper's text.
    pub text: String,
    /// Whether the text is a LaTeX document (not a displays extract).
    pub document: bool,
    /// The units used: the units file's, then the words'.
    pub units: Units,
    /// The paper's displays (each with the number printed after it).
    pub blocks: Vec<(Option<String>, String)>,
    /// Its document, when read from a LaTeX source.
    pub doc: Option<crate::paper::source::document::Document>,
}

impl PaperAudit {
    /// A units file to start from: the units declared and named in the words, then the fewest
    /// symbols whose units, once given, decide every relation ([`crate::paper::units::suggest`]),
    /// each `"?"` with the relations it appears in.
    pub fn suggest(&self) -> String {
        let (rels, inputs) = super::read_relations(&self.blocks, self.doc.as_ref(), &self.units);
        let critical = crate::paper::units::suggest::critical_symbols(&inputs, &self.units.symbols);
        let place = |i: usize| {
            rels[i].number.as_ref().map_or_else(
                || format!("`{}`", super::short(&rels[i].latex)),
                |n| format!("({n})"),
            )
        };
        let mut s = format!(
            "# The units of {}: {} symbol(s) to give (\"?\"), the fewest whose units decide every relation;\n# fill them in and audit again with --units FILE.\n[symbols]\n",
            self.name,
            critical.len()
        );
        for (name, text) in &self.units.texts {
            s.push_str(&format!("{} = \"{text}\"\n", super::init::key(name)));
        }
        for (name, w) in &self.units.words {
            s.push_str(&format!(
                "{} = \"{}\"  # {}\n",
                super::init::key(name),
                w.unit,
                w.source()
            ));
        }
        for (name, at) in &critical {
            let places: Vec<String> = at.iter().take(6).map(|&i| place(i)).collect();
            let more = if at.len() > 6 { ", ..." } else { "" };
            s.push_str(&format!(
                "{} = \"?\"  # in {}{more}\n",
                super::init::key(name),
                places.join(", ")
            ));
        }
        s
    }

    /// The audit's power on this paper: each relation it calls consistent misprinted with a
    /// unit error and the paper audited again ([`super::power`]).
    pub fn power(&self) -> super::power::AuditPower {
        let (rels, inputs) = super::read_relations(&self.blocks, self.doc.as_ref(), &self.units);
        super::power::measure(&self.audit, &rels, &inputs, &self.units)
    }
}

/// Reads `paper` and audits it as `verify audit` does; `say` hears what the command line prints
/// on stderr (a reader's problem, the words' notes) as it happens. `init` refuses a paper with no
/// display (a scaffold of nothing is no scaffold), where an audit is only empty.
pub fn audit_paper(
    paper: &Path,
    units: Option<&Path>,
    preamble: &[PathBuf],
    vocabulary: &[PathBuf],
    init: bool,
    say: &mut dyn FnMut(String),
) -> anyhow::Result<PaperAudit> {
    use anyhow::Context;
    let mut vocab = Vocabulary::builtin().map_err(|message| PaperError::BadFile {
        path: "src/paper/words/vocabulary.toml".into(),
        message,
    })?;
    for v in vocabulary {
        let text = std::fs::read_to_string(v).map_err(|e| PaperError::BadFile {
            path: v.clone(),
            message: format!("cannot read the vocabulary: {e}"),
        })?;
        let more =
            Vocabulary::parse(&text, "the vocabulary").map_err(|message| PaperError::BadFile {
                path: v.clone(),
                message,
            })?;
        vocab = vocab.extended(more);
    }
    let text = crate::paper::source::files::read_text(paper)
        .with_context(|| format!("reading the paper {}", paper.display()))?;
    let units = match units {
        Some(u) => super::read_units(u)?,
        None => Default::default(),
    };
    let mut macros = String::new();
    // a `subfiles` chapter built alone has its main file's preamble, as LaTeX gives it
    let main = crate::paper::source::blocks::subfiles_main(&text, paper);
    for p in main.iter().chain(preamble) {
        let text = crate::paper::source::files::read_text(p)
            .with_context(|| format!("reading the preamble {}", p.display()))?;
        let (text, problems) = crate::paper::source::blocks::preamble_part(&text, p);
        for problem in problems {
            say(format!("{} (preamble): {problem}", p.display()));
        }
        macros.push_str(&text);
        macros.push('\n');
    }
    let (blocks, doc) = blocks_at(&text, paper.parent(), &macros);
    // a file that cannot be followed (missing, outside the paper's folder) is named, and the
    // rest of the paper read
    for problem in doc.iter().flat_map(|d| &d.problems) {
        say(format!("{}: {problem}", paper.display()));
    }
    if blocks.is_empty() {
        let none = format!(
            "{}: no display math found ($$ ... $$, \\[ ... \\], equation, align, gather, multline, eqnarray)",
            paper.display()
        );
        // an audit of a text without displays is empty (a thesis whose chapters are missing,
        // a note in words); a scaffold of nothing is no scaffold
        if init {
            anyhow::bail!("{none}");
        }
        say(format!("{none}: the audit is empty"));
    }
    // the units the paper's words give its symbols (a displays extract has no words)
    let units = if let Some(d) = &doc {
        // the prose of every file of the paper, its lines those of the displays
        let known = crate::paper::source::packages::preamble_of(&format!("{}\n{macros}", d.text));
        let expanded =
            crate::paper::source::macros::expand_with(&d.text, &format!("{known}{macros}"))
                .map_or_else(|_| d.text.clone(), |e| e.0);
        let mut words = super::paper_words(&expanded, &blocks, &units, &vocab);
        if d.has_inputs() {
            for w in words.units.values_mut() {
                let (f, l) = d.place(w.line);
                let f = if f.is_empty() {
                    name_of(paper)
                } else {
                    f.to_string()
                };
                w.file = Some((f, l));
            }
        }
        for note in &words.notes {
            say(format!("{}: {note}", paper.display()));
        }
        units.with_words(words)
    } else {
        units
    };
    let audit = super::audit(&blocks, doc.as_ref(), &units);
    let name = name_of(paper);
    Ok(PaperAudit {
        audit,
        name,
        text,
        document: doc.is_some(),
        units,
        blocks,
        doc,
    })
}

/// The file name of `paper`.
fn name_of(paper: &Path) -> String {
    paper
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().to_string())
}

/// The claims file `verify init` prints for an audited paper, its claims' ids starting `id`.
pub fn init_claims(p: &PaperAudit, id: &str) -> String {
    // the numbers of every file of the paper, as LaTeX gives them
    let numbers = match &p.doc {
        Some(d) if p.name.ends_with(".tex") => {
            let mut out: Vec<String> = Vec::new();
            for n in &d.numbers {
                if !out.contains(n) {
                    out.push(n.clone());
                }
            }
            out
        }
        _ => numbers(&p.name, &p.text),
    };
    let title = if p.document {
        super::title_of(&p.text)
    } else {
        None
    }
    .unwrap_or_else(|| p.name.clone());
    super::init::init_claims(&p.audit, &numbers, id, &p.name, &title, &p.units)
}
