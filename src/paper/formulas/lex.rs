//! The LaTeX reader's lexer: commands, characters, numbers, braces, and the spellings of a
//! [`TexSymbols`] table as symbols; the Greek letters, functions and accents it knows.

use super::TexSymbols;
use crate::algebra::expr::Func;

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    Cmd(String),
    Ch(char),
    Num(String),
    Sym(String),
    Open,
    Close,
    End,
}

pub(super) fn lex(src: &str, syms: &TexSymbols) -> Vec<(Tok, usize)> {
    let chars: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    'outer: while i < chars.len() {
        let col = i + 1;
        for (spelling, sym) in &syms.0 {
            let sp: Vec<char> = spelling.chars().collect();
            if !sp.is_empty() && chars[i..].starts_with(&sp) {
                out.push((Tok::Sym(sym.clone()), col));
                i += sp.len();
                continue 'outer;
            }
        }
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '\\' {
            let start = i + 1;
            let mut j = start;
            while j < chars.len() && chars[j].is_ascii_alphabetic() {
                j += 1;
            }
            if j == start && j < chars.len() {
                j += 1;
            }
            let mut name: String = chars[start..j].iter().collect();
            // `\` before a line break or a tab: TeX's control space
            if !name.is_empty() && name.chars().all(char::is_whitespace) {
                name = " ".into();
            }
            // `\mkern-3mu`, `\kern 0.2em`: a space of the length that follows
            if matches!(name.as_str(), "mkern" | "kern" | "mskip" | "hskip") {
                let mut k = j;
                while k < chars.len() && chars[k] == ' ' {
                    k += 1;
                }
                if k < chars.len() && (chars[k] == '-' || chars[k] == '+') {
                    k += 1;
                }
                let digits = k;
                while k < chars.len() && (chars[k].is_ascii_digit() || chars[k] == '.') {
                    k += 1;
                }
                if k > digits && k + 1 < chars.len() && chars[k].is_ascii_alphabetic() {
                    i = k + 2;
                    continue;
                }
            }
            // `\text{,}`, `\mbox{ .}`: the sentence's punctuation, no part of the formula
            if matches!(name.as_str(), "text" | "mbox" | "textrm" | "mathrm")
                && chars.get(j) == Some(&'{')
                && let Some(len) = chars[j + 1..].iter().position(|c| *c == '}')
                && chars[j + 1..j + 1 + len]
                    .iter()
                    .all(|c| " ,.;:".contains(*c))
            {
                i = j + len + 2;
                continue;
            }
            out.push((Tok::Cmd(name), col));
            i = j;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(char::is_ascii_digit))
        {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            out.push((Tok::Num(chars[start..i].iter().collect()), col));
            // a value's unit (`79\,\text{mm}`, `0.23\mathrm{m/s}`): the number is a value,
            // its unit no symbol
            let unit = unit_after_number(&chars[i..]);
            if unit > 0 {
                i += unit;
                out.push((Tok::Sym(crate::algebra::units::WRITTEN_UNIT.into()), col));
            }
        } else if chars[i..].starts_with(&['.', '.', '.']) {
            // `c_1 N_1 + ... + c_n N_n`: an ellipsis typed as three dots
            out.push((Tok::Cmd("ldots".into()), col));
            i += 3;
        } else if c == '{'
            && chars[i + 1..]
                .iter()
                .find(|c| !c.is_whitespace())
                .is_some_and(|c| *c == '}')
        {
            // an empty group (`x'_k{}^2`, `\rho_{x}{ }^{2}`) only separates scripts
            i += 1;
            while chars[i] != '}' {
                i += 1;
            }
            i += 1;
            // an empty script (`\mathrm{d}^{} x`, a macro's order left empty) is none
            if matches!(out.last(), Some((Tok::Ch('^' | '_'), _))) {
                out.pop();
            }
        } else if c == '{' {
            out.push((Tok::Open, col));
            i += 1;
        } else if c == '}' {
            out.push((Tok::Close, col));
            i += 1;
        } else {
            out.push((Tok::Ch(c), col));
            i += 1;
        }
    }
    out.push((Tok::End, chars.len() + 1));
    set_operations(repeated_integrals(empty_bases(bounds_in_order(
        unstyled_operators(out),
    ))))
}

