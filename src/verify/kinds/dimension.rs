//! Kind `dimension`: the unit of `printed` (units from the file's `[symbols]`, definitions by
//! their formulas) against `expect`; a sum whose terms disagree names each term's unit.

use super::{Checked, Kind, Session, Where, claim_err, parse_formula};
use crate::algebra::expr::{self, Expr};
use crate::algebra::units::{self, Unit};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;

/// The keys of a `dimension` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DimensionSpec {
    /// The formula as printed.
    printed: String,
    /// The expected unit (`"N"`).
    expect: String,
    /// Definitions for this claim only, expanded in `printed`.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// A checked `dimension` claim.
pub struct Dimension {
    /// As written (the detail quotes it).
    printed: Expr,
    /// With `where` expanded (its unit is computed).
    expanded: Expr,
    where_: Where,
    expect_text: String,
    expect: Unit,
}

impl Kind for Dimension {
    const NAME: &'static str = "dimension";
    const BLIND: Option<&'static str> = Some(
        "a unit check sees only the misprints that change the unit: a coefficient, a sign, a dropped term of the same unit or a symbol of the same unit keep it",
    );
    const PRINTED: &'static [&'static str] = &["printed"];
    const UNITS_ONLY: bool = true;
    type Spec = DimensionSpec;

    fn validate(cx: &Checked, c: &Head, s: DimensionSpec) -> Result<Self, VerifyError> {
        let printed = parse_formula(cx.file, c, "printed", &s.printed)?;
        let expanded = cx.expand_local(c, &cx.where_for_units(&s.where_), &printed)?;
        cx.units_of(c, "printed", &expanded, &[])?;
        let expect = Unit::parse(&s.expect).map_err(|m| claim_err(cx.file, c, "expect", m))?;
        Ok(Dimension {
            printed,
            expanded,
            where_: s.where_,
            expect_text: s.expect,
            expect,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, _: &mut Session) -> Result<Outcome, VerifyError> {
        let (p, want) = (&self.printed, self.expect);
        let unit = |e: &Expr| {
            let e = cx.expand_local(c, &cx.where_for_units(&self.where_), e)?;
            Ok::<_, VerifyError>(units::dimension(&e, &cx.unit_fn()))
        };
        // a definition the formula uses that has no unit of its own is named first
        let bad_defs: Vec<String> = p
            .symbols()
            .iter()
            .filter_map(|s| match cx.def_units.get(s) {
                Some(Err(e)) => Some(format!(
                    "`{s}` (defined as `{}`) has no single unit: {e}",
                    cx.defs[s]
                )),
                _ => None,
            })
            .collect();
        // the unit of every term of the top-level sum, so that the odd one is seen
        let terms = || -> Result<String, VerifyError> {
            Ok(top_terms(p)
                .iter()
                .map(|t| {
                    Ok(match unit(t)? {
                        Ok(u) if u == want => format!("`{t}`: {u}"),
                        Ok(u) => format!("`{t}`: {u} (not {want})"),
                        Err(units::DimError::Unknown(s)) if cx.defs.contains_key(&s) => {
                            format!("`{t}`: none (`{s}` has none)")
                        }
                        Err(e) => format!("`{t}`: none ({e})"),
                    })
                })
                .collect::<Result<Vec<_>, VerifyError>>()?
                .join("; "))
        };
        let several = top_terms(p).len() > 1;
        let (verdict, detail) = match units::dimension(&self.expanded, &cx.unit_fn()) {
            _ if !bad_defs.is_empty() => (
                Verdict::Fails,
                format!(
                    "{}{}",
                    bad_defs.join("; "),
                    if several {
                        format!("; the terms: {}", terms()?)
                    } else {
                        String::new()
                    }
                ),
            ),
            Ok(u) if u == want => (Verdict::Holds, format!("`{p}` is {u}, as expected")),
            Ok(u) => (
                Verdict::Fails,
                format!("`{p}` is {u}, not {want} (expected `{}`)", self.expect_text),
            ),
            Err(e) if several => (
                Verdict::Fails,
                format!("no single unit: {e}; the terms: {}", terms()?),
            ),
            Err(e) => (Verdict::Fails, format!("`{p}` has no single unit: {e}")),
        };
        Ok(outcome(cx.file, c, verdict, detail))
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `dimension`. Printed: `{}`; expected unit: `{}`.",
            self.printed, self.expect_text
        )
    }
}

/// The terms of a top-level sum (`a + b - c` gives `a`, `b`, `c`).
fn top_terms(e: &Expr) -> Vec<Expr> {
    match e {
        Expr::Bin(expr::Op::Add | expr::Op::Sub, a, b) => {
            let mut v = top_terms(a);
            v.extend(top_terms(b));
            v
        }
        other => vec![other.clone()],
    }
}
