//! Reading a formula: the lexer and a recursive-descent parser (precedence climbing) into
//! [`Expr`], with errors that name the column.

use super::*;

/// Why a formula could not be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("column {column}: expected {expected}, found {found}")]
pub struct ParseError {
    /// 1-based column (in characters) where reading stopped.
    pub column: usize,
    /// What the grammar allows there.
    pub expected: String,
    /// What was there.
    pub found: String,
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    Num(Q, String),
    Name(String),
    Op(char),
    Rel(Rel),
    LParen,
    RParen,
    Comma,
    End,
}

impl Tok {
    fn describe(&self) -> String {
        match self {
            Tok::Num(_, t) => format!("number `{t}`"),
            Tok::Name(n) => format!("name `{n}`"),
            Tok::Op(c) => format!("`{c}`"),
            Tok::Rel(r) => format!("`{}`", r.symbol()),
            Tok::LParen => "`(`".into(),
            Tok::RParen => "`)`".into(),
            Tok::Comma => "`,`".into(),
            Tok::End => "the end of the formula".into(),
        }
    }
}

pub(super) fn lex(text: &str) -> Result<Vec<(Tok, usize)>, ParseError> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let col = i + 1;
        if c.is_whitespace() {
            i += 1;
            continue;
        }
        if c.is_ascii_digit() || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            // an exponent only when digits follow `e`, `e+` or `e-` (so `2e` is 2 times e? no:
            // it is an error below, since a name cannot follow a number)
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    while j < chars.len() && chars[j].is_ascii_digit() {
                        j += 1;
                    }
                    i = j;
                }
            }
            let t: String = chars[start..i].iter().collect();
            let v = crate::algebra::poly::parse_q(&t).filter(|_| t.matches('.').count() <= 1);
            let Some(v) = v else {
                return Err(ParseError {
                    column: col,
                    expected: "a number such as 3, 0.25 or 1e-3".into(),
                    found: format!("`{t}`"),
                });
            };
            out.push((Tok::Num(v, t), col));
            continue;
        }
        if c.is_ascii_alphabetic() || c == '_' {
            let start = i;
            loop {
                while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                // a dotted part is a name or an index (`contact.duration`, `impulse.0`)
                let dotted_next = i + 1 < chars.len()
                    && chars[i] == '.'
                    && (chars[i + 1].is_ascii_alphanumeric() || chars[i + 1] == '_');
                if dotted_next {
                    i += 1;
                } else {
                    break;
                }
            }
            out.push((Tok::Name(chars[start..i].iter().collect()), col));
            continue;
        }
        let next = chars.get(i + 1).copied();
        let (tok, len) = match (c, next) {
            ('<', Some('=')) => (Tok::Rel(Rel::Le), 2),
            ('>', Some('=')) => (Tok::Rel(Rel::Ge), 2),
            ('<', _) => (Tok::Rel(Rel::Lt), 1),
            ('>', _) => (Tok::Rel(Rel::Gt), 1),
            ('(', _) => (Tok::LParen, 1),
            (')', _) => (Tok::RParen, 1),
            (',', _) => (Tok::Comma, 1),
            ('+' | '-' | '*' | '/' | '^', _) => (Tok::Op(c), 1),
            _ => {
                return Err(ParseError {
                    column: col,
                    expected: "a number, a name, an operator (+ - * / ^) or a parenthesis".into(),
                    found: format!("`{c}`"),
                });
            }
        };
        out.push((tok, col));
        i += len;
    }
    out.push((Tok::End, chars.len() + 1));
    Ok(out)
}

pub(super) struct Parser {
    toks: Vec<(Tok, usize)>,
    pos: usize,
    depth: usize,
}

/// Nesting deeper than this is refused (a formula from a paper is far shallower; the limit keeps
/// the recursive parser from overflowing the stack on hostile input).
const MAX_DEPTH: usize = 200;

