//! Units as siunitx writes them (issue 66), rewritten into the plain forms the rest of the reader
//! takes: `\SI{115.4}{\giga\pascal}` and `\qty{..}{..}` become `115.4\,\mathrm{GPa}`,
//! `\si{\kilo\gram\per\cubic\metre}` and `\unit{..}` become `\mathrm{kg m^-3}`, `\num{1.5e3}`
//! becomes `1.5\times10^{3}`, the ranges and lists their values with the unit on the last.
//!
//! Both of siunitx's unit syntaxes are read: the macros (prefixes `\kilo`..., units `\metre`...,
//! `\per`, `\square`/`\squared`, `\cubic`/`\cubed`, `\tothe{n}`, `\raiseto{n}`) and the literal
//! one (`kg.m/s^2`, `m s^{-1}`, `GPa`). Written by hand: no crate reads siunitx, and the rewrite
//! is a small table.

use super::files::braced;

/// The prefixes, as siunitx names them, with their symbols (`u` for micro, as the unit reader
/// takes it).
const PREFIXES: &[(&str, &str)] = &[
    ("yocto", "y"),
    ("zepto", "z"),
    ("atto", "a"),
    ("femto", "f"),
    ("pico", "p"),
    ("nano", "n"),
    ("micro", "u"),
    ("milli", "m"),
    ("centi", "c"),
    ("deci", "d"),
    ("deca", "da"),
    ("deka", "da"),
    ("hecto", "h"),
    ("kilo", "k"),
    ("mega", "M"),
    ("giga", "G"),
    ("tera", "T"),
    ("peta", "P"),
    ("exa", "E"),
];

/// The units, as siunitx names them, with their symbols.
const UNITS: &[(&str, &str)] = &[
    ("metre", "m"),
    ("meter", "m"),
    ("gram", "g"),
    ("kilogram", "kg"),
    ("second", "s"),
    ("newton", "N"),
    ("pascal", "Pa"),
    ("joule", "J"),
    ("watt", "W"),
    ("hertz", "Hz"),
    ("radian", "rad"),
    ("steradian", "rad"),
    ("degree", "deg"),
    ("arcminute", "deg"),
    ("arcsecond", "deg"),
    ("kelvin", "K"),
    ("degreeCelsius", "K"),
    ("celsius", "K"),
    ("ampere", "A"),
    ("mole", "mol"),
    ("candela", "cd"),
    ("coulomb", "C"),
    ("volt", "V"),
    ("ohm", "ohm"),
    ("litre", "L"),
    ("liter", "L"),
    ("minute", "min"),
    ("hour", "h"),
    ("day", "d"),
    ("bar", "bar"),
    ("tonne", "t"),
    ("percent", "1"),
    ("rpm", "rpm"),
];

