//! A paper across its files (issue 66): the text LaTeX reads, every `\input`, `\include`,
//! `\subfile`, `\import` / `\subimport` (and their `from` forms) and every macro of the paper's
//! own that wraps one (`\newcommand{\chapterinclude}[1]{\include{chapters/#1}}`) replaced by
//! the file it names, with a map from each line of that text back to its file and line.
//!
//! A file that cannot be followed (missing, outside the paper's folder, inputting itself, nested
//! too deep) is left out and named in the problems with the `file:line` of the command; the
//! rest is read all the same.

/// A file's text: UTF-8, or else Latin-1 (each byte its character), as the TeX sources
/// written before UTF-8 (`\usepackage[latin1]{inputenc}`) are.
pub fn read_text(path: &std::path::Path) -> std::io::Result<String> {
    let bytes = std::fs::read(path)?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => e.into_bytes().iter().map(|&b| char::from(b)).collect(),
    })
}

/// How a paper's `\input{name}` is read: its text, or why not (a path outside the paper's
/// folder is refused by the caller's loader, naming it).
pub type Loader<'a> = &'a dyn Fn(&str) -> Result<String, String>;

/// Text without its comments: `%` to the end of the line, unless escaped (`\%`).
pub fn strip_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let mut prev = ' ';
        let mut cut = None;
        for (i, c) in line.char_indices() {
            if c == '%' && prev != '\\' {
                cut = Some(i);
                break;
            }
            prev = c;
        }
        match cut {
            Some(i) => {
                out.push_str(&line[..i]);
                if line.ends_with('\n') {
                    out.push('\n');
                }
            }
            None => out.push_str(line),
        }
    }
    out
}

/// The argument of the command whose name ends at `at` (`\label{x}` with `at` after
/// `\label`): the text inside the braces and the index after the closing brace.
pub(crate) fn braced(text: &str, at: usize) -> Option<(String, usize)> {
    let rest = &text[at..];
    let open = rest.find(|c: char| !c.is_whitespace())?;
    if !rest[open..].starts_with('{') {
        return None;
    }
    let mut depth = 0;
    for (i, c) in rest[open..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    let inner = rest[open + 1..open + i].to_string();
                    return Some((inner, at + open + i + 1));
                }
            }
            _ => {}
        }
    }
    None
}

/// Where a run of lines of the assembled text comes from: from its line `from` on, the lines of
/// `file` (`""`: the paper's own file) from `line` on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Span {
    /// The first line (1-based) of the assembled text in this run.
    pub from: usize,
    /// The file, as the paper names it (`sections/model.tex`); `""` for the paper itself.
    pub file: String,
    /// The line of `file` that line `from` is.
    pub line: usize,
}

/// The file and line of line `line` of an assembled text with the runs `spans` (the paper's own
/// file, `""`, when no run covers it).
pub fn place(spans: &[Span], line: usize) -> (&str, usize) {
    match spans.iter().rev().find(|s| s.from <= line) {
        Some(s) => (s.file.as_str(), s.line + (line - s.from)),
        None => ("", line),
    }
}

/// The deepest `\input` inside `\input` followed.
pub const MAX_INPUT_DEPTH: usize = 8;

/// The most files one paper inlines (a file that inputs another many times over).
const MAX_FILES: usize = 2000;

/// The state of one assembly: the loader, the paper's macros that wrap an input, the files
/// read so far and the chain of files being read (a file inside itself is a cycle).
struct Assembly<'a> {
    load: Loader<'a>,
    wrappers: Vec<(String, String)>,
    /// The paper's macros without arguments whose body is a path (`\newcommand{\mainpath}{..}`).
    paths: Vec<(String, String)>,
    /// The folders `\def\input@path{{chapters/}{parts/}}` adds to the search for an input.
    search: Vec<String>,
    files: usize,
    stack: Vec<String>,
    problems: Vec<String>,
}

/// `text` (comments dropped) with every input replaced by its file's text (its own inputs
/// followed), the runs of lines of each file, and what could not be followed.
pub fn assemble(text: &str, load: Loader) -> (String, Vec<Span>, Vec<String>) {
    let clean = strip_comments(text);
    let (wrappers, paths) = wrappers(&clean);
    let mut a = Assembly {
        load,
        wrappers,
        paths,
        search: input_path(&clean),
        files: 0,
        stack: Vec::new(),
        problems: Vec::new(),
    };
    let (out, spans) = a.inline(text, "", "");
    (out, spans, a.problems)
}

