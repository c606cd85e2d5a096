//! Displays: the environments a display wraps its rows in, rows split at `\\`, continued
//! rows joined, `\tag{}` taken out as the row's number, and each row's relations read.

use crate::algebra::expr::Expr;
use crate::paper::formulas::{TexRow, TexSymbols, read_relation};

/// The environments a display may wrap its rows in: their `\begin{..}`/`\end{..}` are dropped
/// (with the column count of `alignat`, `alignedat` and the position of `aligned`).
pub(crate) const ENVIRONMENTS: &[&str] = &[
    "equation",
    "equation*",
    "align",
    "align*",
    "aligned",
    "alignat",
    "alignat*",
    "alignedat",
    "flalign",
    "flalign*",
    "gather",
    "gather*",
    "gathered",
    "split",
    "multline",
    "multline*",
    "eqnarray",
    "eqnarray*",
    "subequations",
    "displaymath",
    "math",
    "dmath",
    "dmath*",
];

/// `text` without the `\begin{..}` and `\end{..}` of [`ENVIRONMENTS`] (and their arguments).
pub(crate) fn drop_environments(text: &str) -> String {
    let mut text = text.to_string();
    for env in ENVIRONMENTS {
        let open = format!("\\begin{{{env}}}");
        while let Some(at) = text.find(&open) {
            let mut end = at + open.len();
            // `{2}` of alignat, `[t]` of aligned (a `[m] = M` that starts a `gather` is its
            // first row)
            let rest = &text[end..];
            let arg = rest.trim_start();
            let close = match arg.chars().next() {
                // (only alignat's column count: `{{F}_{n}} = ..` opening an align is its row)
                Some('{')
                    if env.starts_with("align")
                        && arg.find('}').is_some_and(|k| {
                            k > 1 && arg[1..k].trim().chars().all(|c| c.is_ascii_digit())
                        }) =>
                {
                    arg.find('}')
                }
                Some('[') if ["[t]", "[b]", "[c]"].iter().any(|p| arg.starts_with(p)) => Some(2),
                _ => None,
            };
            if let Some(k) = close {
                end += rest.len() - arg.len() + k + 1;
            }
            text.replace_range(at..end, " ");
        }
        text = text.replace(&format!("\\end{{{env}}}"), " ");
    }
    text
}

/// The rows of `text` split at `\\` at the top level, without the space (`\\[2mm]`) or
/// the `*` that may follow a row's end.
pub(crate) fn rows_of(text: &str) -> Vec<String> {
    let mut rows = split_top(text, &["\\\\"]);
    for row in rows.iter_mut().skip(1) {
        let t = row.trim_start();
        let t = t.strip_prefix('*').unwrap_or(t).trim_start();
        let t = match t.strip_prefix('[') {
            Some(rest) => match rest.find(']') {
                Some(k) if is_length(&rest[..k]) => &rest[k + 1..],
                _ => t,
            },
            None => t,
        };
        *row = t.to_string();
    }
    rows
}

/// Whether `s` is a TeX length (`2mm`, `-1.5ex`, `3pt`).
fn is_length(s: &str) -> bool {
    let s = s.trim().trim_start_matches('-');
    let unit = s.trim_start_matches(|c: char| c.is_ascii_digit() || c == '.');
    unit.len() < s.len()
        && [
            "pt", "mm", "cm", "in", "ex", "em", "bp", "pc", "dd", "cc", "sp", "mu",
        ]
        .contains(&unit.trim())
}

