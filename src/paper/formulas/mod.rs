//! Reading the math of papers as written: LaTeX into the same [`Expr`] as the text parser.
//!
//! The papers (`../shared/seeds/*.txt`, and most papers a referee checks) print their formulas
//! in LaTeX; a claim should judge what the paper prints, not a retyped copy. This reader covers
//! the math of such papers: `\frac{}{}` (`\dfrac`, `\tfrac`), `\sqrt{}`, `\sqrt[n]{}`, `^{}`,
//! `_{}`, `\left( \right)` (and `[ ]`, `\{ \}`, `| |` as an absolute value), `\cdot`, `\times`,
//! implicit products (`E \frac{m^{2}}{a^{3}}`, `2 a b`), Greek letters (`\eta` -> `eta`), `\pi`,
//! `\sin \cos \tan \exp \ln` with and without parentheses (`\tan \theta`, `\sin^{2}\phi`),
//! `e^{...}` as `exp` (when the exponent has a symbol), `k!`, `\sum_{i=0}^{k}`, `\int_{a}^{b}
//! ... d x` (an integral over a region, `\int ... d\sigma`, `\iint`, as an opaque symbol), `\frac{\partial w}{\partial t}`, accents (`\tilde{E}` -> `Et`, `\hat` -> `h`,
//! `\bar` -> `b`, `\dot{z}` -> `zd`, `\ddot{z}` -> `zdd`), `\mathrm{}`, `\operatorname{}`,
//! `\mathbf{}`, spacing (`\,`, `\;`, `\quad`), rows of `align`/`aligned`/`gather` with `&` and
//! `\\`, `\tag{}`, and chains of relations (`a = b = 0`, `\le`, `\approx`).
//!
//! Names: a subscript joins its name (`A_{5}` -> `A5`, `m_{s}` -> `ms`, `\rho_{0}` -> `rho0`),
//! a prime adds `p` (`t^{\prime}` -> `tp`). A name applied to arguments (`w(x, y, t)`, `P(t)`,
//! `\tilde{L}(\alpha)`) is an opaque symbol named by its text (`{w(x,y,t)}`), unless a
//! [`TexSymbols`] table maps the spelling to a symbol (`"z(t)" = "z"`, `"\\tilde{E}" = "Et"`); a
//! name before a compound argument (`2(v+1)`, `a(b + c)`) is a product.
//!
//! Written by hand: no crate reads LaTeX math into an expression tree of our own (the crates
//! that parse LaTeX render it, or parse whole documents); the grammar is small and its errors
//! must name the column and the construct that is missing.

//!
//! Here the reader's types and entry points; apart: `lex` (tokens), `reader` (building
//! expressions) and `display` (environments, rows and their tags).

mod lex;
pub mod matrix;
mod reader;

use crate::algebra::expr::Expr;
use crate::algebra::poly::Q;
use lex::lex;
use reader::Reader;

/// Spellings mapped to symbols, longest first (a file's `[tex_symbols]`). A target that is
/// not a bare name is a formula of the text language (`"E(k)" = "ellipe(k)"`): the spelling
/// reads as that formula.
#[derive(Clone, Debug, Default)]
pub struct TexSymbols(
    pub(super) Vec<(String, String)>,
    /// The names the paper applies as functions (`x(t)` somewhere): applied wherever they
    /// stand before parentheses (`x(t + T)`).
    pub(super) std::collections::BTreeSet<String>,
    /// The increment letters (`Delta`, `delta`) the paper also uses alone (`\delta = ..`,
    /// `\Delta^2 w`, `L(\delta)`): there `\delta t` is a product, not an increment.
    pub(super) std::collections::BTreeSet<String>,
    /// The names the paper's words call a Dirac delta ("$\delta(x - a/2)$ is the Dirac delta
    /// function"): applied to one argument, the unit of its inverse.
    pub(super) std::collections::BTreeSet<String>,
);

impl TexSymbols {
    /// A table from `(spelling, symbol or formula)` pairs.
    pub fn new(pairs: impl IntoIterator<Item = (String, String)>) -> Self {
        let mut v: Vec<(String, String)> = pairs.into_iter().collect();
        v.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.0.cmp(&b.0)));
        TexSymbols(
            v,
            Default::default(),
            Default::default(),
            Default::default(),
        )
    }

    /// This table with more pairs.
    pub fn with(&self, more: impl IntoIterator<Item = (String, String)>) -> Self {
        let mut t = TexSymbols::new(self.0.iter().cloned().chain(more));
        t.1 = self.1.clone();
        t.2 = self.2.clone();
        t.3 = self.3.clone();
        t
    }

    /// This table with the names the paper calls Dirac deltas.
    pub fn with_dirac(&self, names: impl IntoIterator<Item = String>) -> Self {
        let mut t = self.clone();
        t.3.extend(names);
        t
    }

    /// The targets that are formulas, parsed (a target that does not parse stays a symbol
    /// with an odd name, which the claim's reader refuses naming it).
    pub(super) fn formulas(&self) -> Vec<(String, Expr)> {
        self.0
            .iter()
            .filter(|(_, t)| !is_name(t))
            .filter_map(|(_, t)| crate::algebra::expr::parse(t).ok().map(|e| (t.clone(), e)))
            .collect()
    }
}

