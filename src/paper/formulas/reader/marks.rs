//! Marks written after a formula that keep its unit: an evaluation bar (`F \big|_{a}^{b}`,
//! `\left. F \right|_{x=0}`), a subscript on a bracket (`(\partial V / \partial q)_0`,
//! `[\mathbf{D}]_{ab}`), a conjugate or transpose (`[P]^*`, `u^\dagger`, `A^\top`); and the
//! operand an operator stands without (`\frac{\partial}{\partial r} = \nabla`), read as
//! [`OPERAND`].

use super::super::lex::{Tok, accent_suffix, greek, is_space};
use super::{R, Reader, mul};
use crate::algebra::expr::{Calc, Expr};
use crate::algebra::units::OPERAND;

/// A letter, Latin or Greek.
fn letter(t: &Tok) -> bool {
    match t {
        Tok::Ch(c) => c.is_ascii_alphabetic(),
        Tok::Cmd(c) => greek(c).is_some(),
        _ => false,
    }
}

/// `e` with a mark that keeps its unit ([`Calc::Marked`]).
pub(super) fn marked(e: Expr) -> Expr {
    Expr::Calc(Calc::Marked, Box::new(e), String::new(), vec![])
}

impl Reader<'_> {
    /// The index of the first token from `pos + k` on that is no space.
    fn past_space(&self, mut k: usize) -> usize {
        while self.at(k).is_some_and(is_space) {
            k += 1;
        }
        k
    }

    /// Whether an evaluation bar stands here: `|` (after a size such as `\bigg`, or `\vert`)
    /// followed by a script, outside an absolute value.
    pub(super) fn evaluation_bar(&self) -> Option<usize> {
        if self.in_abs > 0 {
            return None;
        }
        let k = self.past_space(0);
        let bar = match self.at(k) {
            Some(Tok::Ch('|')) => true,
            Some(Tok::Cmd(c)) => c == "vert" || c == "rvert",
            _ => false,
        };
        (bar && matches!(self.at(k + 1), Some(Tok::Ch('_' | '^')))).then_some(k + 1)
    }

    /// Past the scripts of an evaluation bar or a bracket (`_{x=0}^{1}`), which name where the
    /// formula is taken: the formula keeps its unit.
    pub(super) fn skip_scripts(&mut self) -> R<()> {
        while matches!(self.peek(), Tok::Ch('_' | '^')) {
            self.bump();
            self.skip_group()?;
        }
        Ok(())
    }

    /// `^*`, `^\dagger`, `^{\top}`, `^{\mathrm{T}}` after a formula that is no name: how many
    /// tokens the mark takes (a conjugate or a transpose has the unit of what it marks).
    pub(super) fn conjugate_mark(&self) -> Option<usize> {
        let mark = |t: Option<&Tok>| match t {
            Some(Tok::Ch('*')) => true,
            Some(Tok::Cmd(c)) => {
                matches!(c.as_str(), "dagger" | "ast" | "star" | "top" | "intercal")
            }
            _ => false,
        };
        if mark(self.at(1)) {
            return Some(2);
        }
        // `(\partial T / \partial \dot q)^+`, `0^-`, `S^{'}`: the side or the instant taken, the
        // quantity's unit (a bare sign before an operand, `x^-1`, is TeX's `x^{-}1`: no mark)
        let sign = |t: Option<&Tok>| matches!(t, Some(Tok::Ch('+' | '-' | '\'')));
        let operand = matches!(
            self.at(2),
            Some(Tok::Num(_) | Tok::Sym(_) | Tok::Open | Tok::Cmd(_))
        ) || matches!(self.at(2), Some(Tok::Ch(c)) if c.is_alphanumeric() || *c == '(');
        if sign(self.at(1)) && !operand {
            return Some(2);
        }
        if self.at(1) != Some(&Tok::Open) {
            return None;
        }
        if (mark(self.at(2)) || sign(self.at(2))) && self.at(3) == Some(&Tok::Close) {
            return Some(4);
        }
        // `^{\mathrm{T}}`, `^{\rm T}`: a transpose
        let font = matches!(self.at(2), Some(Tok::Cmd(c)) if matches!(c.as_str(), "mathrm" | "rm" | "mathsf"));
        let t = |k: usize| matches!(self.at(k), Some(Tok::Ch('T' | 'H')));
        match (font, self.at(3)) {
            (true, Some(Tok::Open)) if t(4) && self.at(5) == Some(&Tok::Close) => {
                (self.at(6) == Some(&Tok::Close)).then_some(7)
            }
            (true, _) if t(3) && self.at(4) == Some(&Tok::Close) => Some(5),
            _ => None,
        }
    }

    /// Whether `^{..}` here holds a comma at its top level (`p^{a,b}`, `x^{-,k}`): a label of
    /// the name, not a power.
    pub(super) fn comma_script(&self) -> bool {
        if self.at(1) != Some(&Tok::Open) {
            return false;
        }
        let Some(close) = self.group_close(self.pos + 1) else {
            return false;
        };
        let mut depth = 0usize;
        self.toks[self.pos + 1..close].iter().any(|(t, _)| {
            match t {
                Tok::Open => depth += 1,
                Tok::Close => depth = depth.saturating_sub(1),
                _ => {}
            }
            depth == 1 && *t == Tok::Ch(',')
        })
    }

    /// A braced subscript read as a label whatever it holds: its letters and digits (Greek
    /// letters and commands by name), the reader past its `}`; `None` when no group stands
    /// here or it holds no letter.
    pub(super) fn opaque_label(&mut self) -> Option<String> {
        if *self.peek() != Tok::Open {
            return None;
        }
        let close = self.group_close(self.pos)?;
        let mut text = String::new();
        for (t, _) in &self.toks[self.pos + 1..close] {
            match t {
                // a separator or a relation sign is no label's (`p_{1 ;}`, `x_{a=b}`)
                Tok::Ch(';' | '=' | '<' | '>' | '&') => return None,
                Tok::Ch(c) if c.is_ascii_alphanumeric() => text.push(*c),
                Tok::Num(n) => text.push_str(n),
                Tok::Cmd(c) if greek(c).is_some() => text.push_str(greek(c).unwrap_or_default()),
                _ => {}
            }
        }
        if text.is_empty() {
            return None;
        }
        self.pos = close + 1;
        Some(text)
    }

    /// Whether `^{..}` here ends in a sign after a letter (`R^{M-}`, `r^{s+}`): a label.
    pub(super) fn signed_label(&self) -> bool {
        if self.at(1) != Some(&Tok::Open) {
            return false;
        }
        let Some(close) = self.group_close(self.pos + 1) else {
            return false;
        };
        close >= self.pos + 4
            && matches!(self.toks[close - 1].0, Tok::Ch('+' | '-'))
            && matches!(self.toks[close - 2].0, Tok::Ch(c) if c.is_ascii_alphabetic())
    }

    /// `_{;k}`, `_{,\mathbf{k}}` after a bracket: the derivative's variable (a letter or a
    /// Greek letter, in a font or not) and how many tokens the subscript takes.
    pub(super) fn derivative_subscript(&self) -> Option<(String, usize)> {
        if self.at(1) != Some(&Tok::Open) || !matches!(self.at(2), Some(Tok::Ch(';' | ','))) {
            return None;
        }
        let close = self.group_close(self.pos + 1)?;
        let mut name = String::new();
        // the variable, then a component label (`_{;k^{\mathrm{c}}}`: the c-th component of k)
        let mut label = false;
        for (t, _) in &self.toks[self.pos + 3..close] {
            match t {
                Tok::Ch('^') if !name.is_empty() => label = true,
                Tok::Ch(c) if c.is_ascii_alphabetic() && (name.is_empty() || label) => {
                    name.push(*c)
                }
                Tok::Cmd(c) if greek(c).is_some() && (name.is_empty() || label) => {
                    name.push_str(greek(c).unwrap_or_default())
                }
                Tok::Cmd(c) if accent_suffix(c) == Some("") => {}
                Tok::Open | Tok::Close => {}
                _ => return None,
            }
        }
        (!name.is_empty()).then_some((name, close + 1 - self.pos))
    }

    /// Whether `^{..}` here is a label of letters (`T^{v\ell}`, `\chi^{zxx}`, `\omega^{\Sigma}`):
    /// two or more letters and nothing else, or one capital Greek letter; a power of letters
    /// (`x^{n}`, `x^{\alpha}`) is one letter.
    pub(super) fn letters_label(&self) -> bool {
        let capital_greek = |t: &Tok| matches!(t, Tok::Cmd(c) if greek(c).is_some() && c.starts_with(|c: char| c.is_ascii_uppercase()));
        // `\omega^\Sigma`, unbraced
        if self.at(1).is_some_and(capital_greek) {
            return true;
        }
        if self.at(1) != Some(&Tok::Open) {
            return false;
        }
        let Some(close) = self.group_close(self.pos + 1) else {
            return false;
        };
        let inside = &self.toks[self.pos + 2..close];
        match inside {
            [one] => capital_greek(&one.0),
            [] => false,
            many => many.iter().all(|(t, _)| letter(t)),
        }
    }

    /// Whether `^{..}_` stands here: a braced script of letters (and digits), a subscript
    /// right after it.
    pub(super) fn label_then_subscript(&self) -> bool {
        if self.at(1) != Some(&Tok::Open) {
            return false;
        }
        let Some(close) = self.group_close(self.pos + 1) else {
            return false;
        };
        let inside = &self.toks[self.pos + 2..close];
        matches!(self.toks.get(close + 1), Some((Tok::Ch('_'), _)))
            && inside.iter().any(|(t, _)| letter(t))
            && inside
                .iter()
                .all(|(t, _)| letter(t) || matches!(t, Tok::Num(_)) || is_space(t))
    }

    /// Whether an operator here stands without an operand: what follows ends a term.
    pub(super) fn no_operand(&self) -> bool {
        let k = self.past_space(0);
        match self.at(k) {
            None | Some(Tok::End | Tok::Close) => true,
            Some(Tok::Ch(c)) => {
                matches!(c, '=' | '+' | '-' | ')' | ']' | ',' | ';' | '<' | '>' | '&')
            }
            Some(Tok::Cmd(c)) => matches!(
                c.as_str(),
                "right"
                    | "le"
                    | "leq"
                    | "ge"
                    | "geq"
                    | "equiv"
                    | "approx"
                    | "quad"
                    | "qquad"
                    | "\\"
            ),
            _ => false,
        }
    }

    /// The operand an operator stands without (`\frac{\partial}{\partial x} = \nabla`): the
    /// operator equation holds for any operand, the same on every side, so the operand counts
    /// as a pure number and the operators' units compare.
    pub(super) fn operand(&self) -> Expr {
        Expr::Sym(OPERAND.into())
    }

    /// `\langle a | b \rangle`, `\langle a | H | b \rangle`, `\langle a \vert b \rangle`: a
    /// bracket of states (a product of its parts' units), read after the average and the
    /// scalar product did not fit; closed by `\rangle` (or `\right|` of a bra).
    pub(super) fn bracket_of_states(&mut self, close: &str) -> R<Expr> {
        self.in_abs += 1;
        let e = self.bracket_parts(close);
        self.in_abs -= 1;
        e
    }

    fn bracket_parts(&mut self, close: &str) -> R<Expr> {
        let mut e = self.expr()?;
        loop {
            self.skip_space();
            match self.peek() {
                Tok::Ch('|' | ',') => {
                    self.bump();
                }
                Tok::Cmd(c) if matches!(c.as_str(), "vert" | "mid") => {
                    self.bump();
                }
                _ => break,
            }
            self.skip_space();
            if matches!(self.peek(), Tok::Cmd(c) if c == close || c == "right") {
                break;
            }
            e = mul(e, self.expr()?);
        }
        self.skip_space();
        if matches!(self.peek(), Tok::Cmd(c) if c == "right") {
            self.bump();
            if matches!(self.peek(), Tok::Ch('|' | '.')) {
                self.bump();
                return Ok(e);
            }
        }
        self.expect(Tok::Cmd(close.into()), &format!("`\\{close}`"))?;
        Ok(e)
    }
}
