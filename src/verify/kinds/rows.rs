//! The comparison of a model's values with a printed formula's over the points of a grid, shared
//! by the kinds that run a model (`model`, `threshold`, and a model claim's approximation order).

use super::g4;
use crate::verify::Verdict;

/// The verdict of a model's values against the printed formula's at the points of a grid
/// (`rows`: (model, printed) or why the point did not run): `holds` when the largest relative
/// difference is at most `rtol` and every point ran; the detail names the worst point, a
/// constant factor between the two and the first point that did not run. `what` names the
/// model's value (`model contact.duration`).
pub(super) fn compare_rows(
    points: &[Vec<(String, f64)>],
    rows: &[Result<(f64, f64), String>],
    rtol: f64,
    what: &str,
) -> (Verdict, String) {
    let mut worst: Option<(f64, usize)> = None;
    for (i, r) in rows.iter().enumerate() {
        if let Ok((m, p)) = r {
            let rel = (p - m).abs() / m.abs().max(f64::MIN_POSITIVE);
            let rel = if rel.is_nan() { f64::INFINITY } else { rel };
            if worst.is_none_or(|(w, _)| rel > w) {
                worst = Some((rel, i));
            }
        }
    }
    let failed = super::scene::failed_points(points, rows);
    let n = points.len();
    let (verdict, mut detail) = match worst {
        Some((w, i)) => {
            let (m, p) = rows[i].clone().unwrap_or((f64::NAN, f64::NAN));
            (
                if w <= rtol && failed.is_none() {
                    Verdict::Holds
                } else {
                    Verdict::Fails
                },
                format!(
                    "{n} grid points: largest relative difference {} (rtol {}) at {}: {what} = {}, printed {}",
                    g4(w),
                    g4(rtol),
                    super::scene::point_text(&points[i]),
                    g4(m),
                    g4(p)
                ),
            )
        }
        None => (Verdict::NotCheckable, format!("{n} grid points, none ran")),
    };
    // model/printed the same at every point: a constant factor, a coefficient misprint
    if verdict == Verdict::Fails && failed.is_none() {
        let ratios: Vec<f64> = rows.iter().flatten().map(|(m, p)| m / p).collect();
        if let Some(k) = super::identity::constant_factor(&ratios, rtol) {
            detail.push_str(&format!(
                "; model/printed = {} at every point (within rtol): {}",
                g4(k),
                super::identity::factor_text(&g4(k))
            ));
        }
    }
    if let Some(f) = &failed {
        detail.push_str(&format!("; {f}"));
        if worst.is_some() && verdict == Verdict::Fails {
            detail.push_str(" (a failed point counts against the claim)");
        }
    }
    (verdict, detail)
}
