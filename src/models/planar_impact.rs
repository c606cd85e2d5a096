//! The exact solution of a planar impact with Coulomb friction, by events in closed form: a
//! second method beside the integrated Darboux-Keller equations of [`super::rigid_impact`]
//! (002_b53e4779673eb6ed.txt section 1), written from the theory and sharing nothing with that
//! integrator but the matrix $\mathbf B$ of (1.7).
//!
//! When the plane spanned by the contact normal $\mathbf n$ and a tangent $\mathbf t$ is invariant
//! under $\mathbf B$ ($\mathbf s = \mathbf n\times\mathbf t$ is an eigenvector of $\mathbf B$) and
//! the bodies have no relative velocity along $\mathbf s$, the impact stays in that plane, and
//! (1.5) in the normal impulse $p = I_n$ has constant coefficients while the contact keeps its
//! mode:
//! $$\frac{dV_t}{dp} = b_{tn} + b_{tt}\,\frac{dI_t}{dp},\qquad
//!   \frac{dV_n}{dp} = b_{nn} + b_{tn}\,\frac{dI_t}{dp},\qquad
//!   \frac{dI_t}{dp} = \begin{cases} -\mu\,\operatorname{sgn} V_t & \text{slip}\\
//!   -b_{tn}/b_{tt} & \text{stick, where } |b_{tn}| \le \mu\, b_{tt}\end{cases}$$
//! The velocities are piecewise linear in $p$ and the normal work $W_n = \int V_n\,dp$ piecewise
//! quadratic, so every switch (the slip stops; compression ends at $V_n = 0$; restitution ends
//! by Newton's $V_n = -eV_n^-$, Poisson's $p = (1+e)p_c$ or the energetic law
//! $W_n = (1-e^2)W_n(p_c)$) is a root of a polynomial of degree one or two, found in closed form.
//! At zero slip the contact sticks where the friction cone holds the impulse that keeps
//! $V_t = 0$ (the critical $\mu = |b_{tn}|/b_{tt}$ included), and otherwise slides again in the
//! one direction in which the slip grows ($\operatorname{sgn} b_{tn}$; a reversal). A slip that
//! grows never stops, and a stick never breaks: an impact has at most three phases.
//! A stick along which $V_n$ no longer changes ($\mathbf B(\mathbf n + \tau\mathbf t) = 0$, only
//! with a singular $\mathbf B^*$ of (2.1)) is a cut-off impact: the bodies wedge.

use super::rigid_impact::{ImpactResult, Law, Phase};
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// The plane of a planar impact: $\mathbf t$ in it, tangent to the contact, and
/// $\mathbf s = \mathbf n\times\mathbf t$ normal to it.
#[derive(Clone, Copy, Debug)]
pub struct PlanarFrame {
    /// The unit contact normal, into the first body.
    pub n: Vector3<f64>,
    /// Unit tangent in the plane of motion.
    pub t: Vector3<f64>,
    /// Unit normal of the plane of motion.
    pub s: Vector3<f64>,
}

/// The name of this method in outputs and in a scene's `[solve] method`.
pub const METHOD: &str = "planar-exact";

/// Relative size below which a coupling out of the plane, or a velocity across it, counts as
/// zero: rounding in the inputs (a rod at 45 degrees built with `cos` and `sin`) is of order
/// 1e-16, and an impact that leaves the plane by 1e-12 changes its impulse by that order.
pub const PLANAR_TOL: f64 = 1e-12;

