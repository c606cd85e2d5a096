//! A paper's own source, read as LaTeX numbers it: every display of a `.tex` file (or of a text
//! with display math) with the number its reader sees.
//!
//! Displays: `$$ ... $$`, `\[ ... \]`, and the environments `equation`, `multline`, `align`,
//! `gather`, `eqnarray`, `alignat`, `flalign` (starred or not; `aligned`, `split`, `gathered`
//! inside are rows of their display). Numbers, as LaTeX gives them: `equation` and `multline`
//! take one number; each row of `align`, `gather`, `eqnarray`, `alignat` and `flalign` takes
//! one unless it says `\nonumber` or `\notag`; `\tag{A1}` is the row's own label and takes no
//! number; starred environments, `$$` and `\[` take none, but a plain `(2.10)` printed on the
//! line after a `$$` or `\[` block (as the seeds print their labels) is that block's number.
//! With `\numberwithin{equation}{section}` the numbers are `section.n`, `n` restarting at each
//! `\section`. `\label{..}` names the number of its row (or of its `equation`).
//!
//! The result is a list of displays in the form the display reader takes: each automatic
//! number written into its row as `\tag{n}`, labels and `\nonumber` taken out, so that a claim
//! finds a relation by the number printed beside it. Comments (`%` to the end of a line, not
//! `\%`) are dropped first.

use super::display::{continues, ends_open, lead, rows_of, split_top};
pub use super::files::Loader;
use super::files::braced;

/// One display of a document: its LaTeX with every number as a `\tag{..}`, and the label
/// printed on the line after it (`(2.10)` after a `$$` block), if any.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DocDisplay {
    /// The display's LaTeX, environment kept, numbers as `\tag{..}`, labels taken out.
    pub latex: String,
    /// A number printed after the block rather than in it.
    pub after: Option<String>,
    /// The environment (`"equation"`, `"align*"`, `"$$"`, `"\\["`).
    pub environment: String,
    /// The line (1-based) of the source where the display opens (with `\input` files inlined).
    pub line: usize,
}

/// A paper's displays and the numbers and labels found in them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Document {
    /// Every display, in order.
    pub displays: Vec<DocDisplay>,
    /// Every number a reader sees (automatic, `\tag{..}`, or printed after a block), in order.
    pub numbers: Vec<String>,
    /// `(label, number)` for every `\label{..}` of a numbered row, in order.
    pub labels: Vec<(String, String)>,
    /// What could not be read as LaTeX reads it (an `\input` refused or missing, a macro
    /// that does not expand), each naming the place; the rest is read all the same.
    pub problems: Vec<String>,
    /// The paper's text as LaTeX reads it: its inputs followed, comments dropped, macros not
    /// yet expanded (the prose of every file, for its words and quotes).
    pub text: String,
    /// Where each line of [`Document::text`] comes from ([`super::files::place`]).
    pub spans: Vec<super::files::Span>,
}

impl Document {
    /// Where line `line` of the paper's text (its inputs followed) is: the file (`""`: the
    /// paper's own) and its line there.
    pub fn place(&self, line: usize) -> (&str, usize) {
        super::files::place(&self.spans, line)
    }

    /// Whether the paper's text spans more than its own file.
    pub fn has_inputs(&self) -> bool {
        self.spans.iter().any(|s| !s.file.is_empty())
    }

    /// The number a `\label{..}` names.
    pub fn number_of(&self, label: &str) -> Option<&str> {
        self.labels
            .iter()
            .find(|(l, _)| l == label)
            .map(|(_, n)| n.as_str())
    }

    /// The label of a number, if its row has one.
    pub fn label_of(&self, number: &str) -> Option<&str> {
        self.labels
            .iter()
            .find(|(_, n)| n == number)
            .map(|(l, _)| l.as_str())
    }
}

/// The numbered environments, each with whether every row takes a number (`align`) rather than
/// the whole display one (`equation`).
const NUMBERED: &[(&str, bool)] = &[
    ("equation", false),
    ("multline", false),
    ("align", true),
    ("gather", true),
    ("eqnarray", true),
    ("alignat", true),
    ("flalign", true),
];

