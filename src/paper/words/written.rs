//! A unit as a paper writes it: `Pa`, `kg m$^{-3}$`, `\mathrm{m\,s^{-1}}`, `N·m`, with the
//! prefixes and the units outside SI a paper uses (`GPa`, `mm`, `g`, `min`, `L`): only their
//! dimension counts in an audit, so `GPa` is `Pa` and `g` is `kg`.

use crate::algebra::units::Unit;

/// A unit's name as a paper writes it: an SI name, a name outside SI with its dimension, or
/// either after an SI prefix (`kN`, `um`, `μm`, `GPa`).
fn named(name: &str) -> Option<Unit> {
    let outside = |n: &str| {
        Some(match n {
            "g" | "t" => Unit::named("kg")?,
            "min" | "h" => Unit::named("s")?,
            "L" | "l" => Unit::parse("m^3").ok()?,
            "deg" | "°" => Unit::one(),
            "rpm" => Unit::named("Hz")?,
            "bar" => Unit::named("Pa")?,
            "eV" => Unit::named("J")?,
            _ => return None,
        })
    };
    if let Some(u) = Unit::named(name).or_else(|| (name.len() > 1).then(|| outside(name)).flatten())
    {
        return Some(u);
    }
    if name == "g" || name == "°" {
        return outside(name);
    }
    // a prefix and an SI unit (`t`, `h`, `min` take none: `mt`, `kh` are no units)
    let (p, rest) = if let Some(r) = name.strip_prefix("da") {
        ("da", r)
    } else {
        let first = name.chars().next()?;
        name.split_at(first.len_utf8())
    };
    let prefixes = [
        "y", "z", "a", "f", "p", "n", "u", "μ", "µ", "m", "c", "d", "da", "h", "k", "M", "G", "T",
        "P", "E",
    ];
    if !prefixes.contains(&p) || rest.is_empty() {
        return None;
    }
    Unit::named(rest).or_else(|| {
        matches!(rest, "g" | "L" | "l" | "bar" | "eV")
            .then(|| outside(rest))
            .flatten()
    })
}

/// A unit as a paper writes it (`Pa`, `kg m$^{-3}$`, `\mathrm{m\,s^{-1}}`, `N·m`, `-`), or
/// `None` when the text is no unit (a citation `[1]`, an equation's number `(3)`).
pub fn written_unit(text: &str) -> Option<Unit> {
    let mut t = text.trim().to_string();
    for (from, to) in [
        ("\\mathrm", ""),
        ("\\text", ""),
        ("\\rm", ""),
        ("\\,", " "),
        ("\\;", " "),
        ("\\ ", " "),
        ("\\cdot", " "),
        ("\\times", " "),
        ("·", " "),
        ("⋅", " "),
        ("~", " "),
        ("$", ""),
        ("{", ""),
        ("}", ""),
        ("²", "^2"),
        ("³", "^3"),
        ("⁻¹", "^-1"),
        ("−", "-"),
    ] {
        t = t.replace(from, to);
    }
    let mut t = t.trim().to_string();
    while t.contains(" ^") || t.contains("^ ") {
        t = t.replace(" ^", "^").replace("^ ", "^");
    }
    let t = t.as_str();
    if matches!(t, "-" | "--" | "---" | "—" | "–") {
        return Unit::parse("1").ok();
    }
    // a citation `[1]`, an equation's number `(1.3)`, a variable `(t)`: no unit
    if !t.chars().any(|c| c.is_ascii_alphabetic()) || t.len() == 1 && t != "m" && t != "s" {
        return None;
    }
    if !t
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || " /^-*.()".contains(c))
    {
        return None;
    }
    // `m s^-1`: a negative power without parentheses
    let mut fixed = String::new();
    let mut chars = t.chars().peekable();
    while let Some(c) = chars.next() {
        fixed.push(c);
        if c == '^' && chars.peek() == Some(&'-') {
            fixed.push('(');
            fixed.push(chars.next()?);
            while let Some(d) = chars
                .peek()
                .copied()
                .filter(|d| d.is_ascii_digit() || *d == '.')
            {
                fixed.push(d);
                chars.next();
            }
            fixed.push(')');
        }
    }
    let spaced = fixed.split_whitespace().collect::<Vec<_>>().join("*");
    let e = crate::algebra::expr::parse(&spaced).ok()?;
    crate::algebra::units::dimension(&e, &named).ok()
}

