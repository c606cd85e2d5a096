//! Impact of two rigid bodies with one contact point and Coulomb friction, integrated in the
//! normal impulse (Darboux-Keller), 002_b53e4779673eb6ed.txt section 1.
//!
//! $$\Delta\mathbf V_C = \mathbf B\mathbf I,\quad \mathbf B = (m_1^{-1} + m_2^{-1})\mathbf E_3 + \|b_{ij}\|,\quad
//!   b_{ij} = \sum_k (\mathbf J_k^{-1}(\mathbf G_k\mathbf C\times\mathbf e_i), \mathbf G_k\mathbf C\times\mathbf e_j) \quad (1.7)$$
//! With $\chi = I_n$ the independent variable, $d\mathbf V/d\chi = \mathbf B\,d\mathbf I/d\chi$ and
//! $d\mathbf I/d\chi = \mathbf n - \mu\,\mathbf V_t/|\mathbf V_t|$ while sliding (1.5); when the
//! slip speed reaches zero the body sticks if the tangential impulse rate $\boldsymbol\tau$ that
//! keeps $\mathbf V_t = 0$ satisfies $|\boldsymbol\tau| \le \mu$, and otherwise slides again in the
//! direction $\mathbf u$ the dynamics give ($\mathbf P_t\mathbf B(\mathbf n - \mu\mathbf u) =
//! \kappa\mathbf u$, $\kappa > 0$): no chattering and no division by zero at zero slip.
//! Compression ends at $V_n = 0$; restitution follows Newton ($V_n^+ = -eV_n^-$), Poisson
//! ($I_n = (1+e)I_{n,c}$) or Stronge (normal work in restitution $= -e^2\times$ that in
//! compression). The normal $\mathbf n$ points into the first body, and $\mathbf I$ is the impulse
//! on the first body (1.2)-(1.4).
//!
//! Every solve also returns the checks of Proposition 1: Kelvin's formula (1.10)/(1.11) against
//! the kinetic energy change computed directly from body velocities, (1.12), and the bounds (1.9)
//! and (1.13) with the eigenvalues of $\mathbf B$.

use crate::integrate::{Direction, Event, IntegrateError, Method, OdeSystem, Options, Stop, solve};
use nalgebra::{Matrix2, Matrix3, SymmetricEigen, Vector2, Vector3};

/// A rigid body at the contact.
#[derive(Clone, Debug)]
pub struct Body {
    /// Mass (kg); `None` for a fixed massive obstacle.
    pub mass: Option<f64>,
    /// Central inertia tensor (kg m^2), symmetric positive-definite.
    pub inertia: Matrix3<f64>,
    /// Vector from the centre of mass G to the contact point C (m).
    pub offset: Vector3<f64>,
}

/// Restitution law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// Newton: $V_n^+ = -e V_n^-$.
    Newton,
    /// Poisson: $I_n = (1 + e) I_{n,c}$.
    Poisson,
    /// Stronge: restitution work $= -e^2 \times$ compression work.
    Energetic,
}

impl Law {
    /// Scene name.
    pub fn name(self) -> &'static str {
        match self {
            Law::Newton => "newton",
            Law::Poisson => "poisson",
            Law::Energetic => "energetic",
        }
    }
}

/// The matrix B of (1.7) for two bodies (a body with no mass contributes nothing).
pub fn b_matrix(b1: &Body, b2: &Body) -> Option<Matrix3<f64>> {
    let mut b = Matrix3::zeros();
    for body in [b1, b2] {
        let Some(m) = body.mass else { continue };
        let jinv = body.inertia.try_inverse()?;
        b += Matrix3::identity() / m;
        let r = body.offset;
        for i in 0..3 {
            for j in 0..3 {
                let ei = Vector3::ith(i, 1.0);
                let ej = Vector3::ith(j, 1.0);
                b[(i, j)] += (jinv * r.cross(&ei)).dot(&r.cross(&ej));
            }
        }
    }
    Some(b)
}

/// A phase of the impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Phase {
    /// "slip", "stick" or "reversal" (slip resumed in a new direction).
    pub kind: String,
    /// Normal impulse at which the phase starts (N s).
    pub normal_impulse: f64,
}

