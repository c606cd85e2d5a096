//! Building expressions from the LaTeX reader's tokens: a recursive-descent reader of formulas
//! and relations (fractions, roots, scripts, functions, sums, integrals, derivatives, implicit
//! products).

use super::lex::{Tok, accent_suffix, describe, func, greek, is_space};
use super::{TexError, TexRelation, is_name};
use crate::algebra::expr::{Calc, Expr, Func, Op};

pub(super) struct Reader<'a> {
    toks: &'a [(Tok, usize)],
    pos: usize,
    /// Inside an integrand: `d x` ends the product.
    in_integral: usize,
    /// Inside `| ... |`: a `|` closes, it does not open.
    in_abs: usize,
    /// How deep the formulas nest (a file from anyone must not overflow the stack).
    depth: usize,
}

/// The deepest nesting read (as the text parser's limit).
pub(super) const MAX_DEPTH: usize = 200;

type R<T> = Result<T, TexError>;

impl<'a> Reader<'a> {
    /// A reader at the first of `toks` (which end in [`Tok::End`]).
    pub(super) fn new(toks: &'a [(Tok, usize)]) -> Self {
        Reader {
            toks,
            pos: 0,
            in_integral: 0,
            in_abs: 0,
            depth: 0,
        }
    }

    fn peek(&self) -> &Tok {
        &self.toks[self.pos].0
    }

    fn col(&self) -> usize {
        self.toks[self.pos].1
    }

    fn bump(&mut self) -> Tok {
        let t = self.toks[self.pos].0.clone();
        if t != Tok::End {
            self.pos += 1;
        }
        t
    }

    fn skip_space(&mut self) {
        while is_space(self.peek()) {
            self.bump();
        }
    }

    fn err<T>(&self, construct: impl Into<String>) -> R<T> {
        Err(TexError {
            column: self.col(),
            construct: construct.into(),
            found: describe(self.peek()),
        })
    }

    fn expect(&mut self, t: Tok, what: &str) -> R<()> {
        self.skip_space();
        if *self.peek() == t {
            self.bump();
            Ok(())
        } else {
            self.err(format!("expected {what}"))
        }
    }

    /// `{ ... }` read as a formula.
    fn group(&mut self) -> R<Expr> {
        self.skip_space();
        if *self.peek() != Tok::Open {
            // a single token argument, as TeX allows (`\frac12`, `x^2`)
            return self.single();
        }
        self.bump();
        let e = self.expr()?;
        self.expect(Tok::Close, "`}`")?;
        Ok(e)
    }

    /// One token as an argument (`^2`, `\frac12`): a digit, a letter or a command.
    fn single(&mut self) -> R<Expr> {
        if let Tok::Num(n) = self.peek().clone() {
            // `x^23` is x^2 * 3 in TeX; rare in papers, so an error rather than a misreading
            if n.chars().count() > 1 {
                return self.err(format!("a multi-digit script without braces (`{n}`)"));
            }
            self.bump();
            return num(&n).ok_or_else(|| TexError {
                column: self.col(),
                construct: "a number".into(),
                found: n,
            });
        }
        self.atom()
    }

