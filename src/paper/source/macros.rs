//! A paper's own macros, expanded before anything is read (TeX's expansion stage): the
//! definitions of `\newcommand`, `\renewcommand`, `\providecommand` (starred or not, with a
//! number of arguments and an optional first argument's default), `\def\name#1#2{..}` and
//! `\DeclareMathOperator{\name}{text}` are collected in the order of the source and taken out
//! of it, and every use of a defined macro is replaced by its body with the arguments put in,
//! again until none is left (at most [`MAX_EXPANSIONS`], so that `\def\a{\a}` ends in an
//! error naming the macro, not in a loop).
//!
//! Line numbers survive: a definition leaves its newlines behind, and an expansion that
//! swallows a newline of its arguments puts it back after the body, so that a line of the
//! expanded text is the line of the source.
//!
//! Written by hand: the crates that expand TeX macros are whole TeX engines; papers use the
//! few forms above.

use std::collections::BTreeMap;

/// The most macro uses one source may expand (a recursive definition stops here).
pub const MAX_EXPANSIONS: usize = 20_000;

/// The most bytes expansion may grow a source to (a definition that doubles itself stops
/// here): four times the source and a megabyte.
fn max_size(source: usize) -> usize {
    4 * source + (1 << 20)
}

/// A macro: how many arguments, the default of an optional first one, and its body.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Macro {
    args: usize,
    default: Option<String>,
    body: String,
}

/// Why a source's macros could not be expanded.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("line {line}: the macro `\\{name}`: {problem}")]
pub struct MacroError {
    /// The line (1-based) of the use or definition.
    pub line: usize,
    /// The macro's name, without its backslash.
    pub name: String,
    /// What went wrong.
    pub problem: String,
}

/// A source expanded: its text, the names defined, and the uses that could not be expanded
/// (left as they are, each named).
pub type Expanded = (String, Vec<String>, Vec<MacroError>);

/// The source with its macro definitions taken out and every use expanded; the names defined.
pub fn expand(source: &str) -> Result<Expanded, MacroError> {
    expand_with(source, "")
}

/// As [`expand`], with the definitions of `preamble` (a file of macros the paper uses but
/// does not hold, as a Markdown note's) made first.
pub fn expand_with(source: &str, preamble: &str) -> Result<Expanded, MacroError> {
    let (_, mut defs) = collect(preamble)?;
    let (text, own) = collect(source)?;
    defs.extend(own);
    // a body that uses its own name (`\renewcommand\Large{\@setsize\Large{20pt}..}` of a class
    // file, where TeX takes the name as a token) would expand without end: left undefined
    defs.retain(|name, mac| !uses(&mac.body, name));
    let names = defs.keys().cloned().collect();
    let mut problems = Vec::new();
    if defs.is_empty() {
        return Ok((text, names, problems));
    }
    let text = expand_uses(&text, &defs, &mut problems)?;
    Ok((text, names, problems))
}

/// Whether `body` holds the control word `\name` (not as the start of a longer one).
fn uses(body: &str, name: &str) -> bool {
    let pat = format!("\\{name}");
    let mut from = 0;
    while let Some(k) = body[from..].find(&pat) {
        let end = from + k + pat.len();
        let word = name.chars().all(|c| c.is_ascii_alphabetic());
        if !word || !body[end..].starts_with(|c: char| c.is_ascii_alphabetic()) {
            return true;
        }
        from = end;
    }
    false
}

/// The line (1-based) of byte `at` of `text`.
fn line_at(text: &str, at: usize) -> usize {
    text[..at.min(text.len())].matches('\n').count() + 1
}

/// The name of the control word or symbol at `at` (just after its backslash), and its end.
fn control_name(text: &str, at: usize) -> Option<(String, usize)> {
    let rest = &text[at..];
    let letters = rest
        .char_indices()
        .find(|(_, c)| !c.is_ascii_alphabetic())
        .map_or(rest.len(), |(i, _)| i);
    if letters > 0 {
        return Some((rest[..letters].to_string(), at + letters));
    }
    let c = rest.chars().next()?;
    Some((c.to_string(), at + c.len_utf8()))
}

