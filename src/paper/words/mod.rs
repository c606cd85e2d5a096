//! A paper's units from its own words (issue 52): the prose around the displays read for the
//! phrases that name a symbol, each symbol given the unit of the quantity named
//! ([`vocabulary`]) or the unit written beside it, with the sentence quoted and its line.
//!
//! The phrases read:
//! - a description after a symbol or a list of symbols: "where $x$ is/are/denotes/stands for
//!   (the) <quantity>", "$a$, $b$ and $c$ are the A, B and C, respectively", "$E, \nu, \eta$
//!   are ..."; also "we denote by $x$ the <quantity>";
//! - a quantity right before a symbol: "a ball of mass $m$", "the stiffness $k$ of the spring",
//!   "with the dimensions $a$ and $b$" (a plural names the whole list);
//! - a subject named after it: "the velocity of the centre is denoted by $v$";
//! - a nomenclature: a line that opens with a symbol and a separator (`&`, `:`, `--`, `|`,
//!   `\item[$x$]`), its description, and a unit in brackets or a column of its own (`[Pa]`,
//!   `[kg m$^{-3}$]`, `(N/m)`): a unit written in the paper is taken as written.
//!
//! A symbol the words give two units is given none (both named in the notes). Written by
//! hand, as [`vocabulary`] says why.

mod bare;
mod dimensionless;
mod written;
pub use dimensionless::dimensionless_spans;
pub use written::written_unit;
pub mod vocabulary;

use bare::bare_lists;
#[cfg(test)]
use bare::bare_symbol;

use crate::algebra::expr::Expr;
use crate::algebra::units::Unit;
use crate::paper::formulas::{TexSymbols, read_formula};
use crate::paper::units::unit_name;
use serde::Serialize;
use std::collections::BTreeMap;
use vocabulary::{Hit, Vocabulary};

/// A symbol's unit as the paper's words give it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct WordUnit {
    /// The symbol as the audit names it (`rho`, `K_w`).
    pub symbol: String,
    /// Its unit.
    #[serde(serialize_with = "as_text")]
    pub unit: Unit,
    /// The quantity of the vocabulary (`density`), or `written` for a unit the paper writes.
    pub quantity: String,
    /// The words that named it, quoted from the paper.
    pub quote: String,
    /// The line of the paper (of its text with its inputs followed).
    pub line: usize,
    /// Whether the words are the paper's key to a display ("where $x$ is ...", a
    /// nomenclature), not a mention in passing: a key is never set aside.
    pub key: bool,
    /// For a paper over several files: the file the words are in and their line there.
    #[serde(skip)]
    pub file: Option<(String, usize)>,
}

fn as_text<S: serde::Serializer>(u: &Unit, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&u.to_string())
}

impl WordUnit {
    /// `line 38: "$\rho$ is the density of plate"`, or `sections/model.tex:3: ".."` for words
    /// in another file of the paper.
    pub fn source(&self) -> String {
        match &self.file {
            Some((f, l)) => format!("{f}:{l}: \"{}\"", self.quote),
            None => format!("line {}: \"{}\"", self.line, self.quote),
        }
    }
}

/// A piece of the prose: text, or inline math.
#[derive(Clone, Debug, PartialEq)]
enum Item {
    Text(String),
    Math(String),
}

/// The display environments whose text is no prose.
const DISPLAYS: &[&str] = &[
    "equation",
    "align",
    "alignat",
    "gather",
    "multline",
    "eqnarray",
    "displaymath",
    "flalign",
    "math",
    "split",
    "subequations",
];

/// Where a display stood in the prose.
const DISPLAY_MARK: char = '¶';

/// Whether the words at `at` of the prose `p` are in a sentence that opens with "where" (or
/// "here", "in which"), after a display or a full stop: the paper's own key to a display, as
/// against a mention in passing ("at time $t$").
fn in_where_clause(p: &str, at: usize) -> bool {
    let before = &p[..at];
    let start = [
        before.rfind('.'),
        before.rfind(DISPLAY_MARK),
        before.rfind("\n\n"),
    ]
    .into_iter()
    .flatten()
    .max()
    .map_or(0, |k| {
        k + before[k..].chars().next().map_or(1, char::len_utf8)
    });
    let opening = before[start..].trim_start().to_ascii_lowercase();
    [
        "where",
        "here",
        "in which",
        "in these formulae",
        "in this formula",
        "with ",
    ]
    .iter()
    .any(|w| opening.starts_with(w))
}