    /// The text of a `{...}` group of letters, digits and Greek commands (a name's part).
    fn name_text(&mut self) -> R<String> {
        self.skip_space();
        let mut out = String::new();
        let braced = *self.peek() == Tok::Open;
        if braced {
            self.bump();
        }
        loop {
            self.skip_space();
            match self.peek().clone() {
                Tok::Ch(c) if c.is_ascii_alphanumeric() => {
                    self.bump();
                    out.push(c);
                }
                Tok::Num(n) => {
                    self.bump();
                    out.push_str(&n);
                }
                Tok::Cmd(c) if greek(&c).is_some() => {
                    self.bump();
                    out.push_str(greek(&c).unwrap_or_default());
                }
                Tok::Cmd(c) if c == "prime" => {
                    self.bump();
                    out.push('p');
                }
                Tok::Ch(',' | ';' | '\'' | '_' | '^') if braced => {
                    self.bump();
                }
                Tok::Ch('*') if braced => {
                    self.bump();
                    out.push_str("star");
                }
                Tok::Open if braced => {
                    let inner = self.name_text()?;
                    out.push_str(&inner);
                    continue;
                }
                Tok::Cmd(c) if accent_suffix(&c).is_some() && braced => {
                    self.bump();
                    let inner = self.name_text()?;
                    out.push_str(&inner);
                    out.push_str(accent_suffix(&c).unwrap_or_default());
                }
                Tok::Close if braced => {
                    self.bump();
                    break;
                }
                _ if braced => return self.err("a name's part (letters, digits, Greek)"),
                _ => break,
            }
            if !braced {
                break;
            }
        }
        if out.is_empty() {
            return self.err("a name's part (letters, digits, Greek)");
        }
        Ok(out)
    }

    /// A name's subscripts and primes, appended.
    fn name_tail(&mut self, mut name: String) -> R<String> {
        loop {
            match self.peek() {
                Tok::Ch('_') => {
                    self.bump();
                    name.push_str(&self.name_text()?);
                }
                Tok::Ch('\'') => {
                    self.bump();
                    name.push('p');
                }
                Tok::Ch('^') if self.decoration().is_some() => {
                    let (suffix, len) = self.decoration().unwrap_or(("", 1));
                    self.pos += len;
                    name.push_str(suffix);
                }
                Tok::Ch('^') if self.is_prime_script() => {
                    self.bump();
                    self.bump();
                    while matches!(self.peek(), Tok::Cmd(c) if c == "prime") {
                        self.bump();
                        name.push('p');
                    }
                    self.expect(Tok::Close, "`}` after `\\prime`")?;
                }
                _ => return Ok(name),
            }
        }
    }

    /// `^-`, `^+`, `^*` (or braced) after a name: a label (`V^-`, the velocity before impact),
    /// not a power; the suffix and how many tokens it takes.
    fn decoration(&self) -> Option<(&'static str, usize)> {
        let at = |k: usize| self.toks.get(self.pos + k).map(|t| &t.0);
        let label = |t: Option<&Tok>| match t {
            Some(Tok::Ch('-')) => Some("minus"),
            Some(Tok::Ch('+')) => Some("plus"),
            Some(Tok::Ch('*')) => Some("star"),
            _ => None,
        };
        if let Some(l) = label(at(1)) {
            return Some((l, 2));
        }
        if at(1) == Some(&Tok::Open) && at(3) == Some(&Tok::Close) {
            return label(at(2)).map(|l| (l, 4));
        }
        None
    }

    fn is_prime_script(&self) -> bool {
        matches!(self.toks.get(self.pos + 1), Some((Tok::Open, _)))
            && matches!(self.toks.get(self.pos + 2), Some((Tok::Cmd(c), _)) if c == "prime")
    }

    /// Runs `f` one level deeper, refusing to go past [`MAX_DEPTH`].
    fn nest(&mut self, f: impl FnOnce(&mut Self) -> R<Expr>) -> R<Expr> {
        self.depth += 1;
        let e = if self.depth > MAX_DEPTH {
            self.err(format!("a formula nested at most {MAX_DEPTH} deep"))
        } else {
            f(self)
        };
        self.depth -= 1;
        e
    }

    fn expr(&mut self) -> R<Expr> {
        self.nest(Self::expr_inner)
    }

    fn expr_inner(&mut self) -> R<Expr> {
        self.skip_space();
        let mut e = self.term()?;
        loop {
            self.skip_space();
            match self.peek() {
                Tok::Ch('+') => {
                    self.bump();
                    e = Expr::Bin(Op::Add, Box::new(e), Box::new(self.term()?));
                }
                Tok::Ch('-') => {
                    self.bump();
                    e = Expr::Bin(Op::Sub, Box::new(e), Box::new(self.term()?));
                }
                Tok::Cmd(c) if c == "pm" || c == "mp" => {
                    return self.err("`\\pm` (two formulas in one)");
                }
                _ => return Ok(e),
            }
        }
    }