/// The index after the whitespace at `at`.
fn skip_ws(text: &str, at: usize) -> usize {
    at + text[at..].len() - text[at..].trim_start().len()
}

/// A `{..}` group at `at` (after whitespace): its inside and the index after it.
pub(crate) fn group(text: &str, at: usize) -> Option<(String, usize)> {
    let start = skip_ws(text, at);
    if !text[start..].starts_with('{') {
        return None;
    }
    let mut depth = 0usize;
    let mut escaped = false;
    for (i, c) in text[start..].char_indices() {
        if escaped {
            escaped = false;
            continue;
        }
        match c {
            '\\' => escaped = true,
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return Some((text[start + 1..start + i].to_string(), start + i + 1));
                }
            }
            _ => {}
        }
    }
    None
}

/// A `[..]` at `at` (after whitespace): its inside and the index after it.
fn bracket(text: &str, at: usize) -> Option<(String, usize)> {
    let start = skip_ws(text, at);
    if !text[start..].starts_with('[') {
        return None;
    }
    let mut depth = 0usize;
    for (i, c) in text[start..].char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth = depth.saturating_sub(1),
            ']' if depth == 0 => {
                return Some((text[start + 1..start + i].to_string(), start + i + 1));
            }
            _ => {}
        }
    }
    None
}

/// One argument of a use: a group's inside, or a single token (a control word, a character).
fn argument(text: &str, at: usize) -> Option<(String, usize)> {
    let start = skip_ws(text, at);
    if text[start..].starts_with('{') {
        return group(text, start);
    }
    let c = text[start..].chars().next()?;
    if c == '}' {
        return None;
    }
    if c == '\\' {
        let (name, end) = control_name(text, start + 1)?;
        return Some((format!("\\{name}"), end));
    }
    Some((c.to_string(), start + c.len_utf8()))
}

/// LaTeX's structure, which a class redefines for its layout: never expanded.
const STRUCTURE: &[&str] = &[
    "section",
    "subsection",
    "subsubsection",
    "chapter",
    "paragraph",
    "part",
    "begin",
    "end",
    "label",
    "tag",
    "ref",
    "eqref",
    "input",
    "include",
    "item",
    "par",
    "left",
    "right",
];

/// The definitions of `source` in order (a later `\renewcommand` replaces, a
/// `\providecommand` of a defined name does nothing), and the source without them.
fn collect(source: &str) -> Result<(String, BTreeMap<String, Macro>), MacroError> {
    let mut defs: BTreeMap<String, Macro> = BTreeMap::new();
    let mut out = String::with_capacity(source.len());
    let mut pos = 0;
    while let Some(k) = source[pos..].find('\\') {
        let at = pos + k;
        let Some((cmd, after)) = control_name(source, at + 1) else {
            break;
        };
        let def = match cmd.as_str() {
            "newcommand" | "renewcommand" | "providecommand" => newcommand(source, after),
            "def" | "gdef" | "edef" | "xdef" => def(source, after),
            "DeclareMathOperator" => operator(source, after),
            _ => None,
        };
        match def {
            // a class's internals (`\def\\{..}`, `\def\@makefntext`) and its layout of LaTeX's
            // structure (`\renewcommand\section{\@startsection..}`) are no macros of the paper's
            // formulas: taken out, never expanded
            Some((name, _, end))
                if !name.chars().all(|c| c.is_ascii_alphabetic())
                    || STRUCTURE.contains(&name.as_str()) =>
            {
                out.push_str(&source[pos..at]);
                out.push_str(&"\n".repeat(source[at..end].matches('\n').count()));
                pos = end;
            }
            Some((name, mac, end)) => {
                out.push_str(&source[pos..at]);
                // the definition's newlines stay, so that lines keep their numbers
                out.push_str(&"\n".repeat(source[at..end].matches('\n').count()));
                if cmd != "providecommand" || !defs.contains_key(&name) {
                    defs.insert(name, mac);
                }
                pos = end;
            }
            None => {
                out.push_str(&source[pos..after]);
                pos = after;
            }
        }
    }
    out.push_str(&source[pos..]);
    Ok((out, defs))
}

