//! The units of a text model: `[units]` read, and every formula checked against them (a sum must
//! not mix units; a right side is its state's unit per the unit of t).

use super::formulas::Reader;
use crate::algebra::expr::Expr;
use crate::algebra::units::{Unit, dimension};
use crate::models::params::{Fields, SceneError};
use std::collections::BTreeMap;

impl Reader<'_> {
    /// The unit of `e`, written as `shown`.
    /// The formula of `field` as written (definitions by name), checked with the definitions'
    /// units, so that a message names the terms the user wrote.
    pub(super) fn unit_of(&self, e: &Expr, field: &str, shown: &str) -> Result<Unit, SceneError> {
        let raw = self
            .raw
            .borrow()
            .get(field)
            .cloned()
            .unwrap_or_else(|| e.clone());
        dimension(&raw, &|s| {
            self.units.get(s).or_else(|| self.def_units.get(s)).copied()
        })
        .map_err(|err| self.bad_formula(field, shown, format!("the units do not agree: {err}")))
    }

    /// Checks that `e` (written as `shown`) is in `want`, the unit of `what`; a literal 0 is
    /// in every unit.
    pub(super) fn unit_is(
        &self,
        e: &Expr,
        field: &str,
        shown: &str,
        want: Unit,
        what: &str,
    ) -> Result<(), SceneError> {
        let u = self.unit_of(e, field, shown)?;
        // a written 0 is in every unit (`v = 0.0`)
        if u == want || matches!(e, Expr::Num(c) if num_traits::Zero::is_zero(c)) {
            return Ok(());
        }
        Err(self.bad_formula(field, shown, format!("is in {u}, but {what} is in {want}")))
    }
}

/// `[units]`: the unit of every parameter, state and t (and nothing else).
pub(super) fn read_units(
    f: &Fields,
    table: &toml::Table,
    slots: &[String],
) -> Result<BTreeMap<String, Unit>, SceneError> {
    let mut units = BTreeMap::new();
    for (k, v) in table {
        let field = format!("units.{k}");
        let text = v.as_str().ok_or_else(|| {
            f.invalid(
                &field,
                v.to_string(),
                "not a unit; allowed: a unit as text, e.g. \"m/s\"",
            )
        })?;
        let u = Unit::parse(text).map_err(|m| f.invalid(&field, format!("\"{text}\""), &m))?;
        if !slots.contains(k) {
            return Err(f.invalid(
                &field,
                format!("\"{text}\""),
                &format!(
                    "`{k}` is not t, a state or a parameter: a parameter missing from [parameters] \
                     (or a state from [state])? [units] gives the units of t, the states and the \
                     parameters: {}",
                    slots.join(", ")
                ),
            ));
        }
        units.insert(k.clone(), u);
    }
    if let Some(s) = slots.iter().find(|s| !units.contains_key(*s)) {
        return Err(SceneError::Missing {
            path: f.path.into(),
            field: format!("units.{s}"),
            allowed: "the unit of every parameter, state and t, e.g. \"m/s\"".into(),
        });
    }
    Ok(units)
}
