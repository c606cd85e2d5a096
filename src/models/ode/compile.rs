//! Compiling a text model's formulas to flat [`Program`]s, and its Jacobian as their symbolic
//! derivatives.

use super::formulas::Reader;
pub use super::program::Program;
use crate::algebra::expr::Expr;
use crate::models::params::SceneError;

impl Reader<'_> {
    pub(super) fn compile(&self, e: &Expr, field: &str) -> Result<Program, SceneError> {
        let slots = &self.slots;
        Program::compile(e, &|s| slots.iter().position(|n| n == s))
            .map_err(|m| self.bad_formula(field, &e.to_string(), m))
    }

    /// The Jacobian of the right sides `rhs` in the `states`, row-major: each entry the
    /// symbolic derivative, compiled (what Radau5 needs).
    pub(super) fn jacobian(
        &self,
        rhs: &[Expr],
        states: &[String],
    ) -> Result<Vec<Program>, SceneError> {
        let mut progs = Vec::new();
        for (e, s) in rhs.iter().zip(states) {
            let field = format!("equations.{s}");
            let lowered = e
                .lower()
                .map_err(|m| self.bad_formula(&field, &e.to_string(), m))?;
            for x in states {
                let d = crate::algebra::expr::calculus::derivative(&lowered, x).map_err(|m| {
                    self.bad_formula(
                        &field,
                        &e.to_string(),
                        format!("Radau5 needs its Jacobian, and {m} (use method = \"dop853\")"),
                    )
                })?;
                progs.push(self.compile(&d, &field)?);
            }
        }
        Ok(progs)
    }
}