/// The outcome of one impact.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ImpactResult {
    /// Impulse on the first body (N s).
    pub impulse: [f64; 3],
    /// Relative velocity at C after impact (m/s).
    pub v_rel_after: [f64; 3],
    /// Normal impulse at the end of compression (N s).
    pub compression_impulse: f64,
    /// Kinetic energy change computed from the bodies' velocities (J).
    pub energy_change: f64,
    /// Kelvin's formula (1.10), $\tfrac12(\mathbf V^- + \mathbf V^+, \mathbf I)$ (J).
    pub kelvin_energy_change: f64,
    /// Smallest eigenvalue of B (1/kg).
    pub lambda_min: f64,
    /// Largest eigenvalue of B (1/kg).
    pub lambda_max: f64,
    /// (1.9): $2|\mathbf V^-|/\lambda$ (N s).
    pub bound_upper: f64,
    /// (1.13): $|(\mathbf V^-, \mathbf n)|/\Lambda$ (N s).
    pub bound_lower: f64,
    /// Phases with the normal impulse at each switch.
    pub phases: Vec<Phase>,
    /// The bodies wedged: relative velocity zero, contact stresses persist (only with a singular
    /// $\mathbf B^*$); the impulse is the one at the moment of wedging.
    pub cut_off: bool,
    /// Work done.
    pub stats: crate::integrate::Stats,
    /// Impulse of the support on the second body (N s), zero without a support.
    pub support_impulse: [f64; 3],
    /// The relative velocity along the impact: `(normal impulse, V)` at every accepted step.
    #[serde(skip)]
    pub path: Vec<(f64, [f64; 3])>,
}

/// Why an impact could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum ImpactError {
    /// Bad input.
    #[error("{field} = {value} is not allowed; allowed: {allowed}")]
    OutOfRange {
        /// Field.
        field: String,
        /// Value.
        value: String,
        /// Allowed range.
        allowed: String,
    },
    /// The solver failed.
    #[error("solver: {0}")]
    Integrate(#[from] IntegrateError),
    /// The restitution condition was not reached.
    #[error("the {law} restitution condition was not reached by normal impulse {chi_max:e} N s")]
    NoEnd {
        /// Law.
        law: String,
        /// Largest normal impulse tried.
        chi_max: f64,
    },
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    Slip,
    /// Slip held along a ray it has settled on (the friction direction frozen).
    Ray(Vector3<f64>),
    Stick(Vector3<f64>),
}

/// A smooth support under the second body: $\tilde{\mathbf B}$, N and $\beta$ of (3.6).
#[derive(Clone, Debug)]
pub struct SmoothSupport {
    /// $\tilde{\mathbf B}$ of (3.4).
    pub b_tilde: Matrix3<f64>,
    /// Unit normal N at A.
    pub normal: Vector3<f64>,
    /// $\beta = (\mathbf B_A\mathbf N, \mathbf N)$.
    pub beta: f64,
}

struct Keller {
    support: Option<SmoothSupport>,
    b: Matrix3<f64>,
    n: Vector3<f64>,
    mu: f64,
    mode: Mode,
    /// slip direction used when |V_t| is below the floor (set at a re-slide)
    u_hint: Vector3<f64>,
    floor: f64,
}

impl Keller {
    fn tangential(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.n * v.dot(&self.n)
    }

    fn rate(&self, v: &Vector3<f64>) -> Vector3<f64> {
        match self.mode {
            Mode::Stick(tau) => self.n + tau,
            Mode::Ray(u) => self.n - u * self.mu,
            Mode::Slip => {
                let vt = self.tangential(v);
                let s = vt.norm();
                let u = if s > self.floor { vt / s } else { self.u_hint };
                self.n - u * self.mu
            }
        }
    }
}

impl OdeSystem for Keller {
    fn dim(&self) -> usize {
        10
    }
    fn rhs(&self, _chi: f64, y: &[f64], dy: &mut [f64]) {
        let v = Vector3::new(y[0], y[1], y[2]);
        let d = self.rate(&v);
        let (dv, fs) = velocity_rate(&self.b, self.support.as_ref(), &d);
        dy[..3].copy_from_slice(dv.as_slice());
        dy[3..6].copy_from_slice(d.as_slice());
        dy[6] = v.dot(&self.n);
        dy[7..10].copy_from_slice(fs.as_slice());
    }
}

