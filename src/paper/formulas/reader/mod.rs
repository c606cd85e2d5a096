//! Building expressions from the LaTeX reader's tokens: a recursive-descent reader of formulas
//! and relations (fractions, roots, scripts, functions, sums, integrals, derivatives, implicit
//! products).

use super::lex::{Tok, accent_suffix, describe, func, greek, is_space};
use super::{TexError, TexRelation, is_name};
use crate::algebra::expr::{Calc, Expr, Func, Op};
use crate::algebra::units::{ELLIPSIS, INFINITY};
use std::collections::BTreeSet;

mod apply;
mod big;
mod calculus;
mod delims;
mod marks;
mod names;
use marks::marked;

/// A link the reader found between two names: `(name, base, order)`, the name the `order`-th
/// time derivative of its base (`\dot{x}`: `("xd", "x", 1)`), or with order 0 an increment of
/// it (`\Delta t`: `("Deltat", "t", 0)`), in its unit.
pub(super) type Link = (String, String, u32);

pub(super) struct Reader<'a> {
    toks: &'a [(Tok, usize)],
    pos: usize,
    /// Inside an integrand: `d x` ends the product.
    in_integral: usize,
    /// Inside `| ... |`: a `|` closes, it does not open.
    in_abs: usize,
    /// How deep the formulas nest (a file from anyone must not overflow the stack).
    depth: usize,
    /// Inside `\| ... \|`: a `\|` closes.
    in_norm: usize,
    /// The names the paper applies as functions (`x(t)` somewhere): `x(t + T)` is one too.
    functions: &'a BTreeSet<String>,
    /// The increment letters the paper uses alone: no increments of these.
    lone: &'a BTreeSet<String>,
    /// The names the paper calls Dirac deltas.
    dirac: &'a BTreeSet<String>,
    /// The dotted names and increments met, with their bases.
    pub(super) links: Vec<Link>,
    /// A name just read ended in `^{*` of a starred power (`E^{*2}`): the rest of that group is
    /// its exponent.
    star_power: bool,
    /// The variable of a differential read inside an integrand's fraction (`\int \frac{du}{F}`):
    /// the integral's own.
    pending_differential: Option<(String, u32)>,
}

/// The deepest nesting read (as the text parser's limit).
pub(super) const MAX_DEPTH: usize = 200;

type R<T> = Result<T, TexError>;

impl<'a> Reader<'a> {
    /// A reader at the first of `toks` (which end in [`Tok::End`]).
    pub(super) fn new(
        toks: &'a [(Tok, usize)],
        functions: &'a BTreeSet<String>,
        lone: &'a BTreeSet<String>,
        dirac: &'a BTreeSet<String>,
    ) -> Self {
        Reader {
            toks,
            pos: 0,
            in_integral: 0,
            in_abs: 0,
            depth: 0,
            in_norm: 0,
            functions,
            lone,
            dirac,
            links: Vec::new(),
            star_power: false,
            pending_differential: None,
        }
    }