/// `\int\int f dx dy`: integral signs in a row, the first without bounds, are one integral
/// over a region of as many dimensions (`\iint`, `\iiint`), closed by all its differentials.
fn repeated_integrals(toks: Vec<(Tok, usize)>) -> Vec<(Tok, usize)> {
    let int = |t: &Tok| matches!(t, Tok::Cmd(c) if c == "int");
    let mut out: Vec<(Tok, usize)> = Vec::with_capacity(toks.len());
    let mut i = 0;
    while i < toks.len() {
        if int(&toks[i].0) {
            let mut n = 1;
            let mut k = i + 1;
            loop {
                let mut j = k;
                while toks.get(j).is_some_and(|t| is_space(&t.0)) {
                    j += 1;
                }
                if toks.get(j).is_some_and(|t| int(&t.0)) {
                    n += 1;
                    k = j + 1;
                } else {
                    break;
                }
            }
            if n > 1 {
                let name = if n == 2 { "iint" } else { "iiint" };
                out.push((Tok::Cmd(name.into()), toks[i].1));
                i = k;
                continue;
            }
        }
        out.push(toks[i].clone());
        i += 1;
    }
    out
}

/// Two operators of sets and vectors as the reader takes them: `\Omega \setminus \omega`,
/// `A \cap B`, `A \cup B` join sets of one kind of element (as `+` joins terms of one unit);
/// a full stop between two operands (`(\mathbf{u}.\nabla)`, `\mathbf{v}.\mathbf{n}`, a dot
/// product typed as a period) is `\cdot`. A full stop at the end of a formula or before a
/// closing bracket stays punctuation.
fn set_operations(toks: Vec<(Tok, usize)>) -> Vec<(Tok, usize)> {
    let operand_end = |t: &Tok| match t {
        Tok::Close | Tok::Ch(')' | ']') => true,
        Tok::Ch(c) => c.is_ascii_alphabetic(),
        Tok::Cmd(c) => greek(c).is_some() || c == "nabla",
        _ => false,
    };
    let operand_start = |t: &Tok| match t {
        Tok::Open | Tok::Ch('(') => true,
        Tok::Ch(c) => c.is_ascii_alphabetic(),
        Tok::Cmd(c) => {
            greek(c).is_some() || c == "nabla" || accent_suffix(c).is_some() || c == "hat"
        }
        _ => false,
    };
    // the depth of braces, and the depths at which a text's group opened (`\text{s.t.}`,
    // `\mathrm{c.c.}`: a period in words is punctuation)
    let (mut depth, mut texts) = (0usize, Vec::new());
    let mut out: Vec<(Tok, usize)> = Vec::with_capacity(toks.len());
    for (i, (t, col)) in toks.iter().enumerate() {
        match t {
            Tok::Open => {
                depth += 1;
                if matches!(out.last(), Some((Tok::Cmd(c), _)) if accent_suffix(c).is_some() || c == "mbox" || c == "operatorname")
                {
                    texts.push(depth);
                }
            }
            Tok::Close => {
                if texts.last() == Some(&depth) {
                    texts.pop();
                }
                depth = depth.saturating_sub(1);
            }
            _ => {}
        }
        let t = match t {
            Tok::Cmd(c) if matches!(c.as_str(), "setminus" | "cap" | "cup") => Tok::Ch('+'),
            Tok::Ch('.')
                if texts.is_empty()
                    && out.last().is_some_and(|(p, _)| operand_end(p))
                    && toks.get(i + 1).is_some_and(|(n, _)| operand_start(n)) =>
            {
                Tok::Cmd("cdot".into())
            }
            t => t.clone(),
        };
        out.push((t, *col));
    }
    out
}

/// `q^{{}_{(4)}}`: a group that holds only a script of nothing (`{}_{(4)}`, a label set low in a
/// superscript) is the script's text, `q^{(4)}`. A script of nothing before a name
/// (`{}^N\omega`, a frame) is left to the reader.
fn empty_bases(mut toks: Vec<(Tok, usize)>) -> Vec<(Tok, usize)> {
    let mut i = 0;
    // (the empty group itself is dropped as it is lexed: `{` then the script)
    while i + 2 < toks.len() {
        if toks[i].0 == Tok::Open
            && matches!(toks[i + 1].0, Tok::Ch('_' | '^'))
            && let Some(end) = argument_end(&toks, i + 2)
            && toks.get(end).is_some_and(|t| t.0 == Tok::Close)
        {
            // the script's braces too: `^{{}_{(4)}}` is `^{(4)}`
            if toks[i + 2].0 == Tok::Open {
                toks.remove(end - 1);
                toks.remove(i + 2);
            }
            toks.remove(i + 1);
        }
        i += 1;
    }
    toks
}

/// The index after a script's argument that starts at `k`: one token, or a group.
fn argument_end(toks: &[(Tok, usize)], k: usize) -> Option<usize> {
    match toks.get(k)?.0 {
        Tok::Open => {
            let mut depth = 0usize;
            for (j, (t, _)) in toks.iter().enumerate().skip(k) {
                match t {
                    Tok::Open => depth += 1,
                    Tok::Close => {
                        depth -= 1;
                        if depth == 0 {
                            return Some(j + 1);
                        }
                    }
                    Tok::End => return None,
                    _ => {}
                }
            }
            None
        }
        Tok::End | Tok::Close => None,
        _ => Some(k + 1),
    }
}

