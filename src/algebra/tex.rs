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

use super::expr::{Calc, Expr, Func, Op};
use super::poly::Q;

/// Spellings mapped to symbols, longest first (a file's `[tex_symbols]`). A target that is
/// not a bare name is a formula of the text language (`"E(k)" = "ellipe(k)"`): the spelling
/// reads as that formula.
#[derive(Clone, Debug, Default)]
pub struct TexSymbols(Vec<(String, String)>);

impl TexSymbols {
    /// A table from `(spelling, symbol or formula)` pairs.
    pub fn new(pairs: impl IntoIterator<Item = (String, String)>) -> Self {
        let mut v: Vec<(String, String)> = pairs.into_iter().collect();
        v.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.0.cmp(&b.0)));
        TexSymbols(v)
    }

    /// This table with more pairs.
    pub fn with(&self, more: impl IntoIterator<Item = (String, String)>) -> Self {
        TexSymbols::new(self.0.iter().cloned().chain(more))
    }

    /// The targets that are formulas, parsed (a target that does not parse stays a symbol
    /// with an odd name, which the claim's reader refuses naming it).
    fn formulas(&self) -> Vec<(String, Expr)> {
        self.0
            .iter()
            .filter(|(_, t)| !is_name(t))
            .filter_map(|(_, t)| super::expr::parse(t).ok().map(|e| (t.clone(), e)))
            .collect()
    }
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
    /// The relations between them (`=`, `<`, `<=`, `>`, `>=`, `~` for `\approx`, `!=`).
    pub rels: Vec<&'static str>,
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

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Cmd(String),
    Ch(char),
    Num(String),
    Sym(String),
    Open,
    Close,
    End,
}

fn lex(src: &str, syms: &TexSymbols) -> Vec<(Tok, usize)> {
    let chars: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    'outer: while i < chars.len() {
        let col = i + 1;
        for (spelling, sym) in &syms.0 {
            let sp: Vec<char> = spelling.chars().collect();
            if !sp.is_empty() && chars[i..].starts_with(&sp) {
                out.push((Tok::Sym(sym.clone()), col));
                i += sp.len();
                continue 'outer;
            }
        }
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c == '\\' {
            let start = i + 1;
            let mut j = start;
            while j < chars.len() && chars[j].is_ascii_alphabetic() {
                j += 1;
            }
            if j == start && j < chars.len() {
                j += 1;
            }
            out.push((Tok::Cmd(chars[start..j].iter().collect()), col));
            i = j;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(char::is_ascii_digit))
        {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            out.push((Tok::Num(chars[start..i].iter().collect()), col));
        } else if c == '{' {
            out.push((Tok::Open, col));
            i += 1;
        } else if c == '}' {
            out.push((Tok::Close, col));
            i += 1;
        } else {
            out.push((Tok::Ch(c), col));
            i += 1;
        }
    }
    out.push((Tok::End, chars.len() + 1));
    out
}

const GREEK: &[&str] = &[
    "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
    "lambda", "mu", "nu", "xi", "omicron", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
    "Omega",
];

fn greek(cmd: &str) -> Option<&str> {
    Some(match cmd {
        "varepsilon" => "epsilon",
        "varphi" => "phi",
        "vartheta" => "theta",
        "varrho" => "rho",
        "varsigma" => "sigma",
        "varkappa" => "kappa",
        "nabla" => "nabla",
        "ell" => "l",
        c => return GREEK.iter().copied().find(|g| *g == c),
    })
}

fn func(cmd: &str) -> Option<Func> {
    Some(match cmd {
        "sin" => Func::Sin,
        "cos" => Func::Cos,
        "tan" => Func::Tan,
        "exp" => Func::Exp,
        "ln" => Func::Ln,
        "arcsin" => Func::Asin,
        "arccos" => Func::Acos,
        "arctan" => Func::Atan,
        _ => return None,
    })
}

