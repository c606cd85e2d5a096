//! Formulas of a text model: parsed, with the definitions expanded, and checked to use only
//! known names (t, the states, the parameters, the definitions, pi).

use crate::algebra::expr::{Expr, parse};
use crate::algebra::units::Unit;
use crate::models::params::{Fields, SceneError};
use std::collections::BTreeMap;
use toml::Value;

/// Reads the text models' tables into a validated model.
pub(super) struct Reader<'a> {
    pub(super) f: Fields<'a>,
    pub(super) units: BTreeMap<String, Unit>,
    /// The unit of each definition, so that a formula is checked as written.
    pub(super) def_units: BTreeMap<String, Unit>,
    /// Each formula as parsed, before the definitions are expanded.
    pub(super) raw: std::cell::RefCell<BTreeMap<String, Expr>>,
    pub(super) defs: BTreeMap<String, Expr>,
    pub(super) slots: Vec<String>,
}

impl Reader<'_> {
    pub(super) fn bad(&self, field: &str, value: &str, allowed: &str) -> SceneError {
        self.f.out_of_range(field, value.to_string(), allowed)
    }

    /// An error about the formula `shown` of `field`.
    pub(super) fn bad_formula(&self, field: &str, shown: &str, message: String) -> SceneError {
        SceneError::Formula {
            path: self.f.path.into(),
            field: field.into(),
            formula: shown.trim_matches('"').into(),
            message,
        }
    }

    /// A formula (a string or a number), parsed, with the definitions expanded and checked to
    /// use only known names; and its text as written (for messages).
    pub(super) fn formula_text(
        &self,
        v: &Value,
        field: &str,
    ) -> Result<(Expr, String), SceneError> {
        let text = match v {
            Value::String(s) => s.clone(),
            Value::Float(x) if x.is_finite() => format!("{x:e}"),
            Value::Integer(i) => i.to_string(),
            other => {
                return Err(self.bad(
                    field,
                    &other.to_string(),
                    "a formula (a string) or a finite number",
                ));
            }
        };
        let parsed = parse(&text)
            .map_err(|e| self.bad_formula(field, &text, format!("not a formula: {e}")))?;
        let e = expand(&parsed, &self.defs);
        self.raw.borrow_mut().insert(field.to_string(), parsed);
        if let Some(s) = e.symbols().into_iter().find(|s| !self.slots.contains(s)) {
            return Err(self.bad_formula(
                field,
                &text,
                format!(
                    "`{s}` is not t, a state, a parameter or a definition (a formula may use those, and pi)"
                ),
            ));
        }
        Ok((e, text))
    }
}

/// `e` with every defined name replaced by its (expanded) definition.
pub(super) fn expand(e: &Expr, defs: &BTreeMap<String, Expr>) -> Expr {
    e.substitute(&|s| defs.get(s).cloned())
}
pub(super) fn table_of<'t>(
    f: &Fields,
    v: Option<&'t Value>,
    name: &str,
) -> Result<&'t toml::Table, SceneError> {
    f.table(v, name)
}