/// `row` without each `\name{..}` and the arguments taken out.
fn take_command(row: &str, name: &str) -> (String, Vec<String>) {
    let pat = format!("\\{name}");
    let mut out = String::new();
    let mut args = Vec::new();
    let mut rest = row;
    while let Some(i) = rest.find(&pat) {
        let after = i + pat.len();
        // `\tagx` is another command
        if rest[after..].starts_with(|c: char| c.is_ascii_alphabetic()) {
            out.push_str(&rest[..after]);
            rest = &rest[after..];
            continue;
        }
        match braced(rest, after) {
            Some((arg, end)) => {
                out.push_str(&rest[..i]);
                args.push(arg.trim().to_string());
                rest = &rest[end..];
            }
            None => {
                out.push_str(&rest[..after]);
                rest = &rest[after..];
            }
        }
    }
    out.push_str(rest);
    (out, args)
}

/// `row` without `\nonumber` and `\notag`, and whether it had one.
fn take_nonumber(row: &str) -> (String, bool) {
    let mut had = false;
    let mut out = row.to_string();
    for w in ["\\nonumber", "\\notag"] {
        if out.contains(w) {
            had = true;
            out = out.replace(w, " ");
        }
    }
    (out, had)
}

/// The reading state: the equation counter, the section counter, and what was found.
struct Numbering {
    within_section: bool,
    section: u32,
    counter: u32,
    /// Inside `subequations`: how many numbers it has given (`3a`, `3b`, ...).
    sub: Option<u32>,
    doc: Document,
}

impl Numbering {
    fn next(&mut self) -> String {
        if let Some(k) = self.sub.as_mut() {
            *k += 1;
            let letter = char::from_u32('a' as u32 + (*k - 1) % 26).unwrap_or('z');
            return format!("{}{letter}", self.current());
        }
        self.counter += 1;
        self.current()
    }

    /// The counter as printed.
    fn current(&self) -> String {
        if self.within_section {
            format!("{}.{}", self.section, self.counter)
        } else {
            self.counter.to_string()
        }
    }

    /// A row of a display: its `\tag`, else (when it takes one) the next number, written in as
    /// `\tag{..}`; its labels recorded against that number.
    fn row(&mut self, row: &str, numbered: bool) -> String {
        let (row, labels) = take_command(row, "label");
        let (row, nonumber) = take_nonumber(&row);
        let (_, tags) = take_command(&row, "tag");
        let (row, number) = match tags.first() {
            Some(t) => (row.clone(), Some(t.clone())),
            None if numbered && !nonumber && !row.trim().is_empty() => {
                let n = self.next();
                (format!("{} \\tag{{{n}}}", row.trim_end()), Some(n))
            }
            None => (row, None),
        };
        if let Some(n) = &number {
            self.doc.numbers.push(n.clone());
            for l in labels {
                self.doc.labels.push((l, n.clone()));
            }
        }
        row
    }

    /// A numbered or starred environment's body.
    fn environment(&mut self, env: &str, body: &str) -> String {
        let base = env.trim_end_matches('*');
        let starred = env.ends_with('*');
        let per_row = NUMBERED
            .iter()
            .find(|(e, _)| *e == base)
            .is_some_and(|(_, r)| *r);
        if per_row {
            return self.relations_of_rows(body, !starred);
        }
        // one number for the whole display, at its end; a \tag anywhere in it is its label
        let (body, labels) = take_command(body, "label");
        let (body, nonumber) = take_nonumber(&body);
        let (_, tags) = take_command(&body, "tag");
        let (body, number) = match tags.first() {
            Some(t) => (body.clone(), Some(t.clone())),
            None if !starred && !nonumber => {
                let n = self.next();
                (format!("{} \\tag{{{n}}}", body.trim_end()), Some(n))
            }
            None => (body, None),
        };
        if let Some(n) = number {
            self.doc.numbers.push(n.clone());
            for l in labels {
                self.doc.labels.push((l, n.clone()));
            }
        }
        body
    }

