//! A second body resting on a fixed support at A: the matrices of (3.4), the smooth-support
//! reaction (3.6)-(3.8) and the rough-support classification of section 4 (Painleve-type cases),
//! 002_b53e4779673eb6ed.txt.
//!
//! $$\dot{\mathbf V}_C = \mathbf B\mathbf F - \tilde{\mathbf B}'\mathbf F^*,\quad
//!   \dot{\mathbf V}_A = \mathbf B_A\mathbf F^* - \tilde{\mathbf B}\mathbf F,\quad
//!   \tilde{\mathbf B}\mathbf F = m_2^{-1}\mathbf F + \mathbf J_2^{-1}(\mathbf G_2\mathbf C\times\mathbf F)\times\mathbf G_2\mathbf A,\quad
//!   \mathbf B_A\mathbf F^* = m_2^{-1}\mathbf F^* + \mathbf J_2^{-1}(\mathbf G_2\mathbf A\times\mathbf F^*)\times\mathbf G_2\mathbf A .$$
//! With a smooth support $F_N^* = \max(0, -\alpha/\beta)$, $\alpha = -(\tilde{\mathbf B}\mathbf F, \mathbf N)$,
//! $\beta = (\mathbf B_A\mathbf N, \mathbf N)$ (3.7). With Coulomb friction $\mu^*$ at A the four motion
//! types (detach, roll, slide, start to slide) are tested one by one; the count of admissible ones
//! is the classification: one ("unique"), none, or more ("two").

use super::rigid_impact::Body;
use nalgebra::{Matrix3, Vector3};

/// The support of the second body.
#[derive(Clone, Debug)]
pub struct Support {
    /// $\mathbf G_2\mathbf A$ (m).
    pub offset: Vector3<f64>,
    /// Normal N at A, from the support into the body (unit after construction).
    pub normal: Vector3<f64>,
    /// Friction coefficient $\mu^*$ at A (0 for a smooth support).
    pub mu: f64,
}

/// The matrices of (3.4) for body 2 (which must have a mass).
#[derive(Clone, Debug)]
pub struct SupportMatrices {
    /// $\tilde{\mathbf B}$.
    pub b_tilde: Matrix3<f64>,
    /// $\mathbf B_A$.
    pub b_a: Matrix3<f64>,
}

fn columns(f: impl Fn(Vector3<f64>) -> Vector3<f64>) -> Matrix3<f64> {
    Matrix3::from_columns(&[f(Vector3::x()), f(Vector3::y()), f(Vector3::z())])
}

/// $\tilde{\mathbf B}$ and $\mathbf B_A$ of (3.4).
pub fn matrices(body2: &Body, support: &Support) -> Option<SupportMatrices> {
    let m = body2.mass?;
    let jinv = body2.inertia.try_inverse()?;
    let (g2c, g2a) = (body2.offset, support.offset);
    Some(SupportMatrices {
        b_tilde: columns(|f| f / m + (jinv * g2c.cross(&f)).cross(&g2a)),
        b_a: columns(|f| f / m + (jinv * g2a.cross(&f)).cross(&g2a)),
    })
}

/// $\mathbf B^*$ of (3.8): $\mathbf B^*\mathbf F = \mathbf B\mathbf F - \beta^{-1}(\tilde{\mathbf B}\mathbf F, \mathbf N)\tilde{\mathbf B}'\mathbf N$.
pub fn b_star(b: &Matrix3<f64>, sm: &SupportMatrices, n_support: &Vector3<f64>) -> Matrix3<f64> {
    let nn = n_support.normalize();
    let beta = (sm.b_a * nn).dot(&nn);
    let w = sm.b_tilde.transpose() * nn;
    b - w * (sm.b_tilde.transpose() * nn).transpose() / beta
}

/// How (3.6) with (3.2)/(3.3) can be solved for a given contact force direction F.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Classification {
    /// "unique", "none" or "two" (two or more admissible motions).
    pub kind: String,
    /// The admissible motion types ("detach", "roll", "slide").
    pub admissible: Vec<String>,
    /// $\alpha$ of (3.6).
    pub alpha: f64,
    /// $\beta$: (4.4) when sliding, else $(\mathbf B_A\mathbf N, \mathbf N)$.
    pub beta: f64,
}