/// The rate of the relative velocity at C per unit normal impulse, $\mathbf B\mathbf F$, for the
/// contact force direction `f`, less the support's reaction while it pushes ((3.7)-(3.8):
/// $F_N^* = \max(0, -\alpha/\beta)$, $\alpha = -(\tilde{\mathbf B}\mathbf F, \mathbf N)$); and
/// that reaction.
fn velocity_rate(
    b: &Matrix3<f64>,
    support: Option<&SmoothSupport>,
    f: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let mut dv = b * f;
    let mut fs = Vector3::zeros();
    if let Some(s) = support {
        let fn_star = ((s.b_tilde * f).dot(&s.normal) / s.beta).max(0.0);
        fs = s.normal * fn_star;
        dv -= s.b_tilde.transpose() * fs;
    }
    (dv, fs)
}

/// The rate of the relative velocity at C for a contact force direction (see [`velocity_rate`]).
type Rate<'a> = &'a dyn Fn(&Vector3<f64>) -> Vector3<f64>;

/// Orthonormal tangent basis of the plane normal to `n`.
fn tangent_basis(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let a = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t1 = (a - n * a.dot(n)).normalize();
    (t1, n.cross(&t1))
}

/// At zero slip: stick (with the tangential rate that keeps $V_t = 0$) or the direction to slide.
fn stick_or_slide(
    b: &Matrix3<f64>,
    rate: Rate,
    n: &Vector3<f64>,
    mu: f64,
) -> Result<Vector3<f64>, Vector3<f64>> {
    let (t1, t2) = tangent_basis(n);
    let bt = Matrix2::new(
        t1.dot(&(b * t1)),
        t1.dot(&(b * t2)),
        t2.dot(&(b * t1)),
        t2.dot(&(b * t2)),
    );
    let rhs = -Vector2::new(t1.dot(&(b * n)), t2.dot(&(b * n)));
    // least-norm solution of B_tt tau = -B_tn (B_tt may be singular with fixed points, (2.5))
    let scale = b.norm().max(f64::MIN_POSITIVE);
    let svd = bt.svd(true, true);
    if let Ok(x) = svd.solve(&rhs, 1e-12 * scale) {
        let consistent = (bt * x - rhs).norm() <= 1e-9 * scale;
        if consistent && x.norm() <= mu * (1.0 + 1e-12) {
            return Ok(t1 * x[0] + t2 * x[1]);
        }
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
    Err(best.map_or(t1, |r| r.u))
}

/// A ray of slip directions: `u` on the unit circle with $P_t\mathbf B(\mathbf n - \mu\mathbf u)$
/// parallel to `u`; `rate` is the slip speed's rate along it (positive: the slip grows), `stable`
/// whether nearby directions turn towards it.
#[derive(Clone, Copy, Debug)]
struct SlipRay {
    u: Vector3<f64>,
    rate: f64,
    stable: bool,
}

/// Every slip ray, found by scanning the circle and bisecting the cross product
/// $\mathbf u \times P_t\mathbf B(\mathbf n - \mu\mathbf u)$. A root where it falls through zero
/// as the angle grows is stable: a slip direction near it turns towards it.
fn slide_rays(rate: Rate, n: &Vector3<f64>, mu: f64, samples: usize) -> Vec<SlipRay> {
    let (t1, t2) = tangent_basis(n);
    let f = |th: f64| {
        let u = t1 * th.cos() + t2 * th.sin();
        let w = rate(&(n - u * mu));
        let wt = Vector2::new(t1.dot(&w), t2.dot(&w));
        let uu = Vector2::new(th.cos(), th.sin());
        (uu.x * wt.y - uu.y * wt.x, uu.dot(&wt), u)
    };
    let mut rays = Vec::new();
    let mut prev = f(0.0);
    for k in 1..=samples {
        let th1 = 2.0 * std::f64::consts::PI * k as f64 / samples as f64;
        let th0 = 2.0 * std::f64::consts::PI * (k - 1) as f64 / samples as f64;
        let cur = f(th1);
        if prev.0 == 0.0 || prev.0.signum() != cur.0.signum() {
            let stable = prev.0 > 0.0 || (prev.0 == 0.0 && cur.0 < 0.0);
            let (mut a, mut bb) = (th0, th1);
            let fa0 = f(a).0;
            for _ in 0..60 {
                let mid = 0.5 * (a + bb);
                if f(mid).0.signum() == fa0.signum() {
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

/// The stable ray along which a slip dies out (its speed falls at a constant rate there), if any:
/// a slip that settles on it reaches zero at a simple root of $(\mathbf V_t, \mathbf u) -
/// \text{stop}$, where $|\mathbf V_t|$ only touches zero between two samples of a step.
fn decay_ray(rate: Rate, n: &Vector3<f64>, mu: f64) -> Option<Vector3<f64>> {
    slide_rays(rate, n, mu, 180)
        .into_iter()
        .filter(|r| r.stable && r.rate < 0.0)
        .max_by(|x, y| {
            x.rate
                .partial_cmp(&y.rate)
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .map(|r| r.u)
}

fn out_of_range(field: &str, value: String, allowed: &str) -> ImpactError {
    ImpactError::OutOfRange {
        field: field.into(),
        value,
        allowed: allowed.into(),
    }
}

/// Solves one impact. `v_minus` is the relative velocity at C before impact (m/s), with
/// $(\mathbf V^-, \mathbf n) < 0$ (approaching).
#[allow(clippy::too_many_arguments)]
pub fn impact(
    b1: &Body,
    b2: &Body,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let bad = out_of_range;
    let b = b_matrix(b1, b2).ok_or_else(|| {
        bad(
            "body.inertia",
            "singular".into(),
            "symmetric positive-definite",
        )
    })?;
    let mut r = impact_with_matrix(&b, normal, v_minus, mu, law, e, rtol)?;
    r.energy_change = kinetic_change(b1, b2, &v_minus, &Vector3::from(r.impulse));
    Ok(r)
}

/// Solves one impact for a given matrix $\mathbf B$ (or $\mathbf B^*$ of (2.1), possibly
/// singular); `energy_change` is then Kelvin's (1.11) from B. A cut-off impact (the relative
/// velocity vanishes while sticking is possible and $\mathbf B(\mathbf n + \boldsymbol\tau) = 0$:
/// the bodies wedge) is reported with `cut_off = true`.
pub fn impact_with_matrix(
    b: &Matrix3<f64>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    impact_general(b, None, normal, v_minus, mu, law, e, rtol)
}

/// As [`impact_with_matrix`], with an optional smooth support under the second body (section
/// 3): the support reacts only while $\alpha < 0$, so $\mathbf B$ switches to $\mathbf B^*$ (3.8).
#[allow(clippy::too_many_arguments)]
pub fn impact_general(
    b: &Matrix3<f64>,
    support: Option<SmoothSupport>,
    normal: Vector3<f64>,
    v_minus: Vector3<f64>,
    mu: f64,
    law: Law,
    e: f64,
    rtol: f64,
) -> Result<ImpactResult, ImpactError> {
    let bad = out_of_range;
    if normal.norm() <= 0.0 || normal.norm().is_nan() {
        return Err(bad(
            "contact.normal",
            format!("{normal:?}"),
            "a non-zero vector",
        ));
    }
    if !(0.0..=1.0).contains(&e) {
        return Err(bad("contact.e", e.to_string(), "0 <= e <= 1"));
    }
    if !(mu >= 0.0 && mu.is_finite()) {
        return Err(bad("contact.mu", mu.to_string(), "mu >= 0"));
    }
    let b = *b;
    let n = normal.normalize();
    let vn0 = v_minus.dot(&n);
    if vn0 >= 0.0 || vn0.is_nan() {
        return Err(bad(
            "initial.v_rel",
            format!("{v_minus:?} (normal component {vn0})"),
            "a relative velocity with (v_rel, normal) < 0: the bodies must approach",
        ));
    }
    let eig = SymmetricEigen::new(b).eigenvalues;
    let (lmin, lmax) = (eig.min(), eig.max());
    if lmax <= 0.0 || lmax.is_nan() {
        return Err(bad(
            "body",
            format!("B eigenvalues {eig:?}"),
            "at least one body that can move",
        ));
    }
    // Proposition 3 of 002: with a support the bound takes the smaller of the least eigenvalues
    // of B and B* (the support's reaction can make the impulse larger than B alone allows)
    let lmin = match &support {
        Some(s) => {
            let w = s.b_tilde.transpose() * s.normal;
            let b_star = b - w * w.transpose() / s.beta;
            lmin.min(SymmetricEigen::new(b_star).eigenvalues.min())
        }
        None => lmin,
    };
    let lam_floor = lmax * 1e-12;
    let chi_max = 20.0 * 2.0 * v_minus.norm() / lmin.max(lam_floor).max(lmax * 1e-6);
    let scale = v_minus.norm();
    // the matrix that governs V_C near the stick/slip switch: B*, while the support pushes
    // ((B~ n, N) > 0 means alpha < 0 for F along n), else B
    let b_stick = match &support {
        Some(s) if (s.b_tilde * n).dot(&s.normal) > 0.0 => {
            let w = s.b_tilde.transpose() * s.normal;
            b - w * w.transpose() / s.beta
        }
        _ => b,
    };
    // the slip's rate for a friction direction, with the support as the integration has it
    let support_rate = support.clone();
    let rate_of = move |f: &Vector3<f64>| velocity_rate(&b, support_rate.as_ref(), f).0;
    let mut sys = Keller {
        support,
        b,
        n,
        mu,
        mode: Mode::Slip,
        u_hint: Vector3::zeros(),
        floor: 1e-13 * scale,
    };
    let mut y = vec![
        v_minus.x, v_minus.y, v_minus.z, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
    ];
    let mut chi = 0.0;
    let mut phases = Vec::new();
    let mut path: Vec<(f64, [f64; 3])> = Vec::new();
    let mut stats = crate::integrate::Stats::default();
    // initial mode
    let vt0 = sys.tangential(&v_minus);
    if vt0.norm() <= sys.floor || mu == 0.0 {
        match (mu > 0.0).then(|| stick_or_slide(&b_stick, &rate_of, &n, mu)) {
            Some(Ok(tau)) => {
                sys.mode = Mode::Stick(tau);
                phases.push(Phase {
                    kind: "stick".into(),
                    normal_impulse: 0.0,
                });
            }
            Some(Err(u)) => {
                sys.u_hint = u;
                phases.push(Phase {
                    kind: "slip".into(),
                    normal_impulse: 0.0,
                });
            }
            None => phases.push(Phase {
                kind: "slip".into(),
                normal_impulse: 0.0,
            }),
        }
    } else {
        phases.push(Phase {
            kind: "slip".into(),
            normal_impulse: 0.0,
        });
    }
    // B* (or B) and mu are fixed for the impact: the ray a dying slip settles on is found once
    let ray = if mu > 0.0 {
        decay_ray(&rate_of, &n, mu).unwrap_or_else(Vector3::zeros)
    } else {
        Vector3::zeros()
    };
    let mut ray_armed = true;
    let mut chi_c: Option<f64> = None;
    let mut w_c = 0.0;
    let mut cut_off = false;
    let mut switches = 0usize;
    loop {
        switches += 1;
        if switches > 10_000 {
            return Err(ImpactError::NoEnd {
                law: format!(
                    "{} (more than 10000 stick/slip switches at normal impulse {chi:e})",
                    law.name()
                ),
                chi_max,
            });
        }
        if let Mode::Stick(tau) = sys.mode
            && (b_stick * (n + tau)).norm() <= 1e-10 * lmax
        {
            // the velocity no longer changes while the reaction grows: a cut-off impact
            cut_off = true;
            break;
        }
        // the end condition of the current stage
        let target = |y: &[f64]| -> f64 {
            let vn = Vector3::new(y[0], y[1], y[2]).dot(&n);
            match chi_c {
                None => vn,
                Some(_) => match law {
                    Law::Newton => vn + e * vn0,
                    Law::Poisson => 0.0,
                    Law::Energetic => y[6] - w_c * (1.0 - e * e),
                },
            }
        };
        let poisson_end = chi_c.map(|c| (1.0 + e) * c);
        let end_g = |chi: f64, y: &[f64]| match (chi_c, law) {
            (Some(_), Law::Poisson) => chi - poisson_end.unwrap_or(chi),
            _ => target(y),
        };
        // the slip is taken to have stopped at a speed far below the tolerance: when the slip
        // velocity spirals into zero (anisotropic B) its direction turns ever faster and the
        // steps shrink with |V_t|, so chasing it down to the round-off floor costs unbounded
        // steps; stopping at 1e-2 rtol x the velocity scale changes the impulse by less than that
        let slip_stop = (10.0 * sys.floor).max(1e-2 * rtol * scale);
        let slip_g = |_chi: f64, y: &[f64]| {
            let v = Vector3::new(y[0], y[1], y[2]);
            (v - n * v.dot(&n)).norm() - slip_stop
        };
        let stage_done_already = chi_c.is_some() && end_g(chi, &y) >= 0.0;
        if stage_done_already {
            break;
        }
        // when the slip dies out along a stable ray, |V_t| reaches zero with a corner and the
        // integrator overshoots it by more than slip_stop within a step, so |V_t| - slip_stop
        // may never be seen negative; the speed along the ray falls through zero at a simple root
        // (disarmed, constant, after it fired off the ray, until the slip settles or stops)
        let armed = ray_armed;
        let ray_g = move |_chi: f64, y: &[f64]| {
            if armed {
                Vector3::new(y[0], y[1], y[2]).dot(&ray) - slip_stop
            } else {
                scale
            }
        };
        // once the slip lies on that ray to within 1e-2 rtol of the velocity scale and 1e-6 rad
        // (its component across the ray), the friction direction is frozen along it: the true
        // direction only converges further, while keeping it free makes the system ever stiffer
        // as |V_t| goes to zero (the turning rate grows like 1/|V_t|)
        let across = 1e-2 * rtol * scale;
        let aligned_g = |_chi: f64, y: &[f64]| {
            let v = Vector3::new(y[0], y[1], y[2]);
            let vt = v - n * v.dot(&n);
            if vt.dot(&ray) <= 0.0 {
                return scale;
            }
            // across the ray: below 1e-2 rtol scale, and a small angle (not merely a small slip)
            (vt - ray * vt.dot(&ray)).norm() - across.min(1e-6 * vt.norm())
        };
        let mut events = vec![Event::new("stage end", &end_g, Direction::Rising, true)];
        let slipping = matches!(sys.mode, Mode::Slip | Mode::Ray(_)) && mu > 0.0;
        if slipping {
            events.push(Event::new("slip stops", &slip_g, Direction::Falling, true));
            if ray.norm() > 0.0 {
                events.push(Event::new(
                    "slip dies on its ray",
                    &ray_g,
                    Direction::Falling,
                    true,
                ));
                if sys.mode == Mode::Slip {
                    events.push(Event::new(
                        "slip settles on its ray",
                        &aligned_g,
                        Direction::Falling,
                        true,
                    ));
                }
            }
        }
        let opts = Options {
            rtol,
            atol: rtol * scale * 1e-3,
            method: Method::Auto,
            events,
            trajectory: true,
            ..Options::default()
        };
        let sol = solve(&sys, chi, &y, chi_max, &opts)?;

        stats = stats + sol.stats;
        path.extend(sol.trajectory.iter().map(|(c, y)| (*c, [y[0], y[1], y[2]])));
        chi = sol.t;
        y = sol.y.clone();
        match sol.stop {
            Stop::End => {
                return Err(ImpactError::NoEnd {
                    law: law.name().into(),
                    chi_max,
                });
            }
            Stop::Event { index: 0, .. } => {
                if chi_c.is_none() {
                    chi_c = Some(chi);
                    w_c = y[6];
                    // a zero-e law ends with compression
                    let done = match law {
                        Law::Newton | Law::Poisson | Law::Energetic => e == 0.0,
                    };
                    if done {
                        break;
                    }
                    continue;
                }
                break;
            }
            Stop::Event { index: 3, .. } => {
                sys.mode = Mode::Ray(ray);
                ray_armed = true;
                continue;
            }
            Stop::Event { index: 2, .. }
                if sys.tangential(&Vector3::new(y[0], y[1], y[2])).norm() > 10.0 * slip_stop =>
            {
                // the slip crossed the ray's normal line off the ray, away from zero: slip on,
                // without the ray event (it would fire again at once) until the slip settles
                ray_armed = false;
                continue;
            }
            Stop::Event { .. } => {
                ray_armed = true;
                // slip stopped: stick or slide again
                match stick_or_slide(&b_stick, &rate_of, &n, mu) {
                    Ok(tau) => {
                        sys.mode = Mode::Stick(tau);
                        phases.push(Phase {
                            kind: "stick".into(),
                            normal_impulse: chi,
                        });
                    }
                    Err(u) => {
                        sys.u_hint = u;
                        sys.mode = Mode::Slip;
                        // nudge past the floor in the new direction so the slip event re-arms:
                        // 20 slip_stop, far above the absolute tolerance (1e-3 rtol scale), so
                        // that integration noise cannot take the slip back under the stop (the
                        // switches then chatter), and at most 0.2 rtol scale, under the tolerance
                        let v = Vector3::new(y[0], y[1], y[2]);
                        let vt = sys.tangential(&v);
                        let vnew = v - vt + u * (20.0 * slip_stop);
                        y[0] = vnew.x;
                        y[1] = vnew.y;
                        y[2] = vnew.z;
                        phases.push(Phase {
                            kind: "reversal".into(),
                            normal_impulse: chi,
                        });
                    }
                }
            }
        }
    }
    let vp = Vector3::new(y[0], y[1], y[2]);
    // the impulse: integral of dI/dchi over chi (its normal component equals chi)
    let imp = Vector3::new(y[3], y[4], y[5]);
    let kelvin = 0.5 * (v_minus + vp).dot(&imp);
    let direct = v_minus.dot(&imp) + 0.5 * imp.dot(&(b * imp));
    Ok(ImpactResult {
        cut_off,
        impulse: [imp.x, imp.y, imp.z],
        v_rel_after: [vp.x, vp.y, vp.z],
        compression_impulse: chi_c.unwrap_or(chi),
        energy_change: direct,
        kelvin_energy_change: kelvin,
        lambda_min: lmin,
        lambda_max: lmax,
        bound_upper: if lmin > lam_floor {
            2.0 * v_minus.norm() / lmin
        } else {
            f64::INFINITY
        },
        bound_lower: vn0.abs() / lmax,
        phases,
        stats,
        support_impulse: [y[7], y[8], y[9]],
        path,
    })
}

/// Kinetic energy change of the bodies computed from their velocities (1.2)-(1.3): body 1
/// translating with the relative velocity, body 2 at rest (any split gives the same change).
pub fn kinetic_change(b1: &Body, b2: &Body, v_minus: &Vector3<f64>, imp: &Vector3<f64>) -> f64 {
    kinetic_change_supported(b1, b2, v_minus, imp, None)
}

/// As [`kinetic_change`], with the support impulse `(G2->A, I*)` on the second body (3.1).
pub fn kinetic_change_supported(
    b1: &Body,
    b2: &Body,
    v_minus: &Vector3<f64>,
    imp: &Vector3<f64>,
    support: Option<(Vector3<f64>, Vector3<f64>)>,
) -> f64 {
    let ke = |body: &Body, v: &Vector3<f64>, w: &Vector3<f64>| -> f64 {
        body.mass.map_or(0.0, |m| {
            0.5 * m * v.norm_squared() + 0.5 * w.dot(&(body.inertia * w))
        })
    };
    let mut before = 0.0;
    let mut after = 0.0;
    for (k, body) in [b1, b2].into_iter().enumerate() {
        let Some(m) = body.mass else { continue };
        let sign = if k == 0 { 1.0 } else { -1.0 };
        // the relative velocity is carried by body 1, or by body 2 when body 1 is fixed
        let v0 = match (k, b1.mass) {
            (0, _) => *v_minus,
            (_, None) => -v_minus,
            _ => Vector3::zeros(),
        };
        let w0 = Vector3::zeros();
        let (extra_f, extra_m) = match (k, support) {
            (1, Some((g2a, istar))) => (istar, g2a.cross(&istar)),
            _ => (Vector3::zeros(), Vector3::zeros()),
        };
        let dv = (imp * sign + extra_f) / m;
        let dw = body.inertia.try_inverse().unwrap_or_else(Matrix3::zeros)
            * (body.offset.cross(&(imp * sign)) + extra_m);
        before += ke(body, &v0, &w0);
        after += ke(body, &(v0 + dv), &(w0 + dw));
    }
    after - before
}
