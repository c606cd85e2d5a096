//! Kind `definition`: a symbol's defining formula, checked for its unit (`defines`) and against
//! the equations that use it (`agrees`: identities written with the defined symbol, which must
//! hold with the printed formula substituted for it; a use without the symbol is refused, as it
//! holds or fails whatever is printed).

use super::identity::{Identity, IdentitySpec};
use super::{Checked, Claim, Kind, Session, Where, claim_err, parse_formula};
use crate::algebra::expr::Expr;
use crate::algebra::units::{self, Unit};
use crate::verify::{Head, Outcome, Verdict, VerifyError, outcome};
use num_traits::Zero;
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
    defines: (String, Unit),
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
                Some(u) => (d.clone(), *u),
                None => {
                    return Err(claim_err(
                        f,
                        c,
                        "defines",
                        format!("`{d}`: give its unit in [symbols]"),
                    ));
                }
            },
            None => {
                return Err(claim_err(
                    f,
                    c,
                    "defines",
                    "missing: a definition names the symbol it defines (its unit is checked, and its uses in `agrees` read the printed formula through it)".into(),
                ));
            }
        };
        let mut local = s.where_.clone();
        local.insert(defines.0.clone(), s.printed.clone());
        let mut uses = Vec::new();
        for (i, [l, r]) in s.agrees.iter().enumerate() {
            let mut reads = false;
            for (side, text) in [("printed", l), ("derived", r)] {
                let field = format!("agrees[{i}].{side}");
                let e = parse_formula(f, c, &field, text)?;
                reads |= e.symbols().contains(&defines.0);
                cx.units_of(c, &field, &e, &["m", "n"])?;
            }
            if !reads {
                return Err(claim_err(
                    f,
                    c,
                    &format!("agrees[{i}]"),
                    format!(
                        "the use does not contain `{}`: it holds or fails whatever the printed formula is, so it checks nothing of the definition (write the use with `{}`, which stands for `printed`)",
                        defines.0, defines.0
                    ),
                ));
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
            // for its unit: a number in `where` is a value in that name's unit
            printed: cx.expand_all(c, &cx.where_for_units(&s.where_), &raw)?,
            printed_text: s.printed,
            defines,
            uses,
        })
    }

    fn check(&self, cx: &Checked, c: &Head, run: &mut Session) -> Result<Outcome, VerifyError> {
        let p = &self.printed;
        let mut ok = true;
        let mut parts = Vec::new();
        let (d, want) = &self.defines;
        let zero = p.exact_constant().is_some_and(|v| v.is_zero());
        match units::dimension(p, &cx.unit_fn()) {
            _ if zero => parts.push(format!("`{d}` is {want}, and a printed 0 has every unit")),
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
            "Kind `definition` of `{}`: `{}`; checked for units and against {} use(s).",
            self.defines.0,
            self.printed_text,
            self.uses.len()
        )
    }
}
