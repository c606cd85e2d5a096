//! Validation of generic claims before anything runs: each kind's keys, formulas, units and
//! scenes ([`super::KIND_TABLE`]).

use super::*;

impl Checked<'_> {
    pub(super) fn validate_claim(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        match KIND_TABLE.iter().find(|k| k.name == c.kind) {
            Some(k) => (k.validate)(self, c),
            None => Err(claim_err(
                self.file,
                c,
                "kind",
                format!("unknown kind `{}`; allowed: {}", c.kind, KINDS.join(", ")),
            )),
        }
    }

    /// Validates a claim of kind `check`.
    pub(super) fn validate_check(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        // a named check may still read its printed formulas from the file
        for (i, row) in c.printed_matrix.iter().enumerate() {
            for (j, text) in row.iter().enumerate() {
                let field = format!("printed_matrix[{i}][{j}]");
                let e = parse_formula(f, c, &field, text)?;
                self.units_of(c, &field, &e, &[])?;
            }
        }
        if let Some(text) = &c.printed {
            let e = parse_formula(f, c, "printed", text)?;
            self.units_of(c, "printed", &e, &[])?;
        }
        for (i, text) in c.printed_equations.iter().enumerate() {
            let field = format!("printed_equations[{i}]");
            let e = parse_formula(f, c, &field, text)?;
            self.units_of(c, &field, &e, &[])?;
        }
        if c.check.is_empty() {
            return Err(claim_err(
                f,
                c,
                "check",
                "missing; kind `check` names a Rust check".into(),
            ));
        }
        Ok(())
    }

    /// Validates a claim of kind `identity`.
    pub(super) fn validate_identity(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        let p = parse_formula(
            f,
            c,
            "printed",
            required(f, c, "printed", &c.printed, "a formula")?,
        )?;
        self.units_of(c, "printed", &p, &["m", "n"])?;
        if let Some(sel) = &c.part {
            parse_formula(f, c, "part", sel)?;
        }
        let d = required(f, c, "derived", &c.derived, "a formula or @derivation")?;
        let (text, _) = split_refs(d).map_err(|m| claim_err(f, c, "derived", m))?;
        let de = parse_formula(f, c, "derived", &text)?;
        self.units_of(c, "derived", &de, &["m", "n"])?;
        if let Some(k) = &c.corrected {
            let (text, _) = split_refs(k).map_err(|m| claim_err(f, c, "corrected", m))?;
            let ke = parse_formula(f, c, "corrected", &text)?;
            self.units_of(c, "corrected", &ke, &["m", "n"])?;
        }
        Ok(())
    }

    /// Validates a claim of kind `dimension`.
    pub(super) fn validate_dimension(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        let p = parse_formula(
            f,
            c,
            "printed",
            required(f, c, "printed", &c.printed, "a formula")?,
        )?;
        self.units_of(c, "printed", &p, &[])?;
        let e = required(f, c, "expect", &c.expect, "a unit such as \"N\"")?;
        Unit::parse(e).map_err(|m| claim_err(f, c, "expect", m))?;
        Ok(())
    }

    /// Validates a claim of kind `definition`.
    pub(super) fn validate_definition(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        let p = parse_formula(
            f,
            c,
            "printed",
            required(f, c, "printed", &c.printed, "the defining formula")?,
        )?;
        self.units_of(c, "printed", &p, &["m", "n"])?;
        if let Some(d) = &c.defines
            && !self.units.contains_key(d)
        {
            return Err(claim_err(
                f,
                c,
                "defines",
                format!("`{d}`: give its unit in [symbols]"),
            ));
        }
        if c.defines.is_none() && c.agrees.is_empty() {
            return Err(claim_err(
                f,
                c,
                "agrees",
                "a definition needs `defines` (the symbol, whose unit is checked) or `agrees` (identities from the equations that use it), or both".into(),
            ));
        }
        for (i, [l, r]) in c.agrees.iter().enumerate() {
            for (side, text) in [("printed", l), ("derived", r)] {
                let field = format!("agrees[{i}].{side}");
                let e = parse_formula(f, c, &field, text)?;
                self.units_of(c, &field, &e, &["m", "n"])?;
            }
        }
        Ok(())
    }

    /// Validates a claim of kind `not-checkable`.
    pub(super) fn validate_not_checkable(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        let f = self.file;
        required(f, c, "reason", &c.reason, "what the text lacks for a check")?;
        Ok(())
    }

    /// Validates a claim of kind `bound`: with a scene as the other scene kinds; without one, a
    /// bound on formulas alone whose samples are the symbols' values.
    pub(super) fn validate_bound(&self, c: &ClaimSpec) -> Result<(), VerifyError> {
        if c.scene.is_some() {
            return self.validate_scene_kind(c, false, Some("require"));
        }
        let f = self.file;
        // a bound on formulas alone: the samples are the symbols' values
        count_and_seed(f, c)?;
        required(f, c, "require", &c.require, "an inequality")?;
        for (sym, d) in &c.sample {
            let key = format!("sample.{sym}");
            parse_dist(d).map_err(|m| claim_err(f, c, &key, m))?;
            if !self.units.contains_key(sym) {
                return Err(claim_err(
                    f,
                    c,
                    &key,
                    format!("`{sym}`: give its unit in [symbols]"),
                ));
            }
        }
        let ineq = self.inequality(c, "require")?;
        for e in [&ineq.lhs, &ineq.rhs] {
            self.units_of(c, "require", e, &[])?;
            for s in e.free_symbols() {
                if !c.sample.contains_key(&s) {
                    return Err(claim_err(
                        f,
                        c,
                        "require",
                        format!(
                            "`{s}` is not sampled: without a scene every symbol is drawn (sample.{s} = \"uniform(a, b)\")"
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Validates a claim of a kind that runs a scene (`model`, `bound`, `probability`, `map`):
    /// `gridded` for a grid (`vary`) rather than samples, `ineq_field` the key of its inequality
    /// if it has one (bound `require`, probability `event`, a map of a region `require`).
    pub(super) fn validate_scene_kind(
        &self,
        c: &ClaimSpec,
        gridded: bool,
        ineq_field: Option<&'static str>,
    ) -> Result<(), VerifyError> {
        let f = self.file;
        let path = self.scene_path(c)?;
        let (_, mut table) = self.scene_table(c)?;
        if gridded {
            if ineq_field.is_none() {
                required(
                    f,
                    c,
                    "quantity",
                    &c.quantity,
                    "a dotted path of the outcome",
                )?;
                let rtol = *required(f, c, "rtol", &c.rtol, "a relative tolerance")?;
                if !(rtol.is_finite() && rtol >= 0.0) {
                    return Err(claim_err(
                        f,
                        c,
                        "rtol",
                        format!("{rtol} is not a tolerance >= 0"),
                    ));
                }
            }
            if c.kind == "map" && c.vary.len() != 2 {
                return Err(claim_err(
                    f,
                    c,
                    "vary",
                    format!(
                        "a map has two axes, FIELD=START:STOP:COUNT[:log] each; {} given",
                        c.vary.len()
                    ),
                ));
            }
            if c.vary.is_empty() {
                return Err(claim_err(
                    f,
                    c,
                    "vary",
                    "missing; give at least one FIELD=START:STOP:COUNT[:log]".into(),
                ));
            }
            for spec in &c.vary {
                let a = parse_axis(spec).map_err(|m| claim_err(f, c, "vary", m))?;
                set_fields(&mut table, &a.field, a.values[0], "scene")
                    .map_err(|m| claim_err(f, c, "vary", m))?;
            }
        } else {
            count_and_seed(f, c)?;
            if c.sample.is_empty() {
                return Err(claim_err(
                    f,
                    c,
                    "sample",
                    "missing; give at least one FIELD = \"uniform(a, b)\"".into(),
                ));
            }
            for (fields, d) in &c.sample {
                let key = format!("sample.{fields}");
                let d = parse_dist(d).map_err(|m| claim_err(f, c, &key, m))?;
                set_fields(&mut table, fields, d.quantile(0.5), "scene")
                    .map_err(|m| claim_err(f, c, &key, m))?;
            }
        }
        if c.kind == "probability" {
            if let Some(e) = &c.expect {
                parse_expectation(e).map_err(|m| claim_err(f, c, "expect", m))?;
            }
            if let Some(conf) = c.confidence
                && !(conf > 0.0 && conf < 1.0)
            {
                return Err(claim_err(
                    f,
                    c,
                    "confidence",
                    format!("{conf} is out of range; allowed: 0 < confidence < 1"),
                ));
            }
        }
        for (sym, field) in &c.bind {
            if field_value(&table, field).is_none() {
                return Err(claim_err(
                    f,
                    c,
                    &format!("bind.{sym}"),
                    format!(
                        "scene field `{field}` is not a number in {}",
                        path.display()
                    ),
                ));
            }
        }
        // one run of the scene, to know what the model produces
        let outcome = run_table(&table, &path.display().to_string())
            .map_err(|m| claim_err(f, c, "scene", m))?;
        let mut formulas: Vec<(&str, Expr)> = Vec::new();
        match ineq_field {
            None => {
                let q = c.quantity.as_deref().unwrap_or_default();
                if lookup(&outcome, q).is_none() {
                    return Err(claim_err(
                        f,
                        c,
                        "quantity",
                        format!(
                            "`{q}`: the model does not produce this number; it produces: {}",
                            numeric_paths(&outcome).join(", ")
                        ),
                    ));
                }
                formulas.push((
                    "printed",
                    self.formula(
                        c,
                        "printed",
                        required(f, c, "printed", &c.printed, "a formula")?,
                    )?,
                ));
            }
            Some(field) => {
                let text = if field == "event" {
                    &c.event
                } else {
                    &c.require
                };
                required(f, c, field, text, "an inequality")?;
                let ineq = self.inequality(c, field)?;
                formulas.push((field, ineq.lhs));
                formulas.push((field, ineq.rhs));
            }
        }
        for (field, e) in &formulas {
            for s in e.free_symbols() {
                if !c.bind.contains_key(&s) && lookup(&outcome, &s).is_none() {
                    return Err(claim_err(
                        f,
                        c,
                        field,
                        format!(
                            "`{s}` is neither bound to a scene field (bind) nor a number the model produces ({})",
                            numeric_paths(&outcome).join(", ")
                        ),
                    ));
                }
            }
            self.units_of(c, field, e, &[])?;
        }
        Ok(())
    }
}