    /// The rows of an environment numbered per row (`align`, `eqnarray`), each relation one
    /// row: a row that continues the relation before it ([`continues`]) joins it, the relation
    /// takes the number of its numbered row (the last, where it has several: LaTeX prints one
    /// per row without `\nonumber`), and a `\label` on any of its rows names that number.
    fn relations_of_rows(&mut self, body: &str, numbered: bool) -> String {
        let mut groups: Vec<Vec<String>> = Vec::new();
        for row in rows_of(body) {
            match groups.last_mut() {
                // a row that starts with an operator, or follows one that ends with one
                Some(g) if continues(&row) || g.last().is_some_and(|r| ends_open(r)) => g.push(row),
                _ => groups.push(vec![row]),
            }
        }
        let mut out = Vec::new();
        for group in groups {
            let mut labels = Vec::new();
            let mut number = None;
            let mut texts = Vec::new();
            for row in &group {
                let (row, mut l) = take_command(row, "label");
                labels.append(&mut l);
                let (row, nonumber) = take_nonumber(&row);
                let (row, tags) = take_command(&row, "tag");
                let tag = tags.first().cloned().or_else(|| {
                    (numbered && !nonumber && !row.trim().is_empty()).then(|| self.next())
                });
                if let Some(n) = tag {
                    self.doc.numbers.push(n.clone());
                    number = Some(n);
                }
                // a continuation's alignment and spacing go, so that it joins the relation
                // (a `\quad` left in it would split the relation there)
                texts.push(if texts.is_empty() {
                    row
                } else {
                    lead(&row).to_string()
                });
            }
            let mut joined = texts.join("\n");
            if let Some(n) = &number {
                joined = format!("{} \\tag{{{n}}}", joined.trim_end());
                for l in labels {
                    self.doc.labels.push((l, n.clone()));
                }
            }
            out.push(joined);
        }
        out.join("\\\\")
    }

    /// A `$$` or `\[` block: its own `\tag`s count; labels go.
    fn unnumbered(&mut self, body: &str) -> String {
        split_top(body, &["\\\\"])
            .iter()
            .map(|r| self.row(r, false))
            .collect::<Vec<_>>()
            .join("\\\\")
    }
}

/// A plain `(2.10)` (or `(A1)`) alone on the rest of the line after a block, with the index
/// after it.
fn number_after(text: &str, at: usize) -> Option<String> {
    let rest = &text[at..];
    let start = rest.find(|c: char| !c.is_whitespace())?;
    // on the line of the closing delimiter or the next
    if rest[..start].matches('\n').count() > 1 || !rest[start..].starts_with('(') {
        return None;
    }
    let close = rest[start..].find(')')?;
    let inner = &rest[start + 1..start + close];
    let line_end = rest[start + close + 1..]
        .find('\n')
        .map_or(rest.len(), |k| start + close + 1 + k);
    let ok = !inner.is_empty()
        && inner.len() <= 12
        && inner.chars().any(|c| c.is_ascii_digit())
        && inner
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '.' || c == '-')
        && rest[start + close + 1..line_end].trim().is_empty();
    ok.then(|| inner.to_string())
}

/// The next thing the reader acts on at or after `from`: a display opening, a `\section`, or
/// nothing.
enum Next {
    Dollars(usize),
    Bracket(usize),
    Begin(usize, String),
    Section(usize),
    /// `\begin{subequations}` (true) or its end (false), with the index after it.
    Sub(usize, bool),
}

/// Where the first `$$` of `rest` that opens a display is: not one inside inline math, where
/// two formulas meet (`${d\delta}$$/{dt} > 0$` closes one and opens the next). Inline math ends
/// at a blank line, as TeX's does.
fn display_dollars(rest: &str) -> Option<usize> {
    let b = rest.as_bytes();
    let mut inline = false;
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 1,
            b'$' if b.get(i + 1) == Some(&b'$') => {
                if !inline {
                    return Some(i);
                }
                i += 1;
            }
            b'$' => inline = !inline,
            b'\n'
                if inline
                    && rest[i + 1..]
                        .trim_start_matches([' ', '\t'])
                        .starts_with('\n') =>
            {
                inline = false;
            }
            _ => {}
        }
        i += 1;
    }
    None
}

