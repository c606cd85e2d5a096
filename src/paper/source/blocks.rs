//! A paper's displays from its text, and its equation numbers: a LaTeX source read as LaTeX
//! numbers it ([`read_document`]), its `\input` files from its own folder only, or a displays
//! extract of `%% block N` sections (the seeds' cache, `verify/tex/`).

use super::document::{Document, read_document};

/// The blocks of a displays file: (the tag printed after the block, the LaTeX).
pub fn display_blocks(text: &str) -> Vec<(Option<String>, String)> {
    let mut out: Vec<(Option<String>, String)> = Vec::new();
    for line in text.lines() {
        if let Some(head) = line.strip_prefix("%% block ") {
            out.push((
                head.split(" tag=").nth(1).map(str::to_string),
                String::new(),
            ));
        } else if !line.starts_with('%')
            && let Some(last) = out.last_mut()
        {
            last.1.push_str(line);
            last.1.push('\n');
        }
    }
    out
}

/// The words a refused `\input` is named with (a path that leaves the paper's folder).
pub const OUTSIDE: &str = "outside the paper's folder";

/// How a paper in `dir` reads its `\input{name}`: `dir/name` (or `dir/name.tex`), refused
/// when the path is absolute or leads out of `dir` (a paper from anyone must not make the tool
/// read elsewhere), an error naming the file when it cannot be read.
pub fn folder_loader(dir: &std::path::Path) -> impl Fn(&str) -> Result<String, String> + '_ {
    move |name: &str| {
        let refuse = || {
            format!(
                "`\\input{{{name}}}`: {name} is {OUTSIDE} {} (refused)",
                dir.display()
            )
        };
        let rel = std::path::Path::new(name);
        if rel.is_absolute()
            || rel.components().any(|c| {
                !matches!(
                    c,
                    std::path::Component::Normal(_) | std::path::Component::CurDir
                )
            })
        {
            return Err(refuse());
        }
        let mut path = dir.join(rel);
        if !path.is_file() {
            path = dir.join(format!("{name}.tex"));
        }
        let root = dir
            .canonicalize()
            .map_err(|e| format!("{}: {e}", dir.display()))?;
        let real = path
            .canonicalize()
            .map_err(|_| format!("`\\input{{{name}}}`: no file {} in {}", name, dir.display()))?;
        if !real.starts_with(&root) {
            return Err(refuse());
        }
        super::files::read_text(&real)
            .map_err(|e| format!("`\\input{{{name}}}`: {}: {e}", real.display()))
    }
}

/// What a file given as a preamble contributes, and what of it could not be followed: a main
/// file (`\documentclass` or `\begin{document}`) its text before `\begin{document}`, its
/// inputs read from its own folder (the folder of `path`); any other file (a file of macros)
/// its whole text.
pub fn preamble_part(text: &str, path: &std::path::Path) -> (String, Vec<String>) {
    let clean = super::files::strip_comments(text);
    let begin = clean.find("\\begin{document}");
    if begin.is_none() && !clean.contains("\\documentclass") {
        return (text.to_string(), Vec::new());
    }
    let head = &clean[..begin.unwrap_or(clean.len())];
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => std::path::Path::new("."),
    };
    let load = folder_loader(dir);
    let (out, _, problems) = super::files::assemble(head, &load);
    (out, problems)
}

