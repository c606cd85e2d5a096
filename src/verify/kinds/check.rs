//! Kind `check`: a named Rust check of a paper (`check = "billiard-312"`), run through the
//! paper's registry ([`crate::verify::PAPERS`]); the claim may still give printed formulas
//! (`printed`, `printed_equations`, `printed_matrix`), which are read and unit-checked here.

use super::{Checked, Kind, Session, parse_formula};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;
use std::ops::Deref;

/// A named check's claim: its head and the keys a named check may read.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct NamedCheck {
    /// The claim's id, equation, quote (filled from the claim, not a key here).
    #[serde(skip)]
    pub head: Head,
    /// Which Rust check computes it.
    pub check: String,
    /// A printed formula the check reads.
    #[serde(default)]
    pub printed: Option<String>,
    /// Printed equations (their right-hand sides, in order).
    #[serde(default)]
    pub printed_equations: Vec<String>,
    /// A printed matrix (rows of formulas).
    #[serde(default)]
    pub printed_matrix: Vec<Vec<String>>,
    /// A corrected formula the check compares too.
    #[serde(default)]
    pub corrected: Option<String>,
    /// Which part of a check's cases (a hard case's id, a figure's part).
    #[serde(default)]
    pub part: Option<String>,
    /// Highest power, for checks over powers.
    #[serde(default)]
    pub k_max: Option<u32>,
    /// A scene, relative to the repository root.
    #[serde(default)]
    pub scene: Option<String>,
}

/// A printed value that is a number: NaN or an infinity (a root of a negative number, a pole)
/// is an error, so that no comparison (`f64::max` drops a NaN) passes it by.
fn finite(x: f64) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("evaluates to {x}"))
    }
}

impl NamedCheck {
    fn bad(&self, message: String) -> VerifyError {
        VerifyError::BadClaim {
            id: self.head.id.clone(),
            message,
        }
    }

