//! The shape of the house as tests (issue 42), the way rustc's `src/tools/tidy` fails a build on
//! a file too long and ArchUnit states layers as assertions: a rule no test checks erodes.
//!
//! Four rules over every `.rs` file under `src/`, each failure naming the file, the line and the
//! rule:
//! - **file length**: at most [`MAX_FILE_LINES`] lines (every line, as `wc -l` counts them);
//! - **function length**: at most [`MAX_FN_LINES`] lines, counted from the line of the `fn`
//!   keyword to the line of the function's closing brace, both included (its doc comment and
//!   attributes above are not counted; blank and comment lines inside are; a function nested in
//!   another counts for both);
//! - **floors**: a path into the crate (`crate::m::...`, `use crate::{m::..}`, or `super::` chains
//!   that climb to the crate root), outside comments and string literals, names a top-level
//!   module `m` that the file's own module may import ([`FLOORS`], the README's tour). A
//!   top-level module missing from the table is itself a failure, so a new module must be given
//!   its floor;
//! - **no two files importing each other** (issue 64): a file that names an item of another
//!   (through `crate::`, `super::`, `self::` or a child module, in a `use` or in code) imports
//!   it; two files that import each other are one piece of code in two places, and what they
//!   share goes into the lower one. A module's file and the files of its own submodules are
//!   exempt: they are one module's face and parts (a part reaches its module's private helpers
//!   through `super::`).
//!
//! The checks read source text with a small lexer of their own (comments, strings, raw strings,
//! chars and lifetimes): `syn` would parse more exactly but is a heavy dependency for four
//! rules, and the lexer is tested below on the cases that would fool a line-based grep.
//! `planted` tests each rule on a violation planted in text, and on look-alikes that must pass.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

/// The longest file allowed under `src/`.
const MAX_FILE_LINES: usize = 1000;
/// The longest function allowed under `src/`.
const MAX_FN_LINES: usize = 200;

/// Each top-level module of the crate and the top-level modules it may name (itself included).
/// The floors, lowest first: `algebra`, `integrate` and the utilities `rng`, `interrupt` import
/// nothing of the crate but themselves; `paper` (a paper as read: its source, formulas, words,
/// units and audit) imports `algebra` only, and only `verify` and the front ends import it;
/// `models` imports the lowest four but never `paper`; `scene` imports `models`;
/// `report` renders plain data and never imports `verify` or a front end; `verify` imports all
/// of these and never `cli`, `perf` or a binary; `cli` and `perf` are the front ends' library
/// half. `lib` (src/lib.rs) declares the modules.
#[rustfmt::skip]
const FLOORS: &[(&str, &[&str])] = &[
    ("algebra", &["algebra"]),
    ("integrate", &["integrate"]),
    ("rng", &["rng"]),
    ("interrupt", &["interrupt"]),
    ("paper", &["algebra", "paper"]),
    ("models", &["algebra", "integrate", "rng", "models"]),
    ("scene", &["algebra", "integrate", "rng", "models", "scene"]),
    ("report", &["algebra", "integrate", "rng", "models", "scene", "report"]),
    ("verify", &["algebra", "integrate", "rng", "models", "scene", "report", "paper", "verify"]),
    ("perf", &["algebra", "integrate", "rng", "models", "scene", "report", "paper", "verify", "perf"]),
    ("cli", EVERY),
    ("lib", EVERY),
];

#[rustfmt::skip]
/// Every top-level module: what the front ends and the crate root may name.
const EVERY: &[&str] = &[
    "algebra", "integrate", "rng", "interrupt", "paper", "models", "scene", "report", "verify", "cli",
    "perf",
];

/// One broken rule: where, and which.
#[derive(Debug, Clone, PartialEq)]
struct Violation {
    file: String,
    line: usize,
    rule: String,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.rule)
    }
}