/// Commands that only space or style: skipped.
fn is_space(t: &Tok) -> bool {
    match t {
        Tok::Cmd(c) => matches!(
            c.as_str(),
            "," | ";"
                | ":"
                | "!"
                | " "
                | "quad"
                | "qquad"
                | "displaystyle"
                | "textstyle"
                | "limits"
                | "nolimits"
                | "big"
                | "Big"
                | "bigg"
                | "Bigg"
        ),
        Tok::Ch('~') => true,
        _ => false,
    }
}

fn accent_suffix(cmd: &str) -> Option<&'static str> {
    Some(match cmd {
        "tilde" | "widetilde" => "t",
        "hat" | "widehat" => "h",
        "bar" | "overline" => "b",
        "dot" => "d",
        "ddot" => "dd",
        "mathbf" | "boldsymbol" | "mathrm" | "mathit" | "vec" | "bm" | "operatorname" | "text" => {
            ""
        }
        _ => return None,
    })
}

struct Reader<'a> {
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
const MAX_DEPTH: usize = 200;

type R<T> = Result<T, TexError>;

impl Reader<'_> {
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
    fn relation(&mut self) -> R<TexRelation> {
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

fn describe(t: &Tok) -> String {
    match t {
        Tok::Cmd(c) => format!("\\{c}"),
        Tok::Ch(c) => c.to_string(),
        Tok::Num(n) => n.clone(),
        Tok::Sym(s) => s.clone(),
        Tok::Open => "{".into(),
        Tok::Close => "}".into(),
        Tok::End => "the end".into(),
    }
}

fn num(text: &str) -> Option<Expr> {
    super::poly::parse_q(text).map(Expr::Num)
}

fn mul(a: Expr, b: Expr) -> Expr {
    Expr::Bin(Op::Mul, Box::new(a), Box::new(b))
}

fn power(a: Expr, b: Expr) -> Expr {
    Expr::Bin(Op::Pow, Box::new(a), Box::new(b))
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
    let mut r = Reader {
        toks: &toks,
        pos: 0,
        in_integral: 0,
        in_abs: 0,
        depth: 0,
    };
    let mut rel = r.relation()?;
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

/// The environments a display may wrap its rows in: their `\begin{..}`/`\end{..}` are dropped.
const ENVIRONMENTS: &[&str] = &[
    "equation",
    "equation*",
    "align",
    "align*",
    "aligned",
    "gather",
    "gather*",
    "gathered",
    "split",
    "multline",
    "multline*",
];

/// Splits `text` at the top level (outside braces and parentheses) at each of `seps`.
pub(crate) fn split_top(text: &str, seps: &[&str]) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    let (mut depth, mut out, mut cur) = (0i32, Vec::new(), String::new());
    let mut i = 0;
    'next: while i < chars.len() {
        let c = chars[i];
        if c == '\\' && i + 1 < chars.len() && matches!(chars[i + 1], '{' | '}') {
            cur.push(c);
            cur.push(chars[i + 1]);
            i += 2;
            continue;
        }
        let word = |w: &str| {
            let w: Vec<char> = w.chars().collect();
            chars[i..].starts_with(&w)
                && !chars
                    .get(i + w.len())
                    .is_some_and(char::is_ascii_alphabetic)
        };
        // \left\{ ... \right\} nest like the brackets they size
        if word("\\left") {
            depth += 1;
        } else if word("\\right") {
            depth -= 1;
        }
        match c {
            '{' | '(' | '[' => depth += 1,
            '}' | ')' | ']' => depth -= 1,
            _ => {}
        }
        if depth == 0 {
            for sep in seps {
                let sp: Vec<char> = sep.chars().collect();
                let word_end = sep.starts_with('\\')
                    && chars
                        .get(i + sp.len())
                        .is_some_and(char::is_ascii_alphabetic);
                if chars[i..].starts_with(&sp) && !word_end {
                    out.push(std::mem::take(&mut cur));
                    i += sp.len();
                    continue 'next;
                }
            }
        }
        cur.push(c);
        i += 1;
    }
    out.push(cur);
    out
}