fn next_item(text: &str, from: usize) -> Option<Next> {
    let rest = &text[from..];
    let mut best: Option<(usize, Next)> = None;
    let mut offer = |i: usize, n: Next| {
        if best.as_ref().is_none_or(|(b, _)| i < *b) {
            best = Some((i, n));
        }
    };
    if let Some(i) = display_dollars(rest) {
        offer(from + i, Next::Dollars(from + i));
    }
    // `\[` opens a display; `\\[2pt]` is a line break with its space
    let mut search = 0;
    while let Some(i) = rest[search..].find("\\[") {
        let at = search + i;
        let escaped = rest[..at].chars().rev().take_while(|c| *c == '\\').count() % 2 == 1;
        if !escaped {
            offer(from + at, Next::Bracket(from + at));
            break;
        }
        search = at + 2;
    }
    let mut search = 0;
    while let Some(i) = rest[search..].find("\\begin{") {
        let at = search + i;
        if let Some((env, _)) = braced(rest, at + 6) {
            let base = env.trim_end_matches('*');
            if NUMBERED.iter().any(|(e, _)| *e == base) {
                offer(from + at, Next::Begin(from + at, env));
                break;
            }
        }
        search = at + 7;
    }
    for (word, open) in [
        ("\\begin{subequations}", true),
        ("\\end{subequations}", false),
    ] {
        if let Some(i) = rest.find(word) {
            offer(from + i, Next::Sub(from + i + word.len(), open));
        }
    }
    let mut search = 0;
    while let Some(i) = rest[search..].find("\\section") {
        let at = search + i;
        let after = &rest[at + 8..];
        if after.starts_with('{') || after.starts_with("*{") || after.starts_with('[') {
            offer(from + at, Next::Section(from + at));
            break;
        }
        search = at + 8;
    }
    best.map(|(_, n)| n)
}

/// Reads a paper's source: every display with its numbers and labels (an `\input` is left
/// unread and named in [`Document::problems`]; [`read_document_with`] follows it).
pub fn read_document(source: &str) -> Document {
    read_document_with(source, &|name| {
        Err(format!("`\\input{{{name}}}`: no folder to read it from"))
    })
}

/// Reads a paper's source as LaTeX does: comments dropped, every `\input` read through `load`,
/// the paper's macros expanded ([`super::macros`]), then every display with its numbers and
/// labels.
pub fn read_document_with(source: &str, load: Loader) -> Document {
    read_document_full(source, "", load)
}

/// As [`read_document_with`], with the macros of `preamble` (its definitions only: a file of
/// macros the paper uses without holding them).
pub fn read_document_full(source: &str, preamble: &str, load: Loader) -> Document {
    let (text, spans, mut problems) = super::files::assemble(source, load);
    // units as siunitx writes them, in the forms the readers take
    let text = super::siunitx::plain(&text);
    let assembled = text.clone();
    let preamble = super::files::inline_inputs(preamble, load, &mut problems);
    // the macros of the packages it loads first, then the preamble's
    let preamble = format!(
        "{}{preamble}",
        super::packages::preamble_of(&format!("{text}\n{preamble}"))
    );
    let text = drop_verbatim(&text);
    let text = match super::macros::expand_with(&text, &preamble) {
        Ok((expanded, _, short)) => {
            problems.extend(short.iter().map(ToString::to_string));
            expanded
        }
        Err(e) => {
            problems.push(e.to_string());
            text
        }
    };
    let mut st = Numbering {
        within_section: text.contains("\\numberwithin{equation}{section}"),
        section: 0,
        counter: 0,
        sub: None,
        doc: Document {
            problems,
            text: assembled,
            spans,
            ..Document::default()
        },
    };
    let mut pos = 0;
    while let Some(item) = next_item(&text, pos) {
        match item {
            Next::Section(at) => {
                // a starred section takes no number
                if !text[at + 8..].starts_with('*') {
                    st.section += 1;
                    if st.within_section {
                        st.counter = 0;
                    }
                }
                pos = at + 8;
            }
            Next::Sub(end, open) => {
                if open {
                    st.counter += 1;
                    st.sub = Some(0);
                } else {
                    st.sub = None;
                }
                pos = end;
            }
            Next::Dollars(at) | Next::Bracket(at) => {
                let dollars = matches!(item, Next::Dollars(_));
                let close = if dollars { "$$" } else { "\\]" };
                let Some(len) = text[at + 2..].find(close) else {
                    break;
                };
                let body = &text[at + 2..at + 2 + len];
                let end = at + 2 + len + 2;
                let after = number_after(&text, end);
                if let Some(n) = &after {
                    st.doc.numbers.push(n.clone());
                }
                let latex = st.unnumbered(body);
                st.doc.displays.push(DocDisplay {
                    latex: latex.trim().to_string(),
                    after,
                    environment: (if dollars { "$$" } else { "\\[" }).to_string(),
                    line: line_of(&text, at),
                });
                pos = end;
            }
            Next::Begin(at, env) => {
                let open = format!("\\begin{{{env}}}");
                let close = format!("\\end{{{env}}}");
                let start = at + open.len();
                let Some(len) = text[start..].find(&close) else {
                    break;
                };
                let body = st.environment(&env, &text[start..start + len]);
                st.doc.displays.push(DocDisplay {
                    latex: format!("{open}{body}{close}"),
                    after: None,
                    environment: env,
                    line: line_of(&text, at),
                });
                pos = start + len + close.len();
            }
        }
    }
    st.doc
}

