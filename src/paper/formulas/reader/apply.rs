//! Names applied to arguments: `w(x, y, t)` and `P(t)` (opaque symbols with the unit of their
//! function), a name the paper applies elsewhere applied to formulas (`x(t + T)`, `U(L/c)`,
//! `\omega^2(t)`), pairs `(a, b)`, and matrices inside a formula (opaque, a unit of their own).

use super::super::lex::{Tok, accent_suffix, describe, greek, is_space};
use super::{R, Reader, one, power};
use crate::algebra::expr::{Expr, Op};
use crate::paper::formulas::TexError;

impl Reader<'_> {
    /// `(a, b)` (a scalar product of vectors, a pair): an opaque symbol named by its parts.
    pub(super) fn tuple(&mut self, first: Expr) -> R<Expr> {
        self.skip_space();
        if !matches!(self.peek(), Tok::Ch(',' | ';')) {
            return Ok(first);
        }
        let mut parts = vec![first.to_string()];
        // `(q, t; q_0, t_0)`: a semicolon separates as a comma does
        while matches!(self.peek(), Tok::Ch(',' | ';')) {
            self.bump();
            parts.push(self.expr()?.to_string());
            self.skip_space();
        }
        Ok(Expr::Sym(format!("{{({})}}", parts.join(", "))))
    }

    /// A name, or a name applied to arguments (`w(x, y, t)`, `P(t)`): an opaque symbol. A
    /// name the paper applies elsewhere is applied to any arguments (`x(t + T)`, `U(L/c)`),
    /// also after a power (`\omega^2(t)`: the square of `\omega(t)`).
    pub(super) fn maybe_applied(&mut self, name: String) -> R<Expr> {
        if self.functions.contains(&name) && *self.peek() == Tok::Ch('^') && self.power_then_paren()
        {
            self.bump();
            let p = self.group()?;
            let applied = self.maybe_applied(name)?;
            return Ok(power(applied, p));
        }
        if let Some(e) = self.indexed(&name) {
            return Ok(e);
        }
        let open = match (self.peek(), self.toks.get(self.pos + 1)) {
            (Tok::Ch('('), _) => 1,
            (Tok::Cmd(l), Some((Tok::Ch('('), _))) if l == "left" => 2,
            _ => return Ok(Expr::Sym(name)),
        };
        if let Some(e) = self.applied_to_formulas(&name, open)? {
            return Ok(e);
        }
        if let Some(e) = self.evaluated_at(&name, open) {
            return Ok(e);
        }
        // the arguments: names or numbers separated by commas, at one level
        let mut k = self.pos + open;
        let mut args = Vec::new();
        let mut cur = String::new();
        loop {
            match self.toks.get(k).map(|t| &t.0) {
                Some(Tok::Ch(c)) if c.is_ascii_alphanumeric() || *c == '\'' => cur.push(*c),
                Some(Tok::Num(n)) => cur.push_str(n),
                Some(Tok::Ch('_')) => cur.push('_'),
                Some(Tok::Open | Tok::Close) => {}
                // a font on an argument (`\mathbf{x}_p`) is no part of its name here
                Some(Tok::Cmd(c)) if accent_suffix(c) == Some("") => {}
                Some(Tok::Cmd(c)) if greek(c).is_some() || c == "prime" => {
                    cur.push_str(greek(c).unwrap_or("p"))
                }
                Some(Tok::Cmd(c)) if c == "parallel" || c == "perp" => cur.push_str(&c[..3]),
                // `h(\cdot, t)`: a placeholder for the variable left free
                // (`\sim` too: "we omit the arguments by writing (\sim)")
                Some(Tok::Cmd(c))
                    if (c == "cdot" || c == "sim")
                        && cur.is_empty()
                        && matches!(
                            self.toks.get(k + 1).map(|t| &t.0),
                            Some(Tok::Ch(',' | ')'))
                        ) =>
                {
                    cur.push_str(c)
                }
                Some(Tok::Cmd(c)) if is_space(&Tok::Cmd(c.clone())) => {}
                // `S(q_0, t_0; q, t)`: a semicolon separates arguments as a comma does
                Some(Tok::Ch(',' | ';')) => args.push(std::mem::take(&mut cur)),
                Some(Tok::Ch(')')) => {
                    args.push(cur);
                    break;
                }
                Some(Tok::Cmd(c)) if c == "right" => {}
                _ => return Ok(Expr::Sym(name)),
            }
            k += 1;
        }
        if args.iter().any(String::is_empty) {
            return Ok(Expr::Sym(name));
        }
        self.pos = k + 1;
        Ok(Expr::Sym(format!("{{{name}({})}}", args.join(","))))
    }

    /// `y[k]`, `u[k-m]`, `y[N]`: a sequence at an index, the bracket right after the name and
    /// holding index arithmetic only (letters, whole numbers, `+`, `-`): an opaque symbol named
    /// by its text, as a function's value is, not the name times the bracket.
    fn indexed(&mut self, name: &str) -> Option<Expr> {
        let (open, col) = self.toks.get(self.pos)?;
        let (_, before) = self.toks.get(self.pos.checked_sub(1)?)?;
        if *open != Tok::Ch('[') || *col != before + 1 {
            return None;
        }
        let mut k = self.pos + 1;
        let mut index = String::new();
        loop {
            match &self.toks.get(k)?.0 {
                Tok::Ch(']') => break,
                Tok::Ch(c) if c.is_ascii_alphabetic() || *c == '+' || *c == '-' => index.push(*c),
                Tok::Num(n) if n.chars().all(|c| c.is_ascii_digit()) => index.push_str(n),
                _ => return None,
            }
            k += 1;
        }
        if index.is_empty() {
            return None;
        }
        self.pos = k + 1;
        Some(Expr::Sym(format!("{{{name}[{index}]}}")))
    }

    /// Whether `^{..}` then `(` follow (`\omega^2(t)`).
    pub(super) fn power_then_paren(&self) -> bool {
        let mut k = self.pos + 1;
        match self.toks.get(k).map(|t| &t.0) {
            Some(Tok::Open) => match self.group_close(k) {
                Some(close) => k = close,
                None => return false,
            },
            Some(Tok::Num(_) | Tok::Ch(_)) => {}
            _ => return false,
        }
        matches!(self.toks.get(k + 1).map(|t| &t.0), Some(Tok::Ch('(')))
            || matches!(
                (self.toks.get(k + 1).map(|t| &t.0), self.toks.get(k + 2).map(|t| &t.0)),
                (Some(Tok::Cmd(l)), Some(Tok::Ch('('))) if l == "left"
            )
    }

    /// `name(a + b, c)` for a name the paper applies elsewhere: an opaque symbol named by its
    /// arguments as read (`{x(t + T)}`), with the unit of the function; `None` for any other
    /// name (a product follows).
    pub(super) fn applied_to_formulas(&mut self, name: &str, open: usize) -> R<Option<Expr>> {
        if !self.functions.contains(name) && !self.dirac.contains(name) {
            return Ok(None);
        }
        let save = self.pos;
        self.pos += open;
        let mut args = Vec::new();
        loop {
            match self.expr() {
                Ok(a) => args.push(a),
                Err(_) => {
                    self.pos = save;
                    return Ok(None);
                }
            }
            self.skip_space();
            match self.peek() {
                Tok::Ch(',' | ';') => {
                    self.bump();
                }
                Tok::Ch(')') => {
                    self.bump();
                    break;
                }
                Tok::Cmd(r) if r == "right" => {
                    self.bump();
                    self.bump();
                    break;
                }
                _ => {
                    self.pos = save;
                    return Ok(None);
                }
            }
        }
        // `\mathbf{r}(\mathbf{v} \cdot \mathbf{r})`: a function of itself is a product
        if args.iter().any(|a| a.symbols().iter().any(|s| s == name)) {
            self.pos = save;
            return Ok(None);
        }
        // a Dirac delta has the unit of its argument's inverse
        if self.dirac.contains(name) && args.len() == 1 {
            let inverse = Expr::Bin(Op::Div, Box::new(one()), Box::new(args[0].clone()));
            return Ok(Some(super::marks::marked(inverse)));
        }
        let args: Vec<String> = args.iter().map(ToString::to_string).collect();
        Ok(Some(Expr::Sym(format!("{{{name}({})}}", args.join(",")))))
    }

    /// `w(z = h_U)`, `u(x, y = h_m + d)`, `Z(t = 0)`: a function at a point given by the value of
    /// one of its variables, an opaque symbol named by its arguments as read (`{w(z=h_U)}`), with
    /// the unit of the function; `None` unless an argument is such an equation.
    fn evaluated_at(&mut self, name: &str, open: usize) -> Option<Expr> {
        let save = self.pos;
        self.pos += open;
        let mut args = Vec::new();
        let mut equation = false;
        let done = loop {
            let Ok(a) = self.expr() else { break false };
            self.skip_space();
            if *self.peek() == Tok::Ch('=') {
                self.bump();
                let Ok(b) = self.expr() else { break false };
                self.skip_space();
                equation = true;
                args.push(format!("{a}={b}"));
            } else {
                args.push(a.to_string());
            }
            match self.peek() {
                Tok::Ch(',' | ';') => {
                    self.bump();
                }
                Tok::Ch(')') => {
                    self.bump();
                    break true;
                }
                Tok::Cmd(r) if r == "right" => {
                    self.bump();
                    self.bump();
                    break true;
                }
                _ => break false,
            }
        };
        if !(done && equation) {
            self.pos = save;
            return None;
        }
        Some(Expr::Sym(format!("{{{name}({})}}", args.join(","))))
    }

    /// A matrix or vector inside a formula (`\begin{pmatrix} .. \end{pmatrix}`): its entries
    /// read (each must be a formula), the whole an opaque symbol named by its text, with a unit
    /// of its own (a state vector's entries may differ in unit); any other environment refused.
    pub(super) fn matrix(&mut self, col: usize) -> R<Expr> {
        const MATRICES: &[&str] = &[
            "matrix",
            "pmatrix",
            "bmatrix",
            "Bmatrix",
            "vmatrix",
            "Vmatrix",
            "smallmatrix",
            "array",
        ];
        let refuse = || TexError {
            column: col,
            construct: "an environment inside a formula (`\\begin{cases}`, an array)".into(),
            found: "\\begin".into(),
        };
        let start = self.pos.saturating_sub(1);
        if *self.peek() != Tok::Open {
            return Err(refuse());
        }
        self.bump();
        let mut env = String::new();
        while let Tok::Ch(c) = self.peek().clone() {
            if !c.is_ascii_alphabetic() && c != '*' {
                break;
            }
            env.push(c);
            self.bump();
        }
        if *self.peek() != Tok::Close || !MATRICES.contains(&env.as_str()) {
            return Err(refuse());
        }
        self.bump();
        if env == "array" {
            // the column specification
            self.skip_group()?;
        }
        loop {
            self.skip_space();
            match self.peek() {
                Tok::Cmd(c) if c == "end" => break,
                Tok::Ch('&') => {
                    self.bump();
                }
                Tok::Cmd(c) if c == "\\" => {
                    self.bump();
                }
                Tok::End => return self.err("`\\end` closing a matrix"),
                _ => {
                    self.expr()?;
                }
            }
        }
        self.bump();
        self.skip_group()?;
        let text: Vec<String> = self.toks[start..self.pos]
            .iter()
            .filter(|(t, _)| !is_space(t) || matches!(t, Tok::Cmd(c) if c == "\\"))
            .map(|(t, _)| describe(t))
            .collect();
        Ok(Expr::Sym(format!("{{{}}}", text.join(" "))))
    }
}
