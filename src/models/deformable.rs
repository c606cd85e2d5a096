//! The method of deformable elements for the plane example of section 4 of
//! 002_b53e4779673eb6ed.txt: a light body 1 strikes body 2, which rests on a rough support, with
//! a linear spring at the contact C (no friction there) and a linear spring with Coulomb friction
//! at the support point A. Used to check the paper's closing result: "in the non-uniqueness cases
//! one has separation from the support; in the cases in which the classical model produces no
//! solution ... however small the ratio m1/m2, the deformations at the point A are not small".
//!
//! Geometry as in the paper's Example 1: the support is y = 0 with normal N = (0, 1); the contact
//! normal n = (1, 0) points into body 1; G2C = (a2, b2), G2A = (a3, b3), b3 < 0. Body 1 is a
//! particle moving along n. Displacements during the impact are small, so body 2's kinematics is
//! linearised (the displacement of a point r is u + theta z x r). Coulomb's law at A is
//! regularised, $F_T = -\mu^* F_N\, v/\sqrt{v^2 + \varepsilon^2}$ with $\varepsilon$ = 1e-6 of
//! the sliding speed: the force differs from Coulomb's only while $|v| < \varepsilon$.

use crate::integrate::{IntegrateError, Method, OdeSystem, Options, solve};

/// The plane example with deformable elements (SI units, or any consistent ones).
#[derive(Clone, Copy, Debug)]
pub struct Deformable {
    /// Mass of the striking body.
    pub m1: f64,
    /// Mass and radius of inertia of the supported body.
    pub m2: f64,
    /// Its radius of inertia.
    pub rho2: f64,
    /// G2C.
    pub c: [f64; 2],
    /// G2A.
    pub a: [f64; 2],
    /// Friction coefficient at A.
    pub mu_star: f64,
    /// Spring at C (N/m).
    pub k_c: f64,
    /// Spring at A (N/m).
    pub k_a: f64,
    /// Speed of body 1 toward C.
    pub v0: f64,
    /// Initial sliding speed of A along +x (0: at rest on the support).
    pub slide: f64,
}

/// What the deformable-element impact produced.
#[derive(Clone, Copy, Debug)]
pub struct DeformableOutcome {
    /// Normal impulse at C.
    pub impulse_c: f64,
    /// Normal impulse of the support at A.
    pub impulse_a: f64,
    /// Largest compression at A.
    pub max_deformation_a: f64,
    /// Largest compression at C.
    pub max_deformation_c: f64,
    /// Normal velocity of A at the end (positive: away from the support).
    pub v_a_normal_end: f64,
}

impl Deformable {
    fn forces(&self, y: &[f64]) -> (f64, f64, f64) {
        let [_, b2] = self.c;
        let [a3, b3] = self.a;
        let (x2, y2, th) = (y[2], y[3], y[4]);
        let (vx2, w) = (y[5], y[7]);
        let d_c = (x2 - th * b2) - y[0];
        let f_c = self.k_c * d_c.max(0.0);
        let d_a = -(y2 + th * a3);
        let f_n = self.k_a * d_a.max(0.0);
        let v_t = vx2 - w * b3;
        let eps = 1e-6 * self.slide.abs().max(self.v0);
        let f_t = -self.mu_star * f_n * v_t / (v_t * v_t + eps * eps).sqrt();
        (f_c, f_n, f_t)
    }
}

impl OdeSystem for Deformable {
    fn dim(&self) -> usize {
        10
    }
    // y = [u1, v1, x2, y2, theta2, vx2, vy2, omega2, int F_C, int F_N]
    fn rhs(&self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let (f_c, f_n, f_t) = self.forces(y);
        let [_, b2] = self.c;
        let [a3, b3] = self.a;
        let j2 = self.m2 * self.rho2 * self.rho2;
        dy[0] = y[1];
        dy[1] = f_c / self.m1;
        dy[2] = y[5];
        dy[3] = y[6];
        dy[4] = y[7];
        dy[5] = (-f_c + f_t) / self.m2;
        dy[6] = f_n / self.m2;
        // torques about G2: G2C x (-F_C, 0) + G2A x (F_T, F_N)
        dy[7] = (b2 * f_c + a3 * f_n - b3 * f_t) / j2;
        dy[8] = f_c;
        dy[9] = f_n;
    }
}

