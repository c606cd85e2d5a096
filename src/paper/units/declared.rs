//! The units an audit starts from: those declared in a units file (`[symbols]`,
//! `[audit_symbols]`, `[tex_symbols]` of any TOML file, a claims file included), then those the
//! paper's words give ([`crate::paper::words`]), each with its source.

use crate::algebra::units::Unit;
use crate::paper::PaperError;
use crate::paper::words::{WordUnit, Words};
use std::collections::BTreeMap;
use std::path::Path;

/// The declared units and LaTeX spellings an audit starts from.
#[derive(Clone, Debug, Default)]
pub struct Units {
    /// Declared units by symbol.
    pub symbols: BTreeMap<String, Unit>,
    /// The same as written (for the claims file `init` prints).
    pub texts: BTreeMap<String, String>,
    /// LaTeX spellings mapped to symbols.
    pub tex_symbols: BTreeMap<String, String>,
    /// The units of [`Units::symbols`] that the paper's words gave (issue 52), with their
    /// sources.
    pub words: BTreeMap<String, WordUnit>,
    /// The units the words gave symbols that are declared: the declared unit is used.
    pub overridden: BTreeMap<String, WordUnit>,
    /// The names the words call a Dirac delta (read as the inverse of their argument).
    pub dirac: std::collections::BTreeSet<String>,
    /// The lines where the paper's sections open (a mention in passing names its symbol in
    /// its section only).
    pub sections: Vec<usize>,
    /// The spans of lines `[from, to)` the paper says are dimensionless: no unit of the words
    /// holds there, and the symbols of their relations are their own.
    pub dimensionless: Vec<(usize, usize)>,
    /// The lines where a thesis's numbered chapters open: each chapter's letters are its own.
    pub chapters: Vec<usize>,
}

/// The first line of the span of `spans` (each `[from, to)`) that holds `line`.
pub fn span_of(spans: &[(usize, usize)], line: usize) -> Option<usize> {
    spans
        .iter()
        .find(|&&(a, b)| a <= line && line < b)
        .map(|&(a, _)| a)
}

impl Units {
    /// These units with those the paper's words give: a symbol the words name gets their
    /// unit unless it is declared here (the declared unit overrides, and the audit says so).
    pub fn with_words(mut self, words: Words) -> Units {
        self.dirac.extend(words.dirac);
        self.sections = words.sections;
        self.dimensionless = words.dimensionless;
        self.chapters = words.chapters;
        for (name, w) in words.units {
            // a unit from the words of a dimensionless part holds nowhere
            if span_of(&self.dimensionless, w.line).is_some() {
                continue;
            }
            if self.symbols.contains_key(&name) {
                self.overridden.insert(name, w);
            } else {
                self.symbols.insert(name.clone(), w.unit);
                self.words.insert(name, w);
            }
        }
        self
    }
}

/// Reads a units file: `[symbols]` (and `[tex_symbols]`) of any TOML file, a claims file
/// included; every unit checked, a bad one an error naming the file and the symbol.
pub fn read_units(path: &Path) -> Result<Units, PaperError> {
    let bad = |message: String| PaperError::BadFile {
        path: path.to_path_buf(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it: {e}")))?;
    let table: toml::Table = toml::from_str(&text).map_err(|e| bad(format!("not TOML: {e}")))?;
    let mut out = Units::default();
    let section = |name: &str| -> Result<BTreeMap<String, String>, PaperError> {
        match table.get(name) {
            None => Ok(BTreeMap::new()),
            Some(toml::Value::Table(t)) => t
                .iter()
                .map(|(k, v)| {
                    v.as_str()
                        .map(|s| (k.clone(), s.to_string()))
                        .ok_or_else(|| bad(format!("{name}.{k} = {v}: a string (\"m/s\")")))
                })
                .collect(),
            Some(other) => Err(bad(format!("`{name}` = {other}: a table [{name}]"))),
        }
    };
    out.texts = section("symbols")?;
    out.texts.extend(section("audit_symbols")?);
    out.tex_symbols = section("tex_symbols")?;
    if out.texts.is_empty() {
        return Err(bad(
            "no [symbols]: the units file declares the unit of at least one symbol (name = \"unit\")"
                .into(),
        ));
    }
    for (k, u) in &out.texts {
        let unit = Unit::parse(u).map_err(|m| bad(format!("symbols.{k} = \"{u}\": {m}")))?;
        out.symbols.insert(k.clone(), unit);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_line_is_in_a_span_from_its_first_line_to_before_its_last() {
        let spans = [(3, 5), (9, usize::MAX)];
        let got: Vec<Option<usize>> = [2, 3, 4, 5, 8, 9, 100]
            .iter()
            .map(|&l| super::span_of(&spans, l))
            .collect();
        assert_eq!(
            got,
            vec![None, Some(3), Some(3), None, None, Some(9), Some(9)]
        );
    }
}
