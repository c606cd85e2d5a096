//! Printing polynomials and exact rationals, as text (`3*alpha^2*gamma - v0`) and as LaTeX.

use super::{Poly, Q, Sym};
use num_traits::{One, Signed};
use std::fmt;

impl Sym {
    /// The symbol's name in LaTeX (`alpha` -> `\alpha`, `v0` -> `V_{0}`).
    pub fn latex(self) -> String {
        let n = self.name();
        match n.as_str() {
            "alpha" | "gamma" | "eta" | "nu" | "lambda" | "zeta" | "rho" | "pi" | "theta" => {
                format!("\\{n}")
            }
            "v0" => "V_{0}".into(),
            "a8" => "A_{8}".into(),
            "a9" => "A_{9}".into(),
            "m_s" => "m_{s}".into(),
            "Kw" => "K_{w}".into(),
            "KG" => "K_{G}".into(),
            "CT" => "C_{T}".into(),
            "p1" => "p_{1}".into(),
            "p2" => "p_{2}".into(),
            "tan_theta" => "\\tan\\theta".into(),
            _ => n,
        }
    }
}

impl Poly {
    /// Plain-text rendering, largest monomial first (`3*alpha^2*gamma - v0`).
    pub fn to_text(&self) -> String {
        render(self, false)
    }

    /// LaTeX rendering.
    pub fn to_latex(&self) -> String {
        render(self, true)
    }
}

fn render(p: &Poly, latex: bool) -> String {
    if p.is_zero() {
        return "0".into();
    }
    let mut out = String::new();
    for (i, (m, c)) in p.terms.iter().rev().enumerate() {
        let neg = c.is_negative();
        let a = c.abs();
        if i == 0 {
            if neg {
                out.push('-');
            }
        } else {
            out.push_str(if neg { " - " } else { " + " });
        }
        let factors: Vec<String> = m
            .factors()
            .map(|(s, e)| {
                let name = if latex { s.latex() } else { s.name() };
                match (e, latex) {
                    (1, _) => name,
                    (_, true) => format!("{name}^{{{e}}}"),
                    (_, false) => format!("{name}^{e}"),
                }
            })
            .collect();
        let coef = rat_text(&a, latex);
        if factors.is_empty() {
            out.push_str(&coef);
        } else {
            let sep = if latex { " " } else { "*" };
            if !a.is_one() {
                out.push_str(&coef);
                out.push_str(sep);
            }
            out.push_str(&factors.join(sep));
        }
    }
    out
}

/// A non-negative rational as text: `3/2`, or `\frac{3}{2}` in LaTeX.
/// An exact rational as `"-135232/2187"` or `"7"`.
pub fn q_text(c: &Q) -> String {
    use num_traits::Signed;
    let s = rat_text(&c.abs(), false);
    if c.is_negative() { format!("-{s}") } else { s }
}

pub fn rat_text(a: &Q, latex: bool) -> String {
    if a.is_integer() {
        a.numer().to_string()
    } else if latex {
        format!("\\frac{{{}}}{{{}}}", a.numer(), a.denom())
    } else {
        format!("{}/{}", a.numer(), a.denom())
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
    }
}