/// The environments whose content is no LaTeX math (code, pictures, verbatim text): their
/// `$` and `\[` are not displays.
const VERBATIM: &[&str] = &[
    "verbatim",
    "Verbatim",
    "lstlisting",
    "minted",
    "comment",
    "asy",
    "asydef",
    "asyinclude",
    "tikzpicture",
    "pgfpicture",
    "filecontents",
    "filecontents*",
    "alltt",
    "code",
    "python",
];

/// `text` without the content of [`VERBATIM`] environments, of Markdown's fenced code blocks
/// (```) and of HTML comments, their newlines kept so that lines keep their numbers.
fn drop_verbatim(text: &str) -> String {
    let blank = |s: &str| "\n".repeat(s.matches('\n').count());
    let mut out = text.to_string();
    for env in VERBATIM {
        let (open, close) = (format!("\\begin{{{env}}}"), format!("\\end{{{env}}}"));
        let mut from = 0;
        while let Some(k) = out[from..].find(&open) {
            let at = from + k;
            let Some(len) = out[at..].find(&close) else {
                break;
            };
            let end = at + len + close.len();
            let kept = blank(&out[at..end]);
            out.replace_range(at..end, &kept);
            from = at + kept.len();
        }
    }
    // a Markdown note's HTML comments (`<!-- .. -->`), a draft the reader never sees
    let mut from = 0;
    while let Some(k) = out[from..].find("<!--") {
        let at = from + k;
        let Some(len) = out[at..].find("-->") else {
            break;
        };
        let end = at + len + 3;
        let kept = blank(&out[at..end]);
        out.replace_range(at..end, &kept);
        from = at + kept.len();
    }
    if out.contains("```") {
        let mut fenced = false;
        let lines: Vec<String> = out
            .split('\n')
            .map(|l| {
                let fence = l.trim_start().starts_with("```");
                let keep = !fenced && !fence;
                if fence {
                    fenced = !fenced;
                }
                if keep { l.to_string() } else { String::new() }
            })
            .collect();
        out = lines.join("\n");
    }
    out
}

