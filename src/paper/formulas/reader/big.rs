//! Big operators: `\sum`, `\prod`, `\max`, `\min`, `\sup`, `\lim` with their index, bounds
//! and lists; each has the unit of its body (a product its power).

use super::super::lex::{Tok, greek};
use super::{R, Reader, num};
use crate::algebra::expr::{Calc, Expr, Func, Op};
use crate::algebra::units::ELLIPSIS;

impl Reader<'_> {
    /// A big operator: `\sum`, `\prod` (`_{i=lo}^{hi}`, `_{i}`, `_{n = 1, 3, 5, \ldots}`),
    /// `\max_i`, `\min`, `\sup`, `\lim_{k \to \infty}`; `\max(a, b)` the larger of two. Bounds
    /// the paper leaves out are an ellipsis (every unit, no value).
    pub(super) fn big(&mut self, kind: Calc) -> R<Expr> {
        self.skip_space();
        let (mut var, mut lo, mut hi) = (String::new(), None, None);
        let mut listed = false;
        if *self.peek() == Tok::Ch('_') {
            self.bump();
            self.skip_space();
            let braced = *self.peek() == Tok::Open;
            if braced {
                self.bump();
            }
            self.skip_space();
            let start = self.pos;
            let name = match self.peek().clone() {
                Tok::Ch(c) if c.is_ascii_alphabetic() => {
                    self.bump();
                    Some(self.name_tail(c.to_string())?)
                }
                Tok::Cmd(g) if greek(&g).is_some() => {
                    self.bump();
                    Some(self.name_tail(greek(&g).unwrap_or_default().to_string())?)
                }
                _ => None,
            };
            self.skip_space();
            match (name, self.peek().clone()) {
                (Some(n), Tok::Ch('=')) if braced => {
                    self.bump();
                    var = n;
                    lo = Some(self.expr()?);
                    self.skip_space();
                    if *self.peek() == Tok::Ch(',') {
                        listed = true;
                    }
                }
                (Some(n), Tok::Cmd(t)) if braced && (t == "to" || t == "rightarrow") => {
                    self.bump();
                    var = n;
                    lo = Some(self.expr()?);
                }
                (Some(n), Tok::Close) if braced => var = n,
                (Some(n), _) if !braced => var = n,
                _ => {
                    // an index set written another way (`1 \le i \le n`, `i \in S`, `i, j`)
                    self.pos = start;
                    listed = true;
                }
            }
            if braced {
                self.skip_to_close("a big operator's range")?;
            }
        }
        self.skip_space();
        if *self.peek() == Tok::Ch('^') {
            self.bump();
            hi = Some(self.group()?);
        }
        self.skip_space();
        // `\max(a, b)`, `\max\{a, b\}`: the larger of the listed ones
        if matches!(kind, Calc::Max | Calc::Min)
            && var.is_empty()
            && !listed
            && let Some(e) = self.listed_extreme(kind)?
        {
            return Ok(e);
        }
        // `\min_{\mathbf{x}} \quad f(\mathbf{x})` of an optimisation problem: what is
        // minimised stands apart (the operator alone is no relation)
        // `\sum_{k<k_d} -\mathrm{i} k \psi_k`: a minus right after a sum's or a product's
        // range opens its summand, not a difference with an empty sum
        let body = if matches!(kind, Calc::Sum | Calc::Prod) && *self.peek() == Tok::Ch('-') {
            self.bump();
            Expr::Neg(Box::new(self.term()?))
        } else if self.no_operand() {
            self.operand()
        } else {
            self.term()?
        };
        let ellipsis = || Expr::Sym(ELLIPSIS.into());
        Ok(match kind {
            Calc::Sum | Calc::Prod => {
                let lo = if listed { None } else { lo };
                let var = if var.is_empty() { "i".to_string() } else { var };
                let lo = lo.unwrap_or_else(ellipsis);
                let hi = if listed && hi.is_none() {
                    ellipsis()
                } else {
                    hi.unwrap_or_else(ellipsis)
                };
                Expr::Calc(kind, Box::new(body), var, vec![lo, hi])
            }
            Calc::Lim => Expr::Calc(kind, Box::new(body), var, vec![lo.unwrap_or_else(ellipsis)]),
            _ => Expr::Calc(kind, Box::new(body), var, vec![]),
        })
    }

    /// `\max(a, b, ..)` or `\max\{a, b\}`: the larger (smaller) of the two or more, as the
    /// formula language writes it, `(a + b + |a - b|)/2`; `None` when no list follows.
    pub(super) fn listed_extreme(&mut self, kind: Calc) -> R<Option<Expr>> {
        if matches!(self.peek(), Tok::Cmd(c) if c == "left") {
            self.bump();
        }
        let close = match self.peek() {
            Tok::Ch('(') => Tok::Ch(')'),
            Tok::Cmd(c) if c == "{" => Tok::Cmd("}".into()),
            _ => return Ok(None),
        };
        self.bump();
        let mut items = vec![self.expr()?];
        self.skip_space();
        while *self.peek() == Tok::Ch(',') {
            self.bump();
            items.push(self.expr()?);
            self.skip_space();
        }
        if matches!(self.peek(), Tok::Cmd(c) if c == "right") {
            self.bump();
        }
        self.expect(close, "the bracket closing a maximum's list")?;
        let half =
            |e: Expr| Expr::Bin(Op::Div, Box::new(e), Box::new(num("2").unwrap_or(Expr::Pi)));
        let mut acc = items.remove(0);
        for b in items {
            let spread = Expr::Call(
                Func::Abs,
                Box::new(Expr::Bin(
                    Op::Sub,
                    Box::new(acc.clone()),
                    Box::new(b.clone()),
                )),
            );
            let sum = Expr::Bin(Op::Add, Box::new(acc), Box::new(b));
            let op = if kind == Calc::Max { Op::Add } else { Op::Sub };
            acc = half(Expr::Bin(op, Box::new(sum), Box::new(spread)));
        }
        Ok(Some(acc))
    }
}
