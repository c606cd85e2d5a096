//! Work counters of a solve; the work-precision tables and the reports read this same struct.

use std::fmt;

/// What a solve cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Stats {
    /// Evaluations of the right-hand side (all of them, finite-difference Jacobians included).
    pub rhs_evals: usize,
    /// Jacobian evaluations (analytic or by finite differences).
    pub jac_evals: usize,
    /// LU decompositions (a real and a complex one count as two).
    pub lu_decomps: usize,
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Events that fired.
    pub events: usize,
}

impl std::ops::Add for Stats {
    type Output = Stats;
    fn add(self, o: Stats) -> Stats {
        Stats {
            rhs_evals: self.rhs_evals + o.rhs_evals,
            jac_evals: self.jac_evals + o.jac_evals,
            lu_decomps: self.lu_decomps + o.lu_decomps,
            steps: self.steps + o.steps,
            rejected: self.rejected + o.rejected,
            events: self.events + o.events,
        }
    }
}

impl fmt::Display for Stats {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} rhs evals, {} jacobians, {} LU, {} steps ({} rejected), {} events",
            self.rhs_evals, self.jac_evals, self.lu_decomps, self.steps, self.rejected, self.events
        )
    }
}