/// A token of Rust source that the rules need: identifiers, `::` and the brackets, each with its
/// 1-based line. Comments, strings, chars and lifetimes are dropped.
#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Ident(String),
    PathSep,
    Open(char),
    Close(char),
    Semi,
    Comma,
    Other,
}

/// Lexes `src` into [`Tok`]s with their lines. Unterminated literals end the file (rustc would
/// refuse it anyway).
fn lex(src: &str) -> Vec<(Tok, usize)> {
    let c: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    // advances over c[i..j], counting newlines
    let skip = |i: &mut usize, j: usize, line: &mut usize| {
        let j = j.min(c.len());
        *line += c[*i..j].iter().filter(|&&x| x == '\n').count();
        *i = j;
    };
    while i < c.len() {
        let x = c[i];
        let next = c.get(i + 1).copied();
        if x == '/' && next == Some('/') {
            let end = c[i..]
                .iter()
                .position(|&y| y == '\n')
                .map_or(c.len(), |p| i + p);
            skip(&mut i, end, &mut line);
        } else if x == '/' && next == Some('*') {
            // block comments nest
            let (mut j, mut depth) = (i + 2, 1);
            while j < c.len() && depth > 0 {
                if c[j] == '/' && c.get(j + 1) == Some(&'*') {
                    depth += 1;
                    j += 2;
                } else if c[j] == '*' && c.get(j + 1) == Some(&'/') {
                    depth -= 1;
                    j += 2;
                } else {
                    j += 1;
                }
            }
            skip(&mut i, j, &mut line);
        } else if let Some(end) = raw_string_end(&c, i) {
            skip(&mut i, end, &mut line);
        } else if x == '"' || (x == 'b' && next == Some('"')) {
            let mut j = if x == 'b' { i + 2 } else { i + 1 };
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            skip(&mut i, j + 1, &mut line);
        } else if x == '\'' || (x == 'b' && next == Some('\'')) {
            let q = if x == 'b' { i + 1 } else { i };
            if c.get(q + 1) == Some(&'\\') {
                // an escaped char: up to the closing quote
                let mut j = q + 2;
                while j < c.len() && c[j] != '\'' {
                    j += 1;
                }
                skip(&mut i, j + 1, &mut line);
            } else if c.get(q + 2) == Some(&'\'') {
                skip(&mut i, q + 3, &mut line);
            } else {
                // a lifetime or label: the quote alone; the name lexes as an identifier
                out.push((Tok::Other, line));
                i = q + 1;
            }
        } else if x.is_alphabetic() || x == '_' {
            let mut j = i;
            while j < c.len() && (c[j].is_alphanumeric() || c[j] == '_') {
                j += 1;
            }
            // a raw identifier `r#name` is the name
            let word: String = c[i..j].iter().collect();
            if word == "r" && next == Some('#') {
                i += 2;
                continue;
            }
            out.push((Tok::Ident(word), line));
            i = j;
        } else if x == ':' && next == Some(':') {
            out.push((Tok::PathSep, line));
            i += 2;
        } else {
            out.push((
                match x {
                    '(' | '[' | '{' => Tok::Open(x),
                    ')' | ']' | '}' => Tok::Close(x),
                    ';' => Tok::Semi,
                    ',' => Tok::Comma,
                    _ => Tok::Other,
                },
                line,
            ));
            if x == '\n' {
                line += 1;
                out.pop();
            } else if x.is_whitespace() {
                out.pop();
            }
            i += 1;
        }
    }
    out
}

/// The end (one past the closing quote and hashes) of a raw string starting at `i` (`r"`,
/// `r#"`, `br##"`...), or `None` when none starts there.
fn raw_string_end(c: &[char], i: usize) -> Option<usize> {
    // not the tail of an identifier (`attr"`, `bar#`)
    if i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_') {
        return None;
    }
    let mut j = i;
    if c.get(j) == Some(&'b') {
        j += 1;
    }
    if c.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let mut hashes = 0;
    while c.get(j) == Some(&'#') {
        hashes += 1;
        j += 1;
    }
    if c.get(j) != Some(&'"') {
        return None;
    }
    j += 1;
    while j < c.len() {
        if c[j] == '"' && (1..=hashes).all(|k| c.get(j + k) == Some(&'#')) {
            return Some(j + 1 + hashes);
        }
        j += 1;
    }
    Some(c.len())
}