/// The line (1-based) of byte `at` of `text`.
fn line_of(text: &str, at: usize) -> usize {
    text[..at.min(text.len())].matches('\n').count() + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_break_with_its_space_opens_no_display() {
        // by hand: `\\[2pt]` in prose (or in a class's macro put into the text) is no `\[`
        let d = read_document("A\\\\[2pt] B\\\\[\\affilsep] C\n\\[ a = b \\]\n$$ c = d $$");
        let latex: Vec<&str> = d.displays.iter().map(|x| x.latex.trim()).collect();
        assert_eq!(latex, ["a = b", "c = d"], "{:?}", d.displays);
    }

    #[test]
    fn two_inline_formulas_back_to_back_are_no_display() {
        // by hand: `$a$$b$` is two inline formulas; the display after them is the only one
        let d = read_document("we have ${d\\delta}$$/{dt} > 0$ while $x$.\n$$ a = b $$\nthen $y$");
        let latex: Vec<&str> = d.displays.iter().map(|x| x.latex.trim()).collect();
        assert_eq!(latex, ["a = b"], "{:?}", d.displays);
        // a `$` left open ends with its paragraph; an escaped dollar opens nothing
        let d = read_document("costs \\$5 and $x\n\n$$ c = d $$");
        let latex: Vec<&str> = d.displays.iter().map(|x| x.latex.trim()).collect();
        assert_eq!(latex, ["c = d"], "{:?}", d.displays);
    }

    #[test]
    fn an_unbraced_input_is_read_but_no_unbraced_include() {
        // TeX's `\input file` takes a name up to a space; `\include` wants braces
        let load = |_: &str| Ok("$$ c = d $$".to_string());
        let d = read_document_with("\\input chap\n$$ a = b $$", &load);
        assert_eq!(d.displays.len(), 2, "{:?}", d.displays);
        let d = read_document_with("\\include chap\n$$ a = b $$", &load);
        assert_eq!(d.displays.len(), 1, "{:?}", d.displays);
        // the unbraced name ends at a closing brace (`{\input chap}`)
        let named = |name: &str| {
            if name == "chap" {
                Ok("$$ c = d $$".to_string())
            } else {
                Err(format!("no file {name}"))
            }
        };
        let d = read_document_with("{\\input chap}\n$$ a = b $$", &named);
        assert_eq!(d.displays.len(), 2, "{:?} {:?}", d.displays, d.problems);
    }

    #[test]
    fn an_html_comment_is_blanked_to_its_end_and_no_further() {
        // by hand: each comment goes, its newlines stay, and what follows it is kept whole
        assert_eq!(drop_verbatim("<!-- c -->x\n<!--\n-->y"), "x\n\ny");
        let d = read_document("<!-- $$ u = v $$ -->$$ a = b $$\n<!-- c -->\n$$ e = f $$");
        let rows: Vec<&str> = d.displays.iter().map(|x| x.latex.trim()).collect();
        assert_eq!(rows, ["a = b", "e = f"], "{:?}", d.displays);
        assert_eq!(d.displays[1].line, 3);
    }

    #[test]
    fn subequations_number_3a_3b_and_the_counter_goes_on() {
        // by hand, as LaTeX numbers them: 1, then 2a 2b 2c (the counter takes 2), then 3
        let d = read_document(
            r"
\begin{equation} a = b \end{equation}
\begin{subequations}
\begin{align} c &= d \\ e &= f \end{align}
\begin{equation} g = h \end{equation}
\end{subequations}
\begin{equation} i = j \end{equation}
",
        );
        assert_eq!(d.numbers, ["1", "2a", "2b", "2c", "3"]);
    }

    #[test]
    fn numbers_as_latex_gives_them() {
        let src = r"
Intro $x$ and 50\% of it. % a comment with $$ x $$ in it
\begin{equation}\label{eq:a} a = b \end{equation}
\begin{equation*} c = d \end{equation*}
\begin{align}
e &= f \label{eq:e} \\
g &= h \nonumber \\
i &= j \notag \\
k &= l \tag{A1} \\
m &= n \label{eq:m}
\end{align}
$$ o = p $$
(7.1)
$$ q = r \tag{B} $$
\[ s = t \]
\begin{gather} u = v \\ w = x \end{gather}
\begin{multline} y = z \\ + 1 \end{multline}
\begin{eqnarray} aa &=& bb \\ cc &=& dd \nonumber \end{eqnarray}
";
        let d = read_document(src);
        // by hand: equation 1; align rows e (2), g and i none, k A1, m (3); $$ (7.1) after;
        // B; gather 4, 5; multline 6; eqnarray aa 7, cc none
        assert_eq!(
            d.numbers,
            ["1", "2", "A1", "3", "7.1", "B", "4", "5", "6", "7"]
        );
        assert_eq!(d.number_of("eq:a"), Some("1"));
        assert_eq!(d.number_of("eq:e"), Some("2"));
        assert_eq!(d.number_of("eq:m"), Some("3"));
        assert_eq!(d.label_of("3"), Some("eq:m"));
        assert_eq!(d.displays.len(), 9);
        assert!(
            d.displays[0].latex.contains("a = b \\tag{1}"),
            "{:?}",
            d.displays[0]
        );
        assert!(!d.displays[0].latex.contains("label"));
        assert!(!d.displays[1].latex.contains("\\tag"));
        assert!(
            !d.displays[2].latex.contains("nonumber") && !d.displays[2].latex.contains("notag")
        );
        assert_eq!(d.displays[3].after.as_deref(), Some("7.1"));
        assert_eq!(d.displays[5].environment, "\\[");
    }

    #[test]
    fn a_label_with_a_space_before_its_brace() {
        let d = read_document("\\begin{equation} a = b \\label {eq:s} + c \\end{equation}");
        assert_eq!(d.number_of("eq:s"), Some("1"));
        assert_eq!(
            d.displays[0].latex,
            "\\begin{equation} a = b  + c \\tag{1}\\end{equation}"
        );
    }

    #[test]
    fn numbers_within_sections() {
        let src = r"\numberwithin{equation}{section}
\section{One} \begin{equation} a = b \end{equation}
\section*{Unnumbered} \begin{equation} c = d \end{equation}
\section{Two} \begin{equation} e = f \end{equation} \begin{equation} g = h \end{equation}";
        assert_eq!(read_document(src).numbers, ["1.1", "1.2", "2.1", "2.2"]);
    }

    #[test]
    fn a_number_after_a_block_is_one_on_its_own() {
        assert_eq!(number_after("\n(2.10)\nNext", 0).as_deref(), Some("2.10"));
        assert_eq!(number_after("  (A1)  \n", 0).as_deref(), Some("A1"));
        // prose in parentheses, a later line, or text after it: not a number
        assert_eq!(number_after("\n(see above)\n", 0), None);
        assert_eq!(number_after("\n(3) and more\n", 0), None);
        assert_eq!(number_after("\n\n\n(3)\n", 0), None);
        // a hyphen belongs to a number; a space or a comma does not
        assert_eq!(number_after("\n(A-1)\n", 0).as_deref(), Some("A-1"));
        assert_eq!(number_after("\n(3 a)\n", 0), None);
        assert_eq!(number_after("\n(3,4)\n", 0), None);
    }

    #[test]
    fn a_command_that_only_starts_like_section_is_passed_over() {
        // `\sectionmark` is no section: the search goes on to the real one after it
        let src = r"\numberwithin{equation}{section} \sectionmark{x} \sectionmark{y} \section{A}
\begin{equation} a = b \end{equation}";
        assert_eq!(read_document(src).numbers, ["1.1"]);
    }

    #[test]
    fn comments_go_but_an_escaped_percent_stays() {
        assert_eq!(
            super::super::files::strip_comments("a % b\nc \\% d\n"),
            "a \nc \\% d\n"
        );
    }

    #[test]
    fn a_package_with_options_in_the_papers_folder_gives_its_macros() {
        // `\usepackage[opt]{mine}`: the name after the options, read from the folder
        let src = "\\documentclass{article}\n\\usepackage[utf8,  final]{mine}\n\\begin{document}\n$$ \\vv = a t $$\n\\end{document}";
        let doc = read_document_with(src, &|name| {
            if name == "mine.sty" {
                Ok("\\newcommand{\\vv}{v_{0}}".to_string())
            } else {
                Err(format!("no {name}"))
            }
        });
        assert_eq!(doc.displays.len(), 1, "{doc:?}");
        assert!(doc.displays[0].latex.contains("v_{0}"), "{doc:?}");
    }

    #[test]
    fn verbatim_blocks_at_the_start_are_skipped_and_the_display_after_them_read() {
        // the first block opens the text and keeps its two newlines: the search goes on past it
        let doc = read_document(
            "\\begin{verbatim}$$ a = b $$\nand a line of code\n\\end{verbatim}\n\\begin{verbatim}$$ c = d $$\n\\end{verbatim}\n$$ x = y $$",
        );
        assert_eq!(doc.displays.len(), 1, "{doc:?}");
        assert!(doc.displays[0].latex.contains("x = y"), "{doc:?}");
    }
}