impl Parser {
    fn peek(&self) -> &Tok {
        &self.toks[self.pos].0
    }
    fn col(&self) -> usize {
        self.toks[self.pos].1
    }
    fn bump(&mut self) -> Tok {
        let t = self.toks[self.pos].0.clone();
        if self.pos + 1 < self.toks.len() {
            self.pos += 1;
        }
        t
    }
    fn err(&self, expected: &str) -> ParseError {
        ParseError {
            column: self.col(),
            expected: expected.into(),
            found: self.peek().describe(),
        }
    }
    fn deeper(&mut self) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(self.err("a formula nested less than 200 levels deep"));
        }
        Ok(())
    }

    fn expr(&mut self) -> Result<Expr, ParseError> {
        self.deeper()?;
        let mut lhs = self.term()?;
        while let Tok::Op(c @ ('+' | '-')) = *self.peek() {
            self.bump();
            let rhs = self.term()?;
            let op = if c == '+' { Op::Add } else { Op::Sub };
            lhs = Expr::Bin(op, Box::new(lhs), Box::new(rhs));
        }
        self.depth -= 1;
        Ok(lhs)
    }

    fn term(&mut self) -> Result<Expr, ParseError> {
        let mut lhs = self.unary()?;
        while let Tok::Op(c @ ('*' | '/')) = *self.peek() {
            self.bump();
            let rhs = self.unary()?;
            let op = if c == '*' { Op::Mul } else { Op::Div };
            lhs = Expr::Bin(op, Box::new(lhs), Box::new(rhs));
        }
        Ok(lhs)
    }

    fn unary(&mut self) -> Result<Expr, ParseError> {
        if *self.peek() == Tok::Op('-') {
            self.bump();
            self.deeper()?;
            let e = self.unary()?;
            self.depth -= 1;
            return Ok(Expr::Neg(Box::new(e)));
        }
        self.power()
    }

    fn power(&mut self) -> Result<Expr, ParseError> {
        let base = self.atom()?;
        if *self.peek() == Tok::Op('^') {
            self.bump();
            self.deeper()?;
            let e = self.unary()?;
            self.depth -= 1;
            return Ok(Expr::Bin(Op::Pow, Box::new(base), Box::new(e)));
        }
        Ok(base)
    }

    fn atom(&mut self) -> Result<Expr, ParseError> {
        const WHAT: &str = "a number, a name, a function call or `(`";
        match self.peek().clone() {
            Tok::Num(v, _) => {
                self.bump();
                Ok(Expr::Num(v))
            }
            Tok::Name(n) => {
                self.bump();
                // a function's name is a call before `(` and a symbol elsewhere (a paper's
                // gamma, beta, erf ... as a parameter); before a name or a number it is a call
                // missing its parentheses
                let is_function = FUNCTIONS.contains(&n.as_str());
                if is_function && matches!(self.peek(), Tok::Name(_) | Tok::Num(..)) {
                    return Err(self.err(&format!("`(` after the function `{n}`")));
                }
                let called = *self.peek() == Tok::LParen;
                if called && matches!(n.as_str(), "max" | "min" | "beta") {
                    return self.two(&n);
                }
                if let Some(f) = Func::from_name(&n).filter(|_| called) {
                    self.bump();
                    let arg = self.expr()?;
                    if *self.peek() != Tok::RParen {
                        return Err(self.err(&format!("`)` closing `{n}(`")));
                    }
                    self.bump();
                    return Ok(Expr::Call(f, Box::new(arg)));
                }
                if let Some(calc) = Calc::from_name(&n) {
                    return self.calc(calc, &n);
                }
                if *self.peek() == Tok::LParen {
                    return Err(ParseError {
                        column: self.col(),
                        expected: format!(
                            "an operator after `{n}` (write `*` for a product; functions are: {})",
                            FUNCTIONS.join(" ")
                        ),
                        found: "`(`".into(),
                    });
                }
                Ok(if n == "pi" { Expr::Pi } else { Expr::Sym(n) })
            }
            Tok::LParen => {
                self.bump();
                let e = self.expr()?;
                if *self.peek() != Tok::RParen {
                    return Err(self.err("`)` or an operator"));
                }
                self.bump();
                Ok(e)
            }
            _ => Err(self.err(WHAT)),
        }
    }

    /// `max(a, b)`, `min(a, b)` as $(a + b \pm |a - b|)/2$ (exact in floating point when one
    /// side is 0), `beta(a, b)` as $\Gamma(a)\Gamma(b)/\Gamma(a + b)$, after the name (at its `(`).
    fn two(&mut self, n: &str) -> Result<Expr, ParseError> {
        self.bump();
        let a = self.expr()?;
        if *self.peek() != Tok::Comma {
            return Err(self.err(&format!("`,` and the second argument of `{n}(a, b)`")));
        }
        self.bump();
        let b = self.expr()?;
        if *self.peek() != Tok::RParen {
            return Err(self.err(&format!("`)` closing `{n}(`")));
        }
        self.bump();
        let bx = |e: Expr| Box::new(e);
        let bin = |op, x: Expr, y: Expr| Expr::Bin(op, bx(x), bx(y));
        Ok(match n {
            "beta" => {
                let g = |x: Expr| Expr::Call(Func::Gamma, bx(x));
                bin(
                    Op::Div,
                    bin(Op::Mul, g(a.clone()), g(b.clone())),
                    g(bin(Op::Add, a, b)),
                )
            }
            _ => {
                let spread = Expr::Call(Func::Abs, bx(bin(Op::Sub, a.clone(), b.clone())));
                let op = if n == "max" { Op::Add } else { Op::Sub };
                bin(
                    Op::Div,
                    bin(op, bin(Op::Add, a, b), spread),
                    Expr::Num(Q::from_integer(2.into())),
                )
            }
        })
    }

    /// `diff(e, x)`, `int(e, x, lo, hi)`, `at(e, x, v)`, after the name.
    fn calc(&mut self, calc: Calc, n: &str) -> Result<Expr, ParseError> {
        if *self.peek() != Tok::LParen {
            return Err(self.err(&format!("`(` after `{n}`")));
        }
        self.bump();
        let body = self.expr()?;
        if *self.peek() != Tok::Comma {
            return Err(self.err(&format!("`,` and the variable of `{n}(`")));
        }
        self.bump();
        let Tok::Name(var) = self.peek().clone() else {
            return Err(self.err(&format!("the name of the variable of `{n}(`")));
        };
        self.bump();
        let mut extra = Vec::new();
        for _ in 0..calc.extra_args() {
            if *self.peek() != Tok::Comma {
                let what = match calc {
                    Calc::Int => "`,` and the bounds of `int(e, x, lo, hi)`",
                    Calc::Sum => "`,` and the bounds of `sum(e, i, lo, hi)`",
                    _ => "`,` and the value of `at(e, x, v)`",
                };
                return Err(self.err(what));
            }
            self.bump();
            extra.push(self.expr()?);
        }
        if *self.peek() != Tok::RParen {
            return Err(self.err(&format!("`)` closing `{n}(`")));
        }
        self.bump();
        Ok(Expr::Calc(calc, Box::new(body), var, extra))
    }

    fn finish(&self) -> Result<(), ParseError> {
        match self.peek() {
            Tok::End => Ok(()),
            Tok::Num(..) | Tok::Name(_) | Tok::LParen => {
                Err(self.err("an operator (write `*` for a product)"))
            }
            _ => Err(self.err("an operator or the end of the formula")),
        }
    }
}

pub(super) fn parser(text: &str) -> Result<Parser, ParseError> {
    Ok(Parser {
        toks: lex(text)?,
        pos: 0,
        depth: 0,
    })
}

/// Parses a formula (no inequality).
pub fn parse(text: &str) -> Result<Expr, ParseError> {
    let mut p = parser(text)?;
    let e = p.expr()?;
    if let Tok::Rel(_) = p.peek() {
        return Err(p.err("a formula without `<`, `>` here (an inequality is not allowed)"));
    }
    p.finish()?;
    Ok(e)
}

/// Parses an inequality `lhs REL rhs`.
pub fn parse_inequality(text: &str) -> Result<Inequality, ParseError> {
    let mut p = parser(text)?;
    let lhs = p.expr()?;
    let Tok::Rel(rel) = p.peek().clone() else {
        return Err(p.err("one of < <= > >="));
    };
    p.bump();
    let rhs = p.expr()?;
    p.finish()?;
    Ok(Inequality { lhs, rel, rhs })
}