/// The rows of a display (`$$ ... $$` without the dollars): environments dropped, rows split
/// at `\\`, alignment `&` removed, a row that starts with `+`, `-` or `=` joined to the one
/// before, `\tag{}` taken out, and each row's relations (separated by `,`, `;` or `\quad` at
/// the top level) read.
pub fn read_display(block: &str, syms: &TexSymbols) -> Vec<TexRow> {
    let mut text = block.to_string();
    // rows of an array or of cases, often braced by \left\{ ... \right.: the brace and the
    // column specification go
    if text.contains("\\begin{array}") || text.contains("\\begin{cases}") {
        for (open, close) in [
            ("\\begin{array}", "\\end{array}"),
            ("\\begin{cases}", "\\end{cases}"),
        ] {
            while let Some(at) = text.find(open) {
                let mut end = at + open.len();
                if text[end..].starts_with('{') {
                    end += text[end..].find('}').map_or(0, |k| k + 1);
                }
                text.replace_range(at..end, " ");
            }
            text = text.replace(close, " ");
        }
        for brace in ["\\left\\{", "\\right.", "\\left.", "\\right\\}"] {
            text = text.replace(brace, " ");
        }
    }
    for env in ENVIRONMENTS {
        text = text.replace(&format!("\\begin{{{env}}}"), " ");
        text = text.replace(&format!("\\end{{{env}}}"), " ");
    }
    let mut rows: Vec<String> = Vec::new();
    for raw in split_top(&text, &["\\\\"]) {
        let row = raw.replace('&', " ");
        let t = row.trim_start();
        let continues = t.starts_with('+') || t.starts_with('-') || t.starts_with('=');
        match rows.last_mut() {
            // a row that continues a relation joins it, also when the tag was printed on the
            // row before (a long relation tagged on its middle row, 000's (22)); the tag then
            // moves to the end of the joined row
            Some(prev) if continues && (!prev.contains("\\tag") || !starts_relation(&row)) => {
                let (body, tag) = take_tag(prev);
                *prev = format!("{body} {row}");
                if let Some(tag) = tag {
                    prev.push_str(&format!(" \\tag{{{tag}}}"));
                }
            }
            _ => rows.push(row),
        }
    }
    rows.into_iter()
        .filter(|r| !r.trim().is_empty())
        .map(|row| {
            let (tex, tag) = take_tag(&row);
            let relations = split_top(&tex, &[";", ",", "\\quad", "\\qquad"])
                .into_iter()
                .map(|p| p.trim().trim_end_matches('.').to_string())
                .filter(|p| !p.is_empty())
                .map(|p| read_relation(&p, syms))
                .collect();
            TexRow {
                tag,
                tex: tex.trim().to_string(),
                relations,
            }
        })
        .collect()
}

/// Whether a row that starts with `-` or `+` is a relation of its own (`-a = b`) rather than the
/// continuation of the row before (a relation sign at the top level).
fn starts_relation(row: &str) -> bool {
    split_top(row, &["=", "\\le", "\\ge", "<", ">", "\\approx"]).len() > 1
}