/// `text` with its displays and comments blanked (newlines kept, so lines keep their
/// numbers).
fn prose(text: &str) -> String {
    let blank = |s: &str| -> String {
        s.chars()
            .map(|c| if c == '\n' { '\n' } else { ' ' })
            .collect()
    };
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    loop {
        let opens = [
            rest.find("$$")
                .map(|k| (k, "$$".to_string(), "$$".to_string())),
            rest.find("\\[")
                .map(|k| (k, "\\[".to_string(), "\\]".to_string())),
            DISPLAYS
                .iter()
                .filter_map(|e| {
                    let open = format!("\\begin{{{e}");
                    rest.find(&open).map(|k| {
                        let star = rest[k + open.len()..].starts_with('*');
                        let name = if star {
                            format!("{e}*")
                        } else {
                            (*e).to_string()
                        };
                        (k, format!("\\begin{{{name}}}"), format!("\\end{{{name}}}"))
                    })
                })
                .min_by_key(|(k, _, _)| *k),
        ];
        let Some((k, open, close)) = opens.into_iter().flatten().min_by_key(|(k, _, _)| *k) else {
            out.push_str(rest);
            break;
        };
        out.push_str(&rest[..k]);
        let body = &rest[k + open.len()..];
        let end = body.find(&close).map_or(body.len(), |e| e + close.len());
        // a display ends a sentence's clause: its first character marks it
        let blanked = blank(&rest[k..k + open.len() + end]);
        out.push(DISPLAY_MARK);
        out.push_str(&blanked[blanked.chars().next().map_or(0, char::len_utf8)..]);
        rest = &body[end..];
    }
    out = unit_dollars(&out);
    // comments, where the text is LaTeX (`\%` kept)
    if text.contains("\\begin{") || text.contains("\\section") {
        out = out
            .lines()
            .map(|l| {
                let mut cut = l.len();
                let b = l.as_bytes();
                for (i, &c) in b.iter().enumerate() {
                    if c == b'%' && (i == 0 || b[i - 1] != b'\\') {
                        cut = i;
                        break;
                    }
                }
                format!("{}{}", &l[..cut], " ".repeat(l.len() - cut))
            })
            .collect::<Vec<_>>()
            .join("\n");
    }
    out
}

/// A unit written in brackets with math in it (`[kg m$^{-3}$]`, `(m$^2$)`) with its dollars
/// taken out, so that it stays one piece of text (dollars become spaces: offsets kept).
fn unit_dollars(text: &str) -> String {
    let mut out = text.to_string();
    let b = text.as_bytes();
    for (i, &c) in b.iter().enumerate() {
        let close = match c {
            b'[' => b']',
            b'(' => b')',
            _ => continue,
        };
        let Some(len) = b[i + 1..]
            .iter()
            .take(40)
            .position(|&d| d == close || d == b'\n')
        else {
            continue;
        };
        let inner = &text[i + 1..i + 1 + len];
        if b[i + 1 + len] == close
            && inner.contains('$')
            && inner.matches('$').count().is_multiple_of(2)
            && written_unit(inner).is_some()
        {
            out.replace_range(i + 1..i + 1 + len, &inner.replace('$', " "));
        }
    }
    out
}

/// The prose as items with their byte offsets: `$..$` and `\(..\)` are math, the rest text.
fn items(p: &str) -> Vec<(usize, Item)> {
    let mut out = Vec::new();
    let mut pos = 0;
    let mut text_start = 0;
    let b = p.as_bytes();
    while pos < b.len() {
        let (open_len, close) = if b[pos] == b'$' && (pos == 0 || b[pos - 1] != b'\\') {
            (1, "$")
        } else if b[pos..].starts_with(b"\\(") {
            (2, "\\)")
        } else {
            pos += 1;
            continue;
        };
        let Some(end) = p[pos + open_len..].find(close) else {
            break;
        };
        if text_start < pos {
            out.push((text_start, Item::Text(p[text_start..pos].to_string())));
        }
        let math = &p[pos + open_len..pos + open_len + end];
        out.push((pos, Item::Math(math.to_string())));
        pos += open_len + end + close.len();
        text_start = pos;
    }
    if text_start < p.len() {
        out.push((text_start, Item::Text(p[text_start..].to_string())));
    }
    out
}

