//! Kind `definition`: a symbol's defining formula, checked for its unit (`defines`) and against
//! the equations that use it (`agrees`: identities that must hold with the definition
//! substituted).

use super::identity::{Identity, IdentitySpec};
use super::{Checked, Claim, Kind, Session, Where, claim_err, parse_formula};
use crate::algebra::expr::Expr;
use crate::algebra::units::{self, Unit};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use serde::Deserialize;

/// The keys of a `definition` claim.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DefinitionSpec {
    /// The defining formula.
    printed: String,
    /// The symbol it defines (its unit must be the formula's).
    #[serde(default)]
    defines: Option<String>,
    /// Identities `[printed, derived]` from the equations that use the definition.
    #[serde(default)]
    agrees: Vec<[String; 2]>,
    /// Plate modes at which the uses are compared.
    #[serde(default)]
    modes: Vec<[u32; 2]>,
    /// Definitions for this claim only.
    #[serde(default, rename = "where")]
    where_: Where,
}

/// A checked `definition` claim.
pub struct Definition {
    printed_text: String,
    printed: Expr,
    defines: Option<(String, Unit)>,
    /// Each use as written, and as an identity with the definition substituted.
    uses: Vec<([String; 2], Identity)>,
}

impl Kind for Definition {
    const NAME: &'static str = "definition";
    const PRINTED: &'static [&'static str] = &["printed"];
    type Spec = DefinitionSpec;

    fn validate(cx: &Checked, c: &Head, s: DefinitionSpec) -> Result<Self, VerifyError> {
        let f = cx.file;
        let raw = parse_formula(f, c, "printed", &s.printed)?;
        cx.units_of(c, "printed", &raw, &["m", "n"])?;
        let defines = match &s.defines {
            Some(d) => match cx.units.get(d) {
                Some(u) => Some((d.clone(), *u)),
                None => {
                    return Err(claim_err(
                        f,
                        c,
                        "defines",
                        format!("`{d}`: give its unit in [symbols]"),
                    ));
                }
            },
            None if s.agrees.is_empty() => {
                return Err(claim_err(
                    f,
                    c,
                    "agrees",
                    "a definition needs `defines` (the symbol, whose unit is checked) or `agrees` (identities from the equations that use it), or both".into(),
                ));
            }
            None => None,
        };
        let mut local = s.where_.clone();
        if let Some(d) = &s.defines {
            local.insert(d.clone(), s.printed.clone());
        }
        let mut uses = Vec::new();
        for (i, [l, r]) in s.agrees.iter().enumerate() {
            for (side, text) in [("printed", l), ("derived", r)] {
                let field = format!("agrees[{i}].{side}");
                let e = parse_formula(f, c, &field, text)?;
                cx.units_of(c, &field, &e, &["m", "n"])?;
            }
            let spec = IdentitySpec {
                printed: l.clone(),
                derived: r.clone(),
                modes: s.modes.clone(),
                where_: local.clone(),
                ..IdentitySpec::default()
            };
            uses.push(([l.clone(), r.clone()], Identity::of(cx, c, spec)?));
        }
        Ok(Definition {
            printed: cx.expand_all(c, &s.where_, &raw)?,
            printed_text: s.printed,
            defines,
            uses,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, run: &mut Session) -> Result<Outcome, VerifyError> {
        let p = &self.printed;
        let mut ok = true;
        let mut parts = Vec::new();
        if let Some((d, want)) = &self.defines {
            match units::dimension(p, &cx.unit_fn()) {
                Ok(u) if u == *want => parts.push(format!("`{d}` and `{p}` are both {u}")),
                Ok(u) => {
                    ok = false;
                    parts.push(format!("`{d}` is {want} but `{p}` is {u}"));
                }
                Err(e) => {
                    ok = false;
                    parts.push(format!("`{p}` has no single unit: {e}"));
                }
            }
        }
        for (i, ([l, r], identity)) in self.uses.iter().enumerate() {
            let o = identity.run(cx, c, run)?;
            let held = o.verdict == Verdict::Holds;
            ok &= held;
            parts.push(format!(
                "use {}: `{l}` {} `{r}` ({})",
                i + 1,
                if held { "=" } else { "!=" },
                o.detail
            ));
        }
        let verdict = if ok {
            Verdict::Definition
        } else {
            Verdict::Fails
        };
        Ok(outcome(cx.file, c, verdict, parts.join("; ")))
    }

    fn report(&self, _: &Head) -> String {
        format!(
            "Kind `definition`{}: `{}`; checked for units and against {} use(s).",
            self.defines
                .as_ref()
                .map(|(d, _)| format!(" of `{d}`"))
                .unwrap_or_default(),
            self.printed_text,
            self.uses.len()
        )
    }
}