    fn at(&self, k: usize) -> Option<&Tok> {
        self.toks.get(self.pos + k).map(|t| &t.0)
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
        // `\sum_{\beta=1}^s (..)`: a one-letter script is the letter, never applied to what
        // follows it (even where the paper applies `s` elsewhere)
        if let Tok::Ch(c) = self.peek().clone()
            && c.is_ascii_alphabetic()
        {
            self.bump();
            return Ok(Expr::Sym(c.to_string()));
        }
        self.atom()
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
                // a direct sum of two of one kind
                Tok::Cmd(c) if c == "oplus" => {
                    self.bump();
                    e = Expr::Bin(Op::Add, Box::new(e), Box::new(self.term()?));
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
            Tok::Ch(c) => c.is_ascii_alphabetic() || matches!(c, '(' | '[' | '?'),
            Tok::Cmd(c) => {
                greek(c).is_some()
                    || func(c).is_some()
                    || accent_suffix(c).is_some()
                    || matches!(
                        c.as_str(),
                        "cot"
                            | "sec"
                            | "csc"
                            | "coth"
                            | "uppi"
                            | "underbrace"
                            | "overbrace"
                            | "begin"
                            | "lvert"
                            | "Re"
                            | "Im"
                            | "det"
                            | "bullet"
                            | "ddots"
                            | "vdots"
                    )
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
                            | "sup"
                            | "inf"
                            | "lim"
                            | "limsup"
                            | "liminf"
                            | "prod"
                            | "langle"
                            | "lvert"
                            | "lVert"
                            | "ldots"
                            | "cdots"
                            | "dots"
                            | "{"
                    )
                    || ((c == "|" || c == "Vert") && self.in_norm == 0)
                    || (c == "vert" && self.in_abs == 0)
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
        let mut e = match self.slash_derivative()? {
            Some(d) => d,
            None => self.unary()?,
        };
        loop {
            self.skip_space();
            match self.peek().clone() {
                // `\otimes`, `\odot`, `\ast`: products of tensors and arrays
                Tok::Cmd(c)
                    if matches!(
                        c.as_str(),
                        "cdot" | "times" | "otimes" | "odot" | "ast" | "star"
                    ) =>
                {
                    self.bump();
                    e = mul(e, self.unary()?);
                }
                Tok::Ch('*') => {
                    self.bump();
                    e = mul(e, self.unary()?);
                }
                // `\sigma : \nabla v`: a double contraction, a product of units (a colon
                // between relations was split off before)
                Tok::Ch(':') if self.at(1) != Some(&Tok::Ch('=')) => {
                    self.bump();
                    e = mul(e, self.unary()?);
                }
                Tok::Ch('/') => {
                    self.bump();
                    e = Expr::Bin(Op::Div, Box::new(e), Box::new(self.unary()?));
                }
                Tok::Cmd(c)
                    if arg
                        && (func(&c).is_some()
                            || matches!(c.as_str(), "cot" | "sec" | "csc" | "coth")) =>
                {
                    return Ok(e);
                }
                // a parenthesised factor ends a bare argument: `\cos \phi (a + b)` is
                // cos(phi) (a + b), as `\sin \omega t` is sin(omega t)
                Tok::Ch('(' | '[') if arg => return Ok(e),
                // a vector after a bare argument is a factor: `\sin\phi \hat{\mathbf{x}}` is
                // sin(phi) times the unit vector
                Tok::Cmd(c)
                    if arg
                        && matches!(
                            c.as_str(),
                            "hat"
                                | "widehat"
                                | "mathbf"
                                | "boldsymbol"
                                | "vec"
                                | "bm"
                                | "pmb"
                                | "vb"
                                | "vv"
                                | "symbf"
                                | "overrightarrow"
                        ) =>
                {
                    return Ok(e);
                }
                Tok::Cmd(c) if arg && c == "left" => return Ok(e),
                // an integral or a big operator after a bare argument is a factor:
                // `\sin \theta \int ..` is sin(theta) times the integral
                Tok::Cmd(c)
                    if arg
                        && matches!(
                            c.as_str(),
                            "int" | "iint" | "iiint" | "oint" | "sum" | "prod" | "lim"
                        ) =>
                {
                    return Ok(e);
                }
                Tok::Ch('d') if arg && self.is_differential() => return Ok(e),
                _ if self.starts_atom() && !self.is_differential_here() => {
                    e = mul(e, self.postfix()?);
                }
                _ => return Ok(e),
            }
        }
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
        if std::mem::take(&mut self.star_power) {
            let p = self.expr()?;
            self.expect(Tok::Close, "`}` closing a starred power")?;
            e = power(e, p);
        }
        loop {
            // `F \big|_{a}^{b}`, `v\big|_{z=0}`: the formula taken there keeps its unit
            if let Some(k) = self.evaluation_bar() {
                self.pos += k;
                self.skip_scripts()?;
                e = marked(e);
                continue;
            }
            match self.peek() {
                // `[P]^*`, `(\langle p|r \rangle)^*`, `\mathbf{A}^\top`: a conjugate or a
                // transpose keeps the unit
                Tok::Ch('^') if self.conjugate_mark().is_some() => {
                    self.pos += self.conjugate_mark().unwrap_or(1);
                    e = marked(e);
                }
                // `180^{\circ}`: degrees, a number of radians
                Tok::Ch('^') if self.degrees_follow() => {
                    self.pos += if self.at(1) == Some(&Tok::Open) { 4 } else { 2 };
                    let per = Expr::Bin(
                        Op::Div,
                        Box::new(Expr::Pi),
                        Box::new(num("180").unwrap_or(Expr::Pi)),
                    );
                    e = mul(e, per);
                }
                Tok::Ch('^') => {
                    self.bump();
                    let p = self.group()?;
                    e = power(e, p);
                }
                // `x^2_{max}`, `v^2_i`: TeX takes the scripts in either order; the subscript
                // belongs to the name
                Tok::Ch('_') if matches!(&e, Expr::Bin(Op::Pow, b, _) if matches!(&**b, Expr::Sym(s) if is_name(s))) =>
                {
                    self.bump();
                    let part = self.name_text()?;
                    if let Expr::Bin(Op::Pow, b, _) = &mut e
                        && let Expr::Sym(s) = &mut **b
                    {
                        s.push_str(&part);
                    }
                }
                Tok::Ch('!') => {
                    self.bump();
                    e = Expr::Call(Func::Factorial, Box::new(e));
                }
                // `\left(\frac{u'}{\sqrt{1+u'^2}}\right)'`: a bracket's derivative by a variable
                // the prime does not name, an opaque symbol named by its text, in a unit of its
                // own (a name's prime is part of the name: `u'`)
                Tok::Ch('\'') => {
                    let mut primes = String::new();
                    while *self.peek() == Tok::Ch('\'') {
                        self.bump();
                        primes.push('\'');
                    }
                    e = Expr::Sym(format!("{{({e}){primes}}}"));
                }
                // `(\partial V / \partial q)_0`, `[\mathbf{D}]_{ab}`, `\{f, g\}_{qp}`: taken at
                // a point, or a component: the unit of the formula
                // `(\mathcal{O}_{nm})_{;\mathbf{k}}`, `(S)_{,q}`: a derivative by the name after
                // the semicolon or comma
                Tok::Ch('_') if self.derivative_subscript().is_some() => {
                    let (var, len) = self.derivative_subscript().unwrap_or_default();
                    self.pos += len;
                    e = Expr::Calc(Calc::Diff, Box::new(e), var, vec![]);
                }
                Tok::Ch('_') => {
                    self.skip_scripts()?;
                    e = marked(e);
                }
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
            // `{\rm d} x`: an increment of x
            Tok::Open if self.braced_d() => {
                self.skip_space();
                self.bump();
                self.skip_space();
                self.bump();
                self.increment("d")
            }
            Tok::Open => {
                let e = self.expr()?;
                self.expect(Tok::Close, "`}`")?;
                Ok(e)
            }
            Tok::Ch('(') => self.closing(')'),
            // `p = ?` of an exercise: a value asked for, of whatever unit its place needs
            Tok::Ch('?') => Ok(Expr::Sym(ELLIPSIS.into())),
            Tok::Ch('[') => self.closing(']'),
            Tok::Ch('|') => {
                self.in_abs += 1;
                let e = self.expr();
                self.in_abs -= 1;
                let e = e?;
                self.expect(Tok::Ch('|'), "`|` closing an absolute value")?;
                Ok(Expr::Call(Func::Abs, Box::new(e)))
            }
            // a norm has the unit of its argument
            Tok::Cmd(c) if (c == "|" || c == "Vert") && self.in_norm == 0 => {
                self.in_norm += 1;
                let e = self.expr();
                self.in_norm -= 1;
                let e = e?;
                self.skip_space();
                if !matches!(self.peek(), Tok::Cmd(c) if c == "|" || c == "Vert") {
                    return self.err("`\\|` closing a norm");
                }
                self.bump();
                self.norm_subscript()?;
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
            // `{}^N\omega^B`, `^{A}\mathbf{R}`: a frame's label written before the name, part
            // of the name (the angular velocity of B in N is a quantity of its own)
            Tok::Ch('^')
                if !matches!(self.peek(), Tok::End | Tok::Ch(_))
                    || matches!(self.peek(), Tok::Ch(c) if c.is_ascii_alphanumeric()) =>
            {
                let label = self.name_text()?;
                match self.atom()? {
                    Expr::Sym(s) => Ok(Expr::Sym(format!("{label}{s}"))),
                    other => Ok(marked(other)),
                }
            }
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

    fn command(&mut self, c: &str, col: usize) -> R<Expr> {
        // `\Delta t`, `\delta x`: an increment, in the unit of what it increments
        if (c == "Delta" || c == "delta")
            && !self.lone.contains(c)
            && self.name_follows(c == "delta")
        {
            return self.increment(c);
        }
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
            // `\mathrm{Re}[..]`, `\operatorname{Im}(..)`: a real or imaginary part, the unit of
            // its argument
            // (without one, `\mathrm{Re}_p`, `\mathrm{Re}^{1/2}`: the Reynolds number, a name)
            self.skip_space();
            let opens = matches!(self.peek(), Tok::Ch('(' | '[') | Tok::Open)
                || matches!(self.peek(), Tok::Cmd(c) if c == "left" || c.starts_with("big") || c.starts_with("Big"));
            if suffix.is_empty() && matches!(inner.as_str(), "Re" | "Im") && opens {
                let arg = self.function_argument()?;
                return Ok(marked(arg));
            }
            // `\mathrm{d} x`: an increment of x
            if inner == "d" && suffix.is_empty() && self.name_follows(false) {
                return self.increment("d");
            }
            // `\mathbf{0}`: a number in a font is the number
            if suffix.is_empty() && inner.chars().all(|c| c.is_ascii_digit()) {
                return num(&inner).map_or_else(|| self.err("a number"), Ok);
            }
            // the tail read after the name so far (`\vec{P}_i` is no `\Pi`)
            let name = self.name_tail(format!("{inner}{suffix}"))?;
            let tail = name[inner.len() + suffix.len()..].to_string();
            // a dotted name is the time derivative of its base
            let order = ["dot", "ddot", "dddot"].iter().position(|d| *d == c);
            if let Some(k) = order {
                // the base kept apart from a Greek letter as the name is (`\dot{x}_i` is no `\xi`)
                let base = if names::is_greek_name(&format!("{inner}{tail}")) {
                    format!("{inner}_{tail}")
                } else {
                    format!("{inner}{tail}")
                };
                let link = (name.clone(), base, k as u32 + 1);
                if !self.links.contains(&link) {
                    self.links.push(link);
                }
            }
            return self.maybe_applied(name);
        }
        match c {
            "pi" | "uppi" => Ok(Expr::Pi),
            "infty" => Ok(Expr::Sym(INFINITY.into())),
            // cot, sec, csc as the reciprocals they are
            "cot" | "sec" | "csc" | "coth" => {
                let f = match c {
                    "cot" => Func::Tan,
                    "sec" => Func::Cos,
                    "csc" => Func::Sin,
                    _ => Func::Tanh,
                };
                let inner = self.function(f)?;
                // `\cot^{-1} x` is no reciprocal of `\tan^{-1} x`: refused, not misread
                if matches!(&inner, Expr::Call(g, _) if *g != f) {
                    return Err(TexError {
                        column: col,
                        construct: format!("an inverse `\\{c}^{{-1}}`"),
                        found: format!("\\{c}"),
                    });
                }
                Ok(reciprocal_of_call(inner))
            }
            // `\underbrace{-kx}_{\text{spring}}`: the formula, its note dropped
            "underbrace" | "overbrace" | "underset" | "overset" if c.ends_with("brace") => {
                let e = self.group()?;
                self.skip_space();
                if matches!(self.peek(), Tok::Ch('_' | '^')) {
                    self.bump();
                    self.skip_group()?;
                }
                Ok(e)
            }
            "ldots" | "cdots" | "dots" | "dotsb" | "dotsc" | "dotsm" | "dotsi" | "vdots"
            | "ddots" | "iddots" => Ok(Expr::Sym(ELLIPSIS.into())),
            "prod" => self.big(Calc::Prod),
            "max" | "sup" | "esssup" => self.big(Calc::Max),
            "min" | "inf" | "essinf" => self.big(Calc::Min),
            "lim" | "limsup" | "liminf" => self.big(Calc::Lim),
            "partial" => self.partial(),
            // the real or imaginary part has the unit of its argument
            "Re" | "Im" | "real" | "imag" => {
                let arg = self.function_argument()?;
                Ok(marked(arg))
            }
            // a determinant's unit is its matrix's to the order, which the formula does not
            // say: an opaque symbol named by its matrix, a unit of its own
            "det" => {
                let arg = self.function_argument()?;
                Ok(Expr::Sym(format!("{{det[{arg}]}}")))
            }
            // `\nabla \cdot (\bullet)`: a placeholder for an operand
            "bullet" => Ok(self.operand()),
            "langle" => self.angle("rangle"),
            "lvert" | "vert" => {
                self.in_abs += 1;
                let e = self.expr();
                self.in_abs -= 1;
                let e = e?;
                self.skip_space();
                if !matches!(self.peek(), Tok::Cmd(c) if c == "rvert" || c == "vert") {
                    return self.err("`\\rvert` closing an absolute value");
                }
                self.bump();
                Ok(Expr::Call(Func::Abs, Box::new(e)))
            }
            "lVert" => {
                let e = self.expr()?;
                self.expect(Tok::Cmd("rVert".into()), "`\\rVert` closing a norm")?;
                self.norm_subscript()?;
                Ok(Expr::Call(Func::Abs, Box::new(e)))
            }
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
            "sum" => self.big(Calc::Sum),
            "int" if *self.peek() == Tok::Ch('_') && self.bounds_follow() => self.integral(),
            "int" | "iint" | "iiint" | "oint" | "oiint" => {
                // `\iiint_V`: the region named, not a bound; `\int^{t}` an antiderivative's
                // upper end (the unit of `\int f dt` whatever it is)
                let mut region = None;
                if *self.peek() == Tok::Ch('_') {
                    self.bump();
                    region = Some(self.group()?.to_string());
                }
                if *self.peek() == Tok::Ch('^') {
                    self.bump();
                    self.group()?;
                }
                self.region_integral(region)
            }
            "begin" => self.matrix(col),
            other => Err(TexError {
                column: col,
                construct: format!("the command `\\{other}`"),
                found: format!("\\{other}"),
            }),
        }
    }

    /// The index of the `}` closing the group that opens at token `k`; `None` when it is not
    /// closed.
    pub(super) fn group_close(&self, k: usize) -> Option<usize> {
        let mut depth = 0usize;
        for (i, (t, _)) in self.toks.iter().enumerate().skip(k) {
            match t {
                Tok::Open => depth += 1,
                Tok::Close => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        return Some(i);
                    }
                }
                Tok::End => return None,
                _ => {}
            }
        }
        None
    }

    /// Past one argument: a `{..}` group or a single token.
    pub(super) fn skip_group(&mut self) -> R<()> {
        self.skip_space();
        if self.bump() == Tok::Open {
            self.skip_to_close("a group")?;
        }
        Ok(())
    }

    /// Past the `}` that closes the group the reader is inside (its `{` read before); `what`
    /// names it in the error when it is not closed.
    pub(super) fn skip_to_close(&mut self, what: &str) -> R<()> {
        let mut depth = 1usize;
        while depth > 0 {
            match self.bump() {
                Tok::Open => depth += 1,
                Tok::Close => depth -= 1,
                Tok::End => return self.err(format!("`}}` closing {what}")),
                _ => {}
            }
        }
        Ok(())
    }

    /// Whether `^\circ` or `^{\circ}` follows (degrees).
    fn degrees_follow(&self) -> bool {
        let circ = |t: Option<&Tok>| matches!(t, Some(Tok::Cmd(c)) if c == "circ");
        circ(self.at(1))
            || (self.at(1) == Some(&Tok::Open)
                && circ(self.at(2))
                && self.at(3) == Some(&Tok::Close))
    }

    /// The argument of a named operator (`\Re(z)`, `\det A`, `\Re\left(..\right)`).
    fn function_argument(&mut self) -> R<Expr> {
        self.skip_space();
        match self.peek() {
            Tok::Ch('(') | Tok::Open => self.atom(),
            Tok::Cmd(c) if c == "left" || c == "{" => self.atom(),
            _ => self.term_until(true),
        }
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

    /// A chain of relations: `a = b`, `a = b = 0`, `a \le b`.
    pub(super) fn relation(&mut self) -> R<TexRelation> {
        // a display that starts with `=` continues a formula of the prose: what it holds is
        // read without the side it does not show
        self.skip_space();
        if *self.peek() == Tok::Ch('=') {
            self.bump();
        }
        let mut sides = vec![self.expr()?];
        let mut rels = Vec::new();
        loop {
            self.skip_space();
            let rel = match self.peek() {
                // `=:` defines its right side
                Tok::Ch('=') if self.at(1) == Some(&Tok::Ch(':')) => {
                    self.bump();
                    "="
                }
                Tok::Ch('=') => "=",
                Tok::Ch('<') => "<",
                Tok::Ch('>') => ">",
                // `:=` defines
                Tok::Ch(':') if self.at(1) == Some(&Tok::Ch('=')) => {
                    self.bump();
                    "="
                }
                Tok::Cmd(c) => match c.as_str() {
                    // tends to: one unit
                    "to" | "rightarrow" | "longrightarrow" => "->",
                    // membership claims no unit across
                    "in" | "notin" | "subset" | "subseteq" => "in",
                    "le" | "leq" | "leqslant" | "lesssim" | "leqq" => "<=",
                    "ge" | "geq" | "geqslant" | "gtrsim" | "geqq" => ">=",
                    "ll" => "<<",
                    "gg" => ">>",
                    "approx" | "simeq" | "cong" | "doteq" | "approxeq" => "~",
                    // `\=` (a MathJax note's "is defined as")
                    "coloneqq" | "triangleq" | "eqqcolon" | "stackrel" | "=" => "=",
                    // a proportionality and a scaling claim no unit of their factor
                    "propto" => "propto",
                    "sim" => "sim",
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
            Tok::End => Ok(TexRelation {
                sides,
                rels,
                links: std::mem::take(&mut self.links),
            }),
            Tok::Cmd(c) if c == "begin" => {
                self.err("an environment inside a formula (`\\begin{cases}`, an array)")
            }
            Tok::Cmd(c) => self.err(format!("the command `\\{c}`")),
            _ => self.err("an operator or the end of the formula"),
        }
    }
}
/// The operators whose name may be a part of a subscript (`F_{\max}`, `t_{\min}`).
pub(super) fn is_named_operator(c: &str) -> bool {
    matches!(
        c,
        "max" | "min" | "sup" | "inf" | "lim" | "log" | "det" | "exp" | "arg" | "deg" | "dim"
    )
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

/// `1/f(x)` for `f(x)` (and `1/f(x)^p`, `f(x)^(-p)`, for a power of it): a cotangent from a
/// tangent.
fn reciprocal_of_call(e: Expr) -> Expr {
    match e {
        Expr::Bin(Op::Pow, base, p) => power(reciprocal_of_call(*base), *p),
        other => Expr::Bin(Op::Div, Box::new(one()), Box::new(other)),
    }
}

/// The number 1.
fn one() -> Expr {
    num("1").unwrap_or(Expr::Pi)
}