    fn starts_atom(&self) -> bool {
        match self.peek() {
            Tok::Num(_) | Tok::Sym(_) | Tok::Open => true,
            Tok::Ch('|') => self.in_abs == 0,
            Tok::Ch(c) => c.is_ascii_alphabetic() || matches!(c, '(' | '['),
            Tok::Cmd(c) => {
                greek(c).is_some()
                    || func(c).is_some()
                    || accent_suffix(c).is_some()
                    || matches!(
                        c.as_str(),
                        "frac"
                            | "dfrac"
                            | "tfrac"
                            | "sqrt"
                            | "left"
                            | "pi"
                            | "sum"
                            | "int"
                            | "iint"
                            | "infty"
                            | "partial"
                            | "max"
                            | "min"
                            | "{"
                            | "|"
                    )
            }
            _ => false,
        }
    }

    fn term(&mut self) -> R<Expr> {
        self.term_until(false)
    }

    /// A product; `arg` stops before a function (the argument of `\sin` in `\sin a \sin b`).
    fn term_until(&mut self, arg: bool) -> R<Expr> {
        self.skip_space();
        let mut e = self.unary()?;
        loop {
            self.skip_space();
            match self.peek().clone() {
                Tok::Cmd(c) if c == "cdot" || c == "times" => {
                    self.bump();
                    e = mul(e, self.unary()?);
                }
                Tok::Ch('*') => {
                    self.bump();
                    e = mul(e, self.unary()?);
                }
                Tok::Ch('/') => {
                    self.bump();
                    e = Expr::Bin(Op::Div, Box::new(e), Box::new(self.unary()?));
                }
                Tok::Cmd(c) if arg && func(&c).is_some() => return Ok(e),
                // a parenthesised factor ends a bare argument: `\cos \phi (a + b)` is
                // cos(phi) (a + b), as `\sin \omega t` is sin(omega t)
                Tok::Ch('(' | '[') if arg => return Ok(e),
                Tok::Cmd(c) if arg && c == "left" => return Ok(e),
                Tok::Ch('d') if arg && self.is_differential() => return Ok(e),
                _ if self.starts_atom() && !self.is_differential_here() => {
                    e = mul(e, self.postfix()?);
                }
                _ => return Ok(e),
            }
        }
    }

    /// Whether the tokens here are `d x` closing an integral (set while reading an integrand).
    fn is_differential_here(&self) -> bool {
        self.in_integral > 0 && self.is_differential()
    }

    fn is_differential(&self) -> bool {
        matches!(self.peek(), Tok::Ch('d'))
            && matches!(self.toks.get(self.pos + 1), Some((Tok::Ch(c), _)) if c.is_ascii_alphabetic())
            && !matches!(self.toks.get(self.pos + 2), Some((Tok::Ch('('), _)))
            || matches!(self.peek(), Tok::Ch('d'))
                && matches!(self.toks.get(self.pos + 1), Some((Tok::Cmd(c), _)) if greek(c).is_some())
    }

    fn unary(&mut self) -> R<Expr> {
        self.nest(Self::unary_inner)
    }

    fn unary_inner(&mut self) -> R<Expr> {
        self.skip_space();
        match self.peek() {
            Tok::Ch('-') => {
                self.bump();
                Ok(Expr::Neg(Box::new(self.term()?)))
            }
            Tok::Ch('+') => {
                self.bump();
                self.term()
            }
            _ => self.postfix(),
        }
    }

    fn postfix(&mut self) -> R<Expr> {
        let mut e = self.atom()?;
        loop {
            match self.peek() {
                Tok::Ch('^') => {
                    self.bump();
                    let p = self.group()?;
                    e = power(e, p);
                }
                Tok::Ch('!') => {
                    self.bump();
                    e = Expr::Call(Func::Factorial, Box::new(e));
                }
                Tok::Ch('_') => return self.err("a subscript on something that is not a name"),
                _ => return Ok(e),
            }
        }
    }

