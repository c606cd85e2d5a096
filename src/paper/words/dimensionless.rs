//! A text that says it works in dimensionless quantities (issue 65): the sentences that say so
//! and the spans of lines they cover, where no unit of the words holds and the relations'
//! letters are their own.

/// The words that say a text works in dimensionless quantities: a non-dimensionalisation, units
/// chosen so that a quantity is 1, quantities, variables, a form or equations called
/// non-dimensional.
pub(super) fn says_dimensionless(line: &str) -> bool {
    let l = line
        .to_lowercase()
        .replace("non dimension", "non-dimension");
    let scaled = [
        "non-dimensional",
        "nondimensional",
        "dimensionless",
        "scaled",
        "normalised",
        "normalized",
    ];
    let what = [
        "form",
        "variable",
        "quantities",
        "equation",
        "problem",
        "units",
        "system",
        "coordinate",
        "parameters",
    ];
    l.contains("non-dimensionali")
        || l.contains("nondimensionali")
        || [
            "units so that",
            "units such that",
            "units in which",
            "units where",
        ]
        .iter()
        .any(|w| l.contains(w))
        || scaled.iter().any(|a| {
            // the noun within the next three words: "non-dimensional Reynolds equation"
            l.match_indices(a).any(|(k, _)| {
                l[k + a.len()..]
                    .split_whitespace()
                    .take(3)
                    .any(|word| what.iter().any(|w| word.starts_with(w)))
            }) || ["quantities are ", "variables are ", "all are "]
                .iter()
                .any(|v| l.contains(&format!("{v}{a}")))
        })
}

/// The spans of lines `[from, to)` that a paper says are dimensionless: from the first line of a
/// section (0 before the first heading) that [says so](says_dimensionless), or the first of two
/// lines of one section that call something non-dimensional, to the section's end (`usize::MAX`
/// for the last). `sections` as [`section_starts`](super::section_starts) gives them.
pub fn dimensionless_spans(text: &str, sections: &[usize]) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = Vec::new();
    let lines: Vec<&str> = text.lines().collect();
    let mut starts = vec![1];
    starts.extend(sections.iter().copied());
    starts.dedup();
    for (k, &from) in starts.iter().enumerate() {
        let to = starts.get(k + 1).copied().unwrap_or(usize::MAX);
        let span = &lines[(from - 1).min(lines.len())..(to - 1).min(lines.len())];
        let mention = |l: &&str| {
            let l = l.to_lowercase();
            [
                "non-dimensional",
                "nondimensional",
                "non dimensional",
                "dimensionless",
            ]
            .iter()
            .any(|a| l.contains(a))
        };
        let first = span.iter().position(|l| says_dimensionless(l)).or_else(|| {
            let m: Vec<usize> = (0..span.len()).filter(|&j| mention(&span[j])).collect();
            (m.len() >= 2).then(|| m[0])
        });
        if let Some(j) = first {
            out.push((from + j, to));
        }
    }
    out
}

/// Whether the paragraph of the prose `p` around `at` calls a quantity of `head`'s kind
/// *specific* ("the specific orbital energy $\varepsilon$ ... using the kinetic energy
/// $\varepsilon_k$"): per unit mass there, so a plain `head` in the same paragraph is the
/// specific one too and gives no unit.
pub(super) fn specific_in_paragraph(p: &str, at: usize, head: &str) -> bool {
    let start = p[..at].rfind("\n\n").map_or(0, |k| k + 2);
    let end = p[at..].find("\n\n").map_or(p.len(), |k| at + k);
    let words: Vec<String> = p[start..end]
        .split(|c: char| !c.is_alphanumeric() && c != '-')
        .filter(|w| !w.is_empty())
        .map(str::to_lowercase)
        .collect();
    let head = head.to_lowercase();
    words
        .iter()
        .enumerate()
        .any(|(k, w)| w == "specific" && words[k + 1..].iter().take(3).any(|x| *x == head))
}