/// The plane of motion of an impact with matrix `b`, contact normal `n` and relative velocity
/// `v` before it, if the impact is planar: $\mathbf s$ is an eigenvector of $\mathbf B$ and
/// $(\mathbf V^-, \mathbf s) = 0$, each to `tol` relative to $\|\mathbf B\|$ and $|\mathbf V^-|$.
/// With an initial slip, $\mathbf t$ is along it; without, along the tangential part of
/// $\mathbf B\mathbf n$ or, where that vanishes too, along an eigenvector of the tangential block.
pub fn planar_frame(
    b: &Matrix3<f64>,
    n: &Vector3<f64>,
    v: &Vector3<f64>,
    tol: f64,
) -> Option<PlanarFrame> {
    let n = n.try_normalize(0.0)?;
    let (b_scale, v_scale) = (b.norm(), v.norm());
    let tangential = |x: Vector3<f64>| x - n * x.dot(&n);
    let frame =
        |t: Vector3<f64>| {
            let t = t.normalize();
            let s = n.cross(&t);
            let bs = b * s;
            let off_plane = (bs - s * s.dot(&bs)).norm();
            (off_plane <= tol * b_scale && v.dot(&s).abs() <= tol * v_scale)
                .then_some(PlanarFrame { n, t, s })
        };
    let slip = tangential(*v);
    if slip.norm() > tol * v_scale {
        return frame(slip);
    }
    let coupling = tangential(b * n);
    if coupling.norm() > tol * b_scale {
        return frame(coupling);
    }
    // no slip and no coupling from n: the plane is one of the tangential block's eigenplanes
    let a = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = tangential(a).normalize();
    let t2 = n.cross(&t1);
    let block = nalgebra::Matrix2::new(
        t1.dot(&(b * t1)),
        t1.dot(&(b * t2)),
        t2.dot(&(b * t1)),
        t2.dot(&(b * t2)),
    );
    let eig = SymmetricEigen::new(block);
    (0..2).find_map(|k| {
        let c = eig.eigenvectors.column(k);
        frame(t1 * c[0] + t2 * c[1])
    })
}

/// The in-plane problem: $\mathbf B$ in the basis $(\mathbf t, \mathbf n)$ and the relative
/// velocity before the impact.
#[derive(Clone, Copy, Debug)]
pub struct PlanarProblem {
    /// $b_{tt}$ (1/kg).
    pub b_tt: f64,
    /// $b_{tn}$ (1/kg).
    pub b_tn: f64,
    /// $b_{nn}$ (1/kg).
    pub b_nn: f64,
    /// Slip velocity before the impact, $(\mathbf V^-, \mathbf t)$ (m/s).
    pub v_t: f64,
    /// Normal velocity before the impact, $(\mathbf V^-, \mathbf n) < 0$ (m/s).
    pub v_n: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// Restitution law.
    pub law: Law,
    /// Coefficient of restitution, $0 \le e \le 1$.
    pub e: f64,
}

/// The contact's mode in a phase.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Contact {
    /// No friction ($\mu = 0$).
    Smooth,
    /// Slip with the sign of $V_t$.
    Slip(f64),
    /// Stick with the tangential impulse rate $\tau$.
    Stick(f64),
}

/// The exact planar solution.
#[derive(Clone, Debug)]
pub struct PlanarSolution {
    /// Tangential impulse on the first body (N s).
    pub impulse_t: f64,
    /// Normal impulse (N s).
    pub impulse_n: f64,
    /// Slip velocity after the impact (m/s).
    pub v_t: f64,
    /// Normal velocity after the impact (m/s).
    pub v_n: f64,
    /// Normal impulse at the end of compression (N s).
    pub compression_impulse: f64,
    /// Work of the normal impulse, $\int V_n\,dp$ (J).
    pub normal_work: f64,
    /// Work of the tangential impulse, $\int V_t\,dI_t$ (J).
    pub tangential_work: f64,
    /// The bodies wedged ([`Contact::Stick`] with $dV_n/dp = 0$ in compression).
    pub cut_off: bool,
    /// Phases ("slip", "stick", "reversal") with the normal impulse at which each starts.
    pub phases: Vec<Phase>,
    /// The corners of the piecewise linear path: `(p, V_t, V_n)`.
    pub path: Vec<(f64, f64, f64)>,
}

/// Why no exact planar solution exists.
#[derive(Debug, thiserror::Error)]
pub enum PlanarError {
    /// Bad input.
    #[error("{field} = {value} is not allowed; allowed: {allowed}")]
    OutOfRange {
        /// Field.
        field: &'static str,
        /// Value.
        value: String,
        /// Allowed range.
        allowed: &'static str,
    },
    /// The motion never meets the restitution condition (the relative velocity stops changing
    /// while sliding: a degenerate $\mathbf B$).
    #[error(
        "the {law} restitution condition is never met: from normal impulse {p:e} N s the relative velocity no longer changes"
    )]
    NoEnd {
        /// Law.
        law: &'static str,
        /// Where the velocity stops changing (N s).
        p: f64,
    },
}

