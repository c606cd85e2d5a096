//! Names: a letter, a Greek letter or a font's group with its subscripts, primes and labels
//! (`v_{j+1}`, `V^-`, `E^{*2}`, `x^{(k)}`, `R^{M-}`, `p^{a,b}`, `u^\dagger`), each one name.

use super::super::lex::{Tok, accent_suffix, func, greek};
use super::{R, Reader, is_named_operator};

impl Reader<'_> {
    /// The text of a `{...}` group of letters, digits and Greek commands (a name's part).
    pub(super) fn name_text(&mut self) -> R<String> {
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
                // `\dot{\pi}_\nu`: a quasi-velocity's letter under an accent is a name's, not
                // the constant
                Tok::Cmd(c) if braced && c == "pi" => {
                    self.bump();
                    out.push_str("pi");
                }
                Tok::Cmd(c) if c == "prime" => {
                    self.bump();
                    out.push('p');
                }
                // `\hat{\imath}`: the dotless i (j) of a unit vector is the letter
                Tok::Cmd(c) if c == "imath" || c == "jmath" => {
                    self.bump();
                    out.push_str(&c[..1]);
                }
                // `p_{1 ;}` of a scan: a separator put inside the braces, no name's part
                Tok::Ch(';') if braced && self.at(1) == Some(&Tok::Close) => {
                    return self.err("a name's part (letters, digits, Greek)");
                }
                Tok::Ch(',' | ';' | '\'' | '_' | '^') if braced => {
                    self.bump();
                }
                Tok::Ch('*') => {
                    self.bump();
                    out.push_str("star");
                }
                // an index that is an expression: `v_{j+1}`, `t_{n-1}`, `x_{(k)}`; `\omega_+`
                Tok::Ch('+') if braced || out.is_empty() => {
                    self.bump();
                    out.push_str("plus");
                }
                Tok::Ch('-') if braced || out.is_empty() => {
                    self.bump();
                    out.push_str("minus");
                }
                Tok::Ch('(' | ')' | '.' | '/' | '|' | '[' | ']') if braced => {
                    self.bump();
                }
                // `v_\infty`, `v_{\infty}`: the value at infinity
                Tok::Cmd(c) if c == "infty" => {
                    self.bump();
                    out.push_str("inf");
                }
                Tok::Cmd(c) if braced && (c == "ast" || c == "star") => {
                    self.bump();
                    out.push_str("star");
                }
                // `F_{\max}`, `\mu_\min`, `\sigma_{\rm eff}`, `E_{\sin}`: the command's name is
                // the part
                Tok::Cmd(c) if (braced && func(&c).is_some()) || is_named_operator(&c) => {
                    self.bump();
                    out.push_str(&c);
                }
                // `a_{\parallel}`, `v_\perp`
                Tok::Cmd(c) if matches!(c.as_str(), "parallel" | "perp" | "dagger") => {
                    self.bump();
                    out.push_str(&c[..3]);
                }
                // `a_{i+\frac{1}{2}}`: a half index of a grid
                Tok::Cmd(c) if braced && matches!(c.as_str(), "frac" | "tfrac" | "dfrac") => {
                    self.bump();
                    let top = self.name_text()?;
                    let bottom = self.name_text()?;
                    out.push_str(&format!("{top}over{bottom}"));
                }
                Tok::Open if braced => {
                    let inner = self.name_text()?;
                    out.push_str(&inner);
                    continue;
                }
                // `\mathbf{f}_\textrm{red}`: a font's group is the part, braced or not
                Tok::Cmd(c) if accent_suffix(&c).is_some() => {
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
    pub(super) fn name_tail(&mut self, mut name: String) -> R<String> {
        loop {
            match self.peek() {
                Tok::Ch('_') => {
                    self.bump();
                    let save = self.pos;
                    match self.name_text() {
                        // `P_i`, `x_i`, `N_u` spell `\Pi`, `\xi`, `\Nu` when joined: kept apart
                        Ok(part) if is_greek_name(&format!("{name}{part}")) => {
                            name.push('_');
                            name.push_str(&part);
                        }
                        Ok(part) => name.push_str(&part),
                        // a subscript that is a label of another kind (`P_{\left|a\right\rangle}`,
                        // `\mu_{\text{at rest}}`): its letters name it
                        Err(e) => {
                            self.pos = save;
                            name.push_str(&self.opaque_label().ok_or(e)?);
                        }
                    }
                }
                Tok::Ch('\'') => {
                    self.bump();
                    name.push('p');
                }
                // `t"`: a double prime as a scanned paper prints it
                Tok::Ch('"') => {
                    self.bump();
                    name.push_str("pp");
                }
                // `M_0^{\mathbf{p}}`, `A^{\mathrm{ext}}`: a label in a font, part of the name
                Tok::Ch('^')
                    if self.at(1) == Some(&Tok::Open)
                        && matches!(self.at(2), Some(Tok::Cmd(c)) if accent_suffix(c) == Some("") || c == "rm") =>
                {
                    self.bump();
                    let label = self.name_text()?;
                    name.push_str(&label);
                }
                // `p^{a,b}`, `x^{-,k}`: labels separated by commas, and `R^{M-}`, `r^{M+}`
                // (a formula does not end in a sign): part of the name
                Tok::Ch('^') if self.comma_script() || self.signed_label() => {
                    self.bump();
                    let label = self.name_text()?;
                    name.push_str(&label);
                }
                // `x^{(k)}`: an index in parentheses, part of the name
                Tok::Ch('^') if self.paren_index().is_some() => {
                    let (part, len) = self.paren_index().unwrap_or_default();
                    self.pos += len;
                    name.push_str(&part);
                }
                // `E^{*2}`: the star a label, the rest of the group a power
                Tok::Ch('^')
                    if self.at(1) == Some(&Tok::Open)
                        && self.at(2) == Some(&Tok::Ch('*'))
                        && !matches!(self.at(3), Some(Tok::Close) | None) =>
                {
                    self.pos += 3;
                    name.push_str("star");
                    self.star_power = true;
                    return Ok(name);
                }
                // `\mathbf{e}^{\omega}_{\ell}`, `\mathbf{e}^{2\omega}_{b}`: a script of letters with
                // a subscript after it labels the name (a power is written after the index)
                Tok::Ch('^') if name != "e" && self.label_then_subscript() => {
                    self.bump();
                    let label = self.opaque_label().unwrap_or_default();
                    name.push_str(&label);
                }
                // `T^{v\ell}_{p}`, `\chi^{zxx}`: a label of letters (not of `e`, whose `e^{ikx}` is
                // an exponential)
                Tok::Ch('^') if name != "e" && self.letters_label() => {
                    self.bump();
                    let label = self.name_text()?;
                    name.push_str(&label);
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
    pub(super) fn decoration(&self) -> Option<(&'static str, usize)> {
        let at = |k: usize| self.toks.get(self.pos + k).map(|t| &t.0);
        let label = |t: Option<&Tok>| match t {
            Some(Tok::Ch('-')) => Some("minus"),
            Some(Tok::Ch('+')) => Some("plus"),
            Some(Tok::Ch('*')) => Some("star"),
            // `E^\ast`, `r^\prime`: a label of the name (an adjoint or a transpose, `u^\dagger`,
            // `A^\top`, is the same quantity marked, read after the name)
            Some(Tok::Cmd(c)) => match c.as_str() {
                "ast" | "star" => Some("star"),
                "prime" => Some("p"),
                "perp" => Some("perp"),
                _ => None,
            },
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

    /// `^{(k)}` after a name: the index's text and how many tokens it takes.
    pub(super) fn paren_index(&self) -> Option<(String, usize)> {
        if self.at(1) != Some(&Tok::Open) || self.at(2) != Some(&Tok::Ch('(')) {
            return None;
        }
        let mut text = String::new();
        let mut k = 3;
        loop {
            match self.at(k)? {
                Tok::Ch(c) if c.is_ascii_alphanumeric() => text.push(*c),
                Tok::Num(n) => text.push_str(n),
                Tok::Ch('+') => text.push_str("plus"),
                Tok::Ch('-') => text.push_str("minus"),
                Tok::Ch(')') => break,
                _ => return None,
            }
            k += 1;
        }
        (self.at(k + 1) == Some(&Tok::Close) && !text.is_empty()).then_some((text, k + 2))
    }

    pub(super) fn is_prime_script(&self) -> bool {
        matches!(self.toks.get(self.pos + 1), Some((Tok::Open, _)))
            && matches!(self.toks.get(self.pos + 2), Some((Tok::Cmd(c), _)) if c == "prime")
    }
}

/// Whether `name` is the name the reader gives a Greek letter (`xi`, `Pi`, `nu`).
pub(super) fn is_greek_name(name: &str) -> bool {
    const GREEK: &[&str] = &[
        "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
        "lambda", "mu", "nu", "xi", "omicron", "pi", "rho", "sigma", "tau", "upsilon", "phi",
        "chi", "psi", "omega",
    ];
    let lower = name.to_lowercase();
    GREEK.contains(&lower.as_str()) && name.chars().skip(1).all(|c| c.is_lowercase())
}