/// The increment letters (`\Delta`, `\delta`) that stand alone somewhere in `tex`: followed by
/// no name (`\delta =`, `\delta^{3/2}`, `(\delta)`, `\Delta^2 w`).
pub(crate) fn lone_increment_letters(tex: &str) -> Vec<String> {
    let mut out = Vec::new();
    for letter in ["Delta", "delta"] {
        let pat = format!("\\{letter}");
        let mut rest = tex;
        while let Some(k) = rest.find(&pat) {
            rest = &rest[k + pat.len()..];
            if rest.starts_with(|c: char| c.is_ascii_alphabetic()) {
                continue;
            }
            let next = rest.trim_start().chars().next();
            let alone = match next {
                None => true,
                Some(c) => "=^)],+-<>&}/;|.!".contains(c) || rest.trim_start().starts_with("\\\\"),
            };
            if alone && !out.iter().any(|o| o == letter) {
                out.push(letter.to_string());
            }
        }
    }
    out
}

/// A bare symbol name (letters, digits, `_`, not starting with a digit).
fn is_name(t: &str) -> bool {
    t.chars()
        .next()
        .is_some_and(|c| c.is_alphabetic() || c == '_')
        && t.chars().all(|c| c.is_alphanumeric() || c == '_')
}

/// Why a piece of LaTeX could not be read: the column (1-based, in characters of the piece
/// read) and the construct the reader lacks or expected there.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("column {column}: {construct} (at `{found}`)")]
pub struct TexError {
    /// 1-based column in the LaTeX read.
    pub column: usize,
    /// The construct that is missing or expected.
    pub construct: String,
    /// What stands there.
    pub found: String,
}

/// A relation of a formula: `sides[0] rels[0] sides[1] ...`.
#[derive(Clone, Debug, PartialEq)]
pub struct TexRelation {
    /// The sides, left to right.
    pub sides: Vec<Expr>,
    /// The relations between them (`=`, `<`, `<=`, `>`, `>=`, `<<`, `>>`, `~` for `\approx`,
    /// `!=`, `propto`, `sim`).
    pub rels: Vec<&'static str>,
    /// The dotted names and increments the relation holds, each with its base and order
    /// (`("xd", "x", 1)` for `\dot{x}`, `("Deltat", "t", 0)` for `\Delta t`).
    pub links: Vec<(String, String, u32)>,
}

/// One row of a display: its `\tag`, its LaTeX and its relations (rows hold several, separated
/// by `,`, `;` or `\quad` at the top level).
#[derive(Clone, Debug)]
pub struct TexRow {
    /// The row's `\tag{}` (without parentheses), if any.
    pub tag: Option<String>,
    /// The row's LaTeX (tag removed).
    pub tex: String,
    /// Each relation read, or why not.
    pub relations: Vec<Result<TexRelation, TexError>>,
}

/// Reads one formula (no relation).
pub fn read_formula(tex: &str, syms: &TexSymbols) -> Result<Expr, TexError> {
    let rel = read_relation(tex, syms)?;
    if rel.sides.len() != 1 {
        return Err(TexError {
            column: 1,
            construct: "a formula without a relation".into(),
            found: tex.into(),
        });
    }
    Ok(rel
        .sides
        .into_iter()
        .next()
        .unwrap_or(Expr::Num(Q::from_integer(0.into()))))
}

/// Reads one relation (`a = b`, `a \le b = c`) or a bare formula.
pub fn read_relation(tex: &str, syms: &TexSymbols) -> Result<TexRelation, TexError> {
    let toks = lex(tex, syms);
    let mut rel = Reader::new(&toks, &syms.1, &syms.2, &syms.3).relation()?;
    let formulas = syms.formulas();
    if !formulas.is_empty() {
        let lookup = |s: &str| {
            formulas
                .iter()
                .find(|(t, _)| t == s)
                .map(|(_, e)| e.clone())
        };
        for side in &mut rel.sides {
            *side = side.substitute(&lookup);
        }
    }
    Ok(rel)
}

#[cfg(test)]
mod lex_tests;
#[cfg(test)]
mod tests;