    fn atom(&mut self) -> R<Expr> {
        self.nest(Self::atom_inner)
    }

    fn atom_inner(&mut self) -> R<Expr> {
        self.skip_space();
        let col = self.col();
        match self.bump() {
            Tok::Num(n) => num(&n).ok_or(TexError {
                column: col,
                construct: "a number".into(),
                found: n,
            }),
            // a spelling mapped to a name takes primes and subscripts as a name does
            // (`\varepsilon_{On}^{\prime\prime}` with `\varepsilon_{On}` mapped to `eOn`)
            Tok::Sym(s) if is_name(&s) => Ok(Expr::Sym(self.name_tail(s)?)),
            Tok::Sym(s) => Ok(Expr::Sym(s)),
            Tok::Open => {
                let e = self.expr()?;
                self.expect(Tok::Close, "`}`")?;
                Ok(e)
            }
            Tok::Ch('(') => self.closing(')'),
            Tok::Ch('[') => self.closing(']'),
            Tok::Ch('|') => {
                self.in_abs += 1;
                let e = self.expr();
                self.in_abs -= 1;
                let e = e?;
                self.expect(Tok::Ch('|'), "`|` closing an absolute value")?;
                Ok(Expr::Call(Func::Abs, Box::new(e)))
            }
            Tok::Ch(c) if c.is_ascii_alphabetic() => {
                let name = self.name_tail(c.to_string())?;
                if name == "e" && *self.peek() == Tok::Ch('^') {
                    return self.exp_power();
                }
                self.maybe_applied(name)
            }
            Tok::Cmd(c) => self.command(&c, col),
            t => {
                self.pos -= usize::from(t != Tok::End);
                self.err("a formula")
            }
        }
    }

    /// `e^{x}`: `exp(x)` when the exponent has a symbol, else the symbol `e` raised.
    fn exp_power(&mut self) -> R<Expr> {
        self.bump();
        let p = self.group()?;
        if p.symbols().is_empty() {
            Ok(power(Expr::Sym("e".into()), p))
        } else {
            Ok(Expr::Call(Func::Exp, Box::new(p)))
        }
    }

    fn closing(&mut self, close: char) -> R<Expr> {
        let e = self.expr()?;
        let e = self.tuple(e)?;
        self.expect(Tok::Ch(close), &format!("`{close}`"))?;
        Ok(e)
    }

    /// `(a, b)` (a scalar product of vectors, a pair): an opaque symbol named by its parts.
    fn tuple(&mut self, first: Expr) -> R<Expr> {
        self.skip_space();
        if *self.peek() != Tok::Ch(',') {
            return Ok(first);
        }
        let mut parts = vec![first.to_string()];
        while *self.peek() == Tok::Ch(',') {
            self.bump();
            parts.push(self.expr()?.to_string());
            self.skip_space();
        }
        Ok(Expr::Sym(format!("{{({})}}", parts.join(", "))))
    }