/// `\newcommand{\name}[n][default]{body}` (or `\newcommand*\name..`) after the command.
fn newcommand(text: &str, at: usize) -> Option<(String, Macro, usize)> {
    let mut i = skip_ws(text, at);
    if text[i..].starts_with('*') {
        i += 1;
    }
    let (name, mut i) = match group(text, i) {
        Some((inner, end)) => {
            let inner = inner.trim();
            (inner.strip_prefix('\\')?.to_string(), end)
        }
        None => {
            let s = skip_ws(text, i);
            if !text[s..].starts_with('\\') {
                return None;
            }
            control_name(text, s + 1)?
        }
    };
    let mut args = 0;
    let mut default = None;
    if let Some((n, end)) = bracket(text, i) {
        args = n.trim().parse().ok().filter(|n| *n <= 9)?;
        i = end;
        if let Some((d, end)) = bracket(text, i) {
            default = Some(d);
            i = end;
        }
    }
    let (body, end) = group(text, i)?;
    Some((
        name,
        Macro {
            args,
            default,
            body,
        },
        end,
    ))
}

/// `\def\name#1#2{body}` after the command.
fn def(text: &str, at: usize) -> Option<(String, Macro, usize)> {
    let s = skip_ws(text, at);
    if !text[s..].starts_with('\\') {
        return None;
    }
    let (name, mut i) = control_name(text, s + 1)?;
    let mut args = 0;
    while text[i..].starts_with('#') {
        let d = text[i + 1..].chars().next()?.to_digit(10)?;
        args = args.max(d as usize);
        i += 2;
    }
    let (body, end) = group(text, i)?;
    Some((
        name,
        Macro {
            args,
            default: None,
            body,
        },
        end,
    ))
}

/// `\DeclareMathOperator{\name}{text}` (or starred) after the command: `\operatorname{text}`.
fn operator(text: &str, at: usize) -> Option<(String, Macro, usize)> {
    let mut i = skip_ws(text, at);
    if text[i..].starts_with('*') {
        i += 1;
    }
    let (name, i) = group(text, i)?;
    let name = name.trim().strip_prefix('\\')?.to_string();
    let (body, end) = group(text, i)?;
    Some((
        name,
        Macro {
            args: 0,
            default: None,
            body: format!("\\operatorname{{{body}}}"),
        },
        end,
    ))
}

/// `text` with every use of `defs` expanded, rescanning what an expansion gives.
fn expand_uses(
    text: &str,
    defs: &BTreeMap<String, Macro>,
    problems: &mut Vec<MacroError>,
) -> Result<String, MacroError> {
    let limit = max_size(text.len());
    let mut text = text.to_string();
    let mut count = 0;
    let mut pos = 0;
    while let Some(k) = text[pos..].find('\\') {
        let at = pos + k;
        let Some((name, after)) = control_name(&text, at + 1) else {
            break;
        };
        let Some(mac) = defs.get(&name) else {
            pos = after;
            continue;
        };
        count += 1;
        if count > MAX_EXPANSIONS || text.len() > limit {
            return Err(MacroError {
                line: line_at(&text, at),
                name,
                problem: format!(
                    "more than {MAX_EXPANSIONS} expansions or {limit} bytes (a definition that uses itself?)"
                ),
            });
        }
        let mut args = Vec::new();
        let mut end = after;
        let mut needed = mac.args;
        if let Some(d) = &mac.default {
            match bracket(&text, end) {
                Some((a, e)) => {
                    args.push(a);
                    end = e;
                }
                None => args.push(d.clone()),
            }
            needed = needed.saturating_sub(1);
        }
        let mut short = false;
        for _ in 0..needed {
            let Some((a, e)) = argument(&text, end) else {
                short = true;
                break;
            };
            args.push(a);
            end = e;
        }
        // a use without its arguments stays as it is, named; the rest is expanded
        if short {
            problems.push(MacroError {
                line: line_at(&text, at),
                name,
                problem: format!("{} argument(s) expected, fewer given", mac.args),
            });
            pos = after;
            continue;
        }
        let body = substitute(&mac.body, &args).replace('\n', " ");
        // a control word's body must not glue to the letters after it (`\vrel x`)
        let glue = if text[end..].starts_with(|c: char| c.is_ascii_alphabetic()) {
            " "
        } else {
            ""
        };
        // nor to a control word or a letter before it (`\gamma\pres` with `p`: `\gamma p`, not
        // `\gammap`; TeX reads two tokens)
        let lead = if body.starts_with(|c: char| c.is_ascii_alphabetic())
            && text[..at].ends_with(|c: char| c.is_ascii_alphabetic())
        {
            " "
        } else {
            ""
        };
        let lines = "\n".repeat(text[at..end].matches('\n').count());
        text.replace_range(at..end, &format!("{lead}{body}{glue}{lines}"));
        pos = at;
    }
    Ok(text)
}