/// The row without its `\tag{...}`, and the tag.
fn take_tag(row: &str) -> (String, Option<String>) {
    match row.find("\\tag{") {
        Some(at) => {
            let rest = &row[at + 5..];
            match rest.find('}') {
                Some(end) => (
                    format!("{}{}", &row[..at], &rest[end + 1..]),
                    Some(rest[..end].trim().to_string()),
                ),
                None => (row.to_string(), None),
            }
        }
        None => (row.to_string(), None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::expr::parse;

    /// A symbol's test value in [0.5, 2), from its name.
    fn value(name: &str) -> Option<f64> {
        let h = name
            .bytes()
            .fold(7u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b)));
        Some(0.5 + (h % 1000) as f64 / 666.0)
    }

    #[test]
    fn two_formulas_in_one_and_a_derivative_by_a_number_are_refused() {
        let e = read_formula("a \\pm b", &TexSymbols::default()).unwrap_err();
        assert!(e.construct.contains("\\pm"), "{e}");
        let e = read_formula("c \\mp d", &TexSymbols::default()).unwrap_err();
        assert!(e.construct.contains("\\pm"), "{e}");
        assert!(read_formula("\\frac{\\partial f}{\\partial 1}", &TexSymbols::default()).is_err());
        for bad in [
            "\\frac{d f}{d ,}",
            "\\frac{d f}{d +}",
            "\\frac{\\partial f}{\\partial (}",
        ] {
            assert!(read_formula(bad, &TexSymbols::default()).is_err(), "{bad}");
        }
    }

    /// The LaTeX read equals the reference typed by hand: the same value at a point where every
    /// symbol has its own value.
    fn same(tex: &str, text: &str) {
        let a = read_formula(tex, &TexSymbols::default()).unwrap_or_else(|e| panic!("{tex}: {e}"));
        let b = parse(text).expect("the reference parses");
        assert_eq!(a.symbols(), b.symbols(), "{tex} read as {a}");
        let (x, y) = (
            a.eval(&value).expect("evaluates"),
            b.eval(&value).expect("evaluates"),
        );
        assert!(
            (x - y).abs() <= 1e-12 * y.abs().max(1.0),
            "{tex} read as {a}, not {text}"
        );
    }

    #[test]
    fn reads_the_math_of_papers() {
        // references: the same formulas typed in the text language by hand
        same(
            r"\frac{E m^{2} n^{2} \pi^{4} b}{64 a^{3}}",
            "E*m^2*n^2*pi^4*b/(64*a^3)",
        );
        same(r"\dfrac{1}{2} a b", "a*b/2");
        same(r"\sqrt{x^{2}+y^{2}}", "sqrt(x^2 + y^2)");
        same(r"\sqrt[3]{x}", "x^(1/3)");
        same(r"2\left(\nu+1\right)\lambda", "2*(nu + 1)*lambda");
        same(r"a \cdot b \times c", "a*b*c");
        same(r"A_{5} + p_{1} + \rho_{0}", "A5 + p1 + rho0");
        // an unbraced subscript ends at a power: A_5^2 is A5 squared
        same(r"A_5^2 + p_1^{3}", "A5^2 + p1^3");
        same(r"\tan \theta", "tan(theta)");
        same(r"\sin^{2}\phi + \cos^{2}\phi", "sin(phi)^2 + cos(phi)^2");
        same(
            r"\sin \frac{m \pi x}{a} \sin \frac{n \pi y}{b}",
            "sin(m*pi*x/a)*sin(n*pi*y/b)",
        );
        same(r"\exp (-\delta t)", "exp(-delta*t)");
        same(r"e^{-\alpha t}", "exp(-alpha*t)");
        same(r"\tilde{E} h^{3}", "Et*h^3");
        same(r"\frac{k!}{(k-i)!}", "factorial(k)/factorial(k - i)");
        same(r"\left|x\right| + |y|", "abs(x) + abs(y)");
        same(r"t^{\prime} + t'", "tp + tp");
        same(r"\mathrm{w} + \operatorname{sin} x", "w + sin(x)");
        same(r"\cos \phi (a + b)", "cos(phi)*(a + b)");
        // an integral over a region: opaque, named by its text; without its differential, an error
        assert_eq!(
            read_formula(r"\chi \int z x d \sigma", &TexSymbols::default())
                .unwrap()
                .to_string(),
            r"chi*{\int z x d \sigma}"
        );
        let e = read_formula(r"\iint f \, \xi", &TexSymbols::default()).unwrap_err();
        assert!(
            e.construct.contains("closing an integral over a region"),
            "{e}"
        );
        same(r"\sin 2\phi \left( a + b \right)", "sin(2*phi)*(a + b)");
        same(r"x \, y \; z \quad", "x*y*z");
    }

    #[test]
    fn sums_integrals_and_derivatives() {
        let s = TexSymbols::default();
        let e = read_formula(r"\sum_{i=0}^{k} \frac{k!}{(k-i)!} t^{k-i}", &s).unwrap();
        assert_eq!(
            e.to_string(),
            parse("sum(factorial(k)/factorial(k - i)*t^(k - i), i, 0, k)")
                .unwrap()
                .to_string()
        );
        let e = read_formula(r"\int_{0}^{t} e^{\alpha x} x^{k} d x", &s).unwrap();
        assert_eq!(
            e.to_string(),
            parse("int(exp(alpha*x)*x^k, x, 0, t)").unwrap().to_string()
        );
        let e = read_formula(r"\frac{\partial w}{\partial t}", &s).unwrap();
        assert_eq!(e.to_string(), "diff(w, t)");
    }

    #[test]
    fn applications_and_the_symbol_table() {
        let s = TexSymbols::default();
        assert_eq!(
            read_formula("w(x, y, t)", &s).unwrap().to_string(),
            "{w(x,y,t)}"
        );
        same("2(v+1)", "2*(v + 1)");
        let t = TexSymbols::new([
            ("z(t)".to_string(), "z".to_string()),
            (r"\tilde{E}".to_string(), "Eop".to_string()),
        ]);
        assert_eq!(
            read_formula(r"z(t)^{2} \tilde{E}", &t).unwrap().to_string(),
            "z^2*Eop"
        );
    }

    #[test]
    fn errors_name_the_column_and_the_construct() {
        let s = TexSymbols::default();
        let e = read_formula(r"a + \sum_{k=0}^{\infty} a_{k}", &s).unwrap_err();
        assert!(e.construct.contains("infinity"), "{e}");
        assert_eq!(e.column, 17, "{e}");
        let e = read_formula(r"\frac{a}{b", &s).unwrap_err();
        assert!(e.construct.contains('}'), "{e}");
        // nesting from a file from anyone: an error, not a stack overflow
        let deep = format!("{}x{}", "{".repeat(5000), "}".repeat(5000));
        let e = read_formula(&deep, &s).unwrap_err();
        assert!(e.construct.contains("nested"), "{e}");
        let deep = format!("{}x", r"\sqrt".repeat(5000));
        assert!(read_formula(&deep, &s).is_err());
        let deep = format!("{}x", "-".repeat(5000));
        assert!(read_formula(&deep, &s).is_err());
        let e = read_formula(r"a \star b", &s).unwrap_err();
        assert!(e.construct.contains("\\star"), "{e}");
    }

    #[test]
    fn displays_split_into_rows_tags_and_relations() {
        let rows = read_display(
            "\\begin{align*}\n& A_{1}=E \\zeta \\tag{16}\\\\\n& A_{7}=\\frac{2}{\\pi \\tan \\theta}, \\quad x = 1\n\\end{align*}",
            &TexSymbols::default(),
        );
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].tag.as_deref(), Some("16"));
        assert_eq!(rows[1].relations.len(), 2);
        let r = rows[1].relations[0].as_ref().expect("reads");
        assert_eq!(r.rels, vec!["="]);
        assert_eq!(r.sides[0].to_string(), "A7");
    }

    #[test]
    fn a_relation_tagged_on_its_middle_row_keeps_its_continuations() {
        // 000's (22): the tag printed on the middle row of a relation over three rows; a row
        // after it that is a relation of its own stays apart
        let rows = read_display(
            "& x=1+2 \\\\ & +3 \\tag{22} \\\\ & -4 \\\\ & -y=2",
            &TexSymbols::default(),
        );
        assert_eq!(rows.len(), 2, "{rows:?}");
        assert_eq!(rows[0].tag.as_deref(), Some("22"));
        let r = rows[0].relations[0].as_ref().expect("reads");
        assert_eq!(r.sides[1].eval(&|_| None), Ok(2.0));
        assert_eq!(rows[1].tag, None);
    }

    #[test]
    fn a_spelling_may_stand_for_a_formula() {
        let syms = TexSymbols::new([
            ("E(k)".to_string(), "ellipe(k)".to_string()),
            ("\\tilde{E}".to_string(), "Et".to_string()),
        ]);
        let e = read_formula("\\tilde{E} E(k)", &syms).expect("reads");
        assert_eq!(e.to_string(), "Et*ellipe(k)");
    }
}