/// The main file a `subfiles` chapter names (`\documentclass[../main.tex]{subfiles}`), whose
/// preamble LaTeX reads for it when the chapter is built alone: a relative path from the
/// chapter's folder (`.tex` added when it has none) to a main file (a `\documentclass` or a
/// `\begin{document}`, not itself a `subfiles` chapter) that is not the chapter itself. An absolute path, or a file that is no main file, is
/// none.
pub fn subfiles_main(text: &str, paper: &std::path::Path) -> Option<std::path::PathBuf> {
    let clean = super::files::strip_comments(text);
    let k = clean.find("\\documentclass[")?;
    let rest = &clean[k + "\\documentclass[".len()..];
    let close = rest.find(']')?;
    if !rest[close + 1..].trim_start().starts_with("{subfiles}") {
        return None;
    }
    let name = rest[..close].trim();
    let rel = std::path::Path::new(name);
    if name.is_empty() || rel.is_absolute() || name.starts_with('~') {
        return None;
    }
    let dir = paper.parent().unwrap_or(std::path::Path::new(""));
    let mut main = dir.join(rel);
    if main.extension().is_none() {
        main.set_extension("tex");
    }
    let same = |a: &std::path::Path, b: &std::path::Path| matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y);
    let main_text = super::files::read_text(&main).ok()?;
    let main_clean = super::files::strip_comments(&main_text);
    let own_class = (main_clean.contains("\\documentclass")
        || main_clean.contains("\\begin{document}"))
        && subfiles_main_named(&main_text).is_none();
    (own_class && !same(&main, paper)).then_some(main)
}

/// Whether `text` is itself a `subfiles` chapter (its class `subfiles`).
fn subfiles_main_named(text: &str) -> Option<()> {
    let clean = super::files::strip_comments(text);
    let k = clean.find("\\documentclass")?;
    clean[k..]
        .split_once('{')
        .and_then(|(_, r)| r.split_once('}'))
        .filter(|(class, _)| class.trim() == "subfiles")
        .map(|_| ())
}

/// A paper's displays from its text: a displays extract of `%% block N` sections (the seeds'
/// cache, `verify/tex/`), or a LaTeX source (or a text with display math) read as LaTeX numbers
/// it, with its document.
pub fn blocks_of(text: &str) -> (Vec<(Option<String>, String)>, Option<Document>) {
    blocks_at(text, None, "")
}

/// As [`blocks_of`], for a paper in the folder `dir`: its `\input` files read from that folder
/// (a path that leaves it refused, [`folder_loader`]), the macros of `preamble` made first.
pub fn blocks_at(
    text: &str,
    dir: Option<&std::path::Path>,
    preamble: &str,
) -> (Vec<(Option<String>, String)>, Option<Document>) {
    if text.lines().any(|l| l.starts_with("%% block ")) {
        return (display_blocks(text), None);
    }
    let doc = match dir {
        Some(d) => {
            let here = std::path::Path::new(".");
            let load = folder_loader(if d.as_os_str().is_empty() { here } else { d });
            super::document::read_document_full(text, preamble, &load)
        }
        None if preamble.is_empty() => read_document(text),
        None => super::document::read_document_full(text, preamble, &|name| {
            Err(format!("`\\input{{{name}}}`: no folder to read it from"))
        }),
    };
    let blocks = doc
        .displays
        .iter()
        .map(|d| (d.after.clone(), d.latex.clone()))
        .collect();
    (blocks, Some(doc))
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

/// The numbers of a paper's text, in order, once each: for a `.tex` file, as LaTeX numbers a
/// source (automatic numbers, `\tag`s and numbers printed after a block) or, for a displays
/// extract, its blocks' tags and the numbers printed after them; the `\tag{...}` labels for any
/// other text (the seeds).
pub fn numbers(file: &str, text: &str) -> Vec<String> {
    numbers_at(file, text, None)
}

/// As [`numbers`], for a text in the folder `dir`: its `\input` files read from there, so that
/// a main file's numbers are those of the sections it reads.
pub fn numbers_at(file: &str, text: &str, dir: Option<&std::path::Path>) -> Vec<String> {
    if !file.ends_with(".tex") {
        return tags(text);
    }
    let mut out: Vec<String> = Vec::new();
    let all = match blocks_at(text, dir, "") {
        (_, Some(doc)) => doc.numbers,
        // a displays extract: each block's tags, and the number printed after it
        (blocks, None) => blocks
            .iter()
            .flat_map(|(after, tex)| tags(tex).into_iter().chain(after.clone()))
            .collect(),
    };
    for n in all {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}