/// `body` with each `#k` replaced by the k-th of `args`, a space put where a control word would
/// otherwise glue to the letters beside it (`\langle#1` with `a`: `\langle a`, not `\langlea`).
fn substitute(body: &str, args: &[String]) -> String {
    let ends_in_word = |s: &str| {
        let letters = s.len() - s.trim_end_matches(|c: char| c.is_ascii_alphabetic()).len();
        letters > 0 && s[..s.len() - letters].ends_with('\\')
    };
    let mut out = String::with_capacity(body.len());
    let mut rest = body;
    while let Some(k) = rest.find('#') {
        out.push_str(&rest[..k]);
        // `\#` is the character, no parameter
        let escaped = out.ends_with('\\') && !out.ends_with("\\\\");
        let digit = rest[k + 1..].chars().next().and_then(|c| c.to_digit(10));
        let digit = digit.filter(|_| !escaped);
        match digit.and_then(|d| args.get((d as usize).wrapping_sub(1))) {
            Some(a) => {
                let a = a.replace('\n', " ");
                if ends_in_word(&out) && a.starts_with(|c: char| c.is_ascii_alphabetic()) {
                    out.push(' ');
                }
                out.push_str(&a);
                rest = &rest[k + 2..];
                if ends_in_word(&out) && rest.starts_with(|c: char| c.is_ascii_alphabetic()) {
                    out.push(' ');
                }
            }
            None => {
                out.push('#');
                rest = &rest[k + 1..];
            }
        }
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expanded(src: &str) -> String {
        expand(src).expect("expands").0
    }

    #[test]
    fn definitions_of_every_kind_expand() {
        // by hand: each use replaced by its body with the arguments put in
        assert_eq!(
            expanded("\\newcommand{\\vrel}{v_{\\mathrm{rel}}}$\\vrel = 1$").trim(),
            "$v_{\\mathrm{rel}} = 1$"
        );
        assert_eq!(
            expanded("\\newcommand\\pd[2]{\\frac{\\partial #1}{\\partial #2}} \\pd{w}{t}").trim(),
            "\\frac{\\partial w}{\\partial t}"
        );
        assert_eq!(
            expanded("\\newcommand{\\dd}[2][t]{\\frac{d #2}{d #1}} \\dd{x} \\dd[s]{y}").trim(),
            "\\frac{d x}{d t} \\frac{d y}{d s}"
        );
        assert_eq!(
            expanded("\\def\\abs#1{\\left|#1\\right|} \\abs{x}").trim(),
            "\\left|x\\right|"
        );
        assert_eq!(
            expanded("\\DeclareMathOperator{\\sgn}{sgn} \\sgn x").trim(),
            "\\operatorname{sgn} x"
        );
        // a starred \newcommand (no paragraph in its arguments) defines as the plain one
        assert_eq!(
            expanded("\\newcommand*{\\vrel}[1]{v_{#1}} \\vrel{r}").trim(),
            "v_{r}"
        );
        // the starred form (limits under the name) defines it the same way
        assert_eq!(
            expanded("\\DeclareMathOperator*{\\argmax}{arg\\,max} \\argmax_x f").trim(),
            "\\operatorname{arg\\,max}_x f"
        );
        // a later \renewcommand replaces; \providecommand of a defined name does nothing
        assert_eq!(
            expanded(
                "\\newcommand{\\a}{1}\\providecommand{\\a}{2}\\renewcommand{\\a}{3}\\providecommand{\\b}{4}\\a\\b"
            ),
            "34"
        );
        // nested: a macro using another; an argument as a single token
        assert_eq!(
            expanded("\\newcommand{\\x}{y}\\newcommand{\\f}[1]{#1^2} \\f\\x \\f a").trim(),
            "y^2 a^2"
        );
    }

    #[test]
    fn a_body_does_not_glue_to_the_letters_after_it_and_lines_keep_their_numbers() {
        assert_eq!(expanded("\\newcommand{\\m}{\\mu}\\m x").trim(), "\\mu x");
        let src = "\\newcommand{\\e}[1]{e^{#1}}\nline 2\n\\e{a\n+b}\nline 4";
        let out = expanded(src);
        assert_eq!(out.lines().count(), src.lines().count(), "{out:?}");
        assert_eq!(out.lines().nth(4), Some("line 4"));
        // nor to the control word before it (a thesis's `\gamma\pres`, `\pres` being `p`)
        assert_eq!(
            expanded("\\newcommand{\\p}{p}\\gamma\\p + \\p\\p").trim(),
            "\\gamma p + p p"
        );
        // a longer name is another macro
        assert_eq!(expanded("\\newcommand{\\a}{1}\\ab").trim(), "\\ab");
        // nor an argument to the control word before or after it (WSU notes' `\braket`)
        assert_eq!(
            expanded("\\newcommand{\\bk}[2]{\\langle#1|#2\\rangle}\\bk{a}{b}").trim(),
            "\\langle a|b\\rangle"
        );
        assert_eq!(
            expanded("\\newcommand{\\f}[1]{#1x \\lvert#1\\rvert}\\f{\\mu}").trim(),
            "\\mu x \\lvert\\mu\\rvert"
        );
        // `#` without a digit stays (`\#` in a body)
        assert_eq!(expanded("\\newcommand{\\h}{\\#1}\\h").trim(), "\\#1");
        assert_eq!(
            expanded("\\newcommand{\\h}[1]{\\#1 #1}\\h{y}").trim(),
            "\\#1 y"
        );
    }

    #[test]
    fn a_definition_that_uses_itself_and_a_missing_argument_are_errors_naming_the_macro() {
        // two definitions that use each other expand without end: an error naming one
        let e = expand("\\def\\a{\\b x}\\def\\b{\\a} \n $\\a$").unwrap_err();
        assert_eq!((e.name.as_str(), e.line), ("a", 2));
        // one that uses itself (a class file's `\Large`) stays undefined, the others expand
        let (text, _, _) =
            expand("\\def\\Large{\\size\\Large{20pt}}\\def\\c{y}\n$\\Large \\c \\Larger$").unwrap();
        assert_eq!(text.trim(), "$\\Large y \\Larger$");
        // a use short of its arguments stays, named, and the others are expanded
        let (text, _, problems) = expand("\\newcommand{\\f}[2]{#1#2}\n\n\\f{a}}\\f{b}{c}").unwrap();
        assert_eq!(text.trim(), "\\f{a}}bc");
        let e = &problems[0];
        assert_eq!((e.name.as_str(), e.line), ("f", 3));
        assert!(e.problem.contains("2 argument"), "{e}");
    }

    #[test]
    fn a_class_s_internals_and_its_layout_of_the_structure_are_no_macros() {
        // by hand: `\def\\{..}` and `\renewcommand\section{..}` of a class leave the rows and
        // the sections as they are; a macro of letters is expanded
        let (text, _, _) = expand(
            "\\def\\\\{, }\\renewcommand\\section{\\@startsection}\\def\\v{x}\n\\section{A} $a \\\\ \\v$",
        )
        .unwrap();
        assert_eq!(text.trim(), "\\section{A} $a \\\\ x$");
    }

    #[test]
    fn an_optional_default_with_a_group_holding_a_bracket() {
        // the default `{x]}` is one group: its `]` does not close the option
        let (text, _, _) = expand("\\newcommand{\\pt}[1][{x]}]{#1^2}\n$\\pt$").unwrap();
        assert!(text.contains("{x]}^2"), "{text}");
    }
}