    /// A name, or a name applied to arguments (`w(x, y, t)`, `P(t)`): an opaque symbol.
    fn maybe_applied(&mut self, name: String) -> R<Expr> {
        let open = match (self.peek(), self.toks.get(self.pos + 1)) {
            (Tok::Ch('('), _) => 1,
            (Tok::Cmd(l), Some((Tok::Ch('('), _))) if l == "left" => 2,
            _ => return Ok(Expr::Sym(name)),
        };
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
                Some(Tok::Cmd(c)) if greek(c).is_some() || c == "prime" => {
                    cur.push_str(greek(c).unwrap_or("p"))
                }
                Some(Tok::Cmd(c)) if is_space(&Tok::Cmd(c.clone())) => {}
                Some(Tok::Ch(',')) => args.push(std::mem::take(&mut cur)),
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

    fn command(&mut self, c: &str, col: usize) -> R<Expr> {
        if let Some(g) = greek(c) {
            let name = self.name_tail(g.to_string())?;
            return self.maybe_applied(name);
        }
        if let Some(f) = func(c) {
            return self.function(f);
        }
        if let Some(suffix) = accent_suffix(c) {
            let inner = self.name_text()?;
            if (c == "operatorname" || c == "mathrm")
                && let Some(f) = func(&inner)
            {
                return self.function(f);
            }
            let name = self.name_tail(format!("{inner}{suffix}"))?;
            return self.maybe_applied(name);
        }
        match c {
            "pi" => Ok(Expr::Pi),
            "frac" | "dfrac" | "tfrac" => self.frac(),
            "sqrt" => {
                self.skip_space();
                if *self.peek() == Tok::Ch('[') {
                    self.bump();
                    let n = self.expr()?;
                    self.expect(Tok::Ch(']'), "`]` closing the root's index")?;
                    let x = self.group()?;
                    let inv =
                        Expr::Bin(Op::Div, Box::new(num("1").unwrap_or(Expr::Pi)), Box::new(n));
                    return Ok(power(x, inv));
                }
                Ok(Expr::Call(Func::Sqrt, Box::new(self.group()?)))
            }
            "left" => self.left(),
            "{" => self.closing_cmd("}"),
            "sum" => self.sum(),
            "int" if *self.peek() == Tok::Ch('_') => self.integral(),
            "int" | "iint" | "iiint" | "oint" => self.region_integral(),
            "max" | "min" => Err(TexError {
                column: col,
                construct: format!(
                    "`\\{c}` (a maximum over a set; retype it with `{c}(a, b)` of the formula language)"
                ),
                found: format!("\\{c}"),
            }),
            "ldots" | "cdots" | "dots" => Err(TexError {
                column: col,
                construct: "an ellipsis (`\\ldots`): a sequence, not a formula".into(),
                found: format!("\\{c}"),
            }),
            "infty" => Err(TexError {
                column: col,
                construct: "infinity (`\\infty`): an infinite sum or bound is not a formula".into(),
                found: "\\infty".into(),
            }),
            "begin" => Err(TexError {
                column: col,
                construct: "an environment inside a formula (`\\begin{cases}`, an array)".into(),
                found: "\\begin".into(),
            }),
            other => Err(TexError {
                column: col,
                construct: format!("the command `\\{other}`"),
                found: format!("\\{other}"),
            }),
        }
    }

    fn closing_cmd(&mut self, close: &str) -> R<Expr> {
        let e = self.expr()?;
        self.expect(Tok::Cmd(close.into()), &format!("`\\{close}`"))?;
        Ok(e)
    }

    /// `\left( ... \right)` and its kin; `\left|` is an absolute value.
    fn left(&mut self) -> R<Expr> {
        let open = self.bump();
        let e = self.expr()?;
        let e = self.tuple(e)?;
        self.skip_space();
        if !matches!(self.peek(), Tok::Cmd(c) if c == "right") {
            return self.err("`\\right` closing `\\left`");
        }
        self.bump();
        self.bump();
        let abs = open == Tok::Ch('|') || open == Tok::Cmd("|".into());
        Ok(if abs {
            Expr::Call(Func::Abs, Box::new(e))
        } else {
            e
        })
    }

    fn frac(&mut self) -> R<Expr> {
        self.skip_space();
        // \frac{\partial f}{\partial x} and \frac{d f}{d x}: a derivative
        let save = self.pos;
        if *self.peek() == Tok::Open {
            self.bump();
            self.skip_space();
            let partial = matches!(self.peek(), Tok::Cmd(c) if c == "partial");
            if partial || (*self.peek() == Tok::Ch('d') && self.diff_denominator_follows()) {
                self.bump();
                let body = self.expr()?;
                self.expect(Tok::Close, "`}`")?;
                self.expect(Tok::Open, "`{` of the derivative's denominator")?;
                self.skip_space();
                self.bump();
                self.skip_space();
                let var = match self.bump() {
                    Tok::Ch(c) if c.is_ascii_alphabetic() => self.name_tail(c.to_string())?,
                    Tok::Cmd(g) if greek(&g).is_some() => {
                        self.name_tail(greek(&g).unwrap_or_default().to_string())?
                    }
                    _ => return self.err("the variable of a derivative"),
                };
                self.expect(Tok::Close, "`}`")?;
                return Ok(Expr::Calc(Calc::Diff, Box::new(body), var, vec![]));
            }
            self.pos = save;
        }
        let a = self.group()?;
        let b = self.group()?;
        Ok(Expr::Bin(Op::Div, Box::new(a), Box::new(b)))
    }

    /// Whether `{d ...}{d x}` follows (the denominator of a derivative).
    fn diff_denominator_follows(&self) -> bool {
        let mut depth = 0;
        let mut k = self.pos;
        while let Some((t, _)) = self.toks.get(k) {
            match t {
                Tok::Open => depth += 1,
                Tok::Close if depth == 0 => {
                    return matches!(self.toks.get(k + 1), Some((Tok::Open, _)))
                        && matches!(self.toks.get(k + 2), Some((Tok::Ch('d'), _)));
                }
                Tok::Close => depth -= 1,
                Tok::End => return false,
                _ => {}
            }
            k += 1;
        }
        false
    }

    /// `\sin x`, `\sin(x)`, `\sin^{2} x`, `\sin \frac{m \pi x}{a}`.
    fn function(&mut self, f: Func) -> R<Expr> {
        self.skip_space();
        let mut pow = None;
        if *self.peek() == Tok::Ch('^') {
            self.bump();
            pow = Some(self.group()?);
        }
        self.skip_space();
        let arg = match self.peek() {
            Tok::Ch('(') | Tok::Open => self.atom()?,
            Tok::Cmd(c) if c == "left" => self.atom()?,
            _ => self.term_until(true)?,
        };
        // `\cosh^{-1} x` is the inverse function, as papers mean it, not 1/cosh x
        if let Some(p) = &pow
            && p.exact_constant()
                .is_some_and(|c| c == -num_rational::BigRational::from_integer(1.into()))
            && let Some(inv) = inverse(f)
        {
            return Ok(Expr::Call(inv, Box::new(arg)));
        }
        let e = Expr::Call(f, Box::new(arg));
        Ok(match pow {
            Some(p) => power(e, p),
            None => e,
        })
    }

    /// An integral over a region, printed without limits (`\int x d\sigma`, `\iint f d\xi
    /// d\eta`): its integrand read (so that what it holds is a formula), the whole an opaque
    /// symbol named by its text (`{\int x d \sigma}`), as a function application is. The
    /// formula language has no region: a claim maps the spelling in `[tex_symbols]`, or the
    /// claim's reader refuses the symbol naming it.
    fn region_integral(&mut self) -> R<Expr> {
        let start = self.pos - 1;
        // inside the integrand `d \sigma` ends the product; the depth is restored as it was
        let outer = self.in_integral;
        self.in_integral = outer.saturating_add(1);
        let body = self.expr();
        self.in_integral = outer;
        body?;
        self.skip_space();
        if !self.is_differential() {
            return self.err("the differential `d \\sigma` closing an integral over a region");
        }
        while self.is_differential() {
            self.bump();
            self.bump();
            self.skip_space();
        }
        let text: Vec<String> = self.toks[start..self.pos]
            .iter()
            .filter(|(t, _)| !is_space(t))
            .map(|(t, _)| describe(t))
            .collect();
        Ok(Expr::Sym(format!("{{{}}}", text.join(" "))))
    }

    /// `\sum_{i=0}^{k} body`.
    fn sum(&mut self) -> R<Expr> {
        self.expect(Tok::Ch('_'), "`_{i=lo}` after `\\sum`")?;
        self.expect(Tok::Open, "`{` of the sum's range")?;
        self.skip_space();
        let var = match self.bump() {
            Tok::Ch(c) if c.is_ascii_alphabetic() => self.name_tail(c.to_string())?,
            _ => return self.err("the index of a sum"),
        };
        self.expect(Tok::Ch('='), "`=` in the sum's range")?;
        let lo = self.expr()?;
        self.expect(Tok::Close, "`}`")?;
        self.expect(Tok::Ch('^'), "`^{hi}` after `\\sum_{...}`")?;
        let hi = self.group()?;
        let body = self.term()?;
        Ok(Expr::Calc(Calc::Sum, Box::new(body), var, vec![lo, hi]))
    }

    /// `\int_{a}^{b} body d x`.
    fn integral(&mut self) -> R<Expr> {
        self.expect(Tok::Ch('_'), "`_{lo}` after `\\int`")?;
        let lo = self.group()?;
        self.expect(Tok::Ch('^'), "`^{hi}` after `\\int_{...}`")?;
        let hi = self.group()?;
        self.in_integral += 1;
        let body = self.expr();
        self.in_integral -= 1;
        let body = body?;
        self.skip_space();
        if !self.is_differential() {
            return self.err("the differential `d x` closing an integral");
        }
        self.bump();
        let var = match self.bump() {
            Tok::Ch(c) => self.name_tail(c.to_string())?,
            Tok::Cmd(g) => self.name_tail(greek(&g).unwrap_or_default().to_string())?,
            _ => return self.err("the variable of an integral"),
        };
        Ok(Expr::Calc(Calc::Int, Box::new(body), var, vec![lo, hi]))
    }

    /// A chain of relations: `a = b`, `a = b = 0`, `a \le b`.
    pub(super) fn relation(&mut self) -> R<TexRelation> {
        let mut sides = vec![self.expr()?];
        let mut rels = Vec::new();
        loop {
            self.skip_space();
            let rel = match self.peek() {
                Tok::Ch('=') => "=",
                Tok::Ch('<') => "<",
                Tok::Ch('>') => ">",
                Tok::Cmd(c) => match c.as_str() {
                    "le" | "leq" | "leqslant" => "<=",
                    "ge" | "geq" | "geqslant" => ">=",
                    "approx" | "simeq" | "sim" => "~",
                    "ne" | "neq" => "!=",
                    "perp" => "perp",
                    "equiv" => "==",
                    "parallel" => "parallel",
                    _ => break,
                },
                _ => break,
            };
            self.bump();
            rels.push(rel);
            sides.push(self.expr()?);
        }
        self.skip_space();
        match self.peek().clone() {
            Tok::End => Ok(TexRelation { sides, rels }),
            Tok::Cmd(c) if c == "begin" => {
                self.err("an environment inside a formula (`\\begin{cases}`, an array)")
            }
            Tok::Cmd(c) => self.err(format!("the command `\\{c}`")),
            _ => self.err("an operator or the end of the formula"),
        }
    }
}
pub(super) fn num(text: &str) -> Option<Expr> {
    crate::algebra::poly::parse_q(text).map(Expr::Num)
}
pub(super) fn mul(a: Expr, b: Expr) -> Expr {
    Expr::Bin(Op::Mul, Box::new(a), Box::new(b))
}
pub(super) fn power(a: Expr, b: Expr) -> Expr {
    Expr::Bin(Op::Pow, Box::new(a), Box::new(b))
}

/// The inverse of a circular or hyperbolic function (`\sin^{-1}` is `asin`).
fn inverse(f: Func) -> Option<Func> {
    Some(match f {
        Func::Sin => Func::Asin,
        Func::Cos => Func::Acos,
        Func::Tan => Func::Atan,
        Func::Sinh => Func::Asinh,
        Func::Cosh => Func::Acosh,
        Func::Tanh => Func::Atanh,
        _ => return None,
    })
}