/// A row's text with what only aligns or spaces it taken from its start (`&`, `\quad`, `\;`,
/// `\hspace{..}`, `{}`), to see how it starts.
pub(crate) fn lead(row: &str) -> &str {
    let mut t = row.trim_start();
    loop {
        let before = t;
        for w in [
            "&",
            "{}",
            "\\quad",
            "\\qquad",
            "\\;",
            "\\,",
            "\\:",
            "\\!",
            "\\ ",
            "~",
            "\\displaystyle",
            "\\nonumber",
            "\\notag",
        ] {
            if let Some(rest) = t.strip_prefix(w)
                && !(w.ends_with(|c: char| c.is_ascii_alphabetic())
                    && rest.starts_with(|c: char| c.is_ascii_alphabetic()))
            {
                t = rest.trim_start();
            }
        }
        for w in ["\\hspace", "\\hskip", "\\phantom", "\\hphantom"] {
            if let Some(rest) = t.strip_prefix(w) {
                let rest = rest.trim_start().strip_prefix('*').unwrap_or(rest);
                if let Some(r) = rest.trim_start().strip_prefix('{')
                    && let Some(k) = r.find('}')
                {
                    t = r[k + 1..].trim_start();
                }
            }
        }
        if t == before {
            return t;
        }
    }
}

/// The operators a continuation row starts with.
const LEADING_OPERATORS: &[&str] = &[
    "+", "-", "=", "<", ">", "\\cdot", "\\times", "\\le", "\\ge", "\\leq", "\\geq", "\\approx",
    "\\equiv", "\\pm", "\\mp", "\\simeq", "\\ne", "\\neq", "\\ll", "\\gg", "\\propto", "\\sim",
];

/// Whether `row` continues the relation of the row before it: it starts (past its alignment
/// and spacing) with an operator or a relation sign.
pub(crate) fn continues(row: &str) -> bool {
    let t = lead(row);
    LEADING_OPERATORS.iter().any(|op| {
        t.starts_with(op)
            && !(op.ends_with(|c: char| c.is_ascii_alphabetic())
                && t[op.len()..].starts_with(|c: char| c.is_ascii_alphabetic()))
    })
}

/// Whether a row ends with an operator or a relation sign (`\vec\omega \times`, `a + b +`,
/// `y =`), so that the next row continues it.
pub(crate) fn ends_open(row: &str) -> bool {
    let mut t = row.trim_end();
    loop {
        let before = t;
        for w in [
            "\\nonumber",
            "\\notag",
            "&",
            "\\quad",
            "\\qquad",
            "\\;",
            "\\,",
        ] {
            t = t.strip_suffix(w).unwrap_or(t).trim_end();
        }
        if t == before {
            break;
        }
    }
    let sign = ["+", "-", "=", "\\times", "\\cdot", "\\pm", "\\mp"]
        .iter()
        .find(|s| t.ends_with(*s));
    // `v^-`, `x_+`: a label, not an open operator
    sign.is_some_and(|s| !t[..t.len() - s.len()].ends_with(['^', '_']))
}

