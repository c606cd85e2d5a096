//! Coulomb friction at C at zero slip: the stick that keeps $\mathbf V_t = 0$, the slide
//! directions (rays of $P_t\mathbf B(\mathbf n - \mu\mathbf u) = \kappa\mathbf u$) and the rays a slip
//! dies on. 002_b53e4779673eb6ed.txt section 1.

use super::*;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// The rate of the relative velocity at C for a contact force direction (see [`velocity_rate`]).
pub(super) type Rate<'a> = &'a dyn Fn(&Vector3<f64>) -> Vector3<f64>;

/// Orthonormal tangent basis of the plane normal to `n`.
pub(super) fn tangent_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let a = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = (a - n * a.dot(n)).normalize();
    (t1, n.cross(&t1))
}

/// The tangential rate $\boldsymbol\tau$ of the impulse that keeps $\mathbf V_t = 0$ under the matrix
/// `b`: the least-norm solution of $\mathbf B_{tt}\boldsymbol\tau = -\mathbf B_{tn}$ ($\mathbf B_{tt}$ may be
/// singular with fixed points, (2.5)); `None` when that system has no solution.
pub(super) fn stick_tau(b: &Matrix3<f64>, n: &Vector3<f64>) -> Option<Vector3<f64>> {
    let (t1, t2) = tangent_basis(n);
    let bt = Matrix2::new(
        t1.dot(&(b * t1)),
        t1.dot(&(b * t2)),
        t2.dot(&(b * t1)),
        t2.dot(&(b * t2)),
    );
    let rhs = -Vector2::new(t1.dot(&(b * n)), t2.dot(&(b * n)));
    let scale = b.norm().max(f64::MIN_POSITIVE);
    let x = bt.svd(true, true).solve(&rhs, 1e-12 * scale).ok()?;
    ((bt * x - rhs).norm() <= 1e-9 * scale).then(|| t1 * x[0] + t2 * x[1])
}

/// At zero slip: stick (with the tangential rate that keeps $V_t = 0$) or the direction to slide;
/// `Err(None)` where neither is consistent: the stick needs a tangential rate outside the
/// friction cone and every slip direction decays (possible only where the matrix is not
/// symmetric: a rough support that slides).
pub(super) fn stick_or_slide(
    b: &Matrix3<f64>,
    rate: Rate,
    n: &Vector3<f64>,
    mu: f64,
) -> Result<Vector3<f64>, Option<Vector3<f64>>> {
    if let Some(tau) = stick_tau(b, n)
        && tau.norm() <= mu * (1.0 + 1e-12)
    {
        return Ok(tau);
    }
    // slide: the direction u on the unit circle with P_t B (n - mu u) parallel to u, growing
    // (with the support's reaction where it pushes); a stable root first, then the largest rate
    let best = slide_rays(rate, n, mu, 720)
        .into_iter()
        .filter(|r| r.rate > 0.0)
        .max_by(|x, y| {
            (x.stable, x.rate)
                .partial_cmp(&(y.stable, y.rate))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
    Err(best.map(|r| r.u))
}

/// The slide direction [`stick_or_slide`] found at C, or, where it found none: with a support,
/// a Painleve-type case at C (its friction makes the matrix of C non-symmetric, and C then has
/// no consistent motion); without one (B symmetric, where this does not occur but for rounding
/// at a degenerate B), the first tangent direction.
pub(super) fn slide_at_c(
    u: Option<Vector3<f64>>,
    supported: bool,
    n: &Vector3<f64>,
    chi: f64,
) -> Result<Vector3<f64>, ImpactError> {
    match u {
        Some(u) => Ok(u),
        None if supported => Err(no_support_motion(
            chi,
            "C can neither stick (the tangential rate it needs lies outside the friction cone) nor slip (every slip direction decays) while the support moves as it does",
        )),
        None => Ok(tangent_basis(n).0),
    }
}

/// A ray of slip directions: `u` on the unit circle with $P_t\mathbf B(\mathbf n - \mu\mathbf u)$
/// parallel to `u`; `rate` is the slip speed's rate along it (positive: the slip grows), `stable`
/// whether nearby directions turn towards it.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlipRay {
    pub(super) u: Vector3<f64>,
    pub(super) rate: f64,
    pub(super) stable: bool,
}

/// Every slip ray, found by scanning the circle and bisecting the cross product
/// $\mathbf u \times P_t\mathbf B(\mathbf n - \mu\mathbf u)$. A root where it falls through zero
/// as the angle grows is stable: a slip direction near it turns towards it.
///
/// The samples sit half a step off the tangent basis (the rays of a planar or symmetric impact
/// lie on it, where the cross product is zero but for rounding, of either sign), and the scan
/// closes on the value of its first sample: evaluating the same direction twice (at 0 and at
/// 2 pi, whose sines differ by rounding) could give two signs, and a ray at 0 was then missed
/// (tests/regression_planar_rod.rs).
pub(super) fn slide_rays(rate: Rate, n: &Vector3<f64>, mu: f64, samples: usize) -> Vec<SlipRay> {
    let (t1, t2) = tangent_basis(n);
    let f = |th: f64| {
        let u = t1 * th.cos() + t2 * th.sin();
        let w = rate(&(n - u * mu));
        let wt = Vector2::new(t1.dot(&w), t2.dot(&w));
        let uu = Vector2::new(th.cos(), th.sin());
        (uu.x * wt.y - uu.y * wt.x, uu.dot(&wt), u)
    };
    let step = 2.0 * std::f64::consts::PI / samples as f64;
    let angle = |k: usize| (k as f64 + 0.5) * step;
    let mut rays = Vec::new();
    let first = f(angle(0));
    let mut prev = first;
    for k in 1..=samples {
        let (th0, th1) = (angle(k - 1), angle(k));
        let cur = if k == samples { first } else { f(th1) };
        // a root in (th0, th1]: a change of sign, or a zero reached from either side (a zero
        // at th0 belongs to the interval before)
        let crossing = (prev.0 != 0.0) && (cur.0 == 0.0 || prev.0.signum() != cur.0.signum());
        if crossing {
            let stable = prev.0 > 0.0;
            let (mut a, mut bb) = (th0, th1);
            let pa = prev.0 > 0.0;
            for _ in 0..60 {
                let mid = 0.5 * (a + bb);
                let fm = f(mid).0;
                if fm != 0.0 && (fm > 0.0) == pa {
                    a = mid;
                } else {
                    bb = mid;
                }
            }
            let (_, rate, u) = f(0.5 * (a + bb));
            rays.push(SlipRay { u, rate, stable });
        }
        prev = cur;
    }
    rays
}

/// The stable rays along which a slip dies out (its speed falls at a constant rate there): a
/// slip that settles on one reaches zero at a simple root of $(\mathbf V_t, \mathbf u) -
/// \text{stop}$, where $|\mathbf V_t|$ only touches zero between two samples of a step. With a
/// large $\mu$ there can be two; which one a slip settles on depends on where it starts.
pub(super) fn decay_rays(rate: Rate, n: &Vector3<f64>, mu: f64) -> Vec<Vector3<f64>> {
    slide_rays(rate, n, mu, 180)
        .into_iter()
        .filter(|r| r.stable && r.rate < 0.0)
        .map(|r| r.u)
        .collect()
}