fn kind(n: usize) -> String {
    match n {
        0 => "none".into(),
        1 => "unique".into(),
        _ => "two".into(),
    }
}

/// Classifies the support reaction when the second body slides along the support with unit
/// tangential velocity direction `e_t` at A (the start of the impact, section 4 case 3).
pub fn classify_sliding(
    f: &Vector3<f64>,
    sm: &SupportMatrices,
    s: &Support,
    e_t: &Vector3<f64>,
) -> Classification {
    let n = s.normal.normalize();
    let alpha = -(sm.b_tilde * f).dot(&n);
    let i_dir = n - e_t.normalize() * s.mu;
    let beta = (sm.b_a * i_dir).dot(&n);
    let mut admissible = Vec::new();
    // detach: F* = 0 needs (V_A, N)' = alpha >= 0
    if alpha >= 0.0 {
        admissible.push("detach".to_string());
    }
    // slide with contact: F_N* = -alpha/beta > 0
    if beta != 0.0 && -alpha / beta > 0.0 {
        admissible.push("slide".to_string());
    }
    Classification {
        kind: kind(admissible.len()),
        admissible,
        alpha,
        beta,
    }
}

/// Classifies when the support point is at rest (rolling or sticking), section 4 cases 1, 2, 4.
pub fn classify_at_rest(f: &Vector3<f64>, sm: &SupportMatrices, s: &Support) -> Classification {
    let n = s.normal.normalize();
    let alpha = -(sm.b_tilde * f).dot(&n);
    let beta = (sm.b_a * n).dot(&n);
    let mut admissible = Vec::new();
    if alpha >= 0.0 {
        admissible.push("detach".to_string());
    }
    // roll: F* = B_A^{-1} B~ F inside the friction cone
    if let Some(inv) = sm.b_a.try_inverse() {
        let fs = inv * (sm.b_tilde * f);
        let fn_ = fs.dot(&n);
        let ft = (fs - n * fn_).norm();
        if fn_ >= 0.0 && ft <= s.mu * fn_ * (1.0 + 1e-12) {
            admissible.push("roll".to_string());
        }
    }
    // start to slide in a direction e_T (4.5): kappa e_T = F_N* B_A (N - mu e_T) - B~ F, kappa > 0
    let (t1, t2) = {
        let a = if n.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        let t1 = (a - n * a.dot(&n)).normalize();
        (t1, n.cross(&t1))
    };
    let g = sm.b_tilde * f;
    let mut slides = 0;
    let samples = 3600;
    let mut prev: Option<f64> = None;
    let resid = |th: f64| -> (f64, f64, f64) {
        // with e_T fixed, the normal component fixes F_N*; the tangential component must be
        // parallel to e_T with kappa > 0
        let e = t1 * th.cos() + t2 * th.sin();
        let a = sm.b_a * (n - e * s.mu);
        let fn_star = if a.dot(&n).abs() > 0.0 {
            g.dot(&n) / a.dot(&n)
        } else {
            f64::NAN
        };
        let v = a * fn_star - g;
        let vt = v - n * v.dot(&n);
        let perp = e.cross(&vt).dot(&n);
        (perp, vt.dot(&e), fn_star)
    };
    for k in 0..=samples {
        let th = 2.0 * std::f64::consts::PI * k as f64 / samples as f64;
        let (perp, kappa, fn_star) = resid(th);
        if let Some(p) = prev
            && p.signum() != perp.signum()
            && kappa > 0.0
            && fn_star >= 0.0
        {
            slides += 1;
        }
        prev = Some(perp);
    }
    if slides > 0 && s.mu > 0.0 {
        admissible.push("slide".to_string());
    }
    Classification {
        kind: kind(admissible.len()),
        admissible,
        alpha,
        beta,
    }
}