/// Every function with a body: its name, the line of `fn` and the line of its closing brace.
fn functions(toks: &[(Tok, usize)]) -> Vec<(String, usize, usize)> {
    let mut out = Vec::new();
    for (k, (t, line)) in toks.iter().enumerate() {
        let (Tok::Ident(kw), Some((Tok::Ident(name), _))) = (t, toks.get(k + 1)) else {
            continue;
        };
        if kw != "fn" {
            continue;
        }
        // the body opens at the first `{` outside the signature's () and [], unless a `;` (a
        // declaration without body) comes first
        let mut depth = 0i32;
        let mut body = None;
        for (j, (u, _)) in toks.iter().enumerate().skip(k + 2) {
            match u {
                Tok::Open('{') if depth == 0 => {
                    body = Some(j);
                    break;
                }
                Tok::Semi if depth == 0 => break,
                Tok::Open(_) => depth += 1,
                Tok::Close(_) => depth -= 1,
                _ => {}
            }
        }
        let Some(open) = body else { continue };
        let mut depth = 0i32;
        for (u, end) in &toks[open..] {
            match u {
                Tok::Open(_) => depth += 1,
                Tok::Close(_) => {
                    depth -= 1;
                    if depth == 0 {
                        out.push((name.clone(), *line, *end));
                        break;
                    }
                }
                _ => {}
            }
        }
    }
    out
}