/// `\sum^n_{i=1}`, `\int^b_a`: the upper bound written first, put after the lower one (TeX
/// takes the scripts in either order; the reader reads `_` then `^`).
fn bounds_in_order(mut toks: Vec<(Tok, usize)>) -> Vec<(Tok, usize)> {
    let big = |t: &Tok| matches!(t, Tok::Cmd(c) if matches!(c.as_str(), "sum" | "prod" | "int" | "iint" | "iiint" | "oint"));
    let mut i = 0;
    while i + 1 < toks.len() {
        if big(&toks[i].0)
            && toks[i + 1].0 == Tok::Ch('^')
            && let Some(up) = argument_end(&toks, i + 2)
            && toks.get(up).is_some_and(|t| t.0 == Tok::Ch('_'))
            && let Some(down) = argument_end(&toks, up + 1)
        {
            // [^ hi][_ lo] -> [_ lo][^ hi]
            toks[i + 1..down].rotate_left(up - (i + 1));
        }
        i += 1;
    }
    toks
}

/// `\mathrm{\partial}`, `\mathrm{\infty}` (a macro's `\pd` made upright): the operator itself,
/// a font changing nothing of what a symbol that is no letter means; `\limits` and `\nolimits`
/// dropped.
fn unstyled_operators(toks: Vec<(Tok, usize)>) -> Vec<(Tok, usize)> {
    let mut out = Vec::with_capacity(toks.len());
    let mut i = 0;
    while i < toks.len() {
        // `\int\limits_{0}^{x}`, `\sum\nolimits_i`: where the bounds are printed, not what
        if matches!(&toks[i].0, Tok::Cmd(c) if c == "limits" || c == "nolimits") {
            i += 1;
            continue;
        }
        if let [
            (Tok::Cmd(f), _),
            (Tok::Open, _),
            (Tok::Cmd(c), col),
            (Tok::Close, _),
            ..,
        ] = &toks[i..]
            && accent_suffix(f) == Some("")
            && matches!(c.as_str(), "partial" | "infty" | "nabla")
        {
            out.push((Tok::Cmd(c.clone()), *col));
            i += 4;
            continue;
        }
        out.push(toks[i].clone());
        i += 1;
    }
    out
}

pub(super) const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "omicron", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
    "Omega",
];

pub(super) fn greek(cmd: &str) -> Option<&str> {
    Some(match cmd {
        "varepsilon" => "epsilon",
        "varphi" => "phi",
        "vartheta" => "theta",
        "varrho" => "rho",
        "varsigma" => "sigma",
        "varkappa" => "kappa",
        "nabla" => "nabla",
        "ell" => "l",
        "hbar" => "hbar",
        // upright Greek (upgreek) and the variant capitals (`\varOmega`) are the letters
        c if c.starts_with("up") && GREEK.contains(&&c[2..]) => &c[2..],
        c if c.starts_with("var") && GREEK.contains(&&c[3..]) => &c[3..],
        c => return GREEK.iter().copied().find(|g| *g == c),
    })
}

pub(super) fn func(cmd: &str) -> Option<Func> {
    Some(match cmd {
        "sin" => Func::Sin,
        "cos" => Func::Cos,
        "tan" => Func::Tan,
        "exp" => Func::Exp,
        "ln" => Func::Ln,
        "arcsin" => Func::Asin,
        "arccos" => Func::Acos,
        "arctan" => Func::Atan,
        "sinh" => Func::Sinh,
        "cosh" => Func::Cosh,
        "tanh" => Func::Tanh,
        "arsinh" | "arcsinh" => Func::Asinh,
        "arcosh" | "arccosh" => Func::Acosh,
        "artanh" | "arctanh" => Func::Atanh,
        _ => return None,
    })
}

/// Commands that only space or style: skipped.
pub(super) fn is_space(t: &Tok) -> bool {
    match t {
        Tok::Cmd(c) => matches!(
            c.as_str(),
            "," | ";"
                | ":"
                | "!"
                | " "
                | "quad"
                | "qquad"
                | "displaystyle"
                | "textstyle"
                | "limits"
                | "nolimits"
                | "big"
                | "Big"
                | "bigg"
                | "Bigg"
                | "bigl"
                | "bigr"
                | "Bigl"
                | "Bigr"
                | "biggl"
                | "biggr"
                | "Biggl"
                | "Biggr"
                | "rm"
                | "bf"
                | "it"
                | "sf"
                | "tt"
                | "cal"
                | "scriptstyle"
                | "scriptscriptstyle"
                | "hfill"
                | "allowbreak"
                | "nonumber"
                | "notag"
                | "medskip"
                | "smallskip"
                | "enspace"
                | "thinspace"
                | "negthinspace"
                | "relax"
                | "strut"
                // a line break inside brackets (`\Bigg[ .. \\ + .. \Bigg]` in a `multline`)
                | "\\"
        ),
        Tok::Ch('~') => true,
        _ => false,
    }
}