/// The parts of a math span at its top-level commas (`E, \nu, \eta`).
fn split_commas(math: &str) -> Vec<String> {
    let mut parts = Vec::new();
    let mut depth = 0i32;
    let mut start = 0;
    for (i, c) in math.char_indices() {
        match c {
            '{' | '(' | '[' => depth += 1,
            '}' | ')' | ']' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(math[start..i].to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(math[start..].to_string());
    parts
        .into_iter()
        .map(|s| s.trim().trim_start_matches("\\quad").trim().to_string())
        .filter(|s| !s.is_empty())
        .collect()
}

/// The symbols a math span names: a plain symbol or a function's (`w(x, y, t)`), its sign
/// dropped; with `chain`, every side of a relation that is one (`\tau = \lambda^{-1} =
/// \eta/E`: `tau`, and `lambda` with the inverse unit, `true`).
fn symbols_of(math: &str, syms: &TexSymbols, chain: bool) -> Vec<(String, bool)> {
    if ["<", ">", "\\le", "\\ge", "\\to", "\\in"]
        .iter()
        .any(|r| math.contains(r))
        || !chain && math.contains('=')
    {
        return Vec::new();
    }
    let special = [
        crate::algebra::units::ELLIPSIS,
        crate::algebra::units::INFINITY,
        crate::algebra::units::OPERAND,
    ];
    let mut out = Vec::new();
    for (k, side) in math.split('=').enumerate() {
        let Ok(e) = read_formula(side.trim(), syms) else {
            continue;
        };
        let e = match e {
            Expr::Neg(inner) => *inner,
            other => other,
        };
        let (e, inverse) = match e {
            Expr::Bin(crate::algebra::expr::Op::Pow, base, p)
                if p.to_string() == "-1" || p.to_string() == "(-1)" =>
            {
                (*base, true)
            }
            other => (other, false),
        };
        // the first side is named; another only as its inverse (`\tau = \lambda^{-1}`, not
        // `Q = E`, a symbol set to another quantity)
        if let Expr::Sym(s) = e
            && !special.contains(&s.as_str())
            && (k == 0 || inverse)
        {
            out.push((unit_name(&s), inverse));
        }
    }
    out
}

/// The units the words give the symbols of a math span (an inverse power its inverse unit).
fn named_units(
    tex: &str,
    syms: &TexSymbols,
    chain: bool,
    nm: &Named,
    quote: &str,
    line: usize,
    key: bool,
) -> Vec<WordUnit> {
    symbols_of(tex, syms, chain)
        .into_iter()
        .map(|(symbol, inverse)| WordUnit {
            symbol,
            unit: if inverse {
                Unit::one().per(nm.unit)
            } else {
                nm.unit
            },
            quantity: nm.quantity.clone(),
            quote: quote.to_string(),
            line,
            key,
            file: None,
        })
        .collect()
}

/// Whether the text between two math spans joins them into one list (`$a$, $b$ and $c$`).
fn is_joiner(t: &str) -> bool {
    matches!(t.trim(), "" | "," | "and" | ", and" | ",and" | "&") && !t.contains('\n')
}

/// What the words give a symbol of a list: the quantity (or `written`), its unit and the words.
#[derive(Clone, Debug)]
struct Named {
    unit: Unit,
    quantity: String,
    words: String,
}

fn named(hit: &Hit, words: &str) -> Option<Named> {
    Some(Named {
        unit: hit.quantity.unit?,
        quantity: hit.quantity.name.clone(),
        words: words.trim().to_string(),
    })
}

/// The verbs that open a description after a symbol.
const VERBS: &[&str] = &[
    "is called",
    "are called",
    "stands for",
    "stand for",
    "denotes",
    "denote",
    "represents",
    "represent",
    "being",
    "is",
    "are",
];

/// The description that follows a verb (`next` opens with it), or `None`.
fn after_verb(next: &str) -> Option<&str> {
    let t = next.trim_start();
    let lower = t.to_ascii_lowercase();
    let verb = VERBS.iter().find(|v| {
        lower.starts_with(*v)
            && lower[v.len()..]
                .chars()
                .next()
                .is_none_or(|c| !c.is_alphanumeric())
    })?;
    let mut rest = t[verb.len()..].trim_start();
    for skip in [",", "respectively", ","] {
        rest = rest.strip_prefix(skip).unwrap_or(rest).trim_start();
    }
    Some(rest)
}

/// A description up to the end of its clause (a list's commas kept when it names `n > 1`
/// symbols), and a unit written right after it (`[Pa]`).
fn clause(text: &str, n: usize) -> (&str, Option<Unit>) {
    let mut end = text.len();
    let b = text.as_bytes();
    // inside the parentheses of a unit written after a slash (`W/(m K)`)
    let mut in_unit = false;
    for (i, &c) in b.iter().enumerate() {
        let stop = match c {
            b'(' if i > 0 && b[i - 1] == b'/' => {
                in_unit = true;
                false
            }
            b')' if in_unit => {
                in_unit = false;
                false
            }
            b';' | b'(' | b')' | b'[' | b':' | b'&' | b'|' => true,
            b',' => n == 1,
            b'.' => b.get(i + 1).is_none_or(|d| d.is_ascii_whitespace()),
            b'\n' => text[i + 1..]
                .trim_start_matches([' ', '\t'])
                .starts_with('\n'),
            b'\\' => text[i..].starts_with("\\\\"),
            _ => false,
        };
        if stop {
            end = i;
            break;
        }
    }
    let mut desc = &text[..end];
    if let Some(k) = desc.to_ascii_lowercase().find("respectively") {
        desc = &desc[..k];
    }
    let rest = &text[end..];
    let unit = [('[', ']'), ('(', ')')]
        .iter()
        .find_map(|(o, c)| {
            let inner = rest.strip_prefix(*o)?;
            written_unit(&inner[..inner.find(*c)?])
        })
        .or_else(|| unit_said(desc));
    (desc.trim_end_matches([',', ' ', '\n']), unit)
}

/// The unit a description says in words: "measured in K", "given in W/(m K)", "expressed in
/// N m", "in Pa" (the whole rest a written unit).
fn unit_said(desc: &str) -> Option<Unit> {
    let d = desc.trim();
    let lower = d.to_ascii_lowercase();
    let verb = ["measured in ", "given in ", "expressed in ", "in "]
        .iter()
        .find(|v| lower.starts_with(**v))?;
    let unit = d[verb.len()..].trim_end_matches([',', ' ', '\n']);
    // after "in", a unit of one capital letter is that unit ("measured in K")
    let one = unit.len() == 1 && unit.starts_with(|c: char| c.is_ascii_uppercase());
    if one {
        return Unit::named(unit);
    }
    written_unit(unit)
}

/// A list's descriptions: "A, B and C" in three, or one for all.
fn list_items(desc: &str, n: usize) -> Option<Vec<String>> {
    let mut items: Vec<String> = Vec::new();
    for part in desc.split(',') {
        for p in part.split(" and ") {
            let p = p.trim();
            let p = p.strip_prefix("and ").unwrap_or(p).trim();
            if !p.is_empty() {
                items.push(p.to_string());
            }
        }
    }
    if n == 1 {
        return Some(vec![desc.trim().to_string()]);
    }
    match items.len() {
        k if k == n => Some(items),
        1 => Some(vec![items[0].clone(); n]),
        _ => None,
    }
}

/// The units a description gives `n` symbols (`written` overrides the vocabulary).
fn describe_all(
    desc: &str,
    n: usize,
    written: Option<Unit>,
    vocab: &Vocabulary,
) -> Vec<Option<Named>> {
    if let Some(u) = written
        && (n == 1
            || list_items(desc, n)
                .is_some_and(|v| v.len() == n && v.windows(2).all(|w| w[0] == w[1])))
    {
        return vec![
            Some(Named {
                unit: u,
                quantity: "written".into(),
                words: format!("{} [{u}]", desc.trim()),
            });
            n
        ];
    }
    let whole = vocab.describe(desc).filter(|h| h.plural);
    let Some(items) = list_items(desc, n) else {
        return vec![whole.and_then(|h| named(&h, desc)); n];
    };
    let each: Vec<Option<Named>> = items
        .iter()
        .map(|d| vocab.describe(d).and_then(|h| named(&h, desc)))
        .collect();
    // "the angular velocities before and after the impact": one plural for all, not a list
    match whole {
        Some(h) if n > 1 && each.iter().any(Option::is_none) => vec![named(&h, desc); n],
        _ => each,
    }
}

/// Whether a description's verb is in the singular (`$R$ and $J$ is its moment`: the
/// description is the last symbol's).
fn singular_verb(next: &str) -> bool {
    let t = next.trim_start().to_ascii_lowercase();
    [
        "is ",
        "denotes ",
        "stands for ",
        "represents ",
        "is called ",
    ]
    .iter()
    .any(|v| t.starts_with(v))
}

/// A nomenclature line: the symbol opens its line (or `\item[`, a table's `|`), a separator
/// follows, then its description and a unit in brackets or in a column of its own.
fn nomenclature(
    prev: &str,
    next: &str,
    n: usize,
    vocab: &Vocabulary,
) -> Option<Vec<Option<Named>>> {
    let before = prev.rsplit('\n').next().unwrap_or(prev).trim();
    if !(before.is_empty()
        || before.ends_with("\\item[")
        || before == "|"
        || before.ends_with("\\\\"))
    {
        return None;
    }
    let t = next.trim_start();
    let sep = [
        "&", ":", "]", "|", "---", "--", "—", "–", "\\quad", "\\qquad", "- ",
    ]
    .iter()
    .find(|s| t.starts_with(*s))?;
    let line = &t[sep.len()..];
    let line = line.split('\n').next().unwrap_or(line);
    let line = line.split("\\\\").next().unwrap_or(line);
    let mut cells = line
        .split(['&', '|'])
        .map(str::trim)
        .filter(|c| !c.is_empty());
    let desc_cell = cells.next()?;
    let (desc, mut unit) = clause(desc_cell, n);
    for c in cells {
        if unit.is_some() {
            break;
        }
        unit = written_unit(c.trim_matches(|c| "[]()".contains(c)));
    }
    Some(describe_all(desc, n, unit, vocab))
}

/// What the words of one paper give its symbols.
#[derive(Clone, Debug, Default)]
pub struct Words {
    /// Each symbol's unit with its source, by symbol.
    pub units: BTreeMap<String, WordUnit>,
    /// The symbols the words give two units (neither used), each naming both.
    pub notes: Vec<String>,
    /// The names the words call a Dirac delta ("$\delta(x - a/2)$ is the Dirac delta
    /// function").
    pub dirac: std::collections::BTreeSet<String>,
    /// The lines where the paper's sections open (`\section`, `\chapter`, a Markdown `#`,
    /// `##` or `###` heading).
    pub sections: Vec<usize>,
    /// The spans of lines `[from, to)` the paper says are dimensionless ([`dimensionless_spans`]).
    pub dimensionless: Vec<(usize, usize)>,
    /// The lines where numbered chapters open (`\chapter{..}`, not `\chapter*`).
    pub chapters: Vec<usize>,
}

/// The lines (1-based) where sections open.
pub fn section_starts(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, l)| {
            let t = l.trim_start();
            ["\\section", "\\chapter", "\\part{", "# ", "## ", "### "]
                .iter()
                .any(|h| t.starts_with(h))
        })
        .map(|(k, _)| k + 1)
        .collect()
}

/// The section (0 before the first heading) of a line.
pub fn section_of(sections: &[usize], line: usize) -> usize {
    sections.iter().filter(|&&s| s <= line).count()
}

/// Reads the prose of `text` (LaTeX or Markdown with `$..$`) for the units it gives its
/// symbols.
pub fn read_words(text: &str, syms: &TexSymbols, vocab: &Vocabulary) -> Words {
    let text = &written::nomenclature_rows(text);
    let p = prose(text);
    let its = items(&p);
    let line_of = |off: usize| p[..off].matches('\n').count() + 1;
    let text_at = |k: usize| match its.get(k) {
        Some((_, Item::Text(t))) => t.as_str(),
        _ => "",
    };
    let mut found: Vec<WordUnit> = Vec::new();
    let mut dirac = std::collections::BTreeSet::new();
    for (off, item) in &its {
        let Item::Text(t) = item else { continue };
        for (at, group, rest) in bare_lists(t) {
            let Some(after) = after_verb(rest) else {
                continue;
            };
            let n = group.len();
            let (desc, unit) = clause(after, n);
            let quote = collapse(&t[at..t.len() - after.len() + desc.len()]);
            for (tex, nm) in group.iter().zip(describe_all(desc, n, unit, vocab)) {
                let Some(nm) = nm else { continue };
                let key = in_where_clause(&p, off + at);
                found.extend(named_units(
                    tex,
                    syms,
                    false,
                    &nm,
                    &quote,
                    line_of(off + at),
                    key,
                ));
            }
        }
    }
    let mut i = 0;
    // whether the math before was described after a verb, so that a list may go on without one
    let mut listing = false;
    while i < its.len() {
        let (off, Item::Math(first)) = &its[i] else {
            i += 1;
            continue;
        };
        let mut group = split_commas(first);
        let mut spans = vec![first.clone()];
        let mut j = i + 1;
        while let (Some((_, Item::Text(t))), Some((_, Item::Math(m)))) =
            (its.get(j), its.get(j + 1))
        {
            if !is_joiner(t) || (t.trim() == "&" && group.len() == 1) {
                break;
            }
            group.extend(split_commas(m));
            spans.push(m.clone());
            j += 2;
        }
        let prev = if i > 0 { text_at(i - 1) } else { "" };
        let next = text_at(j);
        let n = group.len();
        let said = after_verb(next).map(|r| clause(r, n).0.to_ascii_lowercase());
        if said.is_some_and(|d| d.contains("dirac") || d.contains("delta function")) {
            for g in &group {
                let g = g.trim();
                if let Some(rest) = g.strip_prefix("\\delta")
                    && ["(", "\\left("]
                        .iter()
                        .any(|o| rest.trim_start().starts_with(o))
                {
                    dirac.insert("delta".to_string());
                }
            }
        }
        // a verb in the singular names the last symbol alone
        let alone = n > 1 && singular_verb(next);
        let quote_of = |words: &str| {
            let maths: Vec<String> = spans
                .iter()
                .skip(if alone { spans.len() - 1 } else { 0 })
                .map(|m| format!("${m}$"))
                .collect();
            collapse(&format!("{} {}", maths.join(", "), words))
        };
        let mut given: Vec<Option<(Named, String)>> = vec![None; n];
        let from_nomenclature = nomenclature(prev, next, n, vocab);
        let nomenclature_line = from_nomenclature.is_some();
        // after a verb; in a list that said its verb once ("where $E$ is the modulus, $R$ the
        // radius"); after "denote by"
        let from_next = from_nomenclature
            .or_else(|| after_verb(next).map(|rest| described(rest, n, vocab)))
            .or_else(|| elided(prev, next, listing).map(|d| described(d, n, vocab)))
            .or_else(|| denoted_by(prev).then(|| described(next, n, vocab)));
        listing = after_verb(next).is_some() || listing && elided(prev, next, true).is_some();
        // a verb in the singular describes the last symbol only
        let from_next = from_next.map(|mut v| {
            if n > 1 && singular_verb(next) {
                let last = v.pop().flatten();
                v = vec![None; n - 1];
                v.push(last);
            }
            v
        });
        if let Some(v) = from_next {
            for (g, named) in given.iter_mut().zip(v) {
                *g = named.map(|nm| {
                    let q = quote_of(&format!("{} {}", verb_of(next), nm.words));
                    (nm, q)
                });
            }
        }
        // "the time $t, m, n$ are odd numbers": the words before name the first symbol, the
        // description the others
        let one_for_all = given.len() > 1
            && given.iter().all(Option::is_some)
            && given
                .windows(2)
                .all(|w| w[0].as_ref().map(|g| g.0.unit) == w[1].as_ref().map(|g| g.0.unit));
        if one_for_all
            && let Some(hit) = vocab.before_symbol(clause_tail(prev))
            && hit.quantity.unit != given[0].as_ref().map(|g| g.0.unit)
        {
            given[0] = None;
        }
        if given.first().is_some_and(Option::is_none) {
            let tail = clause_tail(prev);
            let lower = tail.to_ascii_lowercase();
            let subject = [
                "is denoted by",
                "are denoted by",
                "denoted by",
                "is designated by",
            ]
            .iter()
            .find_map(|d| {
                lower
                    .trim_end()
                    .strip_suffix(d)
                    .map(|s| tail[..s.len()].to_string())
            });
            let named_before = match &subject {
                Some(s) => vocab.describe(s).map(|h| (h, true)),
                None => vocab.before_symbol(tail).map(|h| (h, false)),
            };
            if let Some((hit, subj)) = named_before {
                let all = subj || hit.plural;
                let named_spans: Vec<String> = spans
                    .iter()
                    .take(if all { spans.len() } else { 1 })
                    .map(|m| format!("${m}$"))
                    .collect();
                let quote = collapse(&format!("{} {}", tail.trim(), named_spans.join(" and ")));
                for (k, g) in given.iter_mut().enumerate() {
                    if (k == 0 || all) && g.is_none() {
                        *g = named(&hit, tail).map(|nm| (nm, quote.clone()));
                    }
                }
            }
        }
        for (tex, g) in group.iter().zip(given) {
            let Some((nm, quote)) = g else { continue };
            let head = nm.quantity.rsplit('_').next().unwrap_or_default();
            // a quantity specific by its name (the specific heat) is the one named
            let specific = nm.quantity.starts_with("specific");
            if !specific && dimensionless::specific_in_paragraph(&p, *off, head) {
                continue;
            }
            let key = in_where_clause(&p, *off) || nomenclature_line;
            found.extend(named_units(
                tex,
                syms,
                n == 1,
                &nm,
                &quote,
                line_of(*off),
                key,
            ));
        }
        i = j.max(i + 1);
    }
    found.extend(written_values(&its, &p, syms));
    let sections = section_starts(text);
    Words {
        dirac,
        dimensionless: dimensionless_spans(text, &sections),
        chapters: text
            .lines()
            .enumerate()
            .filter(|(_, l)| {
                let t = l.trim_start();
                t.starts_with("\\chapter{") || t.starts_with("\\chapter[")
            })
            .map(|(k, _)| k + 1)
            .collect(),
        sections,
        ..settle(found)
    }
}

/// The units of values written with their units for a symbol (`$E^* = \SI{115}{GPa}$`, `$L =
/// 2$ m`) in the prose `p` cut into `its`.
fn written_values(its: &[(usize, Item)], p: &str, syms: &TexSymbols) -> Vec<WordUnit> {
    let line_of = |off: usize| p[..off].matches('\n').count() + 1;
    let text_at = |k: usize| match its.get(k) {
        Some((_, Item::Text(t))) => t.as_str(),
        _ => "",
    };
    let mut found = Vec::new();
    for (k, (off, item)) in its.iter().enumerate() {
        let Item::Math(m) = item else { continue };
        let Some((lhs, unit)) = written::value_unit(m, text_at(k + 1)) else {
            continue;
        };
        let nm = Named {
            unit,
            quantity: "written".into(),
            words: String::new(),
        };
        // the words after the math quoted when they hold the unit
        let words_after = if written::value_unit(m, "").is_some() {
            ""
        } else {
            text_at(k + 1)
                .split(['.', ',', ';', '\n'])
                .next()
                .unwrap_or_default()
        };
        let quote = collapse(&format!("${m}$ {}", words_after.trim()));
        found.extend(named_units(
            lhs,
            syms,
            false,
            &nm,
            quote.trim(),
            line_of(*off),
            true,
        ));
    }
    found
}

/// What the words `d` say of the `n` symbols before them: each one's quantity and unit.
fn described(d: &str, n: usize, vocab: &Vocabulary) -> Vec<Option<Named>> {
    let (desc, unit) = clause(d, n);
    describe_all(desc, n, unit, vocab)
}

/// Whether the words before a symbol end in "denote by" (not "is denote by").
fn denoted_by(prev: &str) -> bool {
    let lower = prev.trim_end().to_ascii_lowercase();
    ["denote by", "denoting by", "designate by"]
        .iter()
        .any(|d| lower.ends_with(d) && !lower.ends_with(&format!("is {d}")))
}

/// The description of a symbol in a list whose verb was said once ("where $E$ is the modulus,
/// $R$ the radius and $m$ the mass"): after a comma, "and" or a semicolon, while `listing`,
/// the words from a determiner to the next comma or "and".
fn elided<'a>(prev: &str, next: &'a str, listing: bool) -> Option<&'a str> {
    let p = prev.trim_end();
    let joined = [",", ";", " and"].iter().any(|j| p.ends_with(j)) || p.trim() == "and";
    let t = next.trim_start();
    let det = ["the ", "a ", "an ", "its "]
        .iter()
        .any(|d| t.starts_with(d));
    if !(listing && joined && det) {
        return None;
    }
    let end = [t.find(','), t.find(" and "), t.find(" and\n")]
        .into_iter()
        .flatten()
        .min()
        .unwrap_or(t.len());
    Some(&t[..end])
}