/// `text` with its inputs followed, as [`assemble`] does, the problems added to `problems`.
pub(super) fn inline_inputs(text: &str, load: Loader, problems: &mut Vec<String>) -> String {
    let (out, _, p) = assemble(text, load);
    problems.extend(p);
    out
}

/// Pairs of names and texts.
type Pairs = Vec<(String, String)>;

/// The paper's macros of one argument whose body inputs a file named by it
/// (`\newcommand{\chapterinclude}[1]{\include{chapters/#1}}`, `\def\sec#1{\input{#1}}`): each
/// name with the file its argument names (`chapters/#1`); and its macros without argument whose
/// body is a path (`\newcommand{\mainpath}{/home/me/thesis/}`), each name with its path.
fn wrappers(text: &str) -> (Pairs, Pairs) {
    let mut out = Vec::new();
    let mut paths = Vec::new();
    for def in [
        "\\newcommand",
        "\\renewcommand",
        "\\providecommand",
        "\\def",
    ] {
        let mut from = 0;
        while let Some(k) = text[from..].find(def) {
            let at = from + k + def.len();
            from = at;
            let rest = text[at..].trim_start_matches('*').trim_start();
            let rest = rest.strip_prefix('{').unwrap_or(rest);
            let Some(name) = rest.strip_prefix('\\') else {
                continue;
            };
            let len = name
                .find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(name.len());
            let (name, tail) = name.split_at(len);
            let Some(open) = tail.find('{') else { continue };
            // the body: the last group before the next line that starts a definition
            let body_at = at + (text[at..].len() - tail.len()) + open;
            let Some((body, _)) = braced(text, body_at) else {
                continue;
            };
            // no parameter, no command in the body: a path, perhaps
            if tail[..open]
                .trim()
                .trim_start_matches('}')
                .trim()
                .is_empty()
                && !name.is_empty()
                && !body.contains(['\\', '#', '$', ' '])
                && !body.is_empty()
            {
                paths.push((name.to_string(), body.clone()));
            }
            for cmd in ["\\input", "\\include", "\\subfile"] {
                if let Some(j) = body.find(cmd)
                    && let Some((file, _)) = braced(&body, j + cmd.len())
                    && file.contains("#1")
                    && !name.is_empty()
                {
                    out.push((name.to_string(), file));
                }
            }
        }
    }
    (out, paths)
}