    /// The claim's `printed`, evaluated with `values`; `what` says what the check expects there.
    pub fn printed_value(
        &self,
        what: &str,
        values: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<f64, VerifyError> {
        let text = self
            .printed
            .as_deref()
            .ok_or_else(|| self.bad(format!("needs `printed`: {what}")))?;
        self.eval_printed("printed", text, values)
    }

    /// One printed formula of the key `field`, parsed and evaluated with `values`: a finite number.
    fn eval_printed(
        &self,
        field: &str,
        text: &str,
        values: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<f64, VerifyError> {
        crate::algebra::expr::parse(text)
            .map_err(|e| e.to_string())
            .and_then(|e| e.eval(values))
            .and_then(finite)
            .map_err(|e| self.bad(format!("{field}: {e}")))
    }

    /// One printed formula of the key `field` as an exact rational function of its symbols.
    fn exact_printed(
        &self,
        field: &str,
        text: &str,
    ) -> Result<crate::algebra::ratfunc::RatFunc, VerifyError> {
        let e = crate::algebra::expr::parse(text).map_err(|e| self.bad(format!("{field}: {e}")))?;
        e.to_ratfunc().ok_or_else(|| {
            self.bad(format!(
                "{field}: `{text}` is not a rational function of its symbols (exact algebra needs one)"
            ))
        })
    }

    /// The claim's `printed` as an exact rational function; `what` says what the check expects.
    pub fn printed_exact(
        &self,
        what: &str,
    ) -> Result<crate::algebra::ratfunc::RatFunc, VerifyError> {
        let text = self
            .printed
            .as_deref()
            .ok_or_else(|| self.bad(format!("needs `printed`: {what}")))?;
        self.exact_printed("printed", text)
    }

    /// The claim's `printed_equations`, exactly `n` of them, as exact rational functions.
    pub fn printed_exacts(
        &self,
        n: usize,
        what: &str,
    ) -> Result<Vec<crate::algebra::ratfunc::RatFunc>, VerifyError> {
        if self.printed_equations.len() != n {
            return Err(self.bad(format!("printed_equations must give {n} formulas: {what}")));
        }
        self.printed_equations
            .iter()
            .enumerate()
            .map(|(k, text)| self.exact_printed(&format!("printed_equations[{k}]"), text))
            .collect()
    }

    /// The claim's `printed`, parsed, with the file's definitions (`[definitions]`) expanded in
    /// it until none is left; `what` says what the check expects there.
    pub fn printed_expanded(
        &self,
        paper: &crate::verify::PaperClaims,
        what: &str,
    ) -> Result<crate::algebra::expr::Expr, VerifyError> {
        let parse = |field: &str, text: &str| {
            crate::algebra::expr::parse(text).map_err(|e| self.bad(format!("{field}: {e}")))
        };
        let text = self
            .printed
            .as_deref()
            .ok_or_else(|| self.bad(format!("needs `printed`: {what}")))?;
        let defs = paper
            .definitions
            .iter()
            .map(|(k, v)| Ok((k.as_str(), parse(&format!("definitions.{k}"), v)?)))
            .collect::<Result<std::collections::BTreeMap<_, _>, VerifyError>>()?;
        let mut e = parse("printed", text)?;
        // a definition may use another; a cycle is refused when the file is read, so the depth
        // of nesting is at most the number of definitions
        for _ in 0..=defs.len() {
            if !e.symbols().iter().any(|s| defs.contains_key(s.as_str())) {
                return Ok(e);
            }
            e = e.substitute(&|s: &str| defs.get(s).cloned());
        }
        Err(self.bad("printed: the definitions it uses refer to each other in a cycle".into()))
    }

    /// The claim's `printed_equations`, exactly `n` of them, each evaluated with `values`;
    /// `what` says what the check expects there.
    pub fn printed_values(
        &self,
        n: usize,
        what: &str,
        values: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<Vec<f64>, VerifyError> {
        if self.printed_equations.len() != n {
            return Err(self.bad(format!("printed_equations must give {n} formulas: {what}")));
        }
        self.printed_equations
            .iter()
            .enumerate()
            .map(|(k, text)| self.eval_printed(&format!("printed_equations[{k}]"), text, values))
            .collect()
    }

    /// The claim's `printed_matrix` as rows of `width` numbers (any number of rows), each
    /// formula evaluated with `values`; `what` says what a row is.
    pub fn printed_rows(
        &self,
        width: usize,
        what: &str,
        values: &dyn Fn(&str) -> Option<f64>,
    ) -> Result<Vec<Vec<f64>>, VerifyError> {
        if self.printed_matrix.is_empty() || self.printed_matrix.iter().any(|r| r.len() != width) {
            return Err(self.bad(format!(
                "printed_matrix must be rows of {width} formulas: {what}"
            )));
        }
        self.printed_matrix
            .iter()
            .enumerate()
            .map(|(i, row)| {
                row.iter()
                    .enumerate()
                    .map(|(j, text)| {
                        self.eval_printed(&format!("printed_matrix[{i}][{j}]"), text, values)
                    })
                    .collect()
            })
            .collect()
    }
}

impl Deref for NamedCheck {
    type Target = Head;
    fn deref(&self) -> &Head {
        &self.head
    }
}

/// A checked `check` claim.
pub struct Check(NamedCheck);

impl Kind for Check {
    const NAME: &'static str = "check";
    const PRINTED: &'static [&'static str] = &["printed", "printed_equations", "printed_matrix"];
    type Spec = NamedCheck;

    fn validate(cx: &Checked, c: &Head, mut s: NamedCheck) -> Result<Self, VerifyError> {
        let f = cx.file;
        for (i, row) in s.printed_matrix.iter().enumerate() {
            for (j, text) in row.iter().enumerate() {
                let field = format!("printed_matrix[{i}][{j}]");
                let e = parse_formula(f, c, &field, text)?;
                cx.units_of(c, &field, &e, &[])?;
            }
        }
        if let Some(text) = &s.printed {
            let e = parse_formula(f, c, "printed", text)?;
            cx.units_of(c, "printed", &e, &[])?;
        }
        for (i, text) in s.printed_equations.iter().enumerate() {
            let field = format!("printed_equations[{i}]");
            let e = parse_formula(f, c, &field, text)?;
            cx.units_of(c, &field, &e, &[])?;
        }
        if let Some((_, checks)) = crate::verify::PAPERS.iter().find(|(p, _)| *p == f.paper)
            && !checks.iter().any(|(name, _)| *name == s.check)
        {
            let names: Vec<&str> = checks.iter().map(|(n, _)| *n).collect();
            return Err(super::claim_err(
                f,
                c,
                "check",
                format!(
                    "unknown check `{}` of paper {}; allowed: {}",
                    s.check,
                    f.paper,
                    names.join(", ")
                ),
            ));
        }
        s.head = c.clone();
        Ok(Check(s))
    }

    fn check(&self, cx: &Checked, c: &Head, run: &mut Session) -> Result<Outcome, VerifyError> {
        let p = cx.file;
        let named = crate::verify::PAPERS
            .iter()
            .find(|(name, _)| *name == p.paper)
            .and_then(|(_, checks)| checks.iter().find(|(name, _)| *name == self.0.check));
        let mut o = match named {
            Some((_, run_check)) => run_check(&mut run.named, p, &self.0)?,
            None => outcome(
                p,
                c,
                Verdict::NotCheckable,
                format!(
                    "no Rust checks exist for paper {}: use a generic kind",
                    p.paper
                ),
            ),
        };
        o.kind = format!("check `{}`", self.0.check);
        Ok(o)
    }

    fn report(&self, _: &Head) -> String {
        String::new()
    }
}
