//! Displays: the environments a display wraps its rows in, rows split at `\\`, continued
//! rows joined, `\tag{}` taken out as the row's number, and each row's relations read.

use super::{TexRow, TexSymbols, read_relation};

/// The environments a display may wrap its rows in: their `\begin{..}`/`\end{..}` are dropped.
pub(super) const ENVIRONMENTS: &[&str] = &[
    "equation",
    "equation*",
    "align",
    "align*",
    "aligned",
    "gather",
    "gather*",
    "gathered",
    "split",
    "multline",
    "multline*",
];

/// Splits `text` at the top level (outside braces and parentheses) at each of `seps`.
pub(crate) fn split_top(text: &str, seps: &[&str]) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let (mut depth, mut out, mut cur) = (0i32, Vec::new(), String::new());
    let mut i = 0;
    'next: while i < chars.len() {
        let c = chars[i];
        // an escaped brace, and the spacing commands `\,` `\;` (not the separators , ;)
        if c == '\\' && i + 1 < chars.len() && matches!(chars[i + 1], '{' | '}' | ',' | ';') {
            cur.push(c);
            cur.push(chars[i + 1]);
            i += 2;
            continue;
        }
        let word = |w: &str| {
            let w: Vec<char> = w.chars().collect();
            chars[i..].starts_with(&w)
                && !chars
                    .get(i + w.len())
                    .is_some_and(char::is_ascii_alphabetic)
        };
        // \left\{ ... \right\} nest like the brackets they size
        if word("\\left") {
            depth += 1;
        } else if word("\\right") {
            depth -= 1;
        }
        match c {
            '{' | '(' | '[' => depth += 1,
            '}' | ')' | ']' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            for sep in seps {
                let sp: Vec<char> = sep.chars().collect();
                let word_end = sep.starts_with('\\')
                    && chars
                        .get(i + sp.len())
                        .is_some_and(char::is_ascii_alphabetic);
                if chars[i..].starts_with(&sp) && !word_end {
                    out.push(std::mem::take(&mut cur));
                    i += sp.len();
                    continue 'next;
                }
            }
        }
        cur.push(c);
        i += 1;
    }
    out.push(cur);
    out
}

/// The rows of a display (`$$ ... $$` without the dollars): environments dropped, rows split
/// at `\\`, alignment `&` removed, a row that starts with `+`, `-` or `=` joined to the one
/// before, `\tag{}` taken out, and each row's relations (separated by `,`, `;` or `\quad` at
/// the top level) read.
pub fn read_display(block: &str, syms: &TexSymbols) -> Vec<TexRow> {
    let mut text = block.to_string();
    // rows of an array or of cases, often braced by \left\{ ... \right.: the brace and the
    // column specification go
    if text.contains("\\begin{array}") || text.contains("\\begin{cases}") {
        for (open, close) in [
            ("\\begin{array}", "\\end{array}"),
            ("\\begin{cases}", "\\end{cases}"),
        ] {
            while let Some(at) = text.find(open) {
                let mut end = at + open.len();
                if text[end..].starts_with('{') {
                    end += text[end..].find('}').map_or(0, |k| k + 1);
                }
                text.replace_range(at..end, " ");
            }
            text = text.replace(close, " ");
        }
        for brace in ["\\left\\{", "\\right.", "\\left.", "\\right\\}"] {
            text = text.replace(brace, " ");
        }
    }
    for env in ENVIRONMENTS {
        text = text.replace(&format!("\\begin{{{env}}}"), " ");
        text = text.replace(&format!("\\end{{{env}}}"), " ");
    }
    let mut rows: Vec<String> = Vec::new();
    for raw in split_top(&text, &["\\\\"]) {
        let row = raw.replace('&', " ");
        let t = row.trim_start();
        let continues = t.starts_with('+') || t.starts_with('-') || t.starts_with('=');
        match rows.last_mut() {
            // a row that continues a relation joins it, also when the tag was printed on the
            // row before (a long relation tagged on its middle row, 000's (22)); the tag then
            // moves to the end of the joined row
            Some(prev) if continues && (!prev.contains("\\tag") || !starts_relation(&row)) => {
                let (body, tag) = take_tag(prev);
                *prev = format!("{body} {row}");
                if let Some(tag) = tag {
                    prev.push_str(&format!(" \\tag{{{tag}}}"));
                }
            }
            _ => rows.push(row),
        }
    }
    rows.into_iter()
        .filter(|r| !r.trim().is_empty())
        .map(|row| {
            let (tex, tag) = take_tag(&row);
            let relations = split_top(&tex, &[";", ",", "\\quad", "\\qquad"])
                .into_iter()
                .map(|p| p.trim().trim_end_matches('.').to_string())
                .filter(|p| !p.is_empty())
                .map(|p| read_relation(&p, syms))
                .collect();
            TexRow {
                tag,
                tex: tex.trim().to_string(),
                relations,
            }
        })
        .collect()
}

/// Whether a row that starts with `-` or `+` is a relation of its own (`-a = b`) rather than the
/// continuation of the row before (a relation sign at the top level).
pub(super) fn starts_relation(row: &str) -> bool {
    split_top(row, &["=", "\\le", "\\ge", "<", ">", "\\approx"]).len() > 1
}

/// The row without its `\tag{...}`, and the tag.
pub(super) fn take_tag(row: &str) -> (String, Option<String>) {
    match row.find("\\tag{") {
        Some(at) => {
            let rest = &row[at + 5..];
            match rest.find('}') {
                Some(end) => (
                    format!("{}{}", &row[..at], &rest[end + 1..]),
                    Some(rest[..end].trim().to_string()),
                ),
                None => (row.to_string(), None),
            }
        }
        None => (row.to_string(), None),
    }
}