/// A value written with its unit for a symbol: `E^* = 115.4\,\mathrm{GPa}` (siunitx's `\SI`
/// comes here in that form), `\rho \approx 7.8\times10^{3}\,\text{kg/m^3}`, or the number in
/// the math and the unit in the words right after it (`$L = 2$ m`): the symbol's side and the
/// unit. The unit must stand apart from the number (in `\mathrm`, `\text`, or after the math),
/// so that `F = 2 m g` is no value in metres.
pub(super) fn value_unit<'a>(math: &'a str, after: &str) -> Option<(&'a str, Unit)> {
    let (lhs, rhs) = ["=", "\\approx"]
        .iter()
        .filter_map(|r| math.find(r).map(|k| (k, r.len())))
        .min()
        .map(|(k, len)| (&math[..k], &math[k + len..]))?;
    let rhs = rhs.trim().trim_end_matches([',', '.', ';']).trim_end();
    // the number: digits, a decimal point, a sign, and a power of ten
    let mut rest = rhs.trim_start_matches(['-', '+']).trim_start();
    let digits = |r: &str| {
        r.len()
            - r.trim_start_matches(|c: char| {
                c.is_ascii_digit() || c == '.' || c == '{' || c == '}' || c == ' '
            })
            .len()
    };
    let n = digits(rest);
    if n == 0 || !rest[..n].chars().any(|c| c.is_ascii_digit()) {
        return None;
    }
    rest = &rest[n..];
    for times in ["\\times", "\\cdot"] {
        if let Some(r) = rest.trim_start().strip_prefix(times)
            && let Some(r) = r.trim_start().strip_prefix("10")
            && let Some(r) = r.trim_start().strip_prefix('^')
        {
            let r = r.trim_start();
            rest = match r.strip_prefix('{') {
                Some(inner) => &inner[inner.find('}')? + 1..],
                None => r.trim_start_matches('-').get(1..)?,
            };
        }
    }
    let rest = rest.trim_start_matches(|c: char| c.is_whitespace() || c == '~');
    let rest = ["\\,", "\\;", "\\ ", "\\!", "\\:"]
        .iter()
        .fold(rest.to_string(), |r, s| r.replace(s, " "));
    let rest = rest.trim();
    let unit = if rest.is_empty() {
        // the unit in the words right after the math: its first word
        let word: String = after
            .trim_start()
            .chars()
            .take_while(|c| !c.is_whitespace() && !",;)".contains(*c))
            .collect();
        let word = word.trim_end_matches('.');
        written_unit(word).filter(|_| word.chars().any(|c| c.is_ascii_alphabetic()))?
    } else if ["\\mathrm", "\\text", "\\textrm", "\\rm", "\\mbox"]
        .iter()
        .any(|r| rest.starts_with(r))
    {
        // one letter in roman is a unit here (`3\,\mathrm{g}`), as it is no symbol
        let bare: String = ["\\mathrm", "\\textrm", "\\text", "\\rm", "\\mbox"]
            .iter()
            .fold(rest.to_string(), |r, c| r.replace(c, ""))
            .replace(['{', '}'], "");
        written_unit(rest).or_else(|| named(bare.trim()))?
    } else {
        return None;
    };
    Some((lhs.trim(), unit))
}

/// `text` with each entry of the nomencl package (`\nomenclature[a]{$p$}{Roll rate}`, a unit in
/// `\nomunit{..}` or brackets) written as a row of a nomenclature table (`\\ $p$ & Roll rate
/// \\`), as the words read one; its lines kept.
pub(super) fn nomenclature_rows(text: &str) -> String {
    const CMD: &str = "\\nomenclature";
    let glossary = glossary_rows(text);
    let text = glossary.as_str();
    if !text.contains(CMD) {
        return text.to_string();
    }
    let group = crate::paper::source::files::braced;
    let mut out = String::with_capacity(text.len());
    let mut pos = 0;
    while let Some(k) = text[pos..].find(CMD) {
        let at = pos + k;
        let mut end = at + CMD.len();
        if text[end..].starts_with('[') {
            end += text[end..].find(']').map_or(0, |c| c + 1);
        }
        let (Some((sym, mid)), true) = (
            group(text, end),
            !text[end..].starts_with(|c: char| c.is_ascii_alphabetic()),
        ) else {
            out.push_str(&text[pos..end]);
            pos = end;
            continue;
        };
        let Some((desc, close)) = group(text, mid) else {
            out.push_str(&text[pos..end]);
            pos = end;
            continue;
        };
        out.push_str(&text[pos..at]);
        let desc = match desc.find("\\nomunit") {
            Some(u) => match group(&desc, u + "\\nomunit".len()) {
                Some((unit, _)) => format!("{} & [{unit}]", &desc[..u]),
                None => desc.clone(),
            },
            None => desc.clone(),
        };
        let row = format!("\\\\ {} & {} \\\\", sym.trim(), desc.trim());
        out.push_str(&row.replace('\n', " "));
        // the lines the entry took, kept
        out.push_str(&"\n".repeat(text[at..close].matches('\n').count()));
        pos = close;
    }
    out.push_str(&text[pos..]);
    out
}

