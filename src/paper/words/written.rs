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
