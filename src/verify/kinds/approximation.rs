//! An approximation checked as one (`order`, `small`, `small_max` of a `model` claim): a formula
//! right to order N in a small parameter is judged by the observed order of its error as that
//! parameter shrinks, and by `rtol` only within its stated range, not as an identity over the
//! whole grid.
//!
//! The observed order is the least-squares slope of log(relative error) against log(small) over
//! the (up to) five smallest values of the small parameter whose error stands above the solver's
//! floor (1e-11 relative). An approximation to order N has an error of order N + 1: the slope must
//! be at least N + 1 - 1/4.

use super::rows::compare_rows;
use super::scene::exact_point_text;
use super::{Checked, claim_err, g4};
use crate::algebra::expr::Expr;
use crate::verify::{Head, Verdict, VerifyError};

/// Relative errors below this are the solver's, not the approximation's.
const FLOOR: f64 = 1e-11;
/// How far below N + 1 the observed order may fall.
const SLACK: f64 = 0.25;

/// A claim's statement that its formula is an approximation.
pub(super) struct Order {
    /// The order N of the approximation (its error is of order N + 1).
    pub order: f64,
    /// The small parameter, a formula of bound symbols (a pure number).
    pub small: Expr,
    /// As written.
    pub small_text: String,
    /// The largest value of `small` where `rtol` is claimed.
    pub small_max: f64,
}

impl Order {
    /// Reads `order`, `small` and `small_max`: all or none but `small_max`; `small` a pure
    /// number of bound symbols.
    pub fn read(
        cx: &Checked,
        c: &Head,
        order: Option<f64>,
        small: Option<&str>,
        small_max: Option<f64>,
        bound: &dyn Fn(&str) -> bool,
    ) -> Result<Option<Order>, VerifyError> {
        let (order, text) = match (order, small) {
            (None, None) if small_max.is_none() => return Ok(None),
            (Some(o), Some(s)) => (o, s),
            _ => {
                return Err(claim_err(
                    cx.file,
                    c,
                    "order",
                    "an approximation gives `order` (N: right to order N) and `small` (the small parameter, a formula of bound symbols), and may give `small_max`".into(),
                ));
            }
        };
        if !(order.is_finite() && order >= 0.0) {
            return Err(claim_err(
                cx.file,
                c,
                "order",
                format!("{order}: the order of an approximation is a number >= 0"),
            ));
        }
        let small = crate::algebra::expr::parse(text)
            .map_err(|e| claim_err(cx.file, c, "small", format!("`{text}`: {e}")))?;
        if let Some(s) = small.free_symbols().into_iter().find(|s| !bound(s)) {
            return Err(claim_err(
                cx.file,
                c,
                "small",
                format!(
                    "`{s}` is not bound to a scene field: the small parameter is a formula of bound symbols"
                ),
            ));
        }
        if let Ok(u) = crate::algebra::units::dimension(&small, &cx.unit_fn())
            && u != crate::algebra::units::Unit::one()
        {
            return Err(claim_err(
                cx.file,
                c,
                "small",
                format!("`{text}` is in {u}: a small parameter is a pure number"),
            ));
        }
        let small_max = small_max.unwrap_or(f64::INFINITY);
        if small_max.is_nan() || small_max <= 0.0 {
            return Err(claim_err(
                cx.file,
                c,
                "small_max",
                format!("{small_max}: the range's end is a number > 0"),
            ));
        }
        Ok(Some(Order {
            order,
            small,
            small_text: text.to_string(),
            small_max,
        }))
    }

    /// The verdict: `rtol` within the range, and the observed order of the error. `smalls`
    /// holds the small parameter at each point (or why it has no value).
    pub fn judge(
        &self,
        points: &[Vec<(String, f64)>],
        rows: &[Result<(f64, f64), String>],
        smalls: &[Result<f64, String>],
        rtol: f64,
        what: &str,
    ) -> (Verdict, String) {
        let name = &self.small_text;
        // a power of the small parameter, bracketed when it is no single name
        let powered = if name.chars().all(|c| c.is_alphanumeric() || c == '_') {
            name.to_string()
        } else {
            format!("({name})")
        };
        // rtol where the claim states it
        let inside: Vec<usize> = (0..points.len())
            .filter(|&i| smalls[i].as_ref().is_ok_and(|s| s.abs() <= self.small_max))
            .collect();
        let in_points: Vec<Vec<(String, f64)>> =
            inside.iter().map(|&i| points[i].clone()).collect();
        let in_rows: Vec<Result<(f64, f64), String>> =
            inside.iter().map(|&i| rows[i].clone()).collect();
        let (range_verdict, range_detail) = if inside.is_empty() {
            (
                Verdict::NotCheckable,
                format!("no grid point has {name} <= {}", g4(self.small_max)),
            )
        } else {
            compare_rows(&in_points, &in_rows, rtol, what)
        };
        // the observed order, from the smallest values above the floor
        let mut errs: Vec<(f64, f64, usize)> = (0..points.len())
            .filter_map(|i| {
                let s = smalls[i].as_ref().ok()?.abs();
                let (m, p) = rows[i].as_ref().ok()?;
                let e = (p - m).abs() / m.abs().max(f64::MIN_POSITIVE);
                (s > 0.0 && e.is_finite() && e > FLOOR).then_some((s, e, i))
            })
            .collect();
        errs.sort_by(|a, b| a.0.total_cmp(&b.0));
        errs.truncate(5);
        let want = self.order + 1.0;
        let (order_ok, order_detail) = if errs.len() < 3 {
            (
                None,
                format!(
                    "the order of the error is not seen: {} point(s) with an error above {FLOOR:e} (three are needed)",
                    errs.len()
                ),
            )
        } else {
            let (xs, ys): (Vec<f64>, Vec<f64>) =
                errs.iter().map(|(s, e, _)| (s.ln(), e.ln())).unzip();
            let n = xs.len() as f64;
            let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
            let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
            let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
            let slope = sxy / sxx;
            (
                Some(slope >= want - SLACK),
                format!(
                    "the relative error falls as {powered}^{} over the {} smallest values of {name} ({} to {}; from {} at {}), for order {} it must fall at least as {powered}^{}",
                    g4(slope),
                    errs.len(),
                    g4(errs[0].0),
                    g4(errs[errs.len() - 1].0),
                    g4(errs[0].1),
                    exact_point_text(&points[errs[0].2]),
                    self.order,
                    want
                ),
            )
        };
        let verdict = match (range_verdict, order_ok) {
            (Verdict::Holds, Some(true)) => Verdict::Holds,
            (Verdict::Fails, _) | (_, Some(false)) => Verdict::Fails,
            _ => Verdict::NotCheckable,
        };
        let range = if self.small_max.is_finite() {
            format!("for {name} <= {}", g4(self.small_max))
        } else {
            "over the grid".to_string()
        };
        (
            verdict,
            format!(
                "an approximation to order {} in {name}: {order_detail}; {range}, {range_detail}",
                self.order
            ),
        )
    }
}