/// Integrates the impact until both contacts are open and separating (or `t_max`), sampling the
/// deformations on 4000 intervals of the time scale of each contact.
pub fn simulate(p: &Deformable, rtol: f64) -> Result<DeformableOutcome, IntegrateError> {
    let mut y = vec![0.0; 10];
    y[1] = -p.v0;
    y[5] = p.slide; // A slides at `slide` (omega = 0)
    let t_c = (p.m1 / p.k_c).sqrt();
    let t_a = (p.m2 / p.k_a).sqrt();
    let h = t_c.min(t_a) / 40.0;
    let t_max = 50.0 * t_a.max(t_c);
    let (mut t, mut max_a, mut max_c) = (0.0, 0.0f64, 0.0f64);
    let opts = Options {
        rtol,
        atol: rtol * 1e-3 * p.v0 * t_c.min(t_a),
        method: Method::Auto,
        max_steps: 1_000_000,
        ..Options::default()
    };
    while t < t_max {
        let sol = solve(p, t, &y, t + h, &opts)?;
        t = sol.t;
        y = sol.y;
        let [_, b2c] = p.c;
        let [a3, _] = p.a;
        let d_c = (y[2] - y[4] * b2c) - y[0];
        let d_a = -(y[3] + y[4] * a3);
        max_a = max_a.max(d_a);
        max_c = max_c.max(d_c);
        let v_a_n = y[6] + y[7] * a3;
        let v_c_rel = (y[5] - y[7] * b2c) - y[1];
        if d_c < 0.0 && v_c_rel < 0.0 && d_a < 0.0 && v_a_n >= 0.0 {
            break;
        }
    }
    let [a3, _] = p.a;
    Ok(DeformableOutcome {
        impulse_c: y[8],
        impulse_a: y[9],
        max_deformation_a: max_a,
        max_deformation_c: max_c,
        v_a_normal_end: y[6] + y[7] * a3,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_free_body_2_takes_the_momentum_of_a_linear_collision() {
        // C on the line through G2 (b2 = 0), no support contact (A far above: a3 = 0, the support
        // never touched since body 2 only moves along x): a central elastic collision of two
        // masses, body 1 leaves with (m1 - m2)/(m1 + m2) v0 (closed form); the impulse at C is
        // 2 m1 m2 v0/(m1 + m2)
        let p = Deformable {
            m1: 0.5,
            m2: 1.0,
            rho2: 0.5,
            c: [0.3, 0.0],
            a: [0.0, -0.6],
            mu_star: 0.0,
            k_c: 1.0,
            k_a: 1.0,
            v0: 1.0,
            slide: 0.0,
        };
        let o = simulate(&p, 1e-10).unwrap();
        let want = 2.0 * 0.5 * 1.0 / 1.5;
        assert!((o.impulse_c - want).abs() < 1e-7, "{}", o.impulse_c);
        assert!(o.impulse_a.abs() < f64::MIN_POSITIVE, "{}", o.impulse_a);
    }

    /// The degenerate case: no friction, the contact force through G2 (b2 = 0), the support
    /// under G2 (a3 = 0): body 2 slides freely and the impact is the central impact of two
    /// masses through a linear spring, elastic, whose impulse is 2 m1 m2 v0/(m1 + m2) (by hand:
    /// momentum and energy); the support carries nothing.
    #[test]
    fn a_central_frictionless_impact_is_elastic_for_any_masses() {
        for (m1, m2) in [(0.1, 1.0), (1.0, 1.0), (2.0, 0.5)] {
            let p = Deformable {
                m1,
                m2,
                rho2: 0.1,
                c: [0.05, 0.0],
                a: [0.0, -0.05],
                mu_star: 0.0,
                k_c: 1e5,
                k_a: 1e6,
                v0: 2.0,
                slide: 0.0,
            };
            let out = simulate(&p, 1e-10).expect("integrates");
            let want = 2.0 * m1 * m2 * p.v0 / (m1 + m2);
            assert!(
                (out.impulse_c - want).abs() < 1e-7 * want,
                "m1 {m1}, m2 {m2}: {} vs {want}",
                out.impulse_c
            );
            assert!(out.impulse_a.abs() < 1e-12 && out.max_deformation_a.abs() < 1e-15);
            // the largest compression: energy m1 m2/(m1 + m2) v0^2/2 = k_c d^2/2
            let d = p.v0 * (m1 * m2 / ((m1 + m2) * p.k_c)).sqrt();
            assert!(
                (out.max_deformation_c - d).abs() < 1e-3 * d,
                "{}",
                out.max_deformation_c
            );
        }
    }
}