/// The verb a description opens with, as written (`is`, `are, respectively,`), for the quote.
fn verb_of(next: &str) -> String {
    let t = next.trim_start();
    match after_verb(t) {
        Some(rest) => t[..t.len() - rest.len()].trim().to_string(),
        None => String::new(),
    }
}

/// The words after the last clause break of `text` ("where the mass" of "..., where the mass").
fn clause_tail(text: &str) -> &str {
    let cut = text
        .rfind([
            ',',
            ';',
            '.',
            ':',
            '(',
            ')',
            '&',
            '|',
            '[',
            ']',
            '{',
            '}',
            DISPLAY_MARK,
        ])
        .map_or(0, |k| {
            k + text[k..].chars().next().map_or(1, char::len_utf8)
        });
    let tail = &text[cut..];
    let tail = match tail.rfind("\n\n") {
        Some(k) => &tail[k + 2..],
        None => tail,
    };
    // a row of a table or a nomenclature ends at `\\`: the words of the row before name
    // nothing of this one ("Fluid temperature\\ $\gamma$ & Specific heat ratio")
    match tail.rfind("\\\\") {
        Some(k) => &tail[k + 2..],
        None => tail,
    }
}

/// Whitespace collapsed; at most 160 characters.
fn collapse(text: &str) -> String {
    let t = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if t.chars().count() > 160 {
        format!("{}...", t.chars().take(157).collect::<String>())
    } else {
        t
    }
}

/// One unit per symbol: the first source of each; a symbol given two units gets none.
fn settle(found: Vec<WordUnit>) -> Words {
    let mut w = Words::default();
    let mut conflicted: BTreeMap<String, Vec<WordUnit>> = BTreeMap::new();
    for f in found {
        if let Some(c) = conflicted.get_mut(&f.symbol) {
            c.push(f);
            continue;
        }
        match w.units.get(&f.symbol) {
            None => {
                w.units.insert(f.symbol.clone(), f);
            }
            Some(old) if old.unit == f.unit => {}
            Some(_) => {
                let old = w
                    .units
                    .remove(&f.symbol)
                    .into_iter()
                    .chain([f.clone()])
                    .collect();
                conflicted.insert(f.symbol.clone(), old);
            }
        }
    }
    for (symbol, all) in conflicted {
        let each: Vec<String> = all
            .iter()
            .map(|u| format!("{} ({})", u.unit, u.source()))
            .collect();
        w.notes.push(format!(
            "the words give `{symbol}` more than one unit, so none is used: {}",
            each.join("; ")
        ));
    }
    w
}

#[cfg(test)]
mod tests;