/// A siunitx unit argument in the plain form (`kg m^-3`, `GPa`, `m s^-2`).
pub fn unit_text(arg: &str) -> String {
    let arg = arg.trim();
    if !arg.contains('\\') {
        // the literal syntax: `.` and `~` are products, `{-1}` a power
        return arg
            .replace(['.', '~'], " ")
            .replace(['{', '}'], "")
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
    }
    let mut out: Vec<(String, i32)> = Vec::new();
    let mut prefix = String::new();
    let mut per = false;
    let mut before: Option<i32> = None;
    let mut rest = arg;
    while let Some(k) = rest.find('\\') {
        let name: String = rest[k + 1..]
            .chars()
            .take_while(char::is_ascii_alphabetic)
            .collect();
        rest = &rest[k + 1 + name.len()..];
        let power = |out: &mut Vec<(String, i32)>, p: i32| {
            if let Some(last) = out.last_mut() {
                last.1 *= p;
            }
        };
        match name.as_str() {
            "per" => per = true,
            "square" => before = Some(2),
            "cubic" => before = Some(3),
            "squared" => power(&mut out, 2),
            "cubed" => power(&mut out, 3),
            "tothe" | "raiseto" => {
                let Some((n, end)) = braced(rest, 0) else {
                    continue;
                };
                rest = &rest[end..];
                let n: i32 = n.trim().parse().unwrap_or(1);
                if name == "tothe" {
                    power(&mut out, n);
                } else {
                    before = Some(n);
                }
            }
            p if PREFIXES.iter().any(|(n, _)| *n == p) => {
                prefix = PREFIXES
                    .iter()
                    .find(|(n, _)| *n == p)
                    .map_or("", |x| x.1)
                    .to_string();
            }
            u => {
                let sym = UNITS.iter().find(|(n, _)| *n == u).map_or(u, |x| x.1);
                let mut e = before.take().unwrap_or(1);
                if per {
                    e = -e;
                    per = false;
                }
                out.push((format!("{}{sym}", std::mem::take(&mut prefix)), e));
            }
        }
    }
    out.iter()
        .map(|(u, e)| match e {
            1 => u.clone(),
            e => format!("{u}^{e}"),
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// A siunitx number in the plain form: `1.5e3` as `1.5\times10^{3}`, `\pm` and spaces kept.
fn number_text(arg: &str) -> String {
    let t = arg.trim();
    match t.find(['e', 'E']) {
        Some(k) if k > 0 && t[k + 1..].trim().parse::<i32>().is_ok() => {
            format!("{}\\times10^{{{}}}", t[..k].trim(), t[k + 1..].trim())
        }
        _ => t.to_string(),
    }
}

/// `text` with every siunitx command (`\SI`, `\qty`, `\si`, `\unit`, `\num`, `\SIrange`,
/// `\qtyrange`, `\numrange`, `\SIlist`, `\qtylist`, `\numlist`, `\ang`) in its plain form; an
/// optional `[..]` of settings is passed over.
pub fn plain(text: &str) -> String {
    const NAMES: &[(&str, usize)] = &[
        ("SI", 2),
        ("qty", 2),
        ("si", 1),
        ("unit", 1),
        ("num", 1),
        ("SIrange", 3),
        ("qtyrange", 3),
        ("numrange", 2),
        ("SIlist", 2),
        ("qtylist", 2),
        ("numlist", 1),
        ("ang", 1),
    ];
    if !text.contains('\\') {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len());
    let mut pos = 0;
    while let Some(k) = text[pos..].find('\\') {
        let at = pos + k;
        let name: String = text[at + 1..]
            .chars()
            .take_while(char::is_ascii_alphabetic)
            .collect();
        let after = at + 1 + name.len();
        // a control symbol (`\\`, `\,`) whole: `\\SI` is a line break and letters
        let after = if name.is_empty() {
            at + 1 + text[at + 1..].chars().next().map_or(0, char::len_utf8)
        } else {
            after
        };
        let Some(&(_, n)) = NAMES.iter().find(|(x, _)| *x == name) else {
            out.push_str(&text[pos..after]);
            pos = after;
            continue;
        };
        // the settings, then the arguments
        let mut end = after;
        let opts = text[end..].trim_start();
        if opts.starts_with('[')
            && let Some(c) = opts.find(']')
        {
            end += text[end..].len() - opts.len() + c + 1;
        }
        let mut args = Vec::new();
        for _ in 0..n {
            match braced(text, end) {
                Some((a, e)) => {
                    args.push(a);
                    end = e;
                }
                None => break,
            }
        }
        if args.len() < n {
            out.push_str(&text[pos..after]);
            pos = after;
            continue;
        }
        out.push_str(&text[pos..at]);
        let unit = |u: &str| format!("\\mathrm{{{}}}", unit_text(u));
        let values = |list: &str| {
            list.split(';')
                .map(number_text)
                .collect::<Vec<_>>()
                .join(", ")
        };
        out.push_str(&match name.as_str() {
            "SI" | "qty" => format!("{}\\,{}", number_text(&args[0]), unit(&args[1])),
            "si" | "unit" => unit(&args[0]),
            "num" => number_text(&args[0]),
            "numlist" => values(&args[0]),
            "ang" => format!("{}\\,\\mathrm{{deg}}", values(&args[0])),
            "SIrange" | "qtyrange" => format!(
                "{}\\text{{ to }}{}\\,{}",
                number_text(&args[0]),
                number_text(&args[1]),
                unit(&args[2])
            ),
            "numrange" => format!(
                "{}\\text{{ to }}{}",
                number_text(&args[0]),
                number_text(&args[1])
            ),
            // SIlist, qtylist
            _ => format!("{}\\,{}", values(&args[0]), unit(&args[1])),
        });
        pos = end;
    }
    out.push_str(&text[pos..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_in_both_syntaxes_by_hand() {
        assert_eq!(unit_text("\\kilo\\gram\\per\\cubic\\metre"), "kg m^-3");
        assert_eq!(unit_text("\\metre\\per\\second\\squared"), "m s^-2");
        assert_eq!(unit_text("\\giga\\pascal"), "GPa");
        assert_eq!(unit_text("\\newton\\metre"), "N m");
        assert_eq!(unit_text("\\micro\\metre"), "um");
        assert_eq!(unit_text("\\metre\\tothe{4}"), "m^4");
        assert_eq!(unit_text("\\raiseto{2}\\second"), "s^2");
        assert_eq!(unit_text("kg.m/s^2"), "kg m/s^2");
        assert_eq!(unit_text("m s^{-1}"), "m s^-1");
        assert_eq!(unit_text(" GPa "), "GPa");
    }

    #[test]
    fn commands_in_their_plain_forms_by_hand() {
        assert_eq!(
            plain("$E^* = \\SI{115.4}{\\giga\\pascal}$"),
            "$E^* = 115.4\\,\\mathrm{GPa}$"
        );
        assert_eq!(
            plain("[\\si{\\kilo\\gram\\per\\cubic\\metre}]"),
            "[\\mathrm{kg m^-3}]"
        );
        assert_eq!(plain("\\qty[mode=text]{2}{\\metre}"), "2\\,\\mathrm{m}");
        assert_eq!(plain("\\num{1.5e3}"), "1.5\\times10^{3}");
        assert_eq!(plain("\\unit{m.s^{-1}}"), "\\mathrm{m s^-1}");
        assert_eq!(
            plain("\\SIrange{1}{2}{\\milli\\metre}"),
            "1\\text{ to }2\\,\\mathrm{mm}"
        );
        // what is no siunitx command stays, a command without its arguments too
        assert_eq!(plain("\\sigma = \\sin x \\SI"), "\\sigma = \\sin x \\SI");
        assert_eq!(plain("a \\\\ b"), "a \\\\ b");
        assert_eq!(plain("a \\\\SI{1}{m}"), "a \\\\SI{1}{m}");
    }
}
