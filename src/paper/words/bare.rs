//! Symbols a translated paper writes without dollars in its prose ("where m is the mass, J is
//! the central inertia tensor, V is the velocity of the centre of mass G and Ω is the angular
//! velocity of the body"): a word that is a letter, a Greek letter, a bold `**n**` or a font
//! command on a letter, with scripts, standing before "is", "are" or "denote".

/// Unicode Greek letters as LaTeX commands (a translated paper's prose writes `Ω`).
const GREEK: &[(char, &str)] = &[
    ('α', "alpha"),
    ('β', "beta"),
    ('γ', "gamma"),
    ('δ', "delta"),
    ('ε', "varepsilon"),
    ('ϵ', "epsilon"),
    ('ζ', "zeta"),
    ('η', "eta"),
    ('θ', "theta"),
    ('ϑ', "vartheta"),
    ('κ', "kappa"),
    ('λ', "lambda"),
    ('μ', "mu"),
    ('ν', "nu"),
    ('ξ', "xi"),
    ('π', "pi"),
    ('ρ', "rho"),
    ('σ', "sigma"),
    ('τ', "tau"),
    ('υ', "upsilon"),
    ('φ', "varphi"),
    ('ϕ', "phi"),
    ('χ', "chi"),
    ('ψ', "psi"),
    ('ω', "omega"),
    ('Γ', "Gamma"),
    ('Δ', "Delta"),
    ('Θ', "Theta"),
    ('Λ', "Lambda"),
    ('Ξ', "Xi"),
    ('Π', "Pi"),
    ('Σ', "Sigma"),
    ('Υ', "Upsilon"),
    ('Φ', "Phi"),
    ('Ψ', "Psi"),
    ('Ω', "Omega"),
];

/// A word of prose that is a symbol written without `$` (`m`, `Ω`, `M_F`, `**n**`, `ρ_0`,
/// `F^*`, `\mathbf{e}_1`), as LaTeX; `None` for a word of English.
pub(super) fn bare_symbol(word: &str) -> Option<String> {
    let (core, bold) = match word.strip_prefix("**") {
        Some(w) => {
            let end = w.find("**")?;
            (format!("{}{}", &w[..end], &w[end + 2..]), true)
        }
        None => (word.to_string(), false),
    };
    let mut chars = core.chars().peekable();
    let first = chars.next()?;
    let mut tex = if let Some((_, name)) = GREEK.iter().find(|(c, _)| *c == first) {
        format!("\\{name} ")
    } else if first.is_ascii_alphabetic() {
        first.to_string()
    } else if first == '\\' {
        // `\mathbf{e}`: a font command on one letter
        let rest: String = chars.by_ref().take_while(|c| *c != '}').collect();
        let (cmd, arg) = rest.split_once('{')?;
        if !["mathbf", "boldsymbol", "vec", "bm"].contains(&cmd) || arg.chars().count() != 1 {
            return None;
        }
        format!("\\{cmd}{{{arg}}}")
    } else {
        return None;
    };
    if bold {
        tex = format!("\\mathbf{{{}}}", tex.trim());
    }
    // scripts: `_x`, `_{..}`, `^*`, `^{..}`
    while let Some(&c) = chars.peek() {
        if c != '_' && c != '^' {
            return None;
        }
        chars.next();
        let script: String = match chars.next()? {
            '{' => {
                let inner: String = chars.by_ref().take_while(|c| *c != '}').collect();
                format!("{{{inner}}}")
            }
            s if s.is_ascii_alphanumeric() || s == '*' => s.to_string(),
            s => GREEK
                .iter()
                .find(|(g, _)| *g == s)
                .map(|(_, n)| format!("{{\\{n}}}"))?,
        };
        tex.push(c);
        tex.push_str(&script);
    }
    Some(tex)
}

/// The words that may open a clause naming a symbol written without `$` ("where m is").
const CONTEXT: &[&str] = &[
    "where", "and", "let", "letting", "here", "while", "with", "then", "whereas", "also", "if",
    "since", "now",
];

/// Symbols written without `$` and the description that follows them ("where m is the mass,
/// J is the central inertia tensor", "Let Q and M_Q denote ..."): for each, the byte offset of
/// its first symbol in `text`, the symbols as LaTeX, and the text after them (verb first).
pub(super) fn bare_lists(text: &str) -> Vec<(usize, Vec<String>, &str)> {
    let mut words: Vec<(usize, &str)> = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices() {
        match (c.is_whitespace(), start) {
            (true, Some(s)) => {
                words.push((s, &text[s..i]));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        words.push((s, &text[s..]));
    }
    let mut out = Vec::new();
    for (i, (at, w)) in words.iter().enumerate() {
        let verb = w.to_ascii_lowercase();
        if ![
            "is",
            "are",
            "denote",
            "denotes",
            "represents",
            "represent",
            "stands",
            "stand",
        ]
        .contains(&verb.as_str())
            || i == 0
        {
            continue;
        }
        let mut list: Vec<(usize, String)> = Vec::new();
        let mut j = i;
        let mut opened = false;
        while j > 0 {
            let (off, word) = words[j - 1];
            let trimmed = word.trim_end_matches(',');
            // a comma after the list's last symbol ends it ("where V, and V_n are"; not "mass, J is")
            if trimmed.len() < word.len() && list.is_empty() {
                break;
            }
            let inner = trimmed.trim_start_matches('(');
            if inner.len() < trimmed.len() {
                opened = true;
            }
            if trimmed == "and" && !list.is_empty() {
                j -= 1;
                continue;
            }
            match bare_symbol(inner) {
                Some(tex) => {
                    list.push((off, tex));
                    j -= 1;
                    if opened {
                        break;
                    }
                }
                None => break,
            }
        }
        // the list must start a clause: after a context word, a punctuation mark, or a "("; else
        // its tail that does ("the centre of mass G and Ω is": Ω alone)
        let mut list: Vec<(usize, String)> = list.into_iter().rev().collect();
        let opens_clause = |k: usize| {
            k == 0
                || words.get(k - 1).is_some_and(|(_, p)| {
                    let p = p.to_ascii_lowercase();
                    CONTEXT.contains(&p.as_str()) || p.ends_with([',', '.', ';', ':', '('])
                })
        };
        let word_index = |off: usize| words.iter().position(|(o, _)| *o == off).unwrap_or(0);
        while let Some((off, _)) = list.first() {
            let k = word_index(*off);
            if words[k].1.starts_with('(') || opens_clause(k) {
                break;
            }
            list.remove(0);
        }
        if list.is_empty() {
            continue;
        }
        out.push((
            list[0].0,
            list.into_iter().map(|(_, t)| t).collect(),
            &text[*at..],
        ));
    }
    out
}