/// The smallest $x \ge 0$ at which $c + b x + a x^2$ rises through zero (`Some(0)` if it is
/// already $\ge 0$ at 0), in the forms that keep full precision when a root is small.
fn first_rise(c: f64, b: f64, a: f64) -> Option<f64> {
    if c >= 0.0 {
        return Some(0.0);
    }
    if a == 0.0 {
        return (b > 0.0).then(|| -c / b);
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let mut roots = [q / a, if q != 0.0 { c / q } else { f64::NAN }];
    roots.sort_by(|x, y| x.partial_cmp(y).unwrap_or(std::cmp::Ordering::Equal));
    roots
        .into_iter()
        .find(|&x| x >= 0.0 && b + 2.0 * a * x >= -1e-12 * b.abs().max(a.abs() * x))
}

impl PlanarProblem {
    /// The in-plane problem of a planar impact in `frame`.
    pub fn in_plane(
        b: &Matrix3<f64>,
        frame: &PlanarFrame,
        v: &Vector3<f64>,
        mu: f64,
        law: Law,
        e: f64,
    ) -> Self {
        let (t, n) = (frame.t, frame.n);
        PlanarProblem {
            b_tt: t.dot(&(b * t)),
            b_tn: 0.5 * (t.dot(&(b * n)) + n.dot(&(b * t))),
            b_nn: n.dot(&(b * n)),
            v_t: v.dot(&t),
            v_n: v.dot(&n),
            mu,
            law,
            e,
        }
    }

    /// The contact's mode at zero slip: stick where $|b_{tn}| \le \mu b_{tt}$ (the critical
    /// value included, to rounding), else slide in the direction in which the slip grows.
    fn at_zero_slip(&self) -> Contact {
        let scale = self.b_tt.abs().max(self.b_tn.abs()).max(self.b_nn.abs());
        if self.mu == 0.0 {
            return Contact::Smooth;
        }
        if self.b_tt <= 1e-14 * scale {
            // the tangential impulse moves no slip (a singular B* of (2.1)): the slip grows
            // with b_tn whatever the friction, and sticks where b_tn vanishes too
            return if self.b_tn.abs() <= 1e-14 * scale {
                Contact::Stick(0.0)
            } else {
                Contact::Slip(self.b_tn.signum())
            };
        }
        if self.b_tn.abs() <= self.mu * self.b_tt * (1.0 + 1e-12) {
            Contact::Stick((-self.b_tn / self.b_tt).clamp(-self.mu, self.mu))
        } else {
            Contact::Slip(self.b_tn.signum())
        }
    }

    /// `(dI_t/dp, dV_t/dp, dV_n/dp)` in a mode.
    fn rates(&self, mode: Contact) -> (f64, f64, f64) {
        let di_t = match mode {
            Contact::Smooth => 0.0,
            Contact::Slip(sign) => -sign * self.mu,
            Contact::Stick(tau) => tau,
        };
        let dv_t = match mode {
            Contact::Stick(_) => 0.0,
            _ => self.b_tn + self.b_tt * di_t,
        };
        (di_t, dv_t, self.b_nn + self.b_tn * di_t)
    }

    /// Solves the impact exactly.
    pub fn solve(&self) -> Result<PlanarSolution, PlanarError> {
        if !(0.0..=1.0).contains(&self.e) {
            return Err(PlanarError::OutOfRange {
                field: "contact.e",
                value: self.e.to_string(),
                allowed: "0 <= e <= 1",
            });
        }
        if !(self.mu >= 0.0 && self.mu.is_finite()) {
            return Err(PlanarError::OutOfRange {
                field: "contact.mu",
                value: self.mu.to_string(),
                allowed: "mu >= 0",
            });
        }
        if self.v_n >= 0.0 || self.v_n.is_nan() {
            return Err(PlanarError::OutOfRange {
                field: "initial.v_rel",
                value: format!("normal component {}", self.v_n),
                allowed: "(v_rel, normal) < 0: the bodies approach",
            });
        }
        let law_name = self.law.name();
        let speed = self.v_t.hypot(self.v_n);
        let b_scale = self.b_tt.abs().max(self.b_tn.abs()).max(self.b_nn.abs());
        // a slip of rounding size (1e-15 of the speed) is none
        let (mut v_t, mut v_n) = (self.v_t, self.v_n);
        if v_t.abs() <= 1e-15 * speed {
            v_t = 0.0;
        }
        let mut mode = if self.mu == 0.0 {
            Contact::Smooth
        } else if v_t != 0.0 {
            Contact::Slip(v_t.signum())
        } else {
            self.at_zero_slip()
        };
        let kind = |m: Contact| match m {
            Contact::Stick(_) => "stick",
            _ => "slip",
        };
        let mut phases = vec![Phase {
            kind: kind(mode).into(),
            normal_impulse: 0.0,
        }];
        let (mut p, mut i_t, mut w_n, mut w_t) = (0.0, 0.0, 0.0, 0.0);
        let mut path = vec![(p, v_t, v_n)];
        let mut compression: Option<(f64, f64)> = None;
        let mut cut_off = false;
        let target_vn = -self.e * self.v_n;
        // at most: a slip that stops, a stick or reversal, compression's end and the end
        for _ in 0..16 {
            let (di_t, dv_t, dv_n) = self.rates(mode);
            if let Contact::Stick(_) = mode
                && dv_n.abs() <= 1e-10 * b_scale
            {
                // B (n + tau t) = 0: the velocity no longer changes while the reaction grows
                cut_off = true;
                break;
            }
            // the next switch: (distance in p, what happens)
            #[derive(Clone, Copy, PartialEq)]
            enum Switch {
                SlipStops,
                CompressionEnds,
                End,
            }
            let mut next: Option<(f64, Switch)> = None;
            let mut offer = |d: Option<f64>, what: Switch| {
                if let Some(d) = d.filter(|d| d.is_finite() && *d >= 0.0)
                    && next.is_none_or(|(best, _)| d < best)
                {
                    next = Some((d, what));
                }
            };
            if let Contact::Slip(_) = mode
                && v_t * dv_t < 0.0
            {
                offer(Some(-v_t / dv_t), Switch::SlipStops);
            }
            match compression {
                None => offer(first_rise(v_n, dv_n, 0.0), Switch::CompressionEnds),
                Some((p_c, w_c)) => offer(
                    match self.law {
                        Law::Newton => first_rise(v_n - target_vn, dv_n, 0.0),
                        Law::Poisson => Some(((1.0 + self.e) * p_c - p).max(0.0)),
                        Law::Energetic => {
                            first_rise(w_n - (1.0 - self.e * self.e) * w_c, v_n, 0.5 * dv_n)
                        }
                    },
                    Switch::End,
                ),
            }
            let Some((d, what)) = next else {
                return Err(PlanarError::NoEnd { law: law_name, p });
            };
            // advance along the linear piece
            w_n += v_n * d + 0.5 * dv_n * d * d;
            w_t += (v_t * d + 0.5 * dv_t * d * d) * di_t;
            p += d;
            i_t += di_t * d;
            v_t += dv_t * d;
            v_n += dv_n * d;
            match what {
                Switch::SlipStops => {
                    v_t = 0.0;
                    mode = self.at_zero_slip();
                    phases.push(Phase {
                        kind: match mode {
                            Contact::Stick(_) => "stick",
                            _ => "reversal",
                        }
                        .into(),
                        normal_impulse: p,
                    });
                }
                Switch::CompressionEnds => {
                    v_n = 0.0;
                    compression = Some((p, w_n));
                    if self.e == 0.0 {
                        path.push((p, v_t, v_n));
                        break;
                    }
                }
                Switch::End => {
                    if self.law == Law::Newton {
                        v_n = target_vn;
                    }
                    path.push((p, v_t, v_n));
                    break;
                }
            }
            path.push((p, v_t, v_n));
        }
        Ok(PlanarSolution {
            impulse_t: i_t,
            impulse_n: p,
            v_t,
            v_n,
            compression_impulse: compression.map_or(p, |c| c.0),
            normal_work: w_n,
            tangential_work: w_t,
            cut_off,
            phases,
            path,
        })
    }
}

/// The impact of [`super::rigid_impact::impact_with_matrix`] solved exactly, when it is planar
/// ([`planar_frame`] with [`PLANAR_TOL`]); `Ok(None)` when it is not. `energy_change` is
/// $(\mathbf V^-, \mathbf I) + \tfrac12(\mathbf B\mathbf I, \mathbf I)$, `stats` all zero (no
/// integration).
pub fn impact_planar(
    b: &Matrix3<f64>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
) -> Result<Option<ImpactResult>, PlanarError> {
    let Some(frame) = planar_frame(b, &normal, &v_minus, PLANAR_TOL) else {
        return Ok(None);
    };
    let sol = PlanarProblem::in_plane(b, &frame, &v_minus, mu, law, e).solve()?;
    Ok(Some(to_result(b, &frame, &v_minus, &sol)))
}

/// The 3-D result of a planar solution: impulse and velocities in the plane's frame, the out of
/// plane velocity carried through $\mathbf B$.
pub fn to_result(
    b: &Matrix3<f64>,
    frame: &PlanarFrame,
    v_minus: &Vector3<f64>,
    sol: &PlanarSolution,
) -> ImpactResult {
    let imp = frame.t * sol.impulse_t + frame.n * sol.impulse_n;
    let v_s = (v_minus + b * imp).dot(&frame.s);
    let vp = frame.t * sol.v_t + frame.n * sol.v_n + frame.s * v_s;
    let eig = SymmetricEigen::new(*b).eigenvalues;
    let (lmin, lmax) = (eig.min(), eig.max());
    let vn0 = v_minus.dot(&frame.n);
    ImpactResult {
        impulse: [imp.x, imp.y, imp.z],
        v_rel_after: [vp.x, vp.y, vp.z],
        compression_impulse: sol.compression_impulse,
        energy_change: v_minus.dot(&imp) + 0.5 * imp.dot(&(b * imp)),
        kelvin_energy_change: 0.5 * (v_minus + vp).dot(&imp),
        lambda_min: lmin,
        lambda_max: lmax,
        bound_upper: if lmin > 1e-12 * lmax {
            2.0 * v_minus.norm() / lmin
        } else {
            f64::INFINITY
        },
        bound_lower: vn0.abs() / lmax,
        phases: sol.phases.clone(),
        cut_off: sol.cut_off,
        stats: crate::integrate::Stats::default(),
        method: METHOD,
        support_impulse: [0.0; 3],
        support_phases: Vec::new(),
        v_support_after: None,
        path: sol
            .path
            .iter()
            .map(|&(p, vt, vn)| {
                let v = frame.t * vt + frame.n * vn + frame.s * v_s;
                (p, [v.x, v.y, v.z])
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn problem([b_tt, b_tn, b_nn]: [f64; 3], v_t: f64, mu: f64, law: Law, e: f64) -> PlanarProblem {
        PlanarProblem {
            b_tt,
            b_tn,
            b_nn,
            v_t,
            v_n: -1.0,
            mu,
            law,
            e,
        }
    }

    /// Frictionless and collinear (b_tn = 0): every law gives V_n+ = -e V_n-, I_n = (1+e)|V_n-|/b_nn.
    #[test]
    fn central_impact_matches_the_textbook() {
        for law in [Law::Newton, Law::Poisson, Law::Energetic] {
            for e in [0.0, 0.25, 0.5, 0.75, 1.0] {
                let s = problem([3.0, 0.0, 2.0], 0.0, 0.0, law, e)
                    .solve()
                    .expect("solves");
                assert!((s.v_n - e).abs() < 1e-15, "{law:?} {e}: {}", s.v_n);
                assert!((s.impulse_n - (1.0 + e) / 2.0).abs() < 1e-15);
                assert!(s.impulse_t.abs() < 1e-300);
            }
        }
    }

    /// Slip throughout (the slip never stops): V_n linear in p, so Poisson's and the energetic
    /// law agree, and the impulse is (1+e) p_c with p_c = |V_n-| / (b_nn - mu b_tn).
    #[test]
    fn gross_slip_has_the_closed_form() {
        // b_tn > 0 with V_t > 0: dV_t/dp = b_tn - mu b_tt = 0.1 - 0.5 = -0.4 < 0 would stop it;
        // a slip of 10 m/s needs p = 25 N s, far past the end
        let (b_tt, b_tn, b_nn, mu, e) = (1.0, 0.1, 1.0, 0.5, 0.6);
        let p_c = 1.0 / (b_nn - mu * b_tn);
        for law in [Law::Poisson, Law::Energetic] {
            let s = problem([b_tt, b_tn, b_nn], 10.0, mu, law, e)
                .solve()
                .expect("solves");
            assert!(
                (s.impulse_n - (1.0 + e) * p_c).abs() < 1e-14 * p_c,
                "{law:?}"
            );
            assert!((s.impulse_t + mu * s.impulse_n).abs() < 1e-14);
            assert_eq!(s.phases.len(), 1);
        }
    }

    /// A slip that stops below the critical friction reverses; above it, sticks; at it, both
    /// descriptions give the same motion (the stick's tau equals -mu sgn b_tn).
    #[test]
    fn stop_then_stick_or_reversal_around_the_critical_friction() {
        let (b_tt, b_tn, b_nn) = (2.0, 1.0, 3.0);
        let critical = b_tn / b_tt;
        let run = |mu: f64| {
            problem([b_tt, b_tn, b_nn], -0.1, mu, Law::Poisson, 0.5)
                .solve()
                .expect("solves")
        };
        let kinds =
            |s: &PlanarSolution| s.phases.iter().map(|p| p.kind.clone()).collect::<Vec<_>>();
        assert_eq!(kinds(&run(critical * 1.01)), ["slip", "stick"]);
        assert_eq!(kinds(&run(critical * 0.99)), ["slip", "reversal"]);
        let at = run(critical);
        let below = run(critical * (1.0 - 1e-9));
        assert!((at.impulse_t - below.impulse_t).abs() < 1e-8);
        assert!((at.impulse_n - below.impulse_n).abs() < 1e-8);
    }

    /// A rank-one B* (a body turning about a fixed axis, (2.4)): a stick that moves no normal
    /// velocity is a cut-off impact.
    #[test]
    fn a_rank_one_matrix_cuts_off() {
        // B* = w w^T with w = (2, 1): stick tau = -b_tn/b_tt = -1/2, dV_n = b_nn + b_tn tau = 0
        let s = problem([4.0, 2.0, 1.0], 0.0, 1.0, Law::Poisson, 0.5)
            .solve()
            .expect("solves");
        assert!(s.cut_off);
        assert!(s.impulse_n.abs() < 1e-300);
    }

    #[test]
    fn first_rise_finds_small_roots_accurately() {
        // x^2 + 1e8 x - 1 = 0: the small root 1e-8 (cancellation in the textbook form)
        let x = first_rise(-1.0, 1e8, 1.0).expect("root");
        assert!((x - 1e-8).abs() < 1e-22);
        // falling parabola: -x^2 + 3x - 2 rises through 0 at x = 1 (and falls at 2)
        assert!((first_rise(-2.0, 3.0, -1.0).expect("root") - 1.0).abs() < 1e-15);
        assert_eq!(first_rise(-1.0, -1.0, -1.0), None);
    }

    #[test]
    fn the_frame_is_found_only_for_planar_impacts() {
        let b = Matrix3::new(2.0, 0.0, 0.5, 0.0, 3.0, 0.0, 0.5, 0.0, 1.0);
        let n = Vector3::z();
        let f = planar_frame(&b, &n, &Vector3::new(0.3, 0.0, -1.0), PLANAR_TOL).expect("planar");
        assert!((f.t - Vector3::x()).norm() < 1e-15);
        // no slip: the plane from B n
        assert!(planar_frame(&b, &n, &Vector3::new(0.0, 0.0, -1.0), PLANAR_TOL).is_some());
        // a velocity across the plane
        assert!(planar_frame(&b, &n, &Vector3::new(0.3, 1e-6, -1.0), PLANAR_TOL).is_none());
        // a coupling out of the plane
        let mut c = b;
        c[(1, 2)] = 1e-3;
        c[(2, 1)] = 1e-3;
        assert!(planar_frame(&c, &n, &Vector3::new(0.3, 0.0, -1.0), PLANAR_TOL).is_none());
    }
}