/// The module path of a file under `src/` (`models/rigid_impact/driver.rs` ->
/// `[models, rigid_impact, driver]`, `models/mod.rs` -> `[models]`, `lib.rs` -> `[lib]`).
fn module_path(rel: &str) -> Vec<String> {
    let rel = rel.strip_suffix(".rs").unwrap_or(rel);
    let mut parts: Vec<String> = rel.split('/').map(str::to_string).collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// Every top-level module that the tokens name through the crate root, with its line:
/// `crate::m`, each `m` of `crate::{m::.., n}`, and `super::...::m` where the supers climb to the
/// root (a path that stays in the file's own top-level module names that module). `path` is the
/// file's module path.
fn crate_paths(toks: &[(Tok, usize)], path: &[String]) -> Vec<(String, usize)> {
    let mut out: Vec<(String, usize)> = named_paths(toks, path, &BTreeMap::new())
        .into_iter()
        .filter_map(|(segs, line)| Some((segs.into_iter().next()?, line)))
        .collect();
    // the items of one group (`crate::cli::{a, b}`) name their module once
    out.dedup();
    out
}

/// Every rule broken by the file `rel` (its path under `src/`) with text `src`.
fn check_file(rel: &str, src: &str) -> Vec<Violation> {
    let v = |line: usize, rule: String| Violation {
        file: format!("src/{rel}"),
        line,
        rule,
    };
    let mut out = Vec::new();
    let lines = src.lines().count();
    if lines > MAX_FILE_LINES {
        out.push(v(
            MAX_FILE_LINES + 1,
            format!("file length: {lines} lines, over {MAX_FILE_LINES}"),
        ));
    }
    let toks = lex(src);
    for (name, start, end) in functions(&toks) {
        let n = end - start + 1;
        if n > MAX_FN_LINES {
            out.push(v(
                start,
                format!(
                    "function length: `{name}` is {n} lines (to line {end}), over {MAX_FN_LINES}"
                ),
            ));
        }
    }
    let path = module_path(rel);
    let top = path.first().map(String::as_str).unwrap_or("lib");
    if top == "bin" {
        // the binaries are the top floor: they reach the library as `impactcheck::`
        return out;
    }
    let Some((_, allowed)) = FLOORS.iter().find(|(m, _)| *m == top) else {
        out.push(v(
            1,
            format!("floors: module `{top}` has no floor in tests/architecture.rs's FLOORS"),
        ));
        return out;
    };
    for (m, line) in crate_paths(&toks, &path) {
        if !allowed.contains(&m.as_str()) {
            out.push(v(
                line,
                format!(
                    "floors: `{top}` imports `crate::{m}` (it may import only {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    out
}

/// Every path into the crate that the tokens name, as the module path it names (items
/// included: `crate::paper::units::Units` is `[paper, units, Units]`), with its line: paths
/// from `crate::`, from `super::` chains and `self::`, and from a child module of the file's
/// own (`marks::marked` in `reader/mod.rs`); groups (`crate::{a::b, c}`) expanded, renames
/// (`as x`) dropped. `path` is the file's module path; `modules` every module of the crate.
fn named_paths(
    toks: &[(Tok, usize)],
    path: &[String],
    modules: &BTreeMap<Vec<String>, String>,
) -> Vec<(Vec<String>, usize)> {
    let ident = |k: usize| match toks.get(k) {
        Some((Tok::Ident(s), _)) => Some(s.as_str()),
        _ => None,
    };
    let sep = |k: usize| matches!(toks.get(k), Some((Tok::PathSep, _)));
    let mut out = Vec::new();
    let mut inline: Vec<i32> = Vec::new();
    let mut depth = 0i32;
    let mut k = 0;
    while k < toks.len() {
        match &toks[k].0 {
            Tok::Open('{') => {
                if k >= 2 && ident(k - 2) == Some("mod") && ident(k - 1).is_some() {
                    inline.push(depth);
                }
                depth += 1;
            }
            Tok::Close('}') => {
                depth -= 1;
                if inline.last() == Some(&depth) {
                    inline.pop();
                }
            }
            _ => {}
        }
        let starts = k == 0 || !sep(k - 1);
        let from = match ident(k) {
            Some("crate") if starts && sep(k + 1) => Some((Vec::new(), k + 2)),
            Some("self") if starts && sep(k + 1) => Some((path.to_vec(), k + 2)),
            Some("super") if starts && sep(k + 1) => {
                // inline modules are climbed out of first; they stay in this file
                let mut level = path.len() + inline.len();
                let mut j = k;
                while ident(j) == Some("super") && sep(j + 1) {
                    level = level.saturating_sub(1);
                    j += 2;
                }
                Some((path[..level.min(path.len())].to_vec(), j))
            }
            Some(name) if starts && sep(k + 1) => {
                let mut child = path.to_vec();
                child.push(name.to_string());
                modules.contains_key(&child).then_some((path.to_vec(), k))
            }
            _ => None,
        };
        let Some((base, j)) = from else {
            k += 1;
            continue;
        };
        let end = path_items(toks, j, base, &mut out);
        // the braces of a group were walked over: count them as the loop would
        for (t, _) in &toks[k + 1..end.min(toks.len())] {
            match t {
                Tok::Open('{') => depth += 1,
                Tok::Close('}') => depth -= 1,
                _ => {}
            }
        }
        k = end.max(k + 1);
    }
    out
}

/// Walks one path from `toks[j]` on, its segments after `prefix`, into `out`; returns the index
/// after it.
fn path_items(
    toks: &[(Tok, usize)],
    mut j: usize,
    mut segs: Vec<String>,
    out: &mut Vec<(Vec<String>, usize)>,
) -> usize {
    loop {
        let Some((t, line)) = toks.get(j) else {
            out.push((segs, toks.last().map_or(1, |t| t.1)));
            return j;
        };
        match t {
            Tok::Ident(s) => {
                if s != "self" {
                    segs.push(s.clone());
                }
                if matches!(toks.get(j + 1), Some((Tok::PathSep, _))) {
                    j += 2;
                    continue;
                }
                out.push((segs, *line));
                // a rename: `as name`
                if matches!(toks.get(j + 1), Some((Tok::Ident(a), _)) if a == "as") {
                    return j + 3;
                }
                return j + 1;
            }
            Tok::Open('{') => {
                j += 1;
                loop {
                    match toks.get(j) {
                        None => return j,
                        Some((Tok::Close('}'), _)) => return j + 1,
                        Some((Tok::Comma, _)) => j += 1,
                        Some(_) => j = path_items(toks, j, segs.clone(), out).max(j + 1),
                    }
                }
            }
            _ => {
                // a glob `*` or the end of the path
                out.push((segs, *line));
                return j + 1;
            }
        }
    }
}

/// The file of the module a path names: the longest prefix of it that is a module.
fn file_of<'a>(segs: &[String], modules: &'a BTreeMap<Vec<String>, String>) -> Option<&'a str> {
    (1..=segs.len())
        .rev()
        .find_map(|k| modules.get(&segs[..k]).map(String::as_str))
}

/// Every pair of files that import each other (each names an item of the other), one violation
/// per pair at the first file's import. A module's own parts are not such a pair: a file and
/// the files of its submodules (`reader/mod.rs` and `reader/marks.rs`, which reaches its
/// module's private helpers through `super::`) are one module's face and parts. `files` are
/// (path under `src/`, text).
fn check_pairs(files: &[(String, String)]) -> Vec<Violation> {
    let modules: BTreeMap<Vec<String>, String> = files
        .iter()
        .filter(|(rel, _)| rel != "lib.rs" && !rel.starts_with("bin/"))
        .map(|(rel, _)| (module_path(rel), rel.clone()))
        .collect();
    // (importer, imported) -> the first line
    let mut edges: BTreeMap<(String, String), usize> = BTreeMap::new();
    for (rel, src) in files {
        if rel == "lib.rs" || rel.starts_with("bin/") {
            continue;
        }
        let path = module_path(rel);
        for (segs, line) in named_paths(&lex(src), &path, &modules) {
            if let Some(f) = file_of(&segs, &modules)
                && f != rel
            {
                edges.entry((rel.clone(), f.to_string())).or_insert(line);
            }
        }
    }
    let part_of = |a: &str, b: &str| {
        let (a, b) = (module_path(a), module_path(b));
        a.starts_with(&b) || b.starts_with(&a)
    };
    let mut out = Vec::new();
    for ((a, b), line) in &edges {
        if a < b
            && !part_of(a, b)
            && let Some(back) = edges.get(&(b.clone(), a.clone()))
        {
            out.push(Violation {
                file: format!("src/{a}"),
                line: *line,
                rule: format!(
                    "files importing each other: src/{a} imports src/{b} (line {line}), and src/{b} imports src/{a} (line {back}); move what they share into the lower one"
                ),
            });
        }
    }
    out
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

#[test]
fn the_source_keeps_its_shape() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    assert!(
        files.len() > 50,
        "src/ should hold the crate ({} files found)",
        files.len()
    );
    let mut all = Vec::new();
    let mut texts = Vec::new();
    for f in &files {
        let rel = f
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        let text = std::fs::read_to_string(f).unwrap();
        all.extend(check_file(&rel, &text));
        texts.push((rel, text));
    }
    all.extend(check_pairs(&texts));
    let list: Vec<String> = all.iter().map(ToString::to_string).collect();
    assert!(
        list.is_empty(),
        "{} broken rule(s):\n{}",
        list.len(),
        list.join("\n")
    );
}

/// Every top-level module under `src/` has a floor, and every floor is a module (a renamed module
/// must be renamed here too).
#[test]
fn every_module_has_a_floor() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut tops: Vec<String> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter_map(|p| {
            let name = p.file_stem()?.to_string_lossy().to_string();
            (p.is_dir() || p.extension().is_some_and(|x| x == "rs")).then_some(name)
        })
        .filter(|n| n != "bin")
        .collect();
    tops.sort();
    tops.dedup();
    let mut floors: Vec<String> = FLOORS.iter().map(|(m, _)| m.to_string()).collect();
    floors.sort();
    assert_eq!(tops, floors);
}

/// A test of the tests: each rule fails on a violation planted in text, naming the file, the
/// line and the rule, and passes the look-alikes that a line-based grep would flag.
mod planted {
    use super::*;

    fn rules(rel: &str, src: &str) -> Vec<String> {
        check_file(rel, src)
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn a_long_file() {
        let src = "// a line\n".repeat(MAX_FILE_LINES + 1);
        assert_eq!(
            rules("algebra/long.rs", &src),
            ["src/algebra/long.rs:1001: file length: 1001 lines, over 1000"]
        );
        let src = "// a line\n".repeat(MAX_FILE_LINES);
        assert!(rules("algebra/long.rs", &src).is_empty());
    }

    /// A function of `body` inner lines after a doc comment and an attribute.
    fn function(body: usize) -> String {
        format!(
            "/// doc\n#[inline]\npub fn long(x: &[u8; {{ 2 }}]) -> Option<u8>\nwhere\n    u8: Copy,\n{{\n{}}}\n",
            "    let _ = x;\n".repeat(body)
        )
    }

    #[test]
    fn a_long_function() {
        // fn line, `where`, bound, `{`, body, `}`: body + 5 lines
        let src = function(MAX_FN_LINES - 4);
        assert_eq!(
            rules("models/f.rs", &src),
            ["src/models/f.rs:3: function length: `long` is 201 lines (to line 203), over 200"]
        );
        assert!(rules("models/f.rs", &function(MAX_FN_LINES - 5)).is_empty());
        // a nested function counts for both; a trait method without a body for none; braces in
        // strings, chars, comments and raw strings count for nothing; lifetimes are not chars
        let nested = format!(
            "trait T {{ fn declared(&self) -> u8; }}\nfn outer<'a>(s: &'a str) -> &'a str {{\n    let _ = '{{';\n    let _ = \"}}}}\";\n    let _ = r#\"{{\"#;\n    /* {{ */ // {{\n{}    s\n}}\n",
            function(MAX_FN_LINES - 4)
        );
        let got = rules("models/f.rs", &nested);
        assert_eq!(got.len(), 2, "{got:?}");
        assert!(
            got[0]
                .contains("src/models/f.rs:2: function length: `outer` is 210 lines (to line 211)")
        );
        assert!(
            got[1]
                .contains("src/models/f.rs:9: function length: `long` is 201 lines (to line 209)")
        );
    }

    #[test]
    fn imports_above_the_floor() {
        let cases: &[(&str, &str, &str)] = &[
            (
                "models/hertz.rs",
                "use crate::scene::Scene;\n",
                "`models` imports `crate::scene`",
            ),
            (
                "models/a/b.rs",
                "\n\nfn f() { crate::perf::x(); }\n",
                "`models` imports `crate::perf`",
            ),
            (
                "algebra/poly.rs",
                "use crate::integrate::Method;\n",
                "`algebra` imports `crate::integrate`",
            ),
            (
                "integrate/erk.rs",
                "use crate::models::Model;\n",
                "`integrate` imports `crate::models`",
            ),
            (
                "report/mod.rs",
                "use crate::verify::Claim;\n",
                "`report` imports `crate::verify`",
            ),
            (
                "verify/hard_cases.rs",
                "use crate::{algebra::expr, perf::rigid};\n",
                "`verify` imports `crate::perf`",
            ),
            (
                "verify/kinds/mod.rs",
                "use crate::{\n    cli::{a, b},\n};\n",
                "`verify` imports `crate::cli`",
            ),
            (
                "verify/x.rs",
                "use crate::bin::verify;\n",
                "`verify` imports `crate::bin`",
            ),
            // three supers from models/a/b.rs climb to the root, and one more from a module in it
            (
                "models/a/b.rs",
                "use super::super::super::scene::Registry;\n",
                "`models` imports `crate::scene`",
            ),
            (
                "models/a/b.rs",
                "mod t {\n    use super::super::super::super::cli;\n}\n",
                "`models` imports `crate::cli`",
            ),
            (
                "models/a/mod.rs",
                "use super::super::report;\n",
                "`models` imports `crate::report`",
            ),
            ("newfloor/mod.rs", "\n", "module `newfloor` has no floor"),
            // the paper room: above algebra, below verify and everything that runs a model
            (
                "paper/audit/mod.rs",
                "use crate::verify::PaperClaims;\n",
                "`paper` imports `crate::verify`",
            ),
            (
                "paper/words/mod.rs",
                "fn f() { crate::models::registry(); }\n",
                "`paper` imports `crate::models`",
            ),
            (
                "paper/units/mod.rs",
                "use crate::{algebra::units::Unit, scene::Scene};\n",
                "`paper` imports `crate::scene`",
            ),
            (
                "paper/source/blocks.rs",
                "use super::super::super::report::svg;\n",
                "`paper` imports `crate::report`",
            ),
            (
                "paper/audit/paper.rs",
                "use crate::cli::Format;\n",
                "`paper` imports `crate::cli`",
            ),
            (
                "paper/mod.rs",
                "use crate::perf::bench;\n",
                "`paper` imports `crate::perf`",
            ),
            (
                "algebra/expr/mod.rs",
                "use crate::paper::formulas::TexSymbols;\n",
                "`algebra` imports `crate::paper`",
            ),
            (
                "models/ode/mod.rs",
                "use crate::paper::units::unit_name;\n",
                "`models` imports `crate::paper`",
            ),
        ];
        for (rel, src, want) in cases {
            let got = rules(rel, src);
            assert_eq!(got.len(), 1, "{rel}: {src:?} gave {got:?}");
            assert!(got[0].contains(want), "{rel}: {got:?} should say {want}");
            assert!(got[0].starts_with(&format!("src/{rel}:")), "{got:?}");
        }
        // the line is the path's
        assert!(rules("models/a/b.rs", "\n\nfn f() { crate::perf::x(); }\n")[0].contains(":3: "));
        assert!(
            rules(
                "verify/kinds/mod.rs",
                "use crate::{\n    cli::{a, b},\n};\n"
            )[0]
            .contains(":2: ")
        );
    }

    #[test]
    fn look_alikes_pass() {
        let fine: &[(&str, &str)] = &[
            // comments, docs and strings that name a higher floor
            (
                "models/mod.rs",
                "//! the registry is `crate::scene`\n/* crate::verify */ fn f() {}\n",
            ),
            (
                "models/x.rs",
                "fn f() -> &'static str { \"crate::scene::x\" }\n",
            ),
            (
                "models/x.rs",
                "fn f() -> &'static str { r#\"crate::cli\"# }\n",
            ),
            // the module's own floor and those below it
            (
                "verify/x.rs",
                "use crate::{algebra::expr::{parse, Expr}, models::hertz, report};\n",
            ),
            (
                "models/a/b.rs",
                "use super::super::super::integrate::Method;\nuse super::super::scene;\n",
            ),
            // `super` in an inline module climbs out of it first: here to models::scene
            (
                "models/x.rs",
                "mod tests {\n    fn f() {}\n    use super::super::scene;\n}\nuse super::integrate;\n",
            ),
            ("scene/mod.rs", "use crate::models::registry;\n"),
            // a path that only ends in `crate`/`super` words
            (
                "algebra/x.rs",
                "fn f() { my::crate_like::scene(); let _ = a::super_x; }\n",
            ),
            // the binaries are the top floor
            ("bin/verify.rs", "use impactcheck::cli;\nfn main() {}\n"),
            // the paper room reads the algebra; verify reads the paper
            (
                "paper/units/mod.rs",
                "use crate::algebra::{expr::Expr, units::Unit};\n",
            ),
            (
                "verify/tex_claims.rs",
                "use crate::paper::source::blocks::blocks_at;\n",
            ),
        ];
        for (rel, src) in fine {
            assert!(
                rules(rel, src).is_empty(),
                "{rel}: {src:?} gave {:?}",
                rules(rel, src)
            );
        }
    }

    /// The pair rule over a few files (path under `src/`, text).
    fn pairs(files: &[(&str, &str)]) -> Vec<String> {
        let owned: Vec<(String, String)> = files
            .iter()
            .map(|(a, b)| (a.to_string(), b.to_string()))
            .collect();
        check_pairs(&owned)
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn files_importing_each_other() {
        // siblings through `super::`
        let got = pairs(&[
            ("report/mod.rs", "pub mod plot;\npub mod svg;\n"),
            ("report/plot.rs", "\nuse super::svg::{Scale, Series};\n"),
            ("report/svg.rs", "use super::plot::figure;\n"),
        ]);
        assert_eq!(
            got,
            [
                "src/report/plot.rs:2: files importing each other: src/report/plot.rs imports src/report/svg.rs (line 2), and src/report/svg.rs imports src/report/plot.rs (line 1); move what they share into the lower one"
            ]
        );
        // through `crate::` paths, a group, an expression, and a test module inside the file
        let cases: &[[(&str, &str); 2]] = &[
            [
                (
                    "verify/x.rs",
                    "use crate::{paper::audit::Audit, verify::y::f};\n",
                ),
                ("verify/y.rs", "fn g() { crate::verify::x::h(); }\n"),
            ],
            [
                (
                    "verify/kinds/mod.rs",
                    "fn f() {\n    super::power::measure();\n}\n",
                ),
                ("verify/power.rs", "use super::kinds::{Checked, Session};\n"),
            ],
            [
                ("algebra/calculus.rs", "use super::expr::{Calc, Expr};\n"),
                (
                    "algebra/expr/mod.rs",
                    "fn f() {}\n#[cfg(test)]\nmod tests {\n    use super::super::calculus::sum_range;\n}\n",
                ),
            ],
            [
                (
                    "verify/audit.rs",
                    "use crate::verify::words::conflicts as c;\n",
                ),
                (
                    "verify/words/conflicts.rs",
                    "fn f(u: &crate::verify::audit::Units) {}\n",
                ),
            ],
        ];
        for files in cases {
            let got = pairs(files);
            assert_eq!(got.len(), 1, "{files:?} gave {got:?}");
            assert!(got[0].contains("files importing each other"), "{got:?}");
            for (rel, _) in files {
                assert!(got[0].contains(&format!("src/{rel}")), "{got:?}");
            }
        }
    }

    #[test]
    fn files_that_do_not_import_each_other_pass() {
        let fine: &[&[(&str, &str)]] = &[
            // one way only
            &[
                ("report/plot.rs", "pub struct Series;\n"),
                ("report/svg.rs", "pub use super::plot::Series;\n"),
            ],
            // a module and its own parts (the parts reach its private helpers through super)
            &[
                (
                    "paper/formulas/reader/mod.rs",
                    "mod marks;\nuse marks::marked;\n",
                ),
                (
                    "paper/formulas/reader/marks.rs",
                    "use super::{Reader, mul};\n",
                ),
            ],
            // names in comments and strings; a rename that is not a module; the same name in
            // another module
            &[
                (
                    "verify/a.rs",
                    "// crate::verify::b::f\nfn f() -> &'static str { \"super::b\" }\n",
                ),
                ("verify/b.rs", "use super::a::{self as alias, f as g};\n"),
            ],
            &[
                ("verify/a.rs", "use crate::paper::units::Unit;\n"),
                ("paper/units/mod.rs", "use crate::algebra::units::Unit;\n"),
                ("algebra/units.rs", "pub struct Unit;\n"),
            ],
        ];
        for files in fine {
            assert!(pairs(files).is_empty(), "{files:?} gave {:?}", pairs(files));
        }
    }
}
