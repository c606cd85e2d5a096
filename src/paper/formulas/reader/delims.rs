//! Delimiters: `\left( .. \right)` and its kin, absolute values and norms (`|x|`, `\|x\|`,
//! `\lVert x \rVert`: the unit of their argument), `\langle x \rangle` (an average) and
//! `\langle a, b \rangle` (a scalar product).

use super::super::lex::Tok;
use super::{R, Reader, mul};
use crate::algebra::expr::{Calc, Expr, Func};

impl Reader<'_> {
    /// `\left( ... \right)` and its kin; `\left|` is an absolute value.
    pub(super) fn left(&mut self) -> R<Expr> {
        if matches!(self.peek(), Tok::Cmd(c) if c == "langle") {
            self.bump();
            return self.angle("rangle");
        }
        // LaTeX breaks no row inside `\left .. \right`: rows there are a matrix written without
        // its environment (`\left| 1 & 0 \\ 0 & 1 \right|`) or a scan's mistake, not a formula
        if self.row_break_before_right() {
            return self.err("a row break `\\\\` inside `\\left .. \\right` (a matrix?)");
        }
        let open = self.bump();
        let e = self.expr()?;
        // `\left\{ (x, y) \in \mathbb{R}^2 \,|\, .. \right\}`: a set of its elements, in their
        // unit, as `\{x \in D : ..\}` is; what follows the element is no value
        self.skip_space();
        let builder = matches!(self.peek(), Tok::Ch(':' | '|'))
            || matches!(self.peek(), Tok::Cmd(c) if c == "in" || c == "mid" || c == "vert");
        if builder && matches!(&open, Tok::Cmd(c) if c == "{") {
            let mut depth = 0usize;
            loop {
                match self.peek().clone() {
                    Tok::End => return self.err("`\\right\\}` closing a set"),
                    Tok::Cmd(c) if c == "left" => depth += 1,
                    Tok::Cmd(c) if c == "right" && depth == 0 => break,
                    Tok::Cmd(c) if c == "right" => depth -= 1,
                    _ => {}
                }
                self.bump();
            }
            self.bump();
            self.bump();
            return Ok(super::marks::marked(e));
        }
        let e = self.tuple(e)?;
        self.skip_space();
        if !matches!(self.peek(), Tok::Cmd(c) if c == "right") {
            return self.err("`\\right` closing `\\left`");
        }
        self.bump();
        self.bump();
        let abs = matches!(&open, Tok::Ch('|'))
            || matches!(&open, Tok::Cmd(c) if matches!(c.as_str(), "|" | "Vert" | "lVert" | "lvert" | "vert"));
        if abs {
            self.norm_subscript()?;
        }
        Ok(if abs {
            Expr::Call(Func::Abs, Box::new(e))
        } else {
            e
        })
    }

    /// Whether a `\\` stands between here (after a `\left`) and the `\right` that closes it.
    fn row_break_before_right(&self) -> bool {
        let mut depth = 0usize;
        for (t, _) in &self.toks[self.pos..] {
            match t {
                Tok::Cmd(c) if c == "left" => depth += 1,
                Tok::Cmd(c) if c == "right" => {
                    if depth == 0 {
                        return false;
                    }
                    depth -= 1;
                }
                Tok::Cmd(c) if c == "\\" && depth == 0 => return true,
                Tok::End => return false,
                _ => {}
            }
        }
        false
    }

    /// `\langle a \rangle` (an average: the unit of a) or `\langle a, b \rangle` (a scalar
    /// product: the unit of a b); `close` the command that closes it.
    pub(super) fn angle(&mut self, close: &str) -> R<Expr> {
        let (save, links) = (self.pos, self.links.len());
        match self.average_or_product(close) {
            Ok(e) => Ok(e),
            // `\langle a | H | b \rangle`, `\langle r \vert \psi \rangle`: a bracket of states
            Err(first) => {
                self.pos = save;
                self.links.truncate(links);
                self.bracket_of_states(close).map_err(|_| first)
            }
        }
    }

    fn average_or_product(&mut self, close: &str) -> R<Expr> {
        let a = self.expr()?;
        self.skip_space();
        let e = if matches!(self.peek(), Tok::Ch(',' | '|')) {
            self.bump();
            let b = self.expr()?;
            mul(a, b)
        } else {
            Expr::Calc(Calc::Mean, Box::new(a), String::new(), vec![])
        };
        self.skip_space();
        if matches!(self.peek(), Tok::Cmd(c) if c == "right") {
            self.bump();
        }
        self.expect(Tok::Cmd(close.into()), &format!("`\\{close}`"))?;
        Ok(e)
    }

    /// The subscript of a norm (`\|x\|_2`, `\|x\|_{\infty}`), which names the norm: passed over.
    pub(super) fn norm_subscript(&mut self) -> R<()> {
        if *self.peek() == Tok::Ch('_') {
            self.bump();
            self.skip_space();
            if *self.peek() == Tok::Open {
                self.bump();
                self.skip_to_close("a norm's subscript")?;
            } else {
                self.bump();
            }
        }
        Ok(())
    }

    pub(super) fn closing_cmd(&mut self, close: &str) -> R<Expr> {
        let e = self.expr()?;
        // `\{x \in D : x > 0\}`, `\{v \mid v \ge 0\}`: the set of the elements `e` such that
        // ..., in their unit; what they are taken from and the condition are no value
        self.skip_space();
        let builder = matches!(self.peek(), Tok::Ch(':' | '|'))
            || matches!(self.peek(), Tok::Cmd(c) if c == "in" || c == "mid" || c == "vert");
        if builder && close == "}" {
            let mut depth = 0usize;
            loop {
                match self.peek().clone() {
                    Tok::End => return self.err("`\\}` closing a set"),
                    Tok::Open => depth += 1,
                    Tok::Close => depth = depth.saturating_sub(1),
                    Tok::Cmd(c) if c == "{" => depth += 1,
                    Tok::Cmd(c) if c == "}" && depth == 0 => break,
                    Tok::Cmd(c) if c == "}" => depth -= 1,
                    _ => {}
                }
                self.bump();
            }
            self.bump();
            return Ok(super::marks::marked(e));
        }
        // `\{Q, P\}`: a bracket of two, opaque as a pair is
        let e = self.tuple(e)?;
        self.expect(Tok::Cmd(close.into()), &format!("`\\{close}`"))?;
        Ok(e)
    }
}
