//! Derivatives, differentials, increments and integrals: `\frac{\partial^2 w}{\partial t^2}`,
//! `\frac{d}{dt}(..)`, `\partial_t w`, `\mathrm{d}x`, `\Delta t`, `\int_a^b .. dx`, `\iint_S .. d\sigma`.
//! A derivative has the unit of its numerator over its denominator's, an increment the unit of
//! what it increments, an integral its integrand's times its element's.

use super::super::is_name;
use super::super::lex::{Tok, accent_suffix, greek, is_space};
use super::{R, Reader, num, one};
use crate::algebra::expr::{Calc, Expr, Op};

impl Reader<'_> {
    pub(super) fn frac(&mut self) -> R<Expr> {
        self.skip_space();
        // `\frac12`: TeX reads one digit a side
        if let Tok::Num(n) = self.peek().clone()
            && n.len() == 2
            && n.chars().all(|c| c.is_ascii_digit())
        {
            self.bump();
            let (a, b) = n.split_at(1);
            return Ok(Expr::Bin(
                Op::Div,
                Box::new(num(a).unwrap_or(Expr::Pi)),
                Box::new(num(b).unwrap_or(Expr::Pi)),
            ));
        }
        if let Some((a, var, power)) = self.numerator_differential()? {
            let b = self.group()?;
            self.pending_differential = Some((var, power));
            return Ok(Expr::Bin(Op::Div, Box::new(a), Box::new(b)));
        }
        // \frac{\partial f}{\partial x}, \frac{d f}{d x}, \frac{\partial^2 w}{\partial t^2},
        // \frac{\mathrm{d}^2 x}{\mathrm{d} t^2}, \frac{\partial}{\partial t} (..): a derivative
        let save = self.pos;
        if *self.peek() == Tok::Open {
            self.bump();
            self.skip_space();
            let partial = matches!(self.peek(), Tok::Cmd(c) if c == "partial");
            let mark = if partial { 1 } else { self.d_mark(self.pos) };
            // `\frac{d_1}{d_2}`: a name, not a differential
            let mark = match self.at(mark) {
                Some(Tok::Ch('_' | '\'')) => 0,
                _ => mark,
            };
            let partial = partial && mark > 0;
            if partial || (mark > 0 && self.diff_denominator_follows()) {
                self.pos += mark;
                self.derivative_order()?;
                self.skip_space();
                let body = if *self.peek() == Tok::Close {
                    None
                } else {
                    Some(self.expr()?)
                };
                self.expect(Tok::Close, "`}`")?;
                self.expect(Tok::Open, "`{` of the derivative's denominator")?;
                let mut vars = Vec::new();
                loop {
                    self.skip_space();
                    if *self.peek() == Tok::Close {
                        break;
                    }
                    let mark = match self.peek() {
                        Tok::Cmd(c) if c == "partial" => 1,
                        _ => self.d_mark(self.pos),
                    };
                    if mark == 0 {
                        return self.err("`d` or `\\partial` before a derivative's variable");
                    }
                    self.pos += mark;
                    // `\partial x`, `\partial \dot{q}`, `\partial{q_i}`, `\mathrm{d}{t}`
                    let var = self
                        .differential_variable()
                        .or_else(|_| self.err("the variable of a derivative"))?;
                    // `\partial e^{pl}`: a label of letters is part of the variable's name
                    let var = match self.letters_superscript() {
                        Some(label) => format!("{var}{label}"),
                        None => var,
                    };
                    let times = self.derivative_order()?;
                    vars.extend(std::iter::repeat_n(var, times as usize));
                }
                self.expect(Tok::Close, "`}`")?;
                if vars.is_empty() {
                    return self.err("the variable of a derivative");
                }
                let mut body = match body {
                    Some(b) => b,
                    // the operator form: what it acts on follows, or nothing
                    // (`\frac{d}{dt} = ..`, an operator equation)
                    None if self.no_operand() => self.operand(),
                    None => self.postfix()?,
                };
                let last = vars.last().cloned().unwrap_or_default();
                for v in vars {
                    body = Expr::Calc(Calc::Diff, Box::new(body), v, vec![]);
                }
                // `\frac{d r}{d t}(\tau)`: the derivative at a point (a name or a number; a
                // formula in parentheses is a factor: `\frac{dV}{dx}(x - x_0)`)
                if *self.peek() == Tok::Ch('(') {
                    let save = self.pos;
                    self.bump();
                    let at = self.atom();
                    self.skip_space();
                    match at {
                        Ok(at @ (Expr::Num(_) | Expr::Sym(_)))
                            if *self.peek() == Tok::Ch(')')
                                && !matches!(&at, Expr::Sym(s) if !is_name(s)) =>
                        {
                            self.bump();
                            return Ok(Expr::Calc(Calc::At, Box::new(body), last, vec![at]));
                        }
                        _ => self.pos = save,
                    }
                }
                return Ok(body);
            }
            self.pos = save;
        }
        let a = self.group()?;
        let b = self.group()?;
        Ok(Expr::Bin(Op::Div, Box::new(a), Box::new(b)))
    }

    /// `^{pl}`: a superscript of two letters or more (a label, as the plastic strain's
    /// `e^{pl}`), read and returned; `None` (nothing read) otherwise.
    pub(super) fn letters_superscript(&mut self) -> Option<String> {
        if *self.peek() != Tok::Ch('^') || self.at(1) != Some(&Tok::Open) {
            return None;
        }
        let mut k = self.pos + 2;
        let mut label = String::new();
        while let Some((Tok::Ch(c), _)) = self.toks.get(k) {
            if !c.is_ascii_alphabetic() {
                return None;
            }
            label.push(*c);
            k += 1;
        }
        if label.len() < 2 || self.toks.get(k).map(|t| &t.0) != Some(&Tok::Close) {
            return None;
        }
        self.pos = k + 1;
        Some(label)
    }

    /// `^{n}` of a derivative's order (`\partial^2`, `t^2` in its denominator): n, or 1.
    pub(super) fn derivative_order(&mut self) -> R<u32> {
        if *self.peek() != Tok::Ch('^') {
            return Ok(1);
        }
        self.bump();
        let order = self
            .group()?
            .exact_constant()
            .filter(|k| k.is_integer())
            .and_then(|k| num_traits::ToPrimitive::to_u32(&k.to_integer()))
            .filter(|n| (1..10).contains(n));
        match order {
            Some(n) => Ok(n),
            None => self.err("a derivative's order (a whole number from 1 to 9)"),
        }
    }

    /// How many tokens the differential mark at `k` takes: `d` (1), `\mathrm{d}` (4), `{\rm d}`
    /// (with its font switch); 0 when there is none.
    pub(super) fn d_mark(&self, k: usize) -> usize {
        let tok = |i: usize| self.toks.get(i).map(|t| &t.0);
        match tok(k) {
            Some(Tok::Ch('d')) => 1,
            Some(Tok::Cmd(c))
                if matches!(
                    c.as_str(),
                    "mathrm" | "text" | "operatorname" | "mathit" | "rm"
                ) && tok(k + 1) == Some(&Tok::Open)
                    && tok(k + 2) == Some(&Tok::Ch('d'))
                    && tok(k + 3) == Some(&Tok::Close) =>
            {
                4
            }
            Some(Tok::Open) => {
                let mut i = k + 1;
                while tok(i).is_some_and(is_space) {
                    i += 1;
                }
                if tok(i) == Some(&Tok::Ch('d')) && tok(i + 1) == Some(&Tok::Close) {
                    i + 2 - k
                } else {
                    0
                }
            }
            _ => 0,
        }
    }

    /// `d V / d \Omega`, `\mathrm{d}x/\mathrm{d}t^2`: a derivative written with a slash (a
    /// `d` over a `d` is no product of two depths), or `None` with nothing read.
    pub(super) fn slash_derivative(&mut self) -> R<Option<Expr>> {
        let save = self.pos;
        let mut vars = Vec::new();
        for k in 0..2 {
            let mark = self.d_mark(self.pos);
            if mark == 0 {
                self.pos = save;
                return Ok(None);
            }
            self.pos += mark;
            let Ok(var) = self.differential_variable() else {
                self.pos = save;
                return Ok(None);
            };
            vars.push(var);
            self.skip_space();
            if k == 0 {
                if *self.peek() != Tok::Ch('/') {
                    self.pos = save;
                    return Ok(None);
                }
                self.bump();
                self.skip_space();
            }
        }
        let times = self.derivative_order()?;
        let mut body = Expr::Sym(vars[0].clone());
        for _ in 0..times {
            body = Expr::Calc(Calc::Diff, Box::new(body), vars[1].clone(), vec![]);
        }
        Ok(Some(body))
    }

    /// Whether `{d ...}{d x}` follows (the denominator of a derivative).
    pub(super) fn diff_denominator_follows(&self) -> bool {
        let mut depth = 0;
        let mut k = self.pos;
        while let Some((t, _)) = self.toks.get(k) {
            match t {
                Tok::Open => depth += 1,
                Tok::Close if depth == 0 => {
                    if !matches!(self.toks.get(k + 1), Some((Tok::Open, _))) {
                        return false;
                    }
                    let mut i = k + 2;
                    while self.toks.get(i).is_some_and(|(t, _)| is_space(t)) {
                        i += 1;
                    }
                    return self.d_mark(i) > 0;
                }
                Tok::Close => depth -= 1,
                Tok::End => return false,
                _ => {}
            }
            k += 1;
        }
        false
    }

    /// `\partial_t w`, `\partial_{x}^2 u` (a derivative), or `\partial x` alone (an increment,
    /// as in `\partial w / \partial t`).
    pub(super) fn partial(&mut self) -> R<Expr> {
        self.skip_space();
        if *self.peek() == Tok::Ch('_') {
            self.bump();
            let vars = self.name_text()?;
            let order = self.derivative_order()?;
            let mut body = if self.no_operand() {
                self.operand()
            } else {
                self.postfix()?
            };
            // `\partial_{xy}`: one derivative per letter
            let letters: Vec<String> =
                if vars.chars().all(|c| c.is_ascii_alphabetic()) && vars.len() <= 4 && order == 1 {
                    vars.chars().map(|c| c.to_string()).collect()
                } else {
                    vec![vars; order as usize]
                };
            for v in letters {
                body = Expr::Calc(Calc::Diff, Box::new(body), v, vec![]);
            }
            return Ok(body);
        }
        if *self.peek() == Tok::Ch('^') {
            // `\partial^2 w` of a fraction written inline: the increment of w
            self.bump();
            self.group()?;
        }
        self.increment("d")
    }

    /// `\int_{a}^{b} body d x`.
    pub(super) fn integral(&mut self) -> R<Expr> {
        self.expect(Tok::Ch('_'), "`_{lo}` after `\\int`")?;
        let lo = self.group()?;
        self.expect(Tok::Ch('^'), "`^{hi}` after `\\int_{...}`")?;
        let hi = self.group()?;
        self.skip_space();
        self.in_integral += 1;
        // `\int_a^b dx` and `\int_a^b \frac{du}{F(u)}`: the integrand 1, or the differential in
        // the integrand's numerator
        let body = if self.is_differential() {
            Ok(one())
        } else {
            self.expr()
        };
        self.in_integral -= 1;
        let body = body?;
        self.skip_space();
        if let Some((var, power)) = self.pending_differential.take() {
            if power > 1 {
                return self.err("a volume element `d^n x` closing an integral with bounds");
            }
            return Ok(Expr::Calc(Calc::Int, Box::new(body), var, vec![lo, hi]));
        }
        if !self.is_differential() {
            return self.err("the differential `d x` closing an integral");
        }
        if self.skip_differential_mark() > 1 {
            return self.err("a volume element `d^n x` closing an integral with bounds");
        }
        let var = self.differential_variable()?;
        Ok(Expr::Calc(Calc::Int, Box::new(body), var, vec![lo, hi]))
    }

    /// An integral over a region, printed without limits (`\int x d\sigma`, `\iint f d\xi
    /// d\eta`): its integrand read (so that what it holds is a formula), the whole an opaque
    /// symbol named by its text (`{\int x d \sigma}`), as a function application is. The
    /// formula language has no region: a claim maps the spelling in `[tex_symbols]`, or the
    /// claim's reader refuses the symbol naming it. Over a named region without a differential
    /// (`\int_\Omega N f`, as finite-element texts write it), the measure of that region is the
    /// differential: one symbol per region (`{measure Omega}`), its unit the inference's.
    pub(super) fn region_integral(&mut self, region: Option<String>) -> R<Expr> {
        self.skip_space();
        // inside the integrand `d \sigma` ends the product; the depth is restored as it was
        let outer = self.in_integral;
        self.in_integral = outer.saturating_add(1);
        let body = if self.is_differential() {
            Ok(one())
        } else {
            self.expr()
        };
        self.in_integral = outer;
        let mut body = body?;
        self.skip_space();
        // `\int \frac{d^3 k}{8\pi^3} f`: a volume element in the numerator, once per dimension
        if let Some((var, power)) = self.pending_differential.take() {
            for _ in 1..power {
                body = Expr::Calc(Calc::Region, Box::new(body), var.clone(), vec![]);
            }
            return Ok(Expr::Calc(Calc::Region, Box::new(body), var, vec![]));
        }
        if !self.is_differential() {
            return match region {
                Some(r) => Ok(Expr::Calc(
                    Calc::Region,
                    Box::new(body),
                    format!("{{measure {r}}}"),
                    vec![],
                )),
                None => self.err("the differential `d \\sigma` closing an integral over a region"),
            };
        }
        while self.is_differential() {
            let power = self.skip_differential_mark();
            let var = self.differential_variable()?;
            for _ in 1..power {
                body = Expr::Calc(Calc::Region, Box::new(body), var.clone(), vec![]);
            }
            body = Expr::Calc(Calc::Region, Box::new(body), var, vec![]);
            self.skip_space();
        }
        Ok(body)
    }

    /// Whether `_{lo}^{hi}` (or `_a^b`) follows: an integral's bounds, not a region's name.
    pub(super) fn bounds_follow(&self) -> bool {
        let mut k = self.pos + 1;
        match self.toks.get(k).map(|t| &t.0) {
            Some(Tok::Open) => match self.group_close(k) {
                Some(close) => k = close,
                None => return false,
            },
            Some(Tok::Cmd(c)) if c == "infty" || greek(c).is_some() => {}
            Some(Tok::Ch('-')) => k += 1,
            Some(_) => {}
            None => return false,
        }
        matches!(self.toks.get(k + 1).map(|t| &t.0), Some(Tok::Ch('^')))
    }

    /// Inside an integrand, `{d u}` as a fraction's numerator (`\frac{du}{F(u)}`): its variable
    /// becomes the integral's, and the numerator is 1; `None` (nothing read) otherwise.
    /// The numerator and the variable: `{d u}` gives 1 and u, `{l \mathrm{d} u}` gives l and u.
    pub(super) fn numerator_differential(&mut self) -> R<Option<(Expr, String, u32)>> {
        if self.in_integral == 0 || *self.peek() != Tok::Open {
            return Ok(None);
        }
        let (save, links) = (self.pos, self.links.len());
        self.bump();
        self.skip_space();
        // a factor before the differential (inside an integrand a product stops at `d u`)
        let factor = if self.d_mark(self.pos) > 0 {
            Some(one())
        } else {
            self.expr().ok().filter(|_| self.is_differential())
        };
        if let Some(factor) = factor {
            // a volume element `d^3 k` in a numerator: its variable and its power
            let power = self.skip_differential_mark();
            let var = self.differential_variable().ok();
            self.skip_space();
            if let Some(v) = var
                && power >= 1
                && *self.peek() == Tok::Close
            {
                self.bump();
                // `\frac{d r}{d t}` inside an integrand is a derivative, not the integral's `d r`
                let mut k = self.pos + 1;
                while self.toks.get(k).is_some_and(|(t, _)| is_space(t)) {
                    k += 1;
                }
                let derivative = *self.peek() == Tok::Open
                    && (self.d_mark(k) > 0
                        || matches!(self.toks.get(k), Some((Tok::Cmd(c), _)) if c == "partial"));
                if !derivative {
                    return Ok(Some((factor, v, power)));
                }
            }
        }
        self.pos = save;
        self.links.truncate(links);
        Ok(None)
    }

    /// Whether the tokens here are `d x` closing an integral (set while reading an integrand).
    pub(super) fn is_differential_here(&self) -> bool {
        self.in_integral > 0 && self.is_differential()
    }

    pub(super) fn is_differential(&self) -> bool {
        let mark = self.d_mark(self.pos);
        if mark == 0 {
            return false;
        }
        let mut k = self.pos + mark;
        // `\mathrm{d}' A`: an inexact differential, of A's unit as `d A`; `d^3 x` a volume
        if matches!(self.toks.get(k), Some((Tok::Ch('\''), _))) {
            k += 1;
        } else if matches!(self.toks.get(k), Some((Tok::Ch('^'), _))) {
            k += self.volume_power(k).map_or(0, |(_, len)| len);
        }
        while self.toks.get(k).is_some_and(|(t, _)| is_space(t)) {
            k += 1;
        }
        let tok = |i: usize| self.toks.get(i).map(|t| &t.0);
        match tok(k) {
            Some(Tok::Ch(c)) => {
                c.is_ascii_alphabetic() && !matches!(tok(k + 1), Some(Tok::Ch('(')))
            }
            Some(Tok::Cmd(c)) => greek(c).is_some() || accent_suffix(c).is_some(),
            // `\mathrm{d}{y'}`, `\mathrm{d}{\vec{\boldsymbol{y}}}`: a braced name
            Some(Tok::Open) => {
                matches!(tok(k + 1), Some(Tok::Ch(c)) if c.is_ascii_alphabetic())
                    || matches!(tok(k + 1), Some(Tok::Cmd(c)) if greek(c).is_some() || accent_suffix(c).is_some())
            }
            _ => false,
        }
    }

    /// Past the differential mark (`d`, `\mathrm{d}`, `\mathrm{d}'`, `\mathrm{d}^3`) and the
    /// space after it; the power of a volume element (`d^3 x`: 3), else 1.
    pub(super) fn skip_differential_mark(&mut self) -> u32 {
        self.pos += self.d_mark(self.pos);
        if *self.peek() == Tok::Ch('\'') {
            self.bump();
        }
        let mut power = 1;
        if let Some((n, len)) = self.volume_power(self.pos) {
            power = n;
            self.pos += len;
        }
        self.skip_space();
        power
    }

    /// `^3` or `^{3}` at token `k` (of a volume element `d^3 x`): the power and how many tokens
    /// it takes.
    fn volume_power(&self, k: usize) -> Option<(u32, usize)> {
        let tok = |i: usize| self.toks.get(i).map(|t| &t.0);
        if tok(k) != Some(&Tok::Ch('^')) {
            return None;
        }
        let (n, len) = match (tok(k + 1), tok(k + 2), tok(k + 3)) {
            (Some(Tok::Num(n)), ..) => (n, 2),
            (Some(Tok::Open), Some(Tok::Num(n)), Some(Tok::Close)) => (n, 4),
            _ => return None,
        };
        match n.parse::<u32>() {
            Ok(p @ 1..=9) => Some((p, len)),
            _ => None,
        }
    }

    /// The variable of a differential (`x`, `\tau`, `\vec r`, `{y'}`): a name.
    fn differential_variable(&mut self) -> R<String> {
        self.skip_space();
        let braced = *self.peek() == Tok::Open;
        if braced {
            self.bump();
        }
        let save = self.pos;
        let name = match self.bump() {
            Tok::Ch(c) if c.is_ascii_alphabetic() => self.name_tail(c.to_string())?,
            Tok::Cmd(g) if greek(&g).is_some() => {
                self.name_tail(greek(&g).unwrap_or_default().to_string())?
            }
            Tok::Cmd(a) if accent_suffix(&a).is_some() => {
                let inner = self.name_text()?;
                let suffix = accent_suffix(&a).unwrap_or_default();
                self.name_tail(format!("{inner}{suffix}"))?
            }
            _ => {
                self.pos = save;
                return self.err("the variable of an integral");
            }
        };
        if braced {
            self.expect(Tok::Close, "`}` closing the variable of an integral")?;
        }
        Ok(name)
    }

    /// Whether `{\rm d}` (or `{d}`) stands here, followed by a name: an increment.
    pub(super) fn braced_d(&self) -> bool {
        let mut k = self.pos;
        while self.toks.get(k).is_some_and(|(t, _)| is_space(t)) {
            k += 1;
        }
        if !matches!(self.toks.get(k), Some((Tok::Ch('d'), _))) {
            return false;
        }
        k += 1;
        while self.toks.get(k).is_some_and(|(t, _)| is_space(t)) {
            k += 1;
        }
        if !matches!(self.toks.get(k), Some((Tok::Close, _))) {
            return false;
        }
        matches!(self.toks.get(k + 1), Some((Tok::Ch(c), _)) if c.is_ascii_alphabetic())
            || matches!(self.toks.get(k + 1), Some((Tok::Cmd(g), _)) if greek(g).is_some())
    }

    /// Whether a name follows (a letter, a Greek letter, or an accent or font on one), the
    /// variable of an increment; `strict`: a single Latin or Greek letter other than `\delta`
    /// and no accent (so that `\delta \dot{\delta}` stays a product, where δ is an indentation).
    pub(super) fn name_follows(&self, strict: bool) -> bool {
        let mut k = self.pos;
        while self.toks.get(k).is_some_and(|(t, _)| is_space(t)) {
            k += 1;
        }
        match self.toks.get(k).map(|t| &t.0) {
            Some(Tok::Ch(c)) if c.is_ascii_alphabetic() => {
                // `\Delta t`, not `\Delta (a + b)`, and not `\delta x(t)` of a field
                !strict || !matches!(self.toks.get(k + 1).map(|t| &t.0), Some(Tok::Ch('(')))
            }
            Some(Tok::Cmd(g)) if greek(g).is_some() => !strict || g != "delta",
            Some(Tok::Cmd(a)) if accent_suffix(a).is_some() => !strict,
            _ => false,
        }
    }

    /// The increment `prefix` of the name that follows (`\Delta t` -> `Deltat`), linked to it.
    pub(super) fn increment(&mut self, prefix: &str) -> R<Expr> {
        self.skip_space();
        let save = self.pos;
        let base = match self.atom()? {
            Expr::Sym(s) if is_name(&s) => s,
            // `\Delta w(x, y, t)`: a Laplacian of a field, not an increment: the letter alone
            _ => {
                self.pos = save;
                return Ok(Expr::Sym(prefix.to_string()));
            }
        };
        let name = format!("{prefix}{base}");
        let link = (name.clone(), base, 0);
        if !self.links.contains(&link) {
            self.links.push(link);
        }
        Ok(Expr::Sym(name))
    }
}