/// Splits `text` at the top level (outside braces and parentheses) at each of `seps`.
pub(crate) fn split_top(text: &str, seps: &[&str]) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let (mut depth, mut out, mut cur) = (0i32, Vec::new(), String::new());
    // the depth at which a `\text{..}` opened, while inside it
    let mut in_text: Option<i32> = None;
    let mut i = 0;
    'next: while i < chars.len() {
        let c = chars[i];
        // a row break `\\` is no escape of what follows it (`\\{\hat u}^r = ..`)
        if c == '\\' && chars.get(i + 1) == Some(&'\\') && (depth != 0 || !seps.contains(&"\\\\")) {
            cur.push_str("\\\\");
            i += 2;
            continue;
        }
        // an escaped brace, and the spacing commands `\,` `\;` (not the separators , ;)
        if c == '\\' && i + 1 < chars.len() && matches!(chars[i + 1], '{' | '}' | ',' | ';') {
            // a bare `\{ .. \}` (a set, `\max\{0, x\}`) nests; after `\left`, `\right` or a
            // size the command counted already
            let sized = [
                "left", "right", "bigl", "bigr", "Bigl", "Bigr", "big", "Big", "bigg", "Bigg",
            ]
            .iter()
            .any(|w| cur.trim_end().ends_with(&format!("\\{w}")));
            if !sized {
                match chars[i + 1] {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    _ => {}
                }
            }
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
        // \left\{ ... \right\} nest like the brackets they size, and an environment like
        // braces (the rows of a `cases` inside an `align` are not the align's)
        // (and `\langle f, g \rangle`, an inner product or a mean, unless sized by `\left`)
        let sized_angle = cur.trim_end().ends_with("\\left") || cur.trim_end().ends_with("\\right");
        if word("\\left") || word("\\begin") || (word("\\langle") && !sized_angle) {
            depth += 1;
        } else if word("\\right") || word("\\end") || (word("\\rangle") && !sized_angle) {
            depth -= 1;
        }
        // the words of a `\text{ a) }` are no brackets: only its braces count
        if in_text.is_none()
            && ["\\text", "\\mbox", "\\textrm", "\\textit", "\\textbf"]
                .iter()
                .any(|w| word(w))
        {
            in_text = Some(depth);
        }
        match c {
            '{' | '}' if in_text.is_some() => {
                depth += if c == '{' { 1 } else { -1 };
                if c == '}' && in_text == Some(depth) {
                    in_text = None;
                }
            }
            '(' | ')' | '[' | ']' if in_text.is_some_and(|d| depth > d) => {}
            '{' | '(' | '[' => depth += 1,
            '}' | ')' | ']' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            for sep in seps {
                let sp: Vec<char> = sep.chars().collect();
                // `\quad` is not the start of `\quadx`; `\\` ends a row whatever follows
                let word_end = sep.ends_with(|c: char| c.is_ascii_alphabetic())
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
/// at `\\`, alignment `&` removed, a row that continues a relation ([`continues`]) joined to the
/// one before, `\tag{}` taken out, and each row's relations read: separated by `,`, `;`,
/// `\quad`, `\Rightarrow` or a connecting word (`\text{if}`, `\text{and}`) at the top level; a
/// `cases` made one row of its values and conditions ([`cases_row`]); a relation with `\pm`
/// read as its two branches.
pub fn read_display(block: &str, syms: &TexSymbols) -> Vec<TexRow> {
    // a `$` inside a display (`\colorbox{..}{$\displaystyle ..$}`) only switches modes
    let mut text = drop_styling(&drop_phantoms(&brace_notes_dropped(block))).replace('$', " ");
    // rows of an array, often braced by \left\{ ... \right.: the brace and the column
    // specification go
    if text.contains("\\begin{array}") {
        while let Some(at) = text.find("\\begin{array}") {
            let mut end = at + "\\begin{array}".len();
            if text[end..].starts_with('{') {
                end += text[end..].find('}').map_or(0, |k| k + 1);
            }
            text.replace_range(at..end, " ");
        }
        text = text.replace("\\end{array}", " ");
        for brace in ["\\left\\{", "\\right.", "\\left.", "\\right\\}"] {
            text = text.replace(brace, " ");
        }
    }
    let text = drop_environments(&text);
    let mut rows: Vec<String> = Vec::new();
    for raw in rows_of(&text) {
        // `&&` opens a new pair of columns: `u_2 = .. && \delta = ..` are two relations
        let row = empty_columns_apart(&cases_row(&raw)).replace('&', " ");
        // an empty row (`\\\\` twice) is no relation for the next row to continue
        if row.trim().is_empty() {
            continue;
        }
        match rows.last_mut() {
            // a row that continues a relation joins it, also when the tag was printed on the
            // row before (a long relation tagged on its middle row, 000's (22)); the tag then
            // moves to the end of the joined row
            Some(prev)
                if (continues(&row) || ends_open(prev))
                    && (!prev.contains("\\tag") || !starts_relation(&row)) =>
            {
                let (body, tag) = take_tag(prev);
                *prev = format!("{}\n{}", body.trim_end(), lead(&row));
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
            let relations = split_top(&words_as_separators(&tex), RELATION_SEPARATORS)
                .into_iter()
                // a relation left open by a word (`E = T + V = \text{const}`) ends before it
                // and one that ends in a colon (`x(0) = 0 : \quad v = a t`) before it
                .map(|p| {
                    p.trim()
                        .trim_end_matches('.')
                        .trim()
                        .trim_end_matches('=')
                        .trim()
                        .trim_end_matches(':')
                        .trim()
                        .to_string()
                })
                .filter(|p| !blank(p))
                .flat_map(|p| colon_split(&p))
                .flat_map(|p| condition_apart(&p))
                .flat_map(|p| unwrap_condition(&p))
                .flat_map(|p| branches(&p))
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

/// Whether a piece of a row holds nothing but spacing and punctuation (`\,` after the last
/// comma of `\hat{u} = u/U,\,`): no relation.
fn blank(piece: &str) -> bool {
    let mut rest = piece.to_string();
    for space in ["\\qquad", "\\quad", "\\,", "\\;", "\\:", "\\!", "\\ ", "~"] {
        rest = rest.replace(space, "");
    }
    rest.chars().all(|c| c.is_whitespace() || ",.;".contains(c))
}

/// What separates the relations of a row at its top level.
/// `row` with each `&&` (two alignment tabs with only spaces between: an empty column, so
/// that what follows starts a new pair of columns) made a `\quad`, which parts relations.
fn empty_columns_apart(row: &str) -> String {
    let mut out = String::with_capacity(row.len());
    let mut rest = row;
    while let Some(k) = rest.find('&') {
        let after = rest[k + 1..].trim_start();
        let escaped = rest[..k].ends_with('\\');
        out.push_str(&rest[..k]);
        if !escaped && after.starts_with('&') {
            out.push_str(" \\quad ");
            rest = &after[1..];
        } else {
            out.push('&');
            rest = &rest[k + 1..];
        }
    }
    out.push_str(rest);
    out
}

const RELATION_SEPARATORS: &[&str] = &[
    ";",
    ",",
    "\\quad",
    "\\qquad",
    "\\Rightarrow",
    "\\Longrightarrow",
    "\\Leftrightarrow",
    "\\Longleftrightarrow",
    "\\implies",
    "\\iff",
    "\\therefore",
    "\\forall",
    "\\mapsto",
    "\\longmapsto",
    "\\leftarrow",
    "\\Leftarrow",
    "\\lor",
    "\\land",
    "=>",
];

/// The words that join relations in a row of math (`\text{if}`, `\mbox{for all}`,
/// `\text{and}`): a `\text{..}` at the top level that starts with one is a separator.
const CONNECTIVES: &[&str] = &[
    "if",
    "for",
    "when",
    "whenever",
    "where",
    "with",
    "and",
    "or",
    "otherwise",
    "else",
    "elsewhere",
    "as",
    "since",
    "so",
    "then",
    "at",
    "on",
    "in",
    "is",
    "are",
    "all",
    "any",
    "each",
    "every",
    "provided",
    "such",
    "that",
    "hence",
    "thus",
    "but",
    "i.e.",
    "e.g.",
    "from",
    "to",
    "by",
    "we",
    "which",
    "while",
    "until",
    "after",
    "before",
    "during",
    "giving",
    "gives",
    "yields",
    "implies",
    "whence",
    "because",
    "unless",
];

/// `tex` with each `\text{..}` (`\mbox`, `\textrm`, `\textnormal`, `\textit`, `\mathrm`) of
/// connecting words at the top level replaced by `;`.
pub(crate) fn words_as_separators(tex: &str) -> String {
    let mut out = tex.to_string();
    for cmd in [
        "\\text",
        "\\mbox",
        "\\textrm",
        "\\textnormal",
        "\\textit",
        "\\textbf",
        "\\texttt",
        "\\textsf",
        "\\emph",
        "\\mathrm",
    ] {
        let mut from = 0;
        while let Some(k) = out[from..].find(cmd) {
            let at = from + k;
            let after = at + cmd.len();
            from = after;
            let rest = &out[after..];
            let open = after + (rest.len() - rest.trim_start().len());
            if !rest.trim_start().starts_with('{') {
                continue;
            }
            // the whole group, nested groups and `$..$` in it (`\text{Order $\hbar^0$:}`)
            let Some((inner, end)) = super::macros::group(&out, open) else {
                continue;
            };
            // a name in nested styles (`\textit{\textbf{F}}`, as math in text fonts) is a name
            let words = unstyled(inner.trim()).to_lowercase();
            // words of any language but English (`\text{常数}`) are words too, and so is a
            // phrase with punctuation, a formula or a command in it (`\text{ --- \textbf{..}}`,
            // `\textrm{Equilibrium Equations:}`); a name in words (`\text{err}`,
            // `\text{kinetic energy}`) is none
            let foreign = words.chars().any(|c| c.is_alphabetic() && !c.is_ascii())
                || words.contains(['$', ':', '\\', '!', '?', ';', '(', ')'])
                || words.contains("--");
            let first = words
                .split(|c: char| c.is_whitespace() || c == ',' || c == '~')
                .find(|w| !w.is_empty())
                .unwrap_or("");
            // a script's text is a label (`R_\text{\underline{b}b}`), never words between
            // relations
            let script = out[..at].trim_end().ends_with(['_', '^']);
            if depth_at(&out, at) == 0
                && !script
                && (words.is_empty() || foreign || CONNECTIVES.contains(&first))
            {
                out.replace_range(at..end, " ; ");
                from = at + 3;
            }
        }
    }
    out
}

/// `inner` without the font commands around a name in it (`\textbf{F}` is `F`), when what is
/// left is one name of letters and digits or one Greek letter (`\textbf{\tau}`); `inner`
/// itself otherwise.
fn unstyled(inner: &str) -> &str {
    const FONTS: [&str; 8] = [
        "\\textbf",
        "\\textit",
        "\\textrm",
        "\\textsf",
        "\\mathbf",
        "\\mathit",
        "\\mathrm",
        "\\boldsymbol",
    ];
    let mut s = inner.trim();
    while let Some(f) = FONTS.iter().find(|f| s.starts_with(**f)) {
        let rest = s[f.len()..].trim_start();
        match rest.strip_prefix('{').and_then(|r| r.strip_suffix('}')) {
            Some(body) if !body.contains(['{', '}']) || body.starts_with('\\') => s = body.trim(),
            _ => return inner,
        }
    }
    // a Greek letter: its name, as the words of a name would be
    if let Some(g) = s.strip_prefix('\\')
        && super::packages::GREEK.contains(&g)
    {
        return g;
    }
    if s.chars().all(|c| c.is_ascii_alphanumeric()) && !s.is_empty() {
        s
    } else {
        inner
    }
}

/// A piece split at its top-level colons when each part holds a relation (`y(x_1) = 0:
/// \text{err} \sim A`); a colon between formulas (`\sigma : \nabla v`, a double contraction),
/// `:=`, `=:` and the space `\:` stay.
fn colon_split(piece: &str) -> Vec<String> {
    const MASKS: [(&str, &str); 3] = [("\\:", "\u{1}"), (":=", "\u{2}"), ("=:", "\u{3}")];
    if !piece.contains(':') {
        return vec![piece.to_string()];
    }
    let mut masked = piece.to_string();
    for (from, to) in MASKS {
        masked = masked.replace(from, to);
    }
    let parts = split_top(&masked, &[":"]);
    let relation = |p: &str| {
        p.contains(['=', '<', '>', '\u{2}', '\u{3}'])
            || [
                "\\le",
                "\\ge",
                "\\sim",
                "\\approx",
                "\\equiv",
                "\\propto",
                "\\ne",
                "\\to",
                "\\rightarrow",
            ]
            .iter()
            .any(|r| p.contains(r))
    };
    if parts.len() < 2 || !parts.iter().all(|p| relation(p)) {
        return vec![piece.to_string()];
    }
    parts
        .into_iter()
        .map(|p| {
            let mut p = p;
            for (from, to) in MASKS {
                p = p.replace(to, from);
            }
            p
        })
        .collect()
}

/// `tex` without the commands that only colour, box or space what they hold: `\hspace{..}`,
/// `\vspace{..}`, `\color{..}`, `\cellcolor{..}`, `\mathstrut`, `\qedhere` go; `\colorbox{c}{x}`,
/// `\textcolor{c}{x}`, `\smash{x}`, `\ensuremath{x}`, `\boxed{x}` leave `{x}`.
fn drop_styling(tex: &str) -> String {
    // (command, groups dropped with it)
    const STYLING: &[(&str, usize)] = &[
        ("\\hspace*", 1),
        ("\\hspace", 1),
        ("\\vspace*", 1),
        ("\\vspace", 1),
        ("\\color", 1),
        ("\\cellcolor", 1),
        ("\\rowcolor", 1),
        ("\\colorbox", 1),
        ("\\textcolor", 1),
        ("\\mathstrut", 0),
        ("\\qedhere", 0),
        ("\\smash", 0),
        ("\\ensuremath", 0),
        ("\\boxed", 0),
        ("\\cancel", 0),
        ("\\bcancel", 0),
        ("\\xcancel", 0),
    ];
    let mut out = tex.to_string();
    for (cmd, groups) in STYLING {
        let mut from = 0;
        while let Some(k) = out[from..].find(cmd) {
            let at = from + k;
            let mut end = at + cmd.len();
            if out[end..].starts_with(|c: char| c.is_ascii_alphabetic()) {
                from = end;
                continue;
            }
            for _ in 0..*groups {
                match super::macros::group(&out, end) {
                    Some((_, e)) => end = e,
                    None => break,
                }
            }
            out.replace_range(at..end, " ");
            from = at;
        }
    }
    out
}

/// `tex` with each `\underbrace{X}_{note}` and `\overbrace{X}^{note}` the group `{X}` (or `X`
/// when it opens with a sign): the note is words about the term (`\text{Coriolis}`), which must
/// not part the row as words do.
fn brace_notes_dropped(tex: &str) -> String {
    let mut out = tex.to_string();
    for (cmd, mark) in [("\\underbrace", '_'), ("\\overbrace", '^')] {
        let mut from = 0;
        while let Some(k) = out[from..].find(cmd) {
            let at = from + k;
            let after = at + cmd.len();
            let Some((body, end)) = super::macros::group(&out, after) else {
                from = after;
                continue;
            };
            let rest = out[end..].trim_start();
            let mut stop = end;
            if let Some(note) = rest.strip_prefix(mark) {
                let note_at = out.len() - note.len();
                stop = match super::macros::group(&out, note_at) {
                    Some((_, e)) => e,
                    // `_x`: one character
                    None => note_at + note.chars().next().map_or(0, char::len_utf8),
                };
            }
            // a term that opens with its sign (`k \underbrace{-m\Omega^2}_{..}`) is added, as
            // printed; any other stays one factor
            let signed = body.trim_start().starts_with(['-', '+']);
            let term = if signed {
                format!(" {body} ")
            } else {
                format!("{{{body}}}")
            };
            out.replace_range(at..stop, &term);
            from = at + 1;
        }
    }
    out
}

/// `tex` without `\phantom{..}`, `\hphantom{..}`, `\vphantom{..}` (space only).
fn drop_phantoms(tex: &str) -> String {
    let mut out = tex.to_string();
    for cmd in ["\\phantom{", "\\hphantom{", "\\vphantom{"] {
        while let Some(at) = out.find(cmd) {
            // the group as the macro expander reads one; unclosed, the rest goes
            let end = super::macros::group(&out, at + cmd.len() - 1).map_or(out.len(), |(_, e)| e);
            out.replace_range(at..end, " ");
        }
    }
    out
}

/// A piece that ends in a condition in parentheses set apart by a space (`\dot q_\alpha =
/// \partial H / \partial p_\alpha (\alpha = 1,2,\cdots,s)`): the relation and the condition, two
/// pieces; `\dot x(t=0)`, a value at a point, stays.
fn condition_apart(piece: &str) -> Vec<String> {
    let t = piece.trim_end();
    if !t.ends_with(')') {
        return vec![piece.to_string()];
    }
    // the `(` that the last `)` closes
    let mut depth = 0i32;
    let mut open = None;
    for (i, c) in t.char_indices().rev() {
        match c {
            ')' | ']' | '}' => depth += 1,
            '(' | '[' | '{' => {
                depth -= 1;
                if depth == 0 {
                    open = Some(i);
                    break;
                }
            }
            _ => {}
        }
    }
    let Some(at) = open else {
        return vec![piece.to_string()];
    };
    let before = &t[..at];
    let spaced =
        before.ends_with([' ', '\t', '~']) || before.ends_with("\\,") || before.ends_with("\\;");
    let cond = &t[at..];
    if at == 0
        || !spaced
        || !t[at..].starts_with('(')
        || !starts_relation(&cond[1..cond.len() - 1])
        || !starts_relation(before)
    {
        return vec![piece.to_string()];
    }
    vec![before.to_string(), cond.to_string()]
}

/// A relation written in parentheses after another (`\quad (i = 1, 2, \ldots, n)`, `(M \gg
/// m)`): a condition, read without its parentheses (and split at its commas); any other piece
/// as it is.
fn unwrap_condition(piece: &str) -> Vec<String> {
    let mut t = piece.trim();
    // spacing before the parenthesis (`\,\, (\alpha = 1, .., s)`)
    while let Some(rest) = ["\\,", "\\;", "\\quad", "\\qquad", "~", "\\ "]
        .iter()
        .find_map(|sp| t.strip_prefix(sp))
    {
        t = rest.trim_start();
    }
    let inner = if let Some(i) = t.strip_prefix('(').and_then(|r| r.strip_suffix(')')) {
        i
    } else if let Some(i) = t.strip_prefix("\\left(").and_then(|r| {
        r.strip_suffix(")")
            .and_then(|r| r.trim_end().strip_suffix("\\right"))
    }) {
        i
    } else {
        return vec![piece.to_string()];
    };
    // the parentheses enclose the whole piece, and a relation stands inside them
    let mut depth = 0i32;
    let mut prev = ' ';
    let mut balanced = true;
    for c in inner.chars() {
        match c {
            '{' | '(' | '[' if prev != '\\' => depth += 1,
            '}' | ')' | ']' if prev != '\\' => depth -= 1,
            _ => {}
        }
        balanced &= depth >= 0;
        prev = c;
    }
    if !balanced || depth != 0 || !starts_relation(inner) {
        return vec![piece.to_string()];
    }
    split_top(inner, &[","])
        .into_iter()
        .map(|p| p.trim().to_string())
        .filter(|p| !p.is_empty())
        .collect()
}

/// How deep in braces and brackets byte `at` of `text` is.
fn depth_at(text: &str, at: usize) -> i32 {
    let mut depth = 0;
    let mut prev = ' ';
    for c in text[..at].chars() {
        match c {
            '{' | '(' | '[' if prev != '\\' => depth += 1,
            '}' | ')' | ']' if prev != '\\' => depth -= 1,
            _ => {}
        }
        prev = c;
    }
    depth
}

/// A relation with `\pm` or `\mp` as its two branches (`\pm` as `+` then `-`, `\mp` the other
/// way); any other relation as it is.
fn branches(rel: &str) -> Vec<String> {
    if !rel.contains("\\pm") && !rel.contains("\\mp") {
        return vec![rel.to_string()];
    }
    let swap = |first: &str, second: &str| {
        let mut out = String::new();
        let mut rest = rel;
        while let Some(k) = rest.find('\\') {
            out.push_str(&rest[..k]);
            let word: String = rest[k + 1..]
                .chars()
                .take_while(char::is_ascii_alphabetic)
                .collect();
            match word.as_str() {
                "pm" => out.push_str(first),
                "mp" => out.push_str(second),
                _ => {
                    out.push('\\');
                    out.push_str(&word);
                }
            }
            rest = &rest[k + 1 + word.len()..];
        }
        out.push_str(rest);
        out
    };
    vec![swap(" + ", " - "), swap(" - ", " + ")]
}

/// A row with a `cases` (`f = \begin{cases} a & x > 0 \\ b & x \le 0 \end{cases}`) as one
/// row of its relations: each value with what stands before and after the `cases` (`f = a`,
/// `f = b`), each condition a relation of its own (`x > 0`, `x \le 0`), the words of a
/// condition (`\text{if}`, `otherwise`) separators; any other display as it is.
pub(crate) fn cases_row(block: &str) -> String {
    let open = ["\\begin{cases}", "\\begin{dcases}", "\\begin{rcases}"]
        .iter()
        .find_map(|o| block.find(o).map(|at| (at, o.len())));
    let Some((at, len)) = open else {
        return block.to_string();
    };
    let Some(close) = block[at..].find("\\end{").map(|k| at + k) else {
        return block.to_string();
    };
    let close_end = block[close..]
        .find('}')
        .map_or(block.len(), |k| close + k + 1);
    let mut prefix = block[..at].trim_end().to_string();
    for brace in ["\\left\\{", "\\left.", "\\{"] {
        if let Some(p) = prefix.strip_suffix(brace) {
            prefix = p.to_string();
        }
    }
    let mut suffix = block[close_end..].trim_start().to_string();
    for brace in ["\\right.", "\\right\\}"] {
        if let Some(s) = suffix.strip_prefix(brace) {
            suffix = s.to_string();
        }
    }
    // the tag of the whole display stays at its end
    let (suffix, tag) = take_tag(&suffix);
    let mut parts = Vec::new();
    for row in rows_of(&block[at + len..close]) {
        if row.trim().is_empty() {
            continue;
        }
        let cols = split_top(&row, &["&"]);
        let value = cols[0].trim().trim_end_matches(',').trim();
        parts.push(format!("{prefix} {value} {suffix}"));
        for cond in cols.iter().skip(1) {
            let words = cond.replace("otherwise", " ").replace("else", " ");
            parts.push(format!(";{words};"));
        }
    }
    // one cases per row: a second one in the same row stays, and the reader names it
    format!(
        "{}{}",
        parts.join(" ; "),
        tag.map_or_else(String::new, |t| format!(" \\tag{{{t}}}"))
    )
}

/// Whether a row that starts with `-` or `+` is a relation of its own (`-a = b`) rather than the
/// continuation of the row before (a relation sign at the top level).
pub(crate) fn starts_relation(row: &str) -> bool {
    let signs = [
        "=",
        "\\le",
        "\\ge",
        "\\leq",
        "\\geq",
        "\\leqslant",
        "\\geqslant",
        "<",
        ">",
        "\\approx",
        "\\ll",
        "\\gg",
        "\\ne",
        "\\neq",
        "\\sim",
        "\\propto",
        "\\to",
    ];
    split_top(row, &signs).len() > 1
}

/// The row without its `\tag{...}`, and the tag.
pub(crate) fn take_tag(row: &str) -> (String, Option<String>) {
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

/// The names a paper applies as functions, read from its displays (kept with the displays'
/// reader, which finds them).
impl TexSymbols {
    /// This table with the names a paper applies as functions: the names of the applications
    /// read in `displays` (`{x(t)}` read from `x(t)`), each then applied to any arguments.
    pub fn with_functions_of<'a>(&self, displays: impl IntoIterator<Item = &'a str>) -> Self {
        let mut t = self.clone();
        for d in displays {
            t.2.extend(crate::paper::formulas::lone_increment_letters(d));
            for row in read_display(d, self) {
                for rel in row.relations.iter().flatten() {
                    for s in rel.sides.iter().flat_map(Expr::symbols) {
                        let name = crate::paper::units::unit_name(&s);
                        if name != s {
                            t.1.insert(name);
                        }
                    }
                }
            }
        }
        t
    }
}