/// The symbols of the `glossaries` package as rows of a nomenclature:
/// `\newglossaryentry{key}{name={\ensuremath{m}}, description={mass}, symbol={\si{kg}}}` (the
/// symbol's math in `name` or in `symbol`; its unit in `unit` or `user1`, or in `symbol` when
/// `name` holds the math) and `\glsxtrnewsymbol[description={mass}]{key}{$m$}` become
/// `\\ $m$ & mass & [kg] \\`, on the entry's first line, its other lines kept.
fn glossary_rows(text: &str) -> String {
    const ENTRY: &str = "\\newglossaryentry";
    const SYMBOL: &str = "\\glsxtrnewsymbol";
    if !text.contains(ENTRY) && !text.contains(SYMBOL) {
        return text.to_string();
    }
    let group = crate::paper::source::files::braced;
    let math = |v: &str| v.contains('$') || v.contains("\\ensuremath");
    let as_math = |v: &str| {
        let v = v.trim();
        match v.strip_prefix("\\ensuremath") {
            Some(rest) => format!(
                "${}$",
                rest.trim().trim_start_matches('{').trim_end_matches('}')
            ),
            None => v.to_string(),
        }
    };
    let mut out = String::with_capacity(text.len());
    let mut pos = 0;
    loop {
        let next = [ENTRY, SYMBOL]
            .iter()
            .filter_map(|c| text[pos..].find(c).map(|k| (pos + k, *c)))
            .min();
        let Some((at, cmd)) = next else { break };
        let mut end = at + cmd.len();
        let mut options = String::new();
        if cmd == SYMBOL
            && text[end..].starts_with('[')
            && let Some(c) = text[end..].find("]{")
        {
            options = text[end + 1..end + c].to_string();
            end += c + 1;
        }
        let row = group(text, end).and_then(|(_, mid)| {
            group(text, mid).map(|(body, close)| {
                let (name, fields) = if cmd == ENTRY {
                    (None, fields_of(&body))
                } else {
                    (Some(body), fields_of(&options))
                };
                (name, fields, close)
            })
        });
        let Some((name, f, close)) = row else {
            out.push_str(&text[pos..end]);
            pos = end;
            continue;
        };
        let get = |k: &str| f.iter().find(|(key, _)| key == k).map(|(_, v)| v.clone());
        let (name, symbol) = match name {
            Some(n) => (Some(n), get("symbol")),
            None => (get("name"), get("symbol")),
        };
        let (sym, unit) = match (name, symbol) {
            (Some(n), s) if math(&n) => (Some(n), get("unit").or(get("user1")).or(s)),
            (_, Some(s)) if math(&s) => (Some(s), get("unit").or(get("user1"))),
            _ => (None, None),
        };
        out.push_str(&text[pos..at]);
        if let Some(sym) = sym {
            let desc = get("description").unwrap_or_default();
            let unit = unit
                .map(|u| format!(" & [{}]", u.trim()))
                .unwrap_or_default();
            let row = format!("\\\\ {} & {}{unit} \\\\", as_math(&sym), desc.trim());
            out.push_str(&row.replace('\n', " "));
        }
        out.push_str(&"\n".repeat(text[at..close].matches('\n').count()));
        pos = close;
    }
    out.push_str(&text[pos..]);
    out
}

/// The `key=value` pairs of a list at the top level of its braces, each value without one pair
/// of braces around it.
fn fields_of(list: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    let bytes = list.as_bytes();
    for i in 0..=bytes.len() {
        let c = bytes.get(i).copied().unwrap_or(b',');
        match c {
            b'{' => depth += 1,
            b'}' => depth -= 1,
            b',' if depth == 0 => {
                let item = &list[start..i.min(list.len())];
                if let Some((k, v)) = item.split_once('=') {
                    let v = v.trim();
                    let v = v
                        .strip_prefix('{')
                        .and_then(|x| x.strip_suffix('}'))
                        .unwrap_or(v);
                    out.push((k.trim().to_string(), v.to_string()));
                }
                start = i + 1;
            }
            _ => {}
        }
    }
    out
}
