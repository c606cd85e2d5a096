//! Work-precision: one problem over a ladder of tolerances, per method, against a reference.
//!
//! For each method and tolerance the problem is solved `repeats` times; the report keeps the
//! achieved error (max over components of $|y_i - y^{ref}_i| / \max(|y^{ref}_i|, 1)$ at the
//! end point: relative for large components, absolute for small ones), the right-hand-side evaluations and the median wall time.

use super::{IntegrateError, Method, OdeSystem, Options, Stats, solve};
use std::time::Instant;

/// One point of a work-precision diagram.
#[derive(Clone, Debug, serde::Serialize)]
pub struct WorkPoint {
    /// Method.
    pub method: Method,
    /// rtol = atol used.
    pub tol: f64,
    /// Achieved error at the end point (relative, floored).
    pub error: f64,
    /// Work counters of one solve.
    pub stats: Stats,
    /// Median wall time of one solve (s).
    pub seconds: f64,
}

/// Runs `sys` from `(t0, y0)` to `t_end` for each method and tolerance.
pub fn work_precision<S: OdeSystem>(
    sys: &S,
    (t0, y0, t_end): (f64, &[f64], f64),
    reference: &[f64],
    methods: &[Method],
    tols: &[f64],
    repeats: usize,
) -> Result<Vec<WorkPoint>, IntegrateError> {
    let mut out = Vec::new();
    for &method in methods {
        for &tol in tols {
            let opts = Options {
                rtol: tol,
                atol: tol,
                method,
                ..Options::default()
            };
            let mut times = Vec::with_capacity(repeats.max(1));
            let mut last = None;
            for _ in 0..repeats.max(1) {
                let start = Instant::now();
                let sol = solve(sys, t0, y0, t_end, &opts)?;
                times.push(start.elapsed().as_secs_f64());
                last = Some(sol);
            }
            let sol = last.expect("at least one repeat");
            times.sort_by(f64::total_cmp);
            let error = sol
                .y
                .iter()
                .zip(reference)
                .map(|(a, r)| (a - r).abs() / r.abs().max(1.0))
                .fold(0.0, f64::max);
            out.push(WorkPoint {
                method,
                tol,
                error,
                stats: sol.stats,
                seconds: times[times.len() / 2],
            });
        }
    }
    Ok(out)
}