/// The folders of `\def\input@path{{a/}{b/}}` (or `\makeatletter\def\input@path..`), in order.
fn input_path(text: &str) -> Vec<String> {
    let Some(k) = text.find("\\input@path") else {
        return Vec::new();
    };
    let Some((list, _)) = braced(text, k + "\\input@path".len()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut at = 0;
    while let Some((dir, end)) = braced(&list, at) {
        out.push(dir.trim().to_string());
        at = end;
    }
    out
}

/// A file name with the paper's path macros in it (`\mainpath/Header`) as a path of the paper's
/// folder: a macro whose path is relative is its path; one whose path is absolute (the folder
/// of the paper on its author's machine) or that the paper does not define is dropped.
fn resolved(name: &str, paths: &[(String, String)]) -> String {
    if !name.contains('\\') {
        return name.to_string();
    }
    let mut out = String::new();
    let mut rest = name;
    while let Some(k) = rest.find('\\') {
        out.push_str(&rest[..k]);
        let after = &rest[k + 1..];
        let len = after
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(after.len());
        let word = &after[..len];
        if let Some((_, body)) = paths.iter().find(|(n, _)| n == word)
            && !body.starts_with(['/', '~'])
            && !body.contains(':')
        {
            out.push_str(body);
        }
        rest = after[len..]
            .strip_prefix(['{', ' '])
            .unwrap_or(&after[len..]);
        rest = rest.strip_prefix('}').unwrap_or(rest);
    }
    out.push_str(rest);
    // `/Header` after a dropped folder, `a//b` after a path that ends with `/`
    let mut clean = out.replace("//", "/");
    while clean.contains("//") {
        clean = clean.replace("//", "/");
    }
    clean.trim_start_matches('/').to_string()
}

/// The file named `dir` + `file` as a path of the paper's folder (`./a/` and `b` give `a/b`).
fn joined(dir: &str, file: &str) -> String {
    let dir = dir.trim().trim_start_matches("./");
    let file = file.trim().trim_start_matches("./");
    if dir.is_empty() {
        file.to_string()
    } else if dir.ends_with('/') {
        format!("{dir}{file}")
    } else {
        format!("{dir}/{file}")
    }
}

/// The name a file is shown with: `name`, `.tex` added when it has no extension.
fn shown(name: &str) -> String {
    let last = name.rsplit('/').next().unwrap_or(name);
    if last.contains('.') {
        name.to_string()
    } else {
        format!("{name}.tex")
    }
}

impl Assembly<'_> {
    /// Where line `line` of `file` is, for a problem: `line 3` of the paper, `a.tex:3` of
    /// another file.
    fn at(file: &str, line: usize) -> String {
        if file.is_empty() {
            format!("line {line}")
        } else {
            format!("{file}:{line}")
        }
    }

    /// `text` of `file` (inputs relative to `base`, the folder of an `\import`) with its inputs
    /// followed, and its runs of lines.
    fn inline(&mut self, text: &str, file: &str, base: &str) -> (String, Vec<Span>) {
        let text = strip_comments(text);
        let mut out = String::with_capacity(text.len());
        let mut spans = vec![Span {
            from: 1,
            file: file.to_string(),
            line: 1,
        }];
        let mut pos = 0;
        while let Some(k) = text[pos..].find('\\') {
            let at = pos + k;
            let word: String = text[at + 1..]
                .chars()
                .take_while(char::is_ascii_alphabetic)
                .collect();
            let after = at + 1 + word.len();
            if matches!(
                word.as_str(),
                "usepackage" | "RequirePackage" | "documentclass"
            ) {
                out.push_str(&text[pos..after]);
                pos = self.package(&text, &word, after, &mut out);
                continue;
            }
            // what the command inputs: the file, the folder its own inputs are relative to,
            // and where the command ends
            let target = match word.as_str() {
                "input" | "include" | "subfile" => match braced(&text, after) {
                    Some((name, end)) => Some((joined(base, &name), base.to_string(), end)),
                    // `\input file` without braces: the name up to the next space
                    None if word == "input" && text[after..].starts_with(' ') => {
                        let rest = &text[after + 1..];
                        let len = rest
                            .find(|c: char| c.is_whitespace() || c == '\\' || c == '}')
                            .unwrap_or(rest.len());
                        Some((
                            joined(base, &rest[..len]),
                            base.to_string(),
                            after + 1 + len,
                        ))
                    }
                    None => None,
                },
                // `\import{dir}{file}` from the paper's folder, `\subimport` from the current one
                "import" | "inputfrom" | "includefrom" | "subimport" | "subinputfrom"
                | "subincludefrom" => {
                    let sub = word.starts_with("sub");
                    braced(&text, after).and_then(|(dir, mid)| {
                        braced(&text, mid).map(|(name, end)| {
                            let dir = if sub { joined(base, &dir) } else { dir };
                            (joined(&dir, &name), dir, end)
                        })
                    })
                }
                w => self
                    .wrappers
                    .iter()
                    .find(|(n, _)| n == w)
                    .map(|(_, t)| t.clone())
                    .and_then(|t| {
                        braced(&text, after).map(|(arg, end)| {
                            (
                                joined(base, &t.replace("#1", arg.trim())),
                                base.to_string(),
                                end,
                            )
                        })
                    }),
            };
            // a macro's parameter (`\include{chapters/#1}` in the definition of a wrapper) names
            // no file
            let target = target
                .filter(|(name, ..)| !name.contains('#'))
                .map(|(name, b, end)| (resolved(&name, &self.paths), b, end));
            let Some((name, inner_base, end)) = target else {
                out.push_str(&text[pos..after]);
                pos = after;
                continue;
            };
            out.push_str(&text[pos..at]);
            let line = text[..at].matches('\n').count() + 1;
            let here = Self::at(file, line);
            let name_shown = shown(&name);
            let refused = if self.stack.len() >= MAX_INPUT_DEPTH {
                Some(format!(
                    "{here}: `\\{word}{{{name}}}`: inputs nested deeper than {MAX_INPUT_DEPTH}"
                ))
            } else if self.stack.contains(&name_shown) {
                Some(format!(
                    "{here}: `\\{word}{{{name}}}`: {name_shown} inputs itself"
                ))
            } else if self.files >= MAX_FILES {
                Some(format!(
                    "{here}: `\\{word}{{{name}}}`: more than {MAX_FILES} files inlined"
                ))
            } else {
                None
            };
            if let Some(p) = refused {
                self.problems.push(p);
            } else {
                // not beside the paper: in a folder of `\input@path`
                let found = (self.load)(name.trim()).or_else(|e| {
                    self.search
                        .iter()
                        .find_map(|d| (self.load)(&joined(d, name.trim())).ok())
                        .ok_or(e)
                });
                match found {
                    Ok(inner) => {
                        self.files += 1;
                        self.stack.push(name_shown.clone());
                        let (inner, inner_spans) = self.inline(&inner, &name_shown, &inner_base);
                        self.stack.pop();
                        let first = out.matches('\n').count() + 1;
                        for s in inner_spans {
                            spans.push(Span {
                                from: s.from + first - 1,
                                ..s
                            });
                        }
                        out.push_str(&inner);
                        // the rest of this file from the line after the command's end (the
                        // line the file's last line shares with what follows the command is
                        // the file's)
                        spans.push(Span {
                            from: out.matches('\n').count() + 2,
                            file: file.to_string(),
                            line: text[..end].matches('\n').count() + 2,
                        });
                    }
                    Err(e) => self.problems.push(format!("{here}: {e}")),
                }
            }
            pos = end;
        }
        out.push_str(&text[pos..]);
        (out, spans)
    }

    /// A class or package of the paper's own folder (`\usepackage{mymacros}` beside the paper)
    /// read for its macros, as LaTeX reads it, on one line so that the paper's lines keep
    /// their numbers; the others are LaTeX's. Returns where the command ends.
    fn package(&mut self, text: &str, word: &str, after: usize, out: &mut String) -> usize {
        let mut end = after;
        let rest = &text[after..];
        let opts = rest.trim_start();
        if opts.starts_with('[') {
            end += rest.len() - opts.len() + opts.find(']').map_or(0, |k| k + 1);
        }
        let Some((names, close)) = braced(text, end) else {
            return after;
        };
        let ext = if word == "documentclass" {
            "cls"
        } else {
            "sty"
        };
        out.push_str(&text[after..close]);
        for name in names.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let file = format!("{name}.{ext}");
            if self.stack.len() < MAX_INPUT_DEPTH
                && !self.stack.contains(&file)
                && let Ok(inner) = (self.load)(&file)
            {
                // a class may say where the paper's chapters are (`\def\input@path{{chapters/}}`)
                self.search.extend(input_path(&strip_comments(&inner)));
                self.stack.push(file.clone());
                let (inner, _) = self.inline(&inner, &file, "");
                self.stack.pop();
                out.push(' ');
                out.push_str(&inner.replace('\n', " "));
                out.push(' ');
            }
        }
        close
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unbraced_input_is_replaced_by_its_file_and_nothing_of_its_name_stays() {
        // by hand: `\input chap` is the file's text; what follows the name is kept as it was
        let load = |_: &str| Ok("c = d".to_string());
        let mut problems = Vec::new();
        let text = inline_inputs("\\input chap\nX", &load, &mut problems);
        assert_eq!(text, "c = d\nX");
        assert!(problems.is_empty(), "{problems:?}");
        // a file that cannot be read is named with the line of its `\input` (here the third)
        let missing = |name: &str| Err(format!("no file {name}"));
        let text = inline_inputs("a\nb\n\\input{gone}\nc", &missing, &mut problems);
        assert_eq!(problems, ["line 3: no file gone"]);
        assert_eq!(text, "a\nb\n\nc");
    }

    /// A loader over a folder written by hand.
    fn folder(
        files: &'static [(&'static str, &'static str)],
    ) -> impl Fn(&str) -> Result<String, String> {
        move |name: &str| {
            files
                .iter()
                .find(|(n, _)| *n == name || format!("{name}.tex") == *n)
                .map(|(_, t)| t.to_string())
                .ok_or_else(|| format!("no file {name}"))
        }
    }

    #[test]
    fn each_line_of_the_assembled_text_knows_its_file_and_line() {
        let load = folder(&[
            ("sec/a.tex", "a1\na2\n\\input{sec/b}\na4"),
            ("sec/b.tex", "b1\nb2"),
        ]);
        let (text, spans, problems) = assemble("m1\n\\input{sec/a}\nm3\nm4", &load);
        assert!(problems.is_empty(), "{problems:?}");
        // by hand: m1 / a1 / a2 / b1 / b2 a4 / (rest of m2) / m3 / m4
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines, ["m1", "a1", "a2", "b1", "b2", "a4", "m3", "m4"]);
        let at = |l: usize| {
            let (f, n) = place(&spans, l);
            format!("{f}:{n}")
        };
        assert_eq!(at(1), ":1");
        assert_eq!(at(2), "sec/a.tex:1");
        assert_eq!(at(3), "sec/a.tex:2");
        assert_eq!(at(4), "sec/b.tex:1");
        assert_eq!(at(5), "sec/b.tex:2");
        assert_eq!(at(7), ":3");
        assert_eq!(at(8), ":4");
    }

    #[test]
    fn imports_wrapping_macros_and_cycles() {
        let load = folder(&[
            ("parts/intro.tex", "I \\input{deep}"),
            ("parts/deep.tex", "D"),
            ("chapters/one.tex", "ONE"),
            ("self.tex", "S \\input{self}"),
            ("a.tex", "A \\input{b}"),
            ("b.tex", "B \\input{a}"),
        ]);
        // `\import{dir}{file}`: the file and its own inputs from dir
        let (text, _, p) = assemble("\\import{parts/}{intro}", &load);
        assert_eq!(text.trim(), "I D", "{p:?}");
        let (text, _, p) = assemble("\\subimport{parts}{intro.tex}", &load);
        assert_eq!(text.trim(), "I D", "{p:?}");
        // a macro of the paper's own around `\include`
        let (text, _, p) = assemble(
            "\\newcommand{\\chapterinclude}[1]{\\clearpage\\include{chapters/#1}}\n\\chapterinclude{one}",
            &load,
        );
        assert!(text.ends_with("ONE"), "{text:?} {p:?}");
        // a file that inputs itself, two that input each other: once each, and said
        let (text, _, p) = assemble("\\input{self}", &load);
        assert_eq!(text.trim(), "S");
        assert_eq!(p, ["self.tex:1: `\\input{self}`: self.tex inputs itself"]);
        let (text, _, p) = assemble("\\input{a}", &load);
        assert_eq!(text.trim(), "A B");
        assert_eq!(p.len(), 1, "{p:?}");
    }

    #[test]
    fn a_latin1_file_is_read_byte_by_byte() {
        let dir = std::env::temp_dir().join(format!("latin1-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let f = dir.join("a.tex");
        // "Gr\xf6\xdfe $x$" in Latin-1 is no UTF-8
        std::fs::write(&f, b"Gr\xf6\xdfe $x$").expect("write");
        assert_eq!(read_text(&f).expect("read"), "Gr\u{f6}\u{df}e $x$");
        std::fs::write(&f, "Gr\u{f6}\u{df}e".as_bytes()).expect("write");
        assert_eq!(read_text(&f).expect("read"), "Gr\u{f6}\u{df}e");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_path_macro_in_an_input_is_its_relative_path_or_dropped_when_absolute() {
        let load = folder(&[("Header.tex", "H"), ("sub/x.tex", "X")]);
        // the author's absolute folder: dropped, the file read from the paper's folder
        let (text, _, p) = assemble(
            "\\newcommand{\\mainpath}{/home/me/thesis/}\n\\input{\\mainpath/Header}",
            &load,
        );
        assert!(p.is_empty(), "{p:?}");
        assert_eq!(text.lines().last(), Some("H"));
        // a relative folder: kept; `\def` alike
        let (text, _, p) = assemble("\\def\\sub{sub/}\n\\input{\\sub x}", &load);
        assert!(p.is_empty(), "{p:?}");
        assert_eq!(text.lines().last(), Some("X"));
        // a macro of one argument is no path
        assert_eq!(resolved("\\a/b", &[]), "b");
        let (_, paths) = wrappers("\\newcommand{\\f}[1]{x#1}\\newcommand{\\g}{\\alpha}");
        assert!(paths.is_empty(), "{paths:?}");
        // the folders LaTeX searches, `\input@path`, in the paper or in its class
        let (text, _, p) = assemble("\\def\\input@path{{none/}{sub/}}\n\\input{x}", &load);
        assert!(p.is_empty(), "{p:?}");
        assert_eq!(text.lines().last(), Some("X"));
        let load = folder(&[("sub/x.tex", "X"), ("th.cls", "\\def\\input@path{{sub/}}")]);
        let (text, _, p) = assemble("\\documentclass{th}\n\\input{x}", &load);
        assert!(p.is_empty(), "{p:?}");
        assert_eq!(text.lines().last(), Some("X"));
    }
}