/// The length of a unit written after a number (`\,\text{m/s}`, `~\mathrm{kg\,m^{-3}}`,
/// `\text{ mm}`), or 0: a text group whose words are units, each with an SI prefix or not.
fn unit_after_number(rest: &[char]) -> usize {
    let text: String = rest.iter().take(60).collect();
    let mut k = 0;
    loop {
        let t = &text[k..];
        let skip = [" ", "\\,", "\\;", "\\ ", "~", "\\!"]
            .iter()
            .find(|s| t.starts_with(**s))
            .map_or(0, |s| s.len());
        if skip == 0 {
            break;
        }
        k += skip;
    }
    let t = &text[k..];
    let Some(open) = ["\\text{", "\\mathrm{", "\\textrm{", "\\rm{", "\\mbox{"]
        .iter()
        .find(|o| t.starts_with(**o))
    else {
        return 0;
    };
    // the group's own closing brace (`\mathrm{kg\,m^{-3}}` holds one of a power)
    let mut depth = 0usize;
    let Some(close) = t[open.len()..].char_indices().find_map(|(i, c)| match c {
        '{' => {
            depth += 1;
            None
        }
        '}' if depth == 0 => Some(i),
        '}' => {
            depth -= 1;
            None
        }
        _ => None,
    }) else {
        return 0;
    };
    let inner = &t[open.len()..open.len() + close];
    let words: Vec<&str> = inner
        .split(|c: char| !c.is_ascii_alphabetic() && c != '°')
        .filter(|w| !w.is_empty() && *w != "mathrm" && *w != "text")
        .collect();
    let named = |w: &str| crate::algebra::units::Unit::named(w).is_some();
    let is_unit = |w: &str| {
        let first = w.chars().next().map_or(0, char::len_utf8);
        named(w)
            || ["g", "h", "min", "deg", "rpm", "l", "L", "eV", "mph", "°"].contains(&w)
            || w.len() > first
                && "kmcunMGdμ".contains(&w[..first])
                && (named(&w[first..]) || &w[first..] == "g")
    };
    if words.is_empty() || !words.iter().all(|w| is_unit(w)) {
        return 0;
    }
    // and its power (`\text{m/s}^{2}`, `\mathrm{m}^2`)
    let mut end = k + open.len() + close + 1;
    let after = &text[end..];
    if let Some(p) = after.strip_prefix('^') {
        end += 1 + match p.chars().next() {
            Some('{') => p.find('}').map_or(0, |c| c + 1),
            Some(c) if c.is_ascii_digit() || c == '-' => c.len_utf8(),
            _ => 0,
        };
    }
    // characters, not bytes
    text[..end].chars().count()
}

pub(super) fn accent_suffix(cmd: &str) -> Option<&'static str> {
    Some(match cmd {
        "tilde" | "widetilde" => "t",
        "hat" | "widehat" => "h",
        "bar" | "overline" => "b",
        "dot" => "d",
        "ddot" => "dd",
        "mathbf" | "boldsymbol" | "mathrm" | "mathit" | "vec" | "bm" | "operatorname" | "text"
        | "pmb" | "textbf" | "textrm" | "textit" | "mathnormal" | "overrightarrow" | "vb"
        | "mbox" | "textnormal" | "textup" | "texttt" | "textsf" | "mathtt" | "bold" | "vv"
        | "mathsf" | "symbf" | "symbfit" | "mathbfit" => "",
        // a calligraphic or blackboard letter is another quantity than the plain one
        "mathcal" => "cal",
        "mathscr" => "scr",
        "mathbb" => "bb",
        "mathfrak" => "frak",
        "check" => "c",
        "breve" => "br",
        "underline" => "u",
        "dddot" => "ddd",
        _ => return None,
    })
}
pub(super) fn describe(t: &Tok) -> String {
    match t {
        Tok::Cmd(c) => format!("\\{c}"),
        Tok::Ch(c) => c.to_string(),
        Tok::Num(n) => n.clone(),
        Tok::Sym(s) => s.clone(),
        Tok::Open => "{".into(),
        Tok::Close => "}".into(),
        Tok::End => "the end".into(),
    }
}
